"""The user's own cranes from Python: the wheel `my_cranes` that maturin
builds from this crate (feature `python`) runs them as `my-cranes run`
does, bit for bit, beside the package of the built-in cranes."""

import csv
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import my_cranes

ROOT = Path(__file__).resolve().parents[3]
CLI = Path(os.environ.get("MY_CRANES_BIN", ROOT / "target" / "release" / "my-cranes"))


def test_models_lists_the_registry_s_cranes():
    models = {m["name"]: m for m in my_cranes.models()}
    assert list(models) == ["planar-gantry", "hook-crane", "swing-crane"]
    # flat, of path order 4 and 6: the exact reduced formulation by
    # default, as a built-in crane's
    assert models["planar-gantry"]["formulation"] == "dummy-derivative"
    assert models["hook-crane"]["path_order"] == 6
    assert models["hook-crane"]["formulation"] == "dummy-derivative"
    # stable internal dynamics: the reduced formulation with state selection
    assert models["swing-crane"]["formulation"] == "state-selection"


@pytest.mark.parametrize(
    "model,args",
    [("hook-crane", ["--dt", "0.02"]), ("planar-gantry", ["--scheme", "bdf4"]), ("swing-crane", ["--scheme", "bdf4"])],
)
def test_a_run_is_the_tool_s_bit_for_bit(tmp_path, model, args):
    keywords = {"dt": 0.02} if model == "hook-crane" else {"scheme": "bdf4"}
    r = my_cranes.run(model, **keywords)
    assert r.warnings == []
    out = tmp_path / "cli"
    subprocess.run([str(CLI), "run", model, *args, "--quiet", "--out", str(out)], check=True, capture_output=True)
    with open(out / "results.csv") as f:
        rows = list(csv.DictReader(f))
    assert r.u.shape == (len(rows), len(r.inputs))
    for k, name in enumerate(r.inputs):
        assert np.array_equal(r.u[:, k], [float(row[name]) for row in rows]), name
    for k, name in enumerate(r.coordinates):
        assert np.array_equal(r.q[:, k], [float(row[name]) for row in rows]), name


def test_a_model_of_another_registry_is_unknown():
    with pytest.raises(my_cranes.CraneError, match="unknown model `navy-planar`; expected one of planar-gantry, hook-crane, swing-crane"):
        my_cranes.run("navy-planar")


def test_the_built_in_package_keeps_its_own_cranes():
    import crane

    assert len(crane.models()) == 9
    assert len(my_cranes.models()) == 3
    assert crane.run("navy-planar").u.shape == (401, 2)


def test_a_stepper_of_the_user_s_crane_takes_the_run_s_steps():
    """The hook crane's exact reduced formulation, one step at a time."""
    r = my_cranes.run("hook-crane", dt=0.02)
    s = my_cranes.stepper("hook-crane", dt=0.02)
    for i in range(1, 21):
        assert np.array_equal(s.step()["u"], r.u[i]), i
    assert np.array_equal(s.step_to(r.t[-1])["u"], r.u[-1])


def test_a_stepper_of_the_swing_crane_integrates_its_states_as_the_run():
    """State selection one step at a time: the free swing's BDF-2 history
    carried from step to step gives the run's inputs bit for bit."""
    r = my_cranes.run("swing-crane", scheme="bdf2")
    s = my_cranes.stepper("swing-crane", scheme="bdf2")
    for i in range(1, 51):
        assert np.array_equal(s.step()["u"], r.u[i]), i
    assert np.array_equal(s.step_to(r.t[-1])["u"], r.u[-1])


def test_a_sweep_of_the_user_s_crane_is_the_tool_s(tmp_path):
    """The hook crane's load mass swept in its exact reduced formulation,
    as `my-cranes sweep` sweeps it: sweep.csv's peaks bit for bit."""
    s = my_cranes.sweep("hook-crane", {"m_l": [300.0, 400.0]})
    out = tmp_path / "cli"
    subprocess.run([str(CLI), "sweep", "hook-crane", "--param", "m_l=300:400:2", "--quiet", "--out", str(out)],
                   check=True, capture_output=True)
    with open(out / "sweep.csv") as f:
        rows = list(csv.DictReader(f))
    for name in ["m_l", "duration", "peak_u1", "peak_u2"]:
        assert np.array_equal(s[name], [float(row[name]) for row in rows]), name
    assert list(s["feasible"]) == [row["feasible"] == "true" for row in rows]
    # a heavier load needs a larger hoist torque
    assert s["peak_u2"][1] > s["peak_u2"][0]


def test_the_user_s_crane_converges_to_its_exact_inputs():
    """Eqs. (22) with BDF-2 against the hook crane's exact reduced inputs."""
    c = my_cranes.convergence("hook-crane", formulation="redundant", scheme="bdf2", dts=[0.02, 0.01, 0.005])
    assert c["reference"] == "the exact inputs of the dummy-derivative formulation"
    assert np.all(np.diff(c["e_u"]) < 0)
    assert abs(c["order"][-1] - 2.0) < 0.2


def test_the_module_s_classes_are_its_own():
    """The user's module names its classes after itself (they read
    `crane.Run` before), so a pickled run comes back as a `my_cranes.Run`;
    its exception is a ValueError, the base it shares with `crane`'s."""
    import pickle

    import crane

    for name in ["Run", "Stepper", "CraneError", "CraneWarning"]:
        assert getattr(my_cranes, name).__module__ == "my_cranes", name
        assert getattr(crane, name).__module__ == "crane", name
    r = my_cranes.run("hook-crane", dt=0.02)
    back = pickle.loads(pickle.dumps(r))
    assert type(back) is my_cranes.Run
    assert np.array_equal(back.u, r.u)
    assert issubclass(my_cranes.CraneError, ValueError) and issubclass(crane.CraneError, ValueError)
    with pytest.raises(ValueError):
        my_cranes.run("navy-planar")


def test_the_module_s_stepper_class_makes_its_own_cranes():
    """`my_cranes.Stepper(...)` steps the user's cranes (the registry of the
    module the class belongs to), not the built-in ones."""
    s = my_cranes.Stepper("hook-crane", dt=0.02)
    r = my_cranes.run("hook-crane", dt=0.02)
    assert np.array_equal(s.step()["u"], r.u[1])
    with pytest.raises(my_cranes.CraneError, match="unknown model `navy-planar`"):
        my_cranes.Stepper("navy-planar")


def test_a_sweep_of_the_user_s_crane_on_a_dask_cluster_is_the_module_s():
    """`my_cranes.distributed.sweep`: the workers import `my_cranes` and run
    its cranes; the table is `my_cranes.sweep`'s, bit for bit."""
    pytest.importorskip("distributed")
    from dask.distributed import Client, LocalCluster

    grid = {"m_l": [100.0, 150.0, 200.0, 250.0]}
    expected = my_cranes.sweep("planar-gantry", grid, durations=[4.0, 5.0])
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            table = my_cranes.distributed.sweep("planar-gantry", grid, durations=[4.0, 5.0], client=client,
                                                chunk_size=3)
    assert list(table) == list(expected)
    for name, column in expected.items():
        if isinstance(column, np.ndarray):
            assert np.array_equal(column, table[name], equal_nan=True), name
        else:
            assert column == table[name], name
