"""The Python module against the command line and its own promises: the
same numbers as `crane run` (bit for bit), scenario dicts as scenario
files, every error a crane.CraneError with the tool's message."""

import csv
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import crane

ROOT = Path(__file__).resolve().parents[2]
CLI = Path(os.environ.get("CRANE_BIN", ROOT / "target" / "release" / "crane"))


def cli_results(tmp_path, *args):
    """`crane run ARGS` into tmp_path/cli: its results.csv as columns."""
    out = tmp_path / "cli"
    subprocess.run([str(CLI), "run", *args, "--quiet", "--out", str(out)], check=True, capture_output=True)
    with open(out / "results.csv") as f:
        rows = list(csv.DictReader(f))
    return {name: np.array([float(r[name]) for r in rows]) for name in rows[0]}


def test_models_lists_the_built_in_cranes():
    models = {m["name"]: m for m in crane.models()}
    assert len(models) == 9
    navy = models["navy-planar"]
    assert (navy["n"], navy["m"], navy["a"]) == (7, 3, 2)
    assert navy["reference"] and navy["minimal"]
    # every flat crane runs its exact reduced system by default
    assert navy["path_order"] == 4 and navy["formulation"] == "dummy-derivative"
    assert models["coupled-trolley"]["formulation"] == "stable-inversion"
    assert navy["internal_dimension"] == 0
    assert models["navy-3d-pulley"]["formulation"] == "dummy-derivative"
    assert models["coupled-trolley"]["internal_dimension"] == 2


def test_a_run_is_the_command_line_s_bit_for_bit(tmp_path):
    r = crane.run("navy-planar", scheme="bdf4")
    assert r.u.shape == (401, 2) and r.q.shape == (401, 7) and r.v.shape == (401, 7)
    assert r.lambda_.shape == (401, 3) and r.tensions.shape == (401, 2) and r.t.shape == (401,)
    assert r.u.dtype == np.float64 and r.u.flags["C_CONTIGUOUS"] and r.u.flags["OWNDATA"] is not None
    assert r.inputs == ["u1", "u2"] and r.ropes == ["N1", "N2"] and r.coordinates[0] == "L1"
    assert r.summary["steps"] == 400 and r.summary["scheme"] == "bdf4"
    assert r.warnings == []
    cli = cli_results(tmp_path, "navy-planar", "--scheme", "bdf4")
    for k, name in enumerate(r.inputs):
        assert np.array_equal(r.u[:, k], cli[name]), name
    for k, name in enumerate(r.coordinates):
        assert np.array_equal(r.q[:, k], cli[name]), name
    for k, name in enumerate(r.ropes):
        assert np.array_equal(r.tensions[:, k], cli[name]), name
    assert np.array_equal(r.t, cli["t"])


def test_the_summary_is_summary_json(tmp_path):
    """The summary is summary.json's dict, the wall time aside, for a run
    and a replay on another plant."""
    import json

    for args, keywords in [
        ([], {}),
        (["--scheme", "bdf4", "--replay", "--plant", "m_l=130"], {"scheme": "bdf4", "replay": True,
                                                                    "plant": {"m_l": 130.0}}),
    ]:
        r = crane.run("navy-planar", **keywords)
        out = tmp_path / "cli"
        subprocess.run([str(CLI), "run", "navy-planar", *args, "--quiet", "--out", str(out)], check=True,
                       capture_output=True)
        expected = json.loads((out / "summary.json").read_text())
        assert set(r.summary) == set(expected)
        for key in expected:
            if key != "wall_time_s":
                assert r.summary[key] == expected[key], key


def test_to_csv_writes_the_command_line_s_results_csv(tmp_path):
    r = crane.run("navy-planar", scheme="bdf2")
    r.to_csv(tmp_path / "python.csv")
    out = tmp_path / "cli"
    subprocess.run([str(CLI), "run", "navy-planar", "--scheme", "bdf2", "--quiet", "--out", str(out)], check=True)
    assert (tmp_path / "python.csv").read_bytes() == (out / "results.csv").read_bytes()
    with pytest.raises(crane.CraneError, match="writing"):
        r.to_csv(tmp_path / "no" / "such" / "folder.csv")
    (tmp_path / "a-folder").mkdir()
    with pytest.raises(crane.CraneError, match="a-folder"):
        r.to_csv(tmp_path / "a-folder")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a-folder", "cli", "python.csv"]


