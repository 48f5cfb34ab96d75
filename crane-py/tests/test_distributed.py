"""Sweeps on a Dask cluster (`crane.distributed.sweep`): a LocalCluster of
two worker processes runs a 3-parameter grid of 20,000 points in chunks,
and every column equals `crane.sweep`'s on one machine, bit for bit; with
one worker process killed mid-sweep (after the first chunk is done) the
scheduler runs its chunks again and the result is the same."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import crane

distributed = pytest.importorskip("distributed")

GRID = {
    "m_l": np.linspace(80.0, 120.0, 25),
    "l": np.linspace(9.0, 11.0, 20),
    "J1": np.linspace(0.5, 1.5, 20),
}
DURATIONS = [3.5, 4.0]
LIMITS = {"u2": 150.0}


def assert_same(table, expected):
    assert list(table) == list(expected)
    for name, column in expected.items():
        if isinstance(column, np.ndarray):
            assert column.dtype == table[name].dtype and np.array_equal(column, table[name], equal_nan=True), name
        else:
            assert column == table[name], name


@pytest.fixture(scope="module")
def expected():
    return crane.sweep("navy-planar", GRID, durations=DURATIONS, limits=LIMITS)


@pytest.fixture(scope="module")
def client():
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            yield client


def test_a_grid_on_a_local_cluster_is_one_machine_s_sweep(expected, client):
    assert len(expected["m_l"]) == 20_000
    table = crane.distributed.sweep("navy-planar", GRID, durations=DURATIONS, client=client, chunk_size=2_000,
                                    limits=LIMITS)
    assert_same(table, expected)


def test_a_worker_killed_mid_sweep_changes_nothing(expected, client):
    pids = client.run(os.getpid)
    killed = {}

    def kill_after_the_first_chunk():
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            if any(client.has_what().values()):
                worker, pid = next(iter(pids.items()))
                os.kill(pid, signal.SIGKILL)
                killed["at"] = time.monotonic()
                return
            time.sleep(0.01)

    killer = threading.Thread(target=kill_after_the_first_chunk)
    killer.start()
    table = crane.distributed.sweep("navy-planar", GRID, durations=DURATIONS, client=client, chunk_size=1_000,
                                    limits=LIMITS)
    done = time.monotonic()
    killer.join()
    assert "at" in killed and killed["at"] < done, "no worker was killed while the sweep ran"
    assert_same(table, expected)


def test_points_on_a_cluster_are_sweep_points_and_bad_sets_fail_before_any_task(client):
    points = {"m_l": [120.0, 80.0, 100.0]}
    table = crane.distributed.sweep("navy-planar", points=points, durations=[4.0, 3.0, 3.5], client=client,
                                    chunk_size=2, limits=LIMITS)
    assert_same(table, crane.sweep_points("navy-planar", points, durations=[4.0, 3.0, 3.5], limits=LIMITS))
    for kwargs, match in [
        (dict(points={"m_l": [1.0, float("nan")]}), "not finite"),
        (dict(points={"m_x": [1.0]}), "no such parameter"),
        (dict(points={"m_l": [1.0, 2.0], "l": [9.0]}), "ragged"),
        (dict(grid={"m_l": [1.0]}, points={"m_l": [1.0]}), "not both"),
        (dict(points={"m_l": [1.0]}, chunk_size=0), "chunk_size"),
    ]:
        with pytest.raises(crane.CraneError, match=match):
            crane.distributed.sweep("navy-planar", client=client, **kwargs)


def test_to_parquet_writes_a_shard_per_chunk_that_read_back_are_the_sweep(tmp_path, expected, client):
    pandas = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    target = tmp_path / "sweep"
    shards = crane.distributed.to_parquet(target, "navy-planar", GRID, durations=DURATIONS, client=client,
                                          chunk_size=6_000, limits=LIMITS)
    assert [os.path.basename(s) for s in shards] == [f"part-{i:05d}.parquet" for i in range(4)]
    assert sorted(os.listdir(target)) == [os.path.basename(s) for s in shards]
    frame = pandas.read_parquet(target)
    assert list(frame.columns) == list(expected)
    for name, column in expected.items():
        if isinstance(column, np.ndarray):
            assert np.array_equal(frame[name].to_numpy(), column, equal_nan=True), name
        else:
            assert frame[name].tolist() == column, name
    # the folder is new; a sweep that fails leaves nothing behind
    with pytest.raises(crane.CraneError, match="exists"):
        crane.distributed.to_parquet(target, "navy-planar", GRID, client=client)
    with pytest.raises(crane.CraneError, match="has no input"):
        crane.distributed.to_parquet(tmp_path / "bad", "navy-planar", GRID, client=client, limits={"u9": 1.0})
    assert sorted(os.listdir(tmp_path)) == ["sweep"]


def test_the_stub_of_crane_distributed_names_what_it_takes():
    """The stub types `crane.distributed` (a Protocol, for mypy and pyright)
    with every parameter its functions take: their own, with the same
    defaults, and `**options` as the keywords of `sweep_points` (stubtest
    checks `sweep_points`' stub against the extension; this ties the
    two)."""
    import ast
    import inspect
    from pathlib import Path

    tree = ast.parse(Path(crane.__file__).with_name("__init__.pyi").read_text())
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    sweep_points = next(n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "sweep_points")
    options = [a.arg for a in sweep_points.args.kwonlyargs if a.arg != "durations"]
    fields = [n.target.id for n in classes["_SweepOptions"].body if isinstance(n, ast.AnnAssign)]
    assert fields == options
    typed = {n.name: n for n in classes["_Distributed"].body if isinstance(n, ast.FunctionDef)}
    assert sorted(typed) == ["sweep", "to_parquet"]
    for name, stub in typed.items():
        runtime = inspect.signature(getattr(crane.distributed, name)).parameters.values()
        own = [p.name for p in runtime if p.kind is not inspect.Parameter.VAR_KEYWORD]
        assert [p.kind for p in runtime][-1] is inspect.Parameter.VAR_KEYWORD, name
        assert [a.arg for a in stub.args.args[1:]] + [a.arg for a in stub.args.kwonlyargs] == own, name
        assert ast.unparse(stub.args.kwarg.annotation) == "Unpack[_SweepOptions]", name
        defaults = {p.name: p.default for p in runtime if p.default is not inspect.Parameter.empty}
        positional = [a.arg for a in stub.args.args[1:]]
        stub_defaults = dict(zip(positional[len(positional) - len(stub.args.defaults):], stub.args.defaults))
        stub_defaults.update({a.arg: d for a, d in zip(stub.args.kwonlyargs, stub.args.kw_defaults) if d is not None})
        assert sorted(stub_defaults) == sorted(defaults), name
        for key, value in defaults.items():
            assert ast.literal_eval(stub_defaults[key]) == value, (name, key)
