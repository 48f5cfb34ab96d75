"""Points per second of a navy-planar sweep in one process (`crane.sweep`,
all cores) and on a LocalCluster of two single-threaded worker processes
(`crane.distributed.sweep`) at chunks of 100, 1,000 and 10,000 points; the
tables are checked equal. In-process and 10,000-point chunks alternate
`--repeat` times (the machine's own noise is several per cent from one
sweep to the next) and the medians are compared. By hand (not in CI):

    python examples/python/distributed_throughput.py [--points 200000] [--repeat 3]
"""

import argparse
import statistics
import time

import numpy as np
from dask.distributed import Client, LocalCluster

import crane

LIMITS = {"u2": 150.0}


def grid(points):
    """A 40 x 25 x K grid of about `points` points."""
    k = max(1, round(points / 1000))
    return {"m_l": np.linspace(80.0, 120.0, 40), "l": np.linspace(9.0, 11.0, 25), "J1": np.linspace(0.5, 1.5, k)}


def timed(call):
    start = time.perf_counter()
    result = call()
    return time.perf_counter() - start, result


def same(a, b):
    return all(np.array_equal(a[k], b[k], equal_nan=True) if isinstance(a[k], np.ndarray) else a[k] == b[k] for k in a)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--points", type=int, default=200_000)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    axes = grid(args.points)
    count = int(np.prod([len(v) for v in axes.values()]))
    print(f"{count} points of navy-planar, limits {LIMITS}")
    _, local = timed(lambda: crane.sweep("navy-planar", axes, limits=LIMITS))
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            def distributed(chunk):
                return lambda: crane.distributed.sweep("navy-planar", axes, client=client, chunk_size=chunk, limits=LIMITS)

            # the workers import crane on their first task: warm them up
            crane.distributed.sweep("navy-planar", {"m_l": [100.0, 110.0]}, client=client, chunk_size=1)
            for chunk in [100, 1_000]:
                wall, table = timed(distributed(chunk))
                assert same(local, table)
                print(f"chunks of {chunk}: {count / wall:.0f} points/s ({-(-count // chunk)} tasks)")
            inside, outside = [], []
            for _ in range(args.repeat):
                wall, table = timed(lambda: crane.sweep("navy-planar", axes, limits=LIMITS))
                assert same(local, table)
                inside.append(count / wall)
                wall, table = timed(distributed(10_000))
                assert same(local, table)
                outside.append(count / wall)
            a, b = statistics.median(inside), statistics.median(outside)
            print(f"in process: {' '.join(f'{v:.0f}' for v in inside)} points/s, median {a:.0f}")
            print(f"chunks of 10000: {' '.join(f'{v:.0f}' for v in outside)} points/s, median {b:.0f} "
                  f"({-(-count // 10_000)} tasks): {100 * (1 - b / a):.1f} % below in process")


if __name__ == "__main__":
    main()