def test_a_run_releases_the_gil():
    """While a run of about a second goes on in a thread, Python's main
    thread keeps running (with the GIL held for the run it could not)."""
    done = threading.Event()
    result = []

    def work():
        try:
            result.append(crane.run("navy-planar", dt=2e-5))
        finally:
            done.set()

    thread = threading.Thread(target=work)
    ticks = 0
    thread.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    thread.join()
    assert result[0].u.shape == (200001, 2)
    assert ticks > 50, ticks


def test_a_scenario_dict_is_the_scenario_file(tmp_path):
    keys = {"dt": 0.02, "trajectory": "poly9", "end": [-3.0, -13.0], "parameters": {"m_l": 1100.0}, "limits": {"u2": 150}}
    text = 'dt = 0.02\ntrajectory = "poly9"\nend = [-3.0, -13.0]\n[parameters]\nm_l = 1100.0\n[limits]\nu2 = 150\n'
    path = tmp_path / "scenario.toml"
    path.write_text(text)
    from_dict = crane.run("navy-planar", scenario=keys)
    from_file = crane.run("navy-planar", scenario=str(path))
    from_path = crane.run("navy-planar", scenario=path)
    assert from_dict.u.shape == (201, 2)
    assert np.array_equal(from_dict.u, from_file.u) and np.array_equal(from_dict.u, from_path.u)
    assert from_dict.summary["torque_limits"][0]["limit"] == 150.0
    # keywords over the scenario, as flags over the file
    again = crane.run("navy-planar", scenario=keys, dt=0.01, parameters={"m_l": 1000.0})
    assert again.u.shape == (401, 2)
    assert not np.array_equal(again.u[200], from_dict.u[100])


def test_a_path_outside_the_workspace_is_refused_before_the_run():
    # to a point above the boom tip: with the load held there a rope would
    # be shorter than zero
    with pytest.raises(crane.CraneError, match="the load path leaves navy-planar's workspace: with the load held at rest"):
        crane.run("navy-planar", scenario={"end": [-3.0, 5.0]})


def test_the_audit_s_findings_are_the_warnings():
    # the causal inverse of the coupled trolley runs away
    r = crane.run("coupled-trolley", formulation="redundant")
    assert any("unstable internal dynamics" in w for w in r.warnings), r.warnings
    assert "coupled-trolley" in repr(r)


def test_the_coupled_trolley_gets_bounded_inputs_by_stable_inversion():
    # its default: the bounded inputs, acting before the load moves
    r = crane.run("coupled-trolley")
    assert r.summary["formulation"] == "stable-inversion" and r.warnings == []
    assert r.t[0] < -1.0 and r.t[-1] > 6.0
    assert np.abs(r.u[:, 0]).max() < 200.0  # the causal inverse: 3.5e16 N
    inversion = r.summary["stable_inversion"]
    assert abs(inversion["t_pre"] - 2.33) < 0.02 and inversion["boundary_residual"] < 1e-9
    # the trolley moves before the load: pre-actuation
    before = r.t < 0.0
    assert np.abs(r.q[before, 0]).max() > 1e-3 and np.all(r.q[before, 2] == 0.0)
    with pytest.raises(crane.CraneError, match="a stepper cannot know the path ahead"):
        crane.stepper("coupled-trolley", formulation="stable-inversion")


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"model": "no-such-crane"}, "unknown model `no-such-crane`"),
        ({"model": "navy-planar", "dt": -0.01}, "dt"),
        ({"model": "navy-planar", "scheme": "rk4"}, "rk4"),
        ({"model": "navy-planar", "formulation": "exact"}, "unknown formulation `exact`"),
        ({"model": "navy-planar", "scenario": {"dtt": 0.01}}, "dtt"),
        ({"model": "navy-planar", "scenario": {"dt": "fast"}}, "dt"),
        ({"model": "navy-planar", "scenario": "/no/such/file.toml"}, "/no/such/file.toml"),
        ({"model": "navy-planar", "parameters": {"mass": 1.0}}, "mass"),
        ({"model": "navy-planar", "parameters": {"m_l": 1e300}}, "m_l"),
        ({"model": "navy-planar", "scenario": {"end": [80.0, -14.0]}}, "converge"),
    ],
)
def test_every_error_is_a_crane_error_with_the_tool_s_message(kwargs, message):
    model = kwargs.pop("model")
    with pytest.raises(crane.CraneError) as error:
        crane.run(model, **kwargs)
    assert message in str(error.value)
    assert isinstance(error.value, ValueError)
    assert "\n" not in str(error.value)


