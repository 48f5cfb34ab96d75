"""The studies of many runs from Python (fastest, sweep, convergence)
against the command line's fastest.json, sweep.csv and convergence.csv:
the same numbers bit for bit, and every refusal a crane.CraneError."""

import csv
import json
import os
import signal
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest

import crane

ROOT = Path(__file__).resolve().parents[2]
CLI = Path(os.environ.get("CRANE_BIN", ROOT / "target" / "release" / "crane"))


def cli(tmp_path, *args):
    """`crane ARGS --out tmp_path/cli`: the output directory."""
    out = tmp_path / "cli"
    subprocess.run([str(CLI), *args, "--out", str(out)], check=True, capture_output=True)
    return out


def csv_columns(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {name: [r[name] for r in rows] for name in rows[0]}


def test_fastest_is_the_command_line_s(tmp_path):
    f = crane.fastest("navy-planar", limits={"u2": 150.0}, min_tension={"N2": 100.0})
    out = cli(tmp_path, "fastest", "navy-planar", "--limit", "u2=150", "--min-tension", "N2=100")
    expected = json.loads((out / "fastest.json").read_text())
    for key in ["duration", "binding", "limits", "bracket", "evaluations", "interval", "formulation", "scheme", "dt"]:
        assert f[key] == expected[key], key
    # the paper's move at |u2| <= 150 N m: 3.3 s, bound by the slack rope
    # N1 (the duration halves from 4 s and bisects to 1 ms)
    assert 3.3 < f["duration"] < 3.32 and f["bracket"][1] - f["bracket"][0] <= 1e-3
    run = f["run"]
    # the run at the answer: BDF-4 at the step that divides the duration
    assert run["u"].shape == (len(run["t"]), 2) and run["t"][-1] == pytest.approx(f["duration"] + 0.0, abs=1e-12)
    assert np.max(np.abs(run["u"][:, 1])) <= 150.0


def test_the_fastest_shaped_move_is_the_command_line_s_and_runs_from_its_scenario(tmp_path):
    f = crane.fastest("gantry-3d", limits={"u1": 1000.0}, shape="optimal", control_points=8)
    out = cli(tmp_path, "fastest", "gantry-3d", "--limit", "u1=1000", "--shape", "optimal", "--control-points", "8",
              "--quiet")
    expected = json.loads((out / "fastest.json").read_text())
    for key in ["duration", "binding", "limits", "shape", "evaluations", "bracket", "interval"]:
        assert f[key] == expected[key], key
    assert f["shape"]["kind"] == "optimal" and f["shape"]["lower_bound"]["duration"] <= f["duration"]
    # the answer's scenario runs as written: the limit kept, the same path
    assert f["scenario"]["trajectory"] == "spline" and f["scenario"]["t1"] == f["duration"]
    r = crane.run("gantry-3d", scenario=f["scenario"])
    assert np.max(np.abs(r.u[:, 0])) <= 1000.0
    with pytest.raises(crane.CraneError, match="time-scaled"):
        crane.fastest("gantry-3d", limits={"u1": 1000.0}, shape="best")
    with pytest.raises(crane.CraneError, match="control_points"):
        crane.fastest("gantry-3d", limits={"u1": 1000.0}, control_points=8)


def test_a_point_set_is_the_command_line_s_and_the_grid_s(tmp_path):
    points = {"m_l": np.array([120.0, 80.0, 100.0])}
    durations = [4.0, 3.0, 3.5]
    s = crane.sweep_points("navy-planar", points, durations=durations, limits={"u2": 150.0})
    (tmp_path / "pts.csv").write_text("m_l,duration\n120,4\n80,3\n100,3.5\n")
    out = cli(tmp_path, "sweep", "navy-planar", "--points", str(tmp_path / "pts.csv"), "--limit", "u2=150", "--quiet")
    expected = csv_columns(out / "sweep.csv")
    assert list(s) == list(expected)
    for name in ["m_l", "duration", "peak_u1", "peak_u2", "min_N1", "min_N2"]:
        assert [repr(float(v)) for v in s[name]] == expected[name], name
    # each point is the grid's point with the same values, bit for bit
    g = crane.sweep("navy-planar", {"m_l": [80.0, 100.0, 120.0]}, durations=[3.0, 3.5, 4.0], limits={"u2": 150.0})
    for i in range(3):
        j = [k for k in range(9) if g["m_l"][k] == s["m_l"][i] and g["duration"][k] == s["duration"][i]]
        assert len(j) == 1 and g["peak_u2"][j[0]] == s["peak_u2"][i]
    # without durations, the move's own; a pandas DataFrame works as a mapping
    pd = pytest.importorskip("pandas")
    own = crane.sweep_points("navy-planar", pd.DataFrame({"m_l": [100.0, 120.0]}))
    assert list(own["duration"]) == [4.0, 4.0]
    for bad, match in [
        ({"m_l": [1.0, 2.0], "l": [1.0]}, "ragged"),
        ({"m_l": [float("nan")]}, "not finite"),
        ({"m_x": [1.0]}, "no such parameter"),
        ({"m_l": []}, "no points"),
    ]:
        with pytest.raises(crane.CraneError, match=match):
            crane.sweep_points("navy-planar", bad)
    with pytest.raises(crane.CraneError, match="durations"):
        crane.sweep_points("navy-planar", {"m_l": [1.0, 2.0]}, durations=[3.0])


def test_a_sweep_is_the_command_line_s_sweep_csv(tmp_path):
    s = crane.sweep("navy-planar", {"m_l": np.linspace(80.0, 120.0, 3)}, durations=[3.0, 4.0], limits={"u2": 150.0})
    out = cli(tmp_path, "sweep", "navy-planar", "--param", "m_l=80:120:3", "--duration", "3:4:2", "--limit",
              "u2=150", "--quiet")
    expected = csv_columns(out / "sweep.csv")
    assert list(s) == list(expected)
    for name, values in expected.items():
        if name in ("error", "audit"):
            assert s[name] == values, name
        elif name == "feasible":
            assert s[name].dtype == np.bool_ and list(s[name]) == [v == "true" for v in values]
        else:
            assert s[name].dtype == np.float64
            assert np.array_equal(s[name], np.array([float(v) for v in values])), name
    # in 3 s rope N1 goes slack whatever the load's mass; in 4 s it stays
    # taut, and |u2| stays below 150 N m up to 120 kg
    assert list(s["feasible"]) == [False, True] * 3
    assert np.all(s["min_N1"][::2] < -60.0) and s["peak_u2"][-1] < 150.0


def test_convergence_is_the_command_line_s(tmp_path):
    c = crane.convergence("navy-planar", scheme="bdf2", formulation="redundant")
    out = cli(tmp_path, "convergence", "navy-planar", "--scheme", "bdf2", "--formulation", "redundant")
    expected = csv_columns(out / "convergence.csv")
    assert np.array_equal(c["dt"], np.array([float(v) for v in expected["dt"]]))
    assert np.array_equal(c["e_u"], np.array([float(v) for v in expected["e_u"]]))
    order = np.array([float(v) if v else np.nan for v in expected["order"]])
    assert np.array_equal(c["order"], order, equal_nan=True)
    assert c["audit"] == expected["audit"] == [""] * 6
    assert c["reference"] == "the analytical reference" and c["scheme"] == "bdf2"
    # BDF-2 is of order 2 (the paper's Fig. 7)
    assert abs(c["order"][-1] - 2.0) < 0.05


def test_a_study_of_given_steps_and_a_reduced_reference():
    # tower-crane has no analytical reference: the exact reduced inputs are it
    c = crane.convergence("tower-crane", dts=[0.02, 0.01], scheme="bdf1", formulation="redundant")
    assert c["reference"] == "the exact inputs of the dummy-derivative formulation"
    assert list(c["dt"]) == [0.02, 0.01]
    # backward Euler halves its error with the step
    assert abs(c["order"][1] - 1.0) < 0.1


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: crane.sweep("navy-planar", {"m_x": [1.0]}), "no such parameter"),
        (lambda: crane.sweep("navy-planar", {"m_l": [1.0], "J1": [1.0]}, durations=[0.0]), "must be positive"),
        (lambda: crane.sweep("navy-planar"), "nothing to sweep"),
        (lambda: crane.sweep("navy-planar", {"m_l": "heavy"}), "must be a sequence of numbers"),
        (lambda: crane.sweep("navy-planar", {"m_l": [float("nan")]}), "must be finite"),
        (lambda: crane.fastest("navy-planar", limits={"u9": 1.0}), "no input `u9`"),
        (lambda: crane.fastest("navy-planar", limits={"u2": -1.0}), "u2"),
        (lambda: crane.fastest("navy-planar", min_tension={"N9": 1.0}), "no such rope tension"),
        (lambda: crane.fastest("navy-planar", limits={"u2": 150.0}, dt=-0.01), "dt"),
        (lambda: crane.fastest("navy-planar", limits={"u2": 150.0}, tolerance=0.0), "tolerance 0"),
        (lambda: crane.fastest("navy-planar", limits={"u2": 1e-3}), "no feasible duration"),
        (lambda: crane.fastest("no-such-crane", limits={"u2": 150.0}), "unknown model"),
        (lambda: crane.convergence("navy-planar", dts=[]), "at least one time step"),
        # the 1.5 s is the study's (where it measures e_u), named as such
        (lambda: crane.convergence("navy-planar", dts=[1.0]), "each run of the study stops at t = 1.5 s"),
        (lambda: crane.convergence("coupled-trolley"), "internal dynamics of dimension 2"),
    ],
)
def test_refusals_raise_with_the_tool_s_message(call, message):
    with pytest.raises(crane.CraneError, match=message):
        call()


