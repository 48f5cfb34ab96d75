"""The Ray recipe of docs/distributed.md, checked: 100,000 load masses of
navy-planar in chunks of 10,000 as Ray remote tasks, joined in order and
compared with `crane.sweep_points` in this process (bit for bit), with
the points per second of each. By hand (not in CI: Ray is a large
install):

    pip install "ray==2.*" && python examples/python/ray_sweep.py
"""

import time

import numpy as np
import ray

import crane

m = np.linspace(80.0, 120.0, 100_000)    # the points: load masses


@ray.remote
def chunk(points, durations):
    return crane.sweep_points("navy-planar", points, durations=durations, limits={"u2": 150.0})


def main():
    ray.init(include_dashboard=False)
    start = time.perf_counter()
    parts = ray.get([chunk.remote({"m_l": m[i:i + 10_000]}, None) for i in range(0, len(m), 10_000)])
    table = {k: np.concatenate([p[k] for p in parts]) if isinstance(parts[0][k], np.ndarray)
             else sum((p[k] for p in parts), []) for k in parts[0]}
    wall = time.perf_counter() - start
    start = time.perf_counter()
    local = crane.sweep_points("navy-planar", {"m_l": m}, limits={"u2": 150.0})
    wall_local = time.perf_counter() - start
    assert list(table) == list(local)
    for name, column in local.items():
        same = np.array_equal(table[name], column, equal_nan=True) if isinstance(column, np.ndarray) else table[name] == column
        assert same, name
    print(f"{len(m)} points: Ray {len(m) / wall:.0f} points/s, in process {len(m) / wall_local:.0f} points/s; "
          "the same table bit for bit")


if __name__ == "__main__":
    main()