def test_results_are_arrays_the_user_owns():
    r = crane.run("gantry-3d", dt=0.05)
    u = r.u
    u[0, 0] = 1e9
    del r
    assert u[0, 0] == 1e9
    assert crane.run("gantry-3d", dt=0.05).u[0, 0] != 1e9


@pytest.mark.parametrize("model,formulation", [("navy-planar", None), ("navy-3d-pulley", None), ("gantry-3d", "dummy-derivative")])
def test_a_stepper_takes_the_run_s_steps_bit_for_bit(model, formulation):
    """Step by step, the states of a whole run (eqs. 22 on navy-planar, the
    reduced system on the cranes that default to it or ask for it)."""
    r = crane.run(model, formulation=formulation, scheme="bdf2")
    s = crane.stepper(model, formulation=formulation, scheme="bdf2")
    assert s.dt == r.summary["dt"]
    first = s.state
    assert first["t"] == r.t[0] and np.array_equal(first["q"], r.q[0])
    for i in range(1, 51):
        state = s.step()
        assert state["t"] == r.t[i]
        for key, column in [("q", r.q), ("v", r.v), ("u", r.u), ("lambda_", r.lambda_), ("tensions", r.tensions)]:
            assert np.array_equal(state[key], column[i]), (i, key)
    state = s.step_to(r.t[-1])
    assert np.array_equal(state["u"], r.u[-1]) and np.array_equal(s.state["q"], r.q[-1])


def test_a_stepper_says_what_it_cannot_do():
    with pytest.raises(crane.CraneError, match="unknown model `nope`; expected one of navy-planar"):
        crane.stepper("nope")
    with pytest.raises(crane.CraneError, match="a stepper runs the redundant, the dummy-derivative and the state-selection formulation"):
        crane.stepper("navy-planar", formulation="minimal")
    s = crane.stepper("navy-planar", dt=0.01)
    s.step_to(0.5)
    with pytest.raises(crane.CraneError, match="not a step time at or after t = 0.5 s"):
        s.step_to(0.2)
    with pytest.raises(crane.CraneError, match="not a step time"):
        s.step_to(0.505)
    assert s.state["t"] == pytest.approx(0.5, abs=1e-12)
    # a time too far on is refused at once (step_to(1e9) ran without end)
    for far in (1e9, 1e300, 2.0**64 * 0.01):
        with pytest.raises(crane.CraneError, match="step_to takes at most 1e9 steps per call"):
            s.step_to(far)
    assert s.state["t"] == pytest.approx(0.5, abs=1e-12)