@pytest.mark.skipif(not hasattr(os, "fork"), reason="no os.fork on this platform")
def test_a_sweep_in_a_forked_child_does_not_hang():
    # the parent sweeps first, so its thread pool exists when it forks
    grid = {"m_l": [90.0, 110.0]}
    before = crane.sweep("navy-planar", grid)
    pid = os.fork()
    if pid == 0:
        try:
            again = crane.sweep("navy-planar", grid)
            same = all(np.array_equal(again[k], before[k]) for k in ("peak_u1", "peak_u2"))
            os._exit(0 if same else 3)
        except BaseException:
            os._exit(4)
    # the child hung for ever before: give it 60 s
    deadline = time.monotonic() + 60.0
    while True:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        if time.monotonic() > deadline:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
            pytest.fail("the sweep in the forked child did not finish within 60 s")
        time.sleep(0.05)
    assert os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0, status


def interrupt_after(delay):
    """A timer thread that sends this process SIGINT (as a terminal's
    Ctrl-C) after `delay` seconds; the times it sent it at."""
    import threading

    sent = []

    def send():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(delay, send)
    timer.start()
    return timer, sent


def test_ctrl_c_stops_a_long_sweep_within_half_a_second():
    """Ctrl-C during a sweep of about 20 s (120 000 points) is
    KeyboardInterrupt within 0.5 s: the points not started are not
    evaluated, the one under way stops at its next step; the sweep used to
    run to its end (4.5 to 17.7 s late). The same sweep works afterwards."""
    timer, sent = interrupt_after(1.0)
    started = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        crane.sweep("navy-planar", {"m_l": np.linspace(100.0, 120.0, 120_000)})
    stopped = time.monotonic()
    timer.join()
    assert sent, "the sweep ended before the signal"
    assert stopped - sent[0] < 0.5, f"{stopped - sent[0]:.3f} s after Ctrl-C ({stopped - started:.1f} s in all)"
    s = crane.sweep("navy-planar", {"m_l": [100.0, 110.0]})
    assert list(s["feasible"]) == [True, True]


def test_ctrl_c_stops_a_long_fastest_search_within_half_a_second():
    """The same for `fastest`, whose bisection runs one move after another
    (here each at dt = 5e-5)."""
    timer, sent = interrupt_after(1.0)
    with pytest.raises(KeyboardInterrupt):
        crane.fastest("navy-planar", limits={"u1": 1e4}, dt=5e-5)
    stopped = time.monotonic()
    timer.join()
    assert sent, "the search ended before the signal"
    assert stopped - sent[0] < 0.5, f"{stopped - sent[0]:.3f} s after Ctrl-C"


def test_a_duration_too_short_to_resolve_is_named_as_such():
    """A swept duration of 1e-9 s is reported as a move too short to
    evaluate, not as a time step the user never gave."""
    s = crane.sweep("navy-planar", {"m_l": [100.0]}, durations=[1e-9, 4.0])
    assert s["error"][0].startswith("a move of 1e-9 s is too short to evaluate"), s["error"][0]
    assert "invalid time step" not in s["error"][0]
    assert s["error"][1] == ""
