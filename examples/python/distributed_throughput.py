"""Points per second of a navy-planar sweep in one process (`crane.sweep`,
all cores) and on a LocalCluster of two single-threaded worker processes
(`crane.distributed.sweep`) at chunks of 100, 1,000 and 10,000 points; the
tables are checked equal. By hand (not in CI):

    python examples/python/distributed_throughput.py
"""

import time

import numpy as np
from dask.distributed import Client, LocalCluster

import crane

GRID = {"m_l": np.linspace(80.0, 120.0, 40), "l": np.linspace(9.0, 11.0, 25), "J1": np.linspace(0.5, 1.5, 40)}
LIMITS = {"u2": 150.0}


def main():
    count = np.prod([len(v) for v in GRID.values()])
    start = time.perf_counter()
    local = crane.sweep("navy-planar", GRID, limits=LIMITS)
    wall = time.perf_counter() - start
    print(f"{count} points; in process: {count / wall:.0f} points/s")
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            for chunk in [100, 1_000, 10_000]:
                start = time.perf_counter()
                table = crane.distributed.sweep("navy-planar", GRID, client=client, chunk_size=chunk, limits=LIMITS)
                wall = time.perf_counter() - start
                assert all(np.array_equal(local[k], table[k], equal_nan=True) if isinstance(local[k], np.ndarray)
                           else local[k] == table[k] for k in local)
                print(f"chunks of {chunk}: {count / wall:.0f} points/s ({-(-count // chunk)} tasks)")


if __name__ == "__main__":
    main()