def test_a_replay_is_the_command_line_s(tmp_path):
    """replay=True drives the forward dynamics with the computed inputs as
    `crane run --replay` does: the same states as its replay.csv, bit for
    bit, the summary's "replay" and the audit's warning on a plant 30 %
    heavier than the planner's."""
    r = crane.run("navy-planar", scheme="bdf4", replay=True, plant={"m_l": 130.0}, feedback="default")
    out = tmp_path / "cli"
    subprocess.run(
        [str(CLI), "run", "navy-planar", "--scheme", "bdf4", "--replay", "--plant", "m_l=130", "--feedback", "default", "--quiet", "--out", str(out)],
        check=True,
        capture_output=True,
    )
    with open(out / "replay.csv") as f:
        rows = list(csv.DictReader(f))
    replay = r.replay
    assert replay["t"].shape == (len(rows),) and replay["q"].shape == (len(rows), 7)
    assert np.array_equal(replay["t"], [float(row["t"]) for row in rows])
    for k, name in enumerate(r.coordinates):
        assert np.array_equal(replay["q"][:, k], [float(row[name]) for row in rows]), name
    assert r.summary["replay"]["plant"] == {"m_l": 130.0}
    assert r.summary["replay"]["feedback"].startswith("default")
    assert any("does not arrive" in w for w in r.warnings), r.warnings
    # the planner's own plant with BDF-4: the load arrives
    exact = crane.run("navy-planar", scheme="bdf4", replay=True)
    assert exact.warnings == [] and exact.summary["replay"]["residual_sway"] < 1e-3
    assert crane.run("navy-planar").replay is None


def test_a_replay_s_keywords_are_checked():
    with pytest.raises(crane.CraneError, match="apply only to a replay: add replay=True"):
        crane.run("navy-planar", plant={"m_l": 130.0})
    with pytest.raises(crane.CraneError, match="apply only to a replay: add replay=True"):
        crane.run("navy-planar", scenario={"plant": {"m_l": 130.0}})
    with pytest.raises(crane.CraneError, match="feedback `soft`"):
        crane.run("navy-planar", replay=True, feedback="soft")
    with pytest.raises(crane.CraneError, match="settle = -1"):
        crane.run("navy-planar", replay=True, settle=-1.0)
    with pytest.raises(crane.CraneError, match="plant: `m_l` must be a number"):
        crane.run("navy-planar", replay=True, plant={"m_l": "heavy"})


def test_nothing_is_left_open():
    """Runs, replays, steppers, sweeps and failed runs leave no thread, file
    or other descriptor behind (counted in /proc/self/fd and
    /proc/self/task, where Linux lists this process's open descriptors and
    its threads, the native ones included: a sweep's worker pool is made
    once and kept)."""
    fds, tasks = Path("/proc/self/fd"), Path("/proc/self/task")
    if not fds.exists() or not tasks.exists():
        pytest.skip("no /proc/self/fd on this system")

    def work():
        crane.run("navy-planar", dt=0.02)
        crane.run("navy-planar", scheme="bdf4", replay=True)
        s = crane.stepper("navy-3d-pulley")
        s.step_to(0.5)
        with pytest.raises(crane.CraneError):
            crane.run("navy-planar", scenario={"end": [1e300, -5.0]})
        crane.sweep("navy-planar", {"m_l": [90.0, 110.0]}, durations=[3.5, 4.0])

    work()  # the first call may load what stays loaded
    threads, open_fds = threading.active_count(), len(list(fds.iterdir()))
    native = len(list(tasks.iterdir()))
    for _ in range(5):
        work()
    assert threading.active_count() == threads
    assert len(list(fds.iterdir())) == open_fds
    assert len(list(tasks.iterdir())) == native


def test_ctrl_c_stops_a_long_step_to():
    """Ctrl-C (SIGINT) stops `Stepper.step_to` between steps with
    KeyboardInterrupt, the stepper at the last step it took; it used to run
    on to the end, holding the interpreter."""
    s = crane.stepper("navy-planar", dt=0.01)
    # from another process, as a terminal sends it (a thread of this one
    # would wait for the interpreter lock that the call holds)
    kill = subprocess.Popen(["sh", "-c", f"sleep 0.3; kill -INT {os.getpid()}"])
    started = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        s.step_to(1e6)  # 1e8 steps, about two minutes
    stopped = time.monotonic()
    kill.wait()
    # the signal sent 0.3 s after the start (and the shell's own start),
    # stopped within 0.5 s of it: steps are taken 1024 at a time
    assert stopped - started < 0.3 + 0.5 + 0.2
    t = s.state["t"]
    assert 0 < t < 1e6
    # the stepper goes on from where it stopped
    assert s.step()["t"] == pytest.approx(t + 0.01, abs=1e-9)


