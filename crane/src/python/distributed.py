"""Sweeps across machines on a Dask cluster.

`sweep(model, grid=None, points=None, *, client, ...)` splits the points
into chunks, maps the package's `sweep_points` over a
`dask.distributed.Client` (one task per chunk, each a process's parallel
sweep of its points), and gathers the chunks in order into the columns
`sweep` returns: the same numbers, bit for bit, as one machine's. A worker
that dies mid-sweep has its chunks run again elsewhere by the scheduler,
and the result is the same. Dask is imported only here, when used:
`pip install "dask[distributed]"`.

    from dask.distributed import Client, LocalCluster
    from crane import distributed
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        table = distributed.sweep("navy-planar", {"m_l": [80.0, 100.0, 120.0]},
                                  durations=[3.0, 4.0], client=client, limits={"u2": 150.0})
"""

import importlib
import os
import shutil
import sys

import numpy as np

# the package whose cranes the workers run (`crane`, or a user's module
# made with `export_module!`): set when the package imports this module
_PACKAGE = "crane"

#: points per task by default: a task then carries about 2 s of runs on one
#: core, and the scheduler's overhead of about 1 ms per task is 0.05 % of it
CHUNK_SIZE = 10_000


# `_grid_points(grid, durations)`, the grid's points in `sweep`'s order
# (names, one list of values per name, durations or None), is set on this
# module by the extension that loads it.


def _floats(values, what):
    """A sequence of numbers (a list, a numpy array, a pandas Series)."""
    if hasattr(values, "tolist"):
        values = values.tolist()
    try:
        return list(values)
    except TypeError:
        raise _package().CraneError(f"{what} must be a sequence of numbers") from None


def _package():
    return importlib.import_module(_PACKAGE)


def _chunk(package, model, names, columns, durations, options):
    """One task: `sweep_points` of the package `package` on a worker."""
    module = importlib.import_module(package)
    return module.sweep_points(model, dict(zip(names, columns)), durations=durations, **options)


def _join(chunks):
    """The chunks' columns, in order, as one table."""
    table = {}
    for name in chunks[0]:
        parts = [chunk[name] for chunk in chunks]
        if isinstance(parts[0], np.ndarray):
            table[name] = np.concatenate(parts)
        else:
            table[name] = [item for part in parts for item in part]
    return table


def _prepare(model, grid, points, durations, chunk_size, options):
    """The points of a grid or a set, checked: the names, one list of values
    per name, the durations (None: the move's own) and the chunks' starts.
    The first point is run here, so that an unknown name or option fails
    before any task."""
    package = _package()
    if (grid is None) == (points is None):
        raise package.CraneError("give a grid or points, not both or neither")
    if not (isinstance(chunk_size, int) and chunk_size >= 1):
        raise package.CraneError(f"chunk_size {chunk_size!r}: expected a positive integer")
    if grid is not None:
        # the grid in `sweep`'s order (`_grid_points`, set by the extension)
        names, columns, durations = _grid_points(grid, durations)
    else:
        names = list(points)
        columns = [[float(v) for v in _floats(points[name], f"points: `{name}`")] for name in names]
        if durations is not None:
            durations = [float(d) for d in _floats(durations, "durations")]
    count = len(columns[0]) if columns else len(durations or [])
    if any(len(c) != count for c in columns) or (durations is not None and len(durations) != count):
        raise package.CraneError("points: ragged: every parameter and the durations need one value per point")
    if count == 0:
        raise package.CraneError("points: no points")
    for name, column in zip(names, columns):
        if not all(np.isfinite(column)):
            raise package.CraneError(f"points: `{name}` has a value that is not finite")
    _chunk(_PACKAGE, model, names, [c[:1] for c in columns], None if durations is None else durations[:1], options)
    return names, columns, durations, range(0, count, chunk_size)


def _submit(client, task, model, names, columns, durations, starts, chunk_size, options, extra=lambda i: ()):
    """One task per chunk: `task(package, model, names, columns, durations,
    options, *extra(i))` for the chunk starting at point `i`."""
    return [
        client.submit(
            task,
            _PACKAGE,
            model,
            names,
            [c[i:i + chunk_size] for c in columns],
            None if durations is None else durations[i:i + chunk_size],
            options,
            *extra(i),
            pure=False,
        )
        for i in starts
    ]


def _wait(futures, progress):
    """Print the chunks done on stderr as they finish, if asked."""
    if progress:
        from dask.distributed import as_completed

        for done, _ in enumerate(as_completed(futures), start=1):
            print(f"sweep: {done}/{len(futures)} chunks", file=sys.stderr)


def sweep(model, grid=None, points=None, *, client, durations=None, chunk_size=CHUNK_SIZE, progress=False,
          **options):
    """The sweep of `model` over `grid` (with `durations`, as `sweep`) or
    over `points` (with per-point `durations`, as `sweep_points`) on the
    Dask cluster of `client`, in chunks of `chunk_size` points; returns
    `sweep`'s columns in the order of the points. `progress` prints the
    chunks done on stderr. `options` are `sweep_points`' keywords
    (`limits`, `min_tension`, `scenario`, `parameters`, `scheme`, `dt`)."""
    names, columns, durations, starts = _prepare(model, grid, points, durations, chunk_size, options)
    futures = _submit(client, _chunk, model, names, columns, durations, starts, chunk_size, options)
    _wait(futures, progress)
    return _join(client.gather(futures))


def _shard(package, model, names, columns, durations, options, path):
    """One task: a chunk's sweep written by the worker to `path` as Parquet."""
    import pandas

    pandas.DataFrame(_chunk(package, model, names, columns, durations, options)).to_parquet(path, index=False)
    return path


def to_parquet(path, model, grid=None, points=None, *, client, durations=None, chunk_size=CHUNK_SIZE,
               progress=False, **options):
    """The sweep `sweep` makes, written by the workers as Parquet, one shard
    per chunk (`path/part-00000.parquet`, ... in the order of the points),
    for tables larger than one machine's memory: `pandas.read_parquet(path)`
    reads them back as one table. `path` must not exist and be on a file
    system every worker writes to; the shards go into a folder beside it
    that is renamed to `path` only when all of them are written (a failed
    sweep leaves no `path`). Needs pandas and pyarrow on the workers.
    Returns the shards' paths."""
    package = _package()
    target = os.path.abspath(os.fspath(path))
    if os.path.lexists(target):
        raise package.CraneError(f"{target} exists: to_parquet writes a new folder")
    names, columns, durations, starts = _prepare(model, grid, points, durations, chunk_size, options)
    partial = f"{target}.partial-{os.getpid()}"
    os.makedirs(partial)
    try:
        shard = lambda i: (os.path.join(partial, f"part-{i // chunk_size:05d}.parquet"),)
        futures = _submit(client, _shard, model, names, columns, durations, starts, chunk_size, options, shard)
        _wait(futures, progress)
        client.gather(futures)
        os.rename(partial, target)
    except BaseException:
        shutil.rmtree(partial, ignore_errors=True)
        raise
    return [os.path.join(target, f"part-{i // chunk_size:05d}.parquet") for i in starts]