def test_a_stepper_works_from_any_thread():
    """A stepper made in one thread steps in another (a thread pool's), one
    call at a time, with the numbers of the same steps in one thread; it
    raised PanicException ("PyStepper is unsendable, but sent to another
    thread")."""
    from concurrent.futures import ThreadPoolExecutor

    here = crane.stepper("navy-planar", dt=0.01)
    there = crane.stepper("navy-planar", dt=0.01)
    expected = [here.step() for _ in range(20)]
    with ThreadPoolExecutor(max_workers=2) as pool:
        for want in expected:
            got = pool.submit(there.step).result()
            assert got["t"] == want["t"] and np.array_equal(got["u"], want["u"])
        state = pool.submit(there.step_to, 0.5).result()
    assert state["t"] == pytest.approx(0.5, abs=1e-12)


def test_a_fifo_scenario_is_refused_without_blocking(tmp_path):
    """A named pipe without a writer as the scenario is refused by its type,
    at once: opening it blocked for ever, deaf to Ctrl-C."""
    fifo = tmp_path / "scenario.toml"
    os.mkfifo(fifo)
    started = time.monotonic()
    with pytest.raises(crane.CraneError, match="not a regular file"):
        crane.run("navy-planar", scenario=str(fifo))
    assert time.monotonic() - started < 10


def test_scenario_values_that_contain_themselves_are_refused():
    # a list or dict that contains itself, values nested 10^4 deep, and an
    # object whose tolist() returns itself: each a CraneError, not a crash
    # of the interpreter (SIGSEGV)
    looped = []
    looped.append(looped)
    mapping = {}
    mapping["end"] = mapping
    deep = [0.0]
    for _ in range(10_000):
        deep = [deep]

    class Itself:
        def tolist(self):
            return self

    for scenario in ({"end": looped}, mapping, {"end": Itself()}):
        with pytest.raises(crane.CraneError, match="contains itself"):
            crane.run("navy-planar", scenario=scenario)
    with pytest.raises(crane.CraneError, match="nest deeper than 32 levels"):
        crane.run("navy-planar", scenario={"end": deep})
    # shared, not cyclic: the same list nested thirty times is 1e9 values
    # (it ran out of memory, the interpreter held)
    shared = [0.0]
    for _ in range(30):
        shared = [shared, shared]
    twice = []
    twice += [twice, twice]
    with pytest.raises(crane.CraneError, match="more than 1000000 values"):
        crane.run("navy-planar", scenario={"end": shared})
    with pytest.raises(crane.CraneError, match="contains itself"):
        crane.run("navy-planar", scenario={"end": twice})


def test_a_failing_tolist_is_the_cause_of_the_error():
    class Broken:
        def tolist(self):
            raise RuntimeError("no list today")

    with pytest.raises(crane.CraneError, match=r"the Broken's tolist\(\) failed") as caught:
        crane.run("navy-planar", scenario={"end": Broken()})
    assert isinstance(caught.value.__cause__, RuntimeError)
    assert str(caught.value.__cause__) == "no list today"


def test_a_run_pickles_and_copies_bit_for_bit():
    import copy
    import pickle

    r = crane.run("navy-planar")
    for again in (pickle.loads(pickle.dumps(r)), copy.deepcopy(r)):
        assert isinstance(again, crane.Run)
        for name in ("t", "q", "v", "u", "lambda_", "tensions"):
            assert np.array_equal(getattr(again, name), getattr(r, name)), name
        assert (again.coordinates, again.inputs, again.ropes) == (r.coordinates, r.inputs, r.ropes)
        assert again.summary == r.summary and again.warnings == r.warnings and again.replay is None
    replayed = crane.run("navy-planar", replay=True)
    back = pickle.loads(pickle.dumps(replayed))
    assert np.array_equal(back.replay["u"], replayed.replay["u"])


def test_runs_cross_a_process_pool():
    import multiprocessing

    with multiprocessing.get_context("spawn").Pool(2) as pool:
        runs = pool.map(crane.run, ["navy-planar", "gantry-3d"])
    assert [r.summary["model"] for r in runs] == ["navy-planar", "gantry-3d"]
    assert np.array_equal(runs[0].u, crane.run("navy-planar").u)


def test_a_run_from_parts_checks_their_shapes():
    r = crane.run("navy-planar")
    parts = (r.t, r.q, r.v, r.u[:-1], r.lambda_, r.tensions, r.coordinates, r.inputs, r.ropes, r.summary, r.warnings)
    with pytest.raises(crane.CraneError, match="`u` has the shape"):
        crane.Run(*parts)


def test_ctrl_c_during_a_run_in_a_fresh_interpreter_is_keyboard_interrupt():
    """Ctrl-C during `crane.run`, the first call to make numpy arrays in a
    fresh interpreter, is KeyboardInterrupt when the run returns; it was
    `PanicException: Failed to access NumPy array API capsule`."""
    code = "import crane\ncrane.run('navy-planar', dt=2e-6)\n"
    child = subprocess.Popen(
        [sys.executable, "-c", code], stderr=subprocess.PIPE, text=True, env=dict(os.environ)
    )
    time.sleep(1.0)  # the import done, the run (2 000 000 steps, seconds) under way
    child.send_signal(signal.SIGINT)
    sent = time.monotonic()
    _, err = child.communicate(timeout=120)
    # stopped at its next step (it used to run to its end), the
    # interpreter's exit included
    assert time.monotonic() - sent < 1.0
    assert child.returncode != 0
    assert "KeyboardInterrupt" in err and "PanicException" not in err, err


def test_the_module_has_its_version_and_its_public_names():
    from importlib.metadata import version

    assert crane.__version__ == version("crane")
    assert sorted(crane.__all__) == sorted(
        [
            "__version__",
            "CraneError",
            "CraneWarning",
            "Run",
            "Stepper",
            "models",
            "run",
            "stepper",
            "fastest",
            "sweep",
            "sweep_points",
            "convergence",
        ]
    )
    assert all(hasattr(crane, name) for name in crane.__all__)


def test_a_stepper_releases_the_gil_while_it_steps():
    """While `step_to` takes 400 000 steps in a thread, Python's main thread
    keeps running; a call on the same stepper meanwhile raises (it is
    borrowed) instead of waiting or corrupting it; the steps are those of
    a stepper stepped alone."""
    s = crane.stepper("navy-planar", dt=0.01)
    alone = crane.stepper("navy-planar", dt=0.01)
    done = threading.Event()
    result = []

    def work():
        try:
            result.append(s.step_to(4000.0))
        finally:
            done.set()

    thread = threading.Thread(target=work)
    ticks, refused = 0, 0
    thread.start()
    while not done.is_set():
        ticks += 1
        try:
            s.step()
        except RuntimeError:
            refused += 1
        time.sleep(0.001)
    thread.join()
    assert ticks > 20 and refused > 0, (ticks, refused)
    assert result[0]["t"] == pytest.approx(4000.0)
    expected = alone.step_to(4000.0)
    assert np.array_equal(result[0]["u"], expected["u"])


def test_the_audit_s_findings_are_crane_warnings():
    import warnings

    with pytest.warns(crane.CraneWarning, match="unstable internal dynamics") as caught:
        r = crane.run("coupled-trolley", formulation="redundant")
    assert [str(w.message) for w in caught if issubclass(w.category, crane.CraneWarning)] == r.warnings
    # attributed to the line that made the run
    assert all(w.filename == __file__ for w in caught)
    # turned into errors by the warnings filter
    with warnings.catch_warnings():
        warnings.simplefilter("error", crane.CraneWarning)
        with pytest.raises(crane.CraneWarning):
            crane.run("coupled-trolley", formulation="redundant")
    # a trustworthy run warns of nothing
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert crane.run("navy-planar").warnings == []


def test_a_run_as_a_dataframe_is_its_results_csv(tmp_path):
    pd = pytest.importorskip("pandas")
    r = crane.run("navy-planar")
    frame = r.to_dataframe()
    assert frame.index.name == "t" and np.array_equal(frame.index.to_numpy(), r.t)
    r.to_csv(tmp_path / "results.csv")
    written = pd.read_csv(tmp_path / "results.csv", index_col="t", float_precision="round_trip")
    assert list(frame.columns) == list(written.columns)
    assert np.array_equal(frame.to_numpy(), written.to_numpy())
    assert np.array_equal(frame["u1"].to_numpy(), r.u[:, 0])
    # the frame owns its numbers
    frame.iloc[0, 0] = 1e9
    assert r.q[0, 0] != 1e9


def test_a_bool_is_not_a_number():
    # dt=True ran as dt = 1.0, while a scenario dict refused {"dt": True}
    for call in (
        lambda: crane.run("navy-planar", dt=True),
        lambda: crane.run("navy-planar", tf=False),
        lambda: crane.stepper("navy-planar", dt=True),
        lambda: crane.run("navy-planar", parameters={"m_l": True}),
        lambda: crane.fastest("navy-planar", limits={"u2": 150}, dt=True),
    ):
        with pytest.raises(crane.CraneError, match="bool|must be a number"):
            call()
    # numbers of every kind still are
    assert crane.run("navy-planar", dt=np.float64(0.02), tf=4).u.shape == (201, 2)


def test_a_stepper_is_audited_as_the_fmu_is():
    """A stepper runs the FMU's step audit: what it finds is a CraneWarning
    as it is found, and in `Stepper.warnings`; it used to return the numbers
    `run` calls not reliable without a word. A regular move finds nothing."""
    import warnings

    scenario = {"end": [0.0, -5.0]}
    flagged = crane.run("navy-planar", scenario=scenario).warnings
    assert flagged
    with pytest.warns(crane.CraneWarning) as caught:
        s = crane.stepper("navy-planar", scenario=scenario)
        s.step_to(4.0)
    assert s.warnings and [str(w.message) for w in caught if issubclass(w.category, crane.CraneWarning)] == s.warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        clean = crane.stepper("navy-planar")
        clean.step_to(4.0)
        clean.step()
    assert clean.warnings == []


def test_to_csv_refuses_what_it_would_replace_and_writes_through_file_objects(tmp_path):
    """A symbolic link, a FIFO there are refused (the link was replaced by a
    regular file and its target left as it was; a FIFO was replaced, its
    reader got nothing); a file object, a FIFO opened by its caller
    included, is written through."""
    import io

    r = crane.run("navy-planar")
    whole = tmp_path / "whole.csv"
    r.to_csv(whole)
    target = tmp_path / "target.csv"
    target.write_text("mine\n")
    link = tmp_path / "link.csv"
    link.symlink_to(target)
    with pytest.raises(crane.CraneError, match="symbolic link"):
        r.to_csv(link)
    assert link.is_symlink() and target.read_text() == "mine\n"
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    with pytest.raises(crane.CraneError, match="FIFO"):
        r.to_csv(str(fifo))
    assert fifo.is_fifo()
    # a file object: the same text
    buffer = io.StringIO()
    r.to_csv(buffer)
    assert buffer.getvalue() == whole.read_text()
    # a FIFO read by another thread, opened here
    got = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_text()))
    reader.start()
    with open(fifo, "w") as pipe:
        r.to_csv(pipe)
    reader.join(timeout=10)
    assert got == [whole.read_text()]
    with pytest.raises(crane.CraneError, match="neither a path nor a file object"):
        r.to_csv(42)
    # a partial file left in the way (here a link) is not written through
    (tmp_path / ".fresh.csv.partial").symlink_to(target)
    r.to_csv(tmp_path / "fresh.csv")
    assert target.read_text() == "mine\n" and (tmp_path / "fresh.csv").read_text() == whole.read_text()


def test_a_scenario_dict_error_names_the_key_and_no_toml_position():
    """A wrong value in a scenario dict names the key, not a line and
    column of TOML the user never wrote (it read "scenario the scenario
    dict: key `dt`: ... (line 1, column 6)")."""
    with pytest.raises(crane.CraneError) as error:
        crane.run("navy-planar", scenario={"dt": "x"})
    message = str(error.value)
    assert message.startswith("scenario: key `dt`: invalid type"), message
    assert "line" not in message and "the scenario dict" not in message, message


def test_a_replay_step_below_the_smallest_is_refused_before_the_run():
    """`run(dt=1e-6, replay=True)` is refused at once, naming the step the
    user gave (it failed after the whole run, naming dt = 2.5e-7)."""
    started = time.monotonic()
    with pytest.raises(crane.CraneError, match=r"dt = 1e-6 s would step it at 2.5e-7 s.*take dt >= 4e-6 s"):
        crane.run("navy-planar", dt=1e-6, replay=True)
    assert time.monotonic() - started < 0.5


def test_any_mapping_goes_where_a_dict_does():
    """Mappings that are not dicts (a MappingProxyType; a pandas Series,
    which has keys() and item access) give the dict's run bit for bit; a
    list is refused naming what is expected."""
    import types

    expected = crane.run("navy-planar", parameters={"m_l": 110.0}, scenario={"dt": 0.02})
    proxy = crane.run(
        "navy-planar",
        parameters=types.MappingProxyType({"m_l": 110.0}),
        scenario=types.MappingProxyType({"dt": 0.02}),
    )
    assert np.array_equal(proxy.u, expected.u)
    pandas = pytest.importorskip("pandas")
    series = crane.run("navy-planar", parameters=pandas.Series({"m_l": 110.0}), scenario={"dt": 0.02})
    assert np.array_equal(series.u, expected.u)
    with pytest.raises(TypeError, match="expected a mapping of names to values"):
        crane.run("navy-planar", parameters=[("m_l", 110.0)])


def test_a_run_beyond_the_machines_memory_is_refused_before_it_starts():
    """A run whose states and their numpy copies need more than the machine
    has available (tf = 1e8 s at dt = 0.01: 1e10 steps, terabytes) is a
    CraneError at once, naming the size; tf = 1e6 s (17 GiB) was accepted
    and could only end in the kernel's OOM killer."""
    started = time.monotonic()
    with pytest.raises(crane.CraneError, match=r"a run of 1\.000e10 steps needs about .* GiB at its peak .* more than"):
        crane.run("navy-planar", tf=1e8)
    assert time.monotonic() - started < 1.0


def test_a_run_under_a_memory_limit_is_an_error_not_an_abort():
    """Under an address-space limit of 1.5 GB (`ulimit -v 1500000`) a run
    whose results need more (tf = 5e4 s: 5e6 steps, about 1 GB of states and
    0.9 GB of numpy copies) raises CraneError; the interpreter used to abort
    ("memory allocation failed", SIGABRT) while copying the results."""
    import resource

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (1_500_000 * 1024, 1_500_000 * 1024))

    code = (
        "import crane\n"
        "try:\n"
        "    crane.run('navy-planar', tf=5e4)\n"
        "except crane.CraneError as e:\n"
        "    print('CraneError:', e)\n"
    )
    child = subprocess.run(
        [sys.executable, "-c", code], preexec_fn=limit, capture_output=True, text=True, timeout=300
    )
    assert child.returncode == 0, child.stderr[-2000:]
    assert child.stdout.startswith("CraneError:") and "memory" in child.stdout, child.stdout


def test_a_stepper_is_made_by_its_class_too():
    """`crane.Stepper(model, ...)` is `crane.stepper(model, ...)` (it
    raised TypeError: cannot create 'crane.Stepper' instances)."""
    made = crane.Stepper("navy-planar", dt=0.01, scheme="bdf2")
    called = crane.stepper("navy-planar", dt=0.01, scheme="bdf2")
    for _ in range(10):
        assert np.array_equal(made.step()["u"], called.step()["u"])
    with pytest.raises(crane.CraneError, match="unknown model `nope`"):
        crane.Stepper("nope")


def test_a_stepper_says_why_it_does_not_pickle():
    """Pickling or copying a Stepper is a TypeError that says why (a run
    under way) and what to do instead."""
    import copy
    import pickle

    s = crane.stepper("navy-planar")
    with pytest.raises(TypeError, match="a Stepper does not pickle: it holds a run under way"):
        pickle.dumps(s)
    with pytest.raises(TypeError, match="a Stepper does not pickle"):
        copy.deepcopy(s)
