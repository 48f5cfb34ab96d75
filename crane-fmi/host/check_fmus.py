"""The FMUs of every crane of a crane tool through real clients (run by
.ci/run for `crane` and for a user's tool, examples/user-cli's `my-cranes`).

For each model of `TOOL list`: `TOOL fmu MODEL`, FMPy's validate_fmu
(no problem allowed), FMPy's simulate_fmu over the default experiment
(the default move; for a crane whose default is stable inversion, from
t0 - T_pre to tf + T_post) at output interval = dt = 0.01 s against `TOOL
run MODEL --dt 0.01`
(inputs and coordinates, 1e-9 relative to each column's largest value),
a negative mass (must be an FMI error, the process must live on), a
communication step that is not a multiple of dt (an FMI error), a host's
misuse through FMPy's FMU2Slave (gravity of the wrong sign, a time step
below a microsecond, a NaN or infinite communication point, a step size
of zero or below: each an FMI error status naming the problem, and the
instance can still be freed), the audit (the `status` output reads 1
after initialisation where `TOOL run` finds unstable internal dynamics
and runs causally, 0 otherwise; where the run's inputs run away the FMU stops with an FMI
error and `status` 2, and the comparison ends before), and the
C host (host.c) loading the FMU's shared library directly, against the same
run. Prints the time per doStep of the C host and of FMPy next to the
native stepper's (`TOOL bench`).

Then for each MODEL=SCENARIO given: `TOOL fmu MODEL --scenario SCENARIO`
(the FMU starts from the scenario's run, a spline move's shape in
resources/start.toml), validate_fmu, and FMPy's simulate_fmu over its
default experiment (FMPy passes the resource location) against `TOOL run
MODEL --scenario SCENARIO`, to the same 1e-9, and the C host likewise.

usage: python check_fmus.py TOOL_EXECUTABLE HOST_EXECUTABLE OUT_DIR [MODEL=SCENARIO ...]
"""

import csv
import json
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import fmpy
from fmpy.validation import validate_fmu

RELATIVE = 1e-9
DT = 0.01


def run(*args):
    return subprocess.run(args, check=True, capture_output=True, text=True).stdout


def models(crane):
    lines = run(crane, "list").splitlines()[1:]
    return [line.split()[0] for line in lines if line.strip()]


def columns(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {name: [float(r[name]) for r in rows] for name in rows[0]}


def agree(name, expected, found):
    """Largest difference relative to the column's largest value."""
    if len(expected) != len(found):
        raise SystemExit(f"{name}: {len(found)} values against {len(expected)}")
    scale = max(max(abs(v) for v in expected), 1e-300)
    worst = max(abs(a - b) for a, b in zip(expected, found)) / scale
    if not worst <= RELATIVE:
        raise SystemExit(f"{name}: relative difference {worst:.3e} > {RELATIVE:g}")
    return worst


def fmpy_do_step(unzipped, md, start, stop):
    """Median time of FMPy's doStep on the default move (FMU2Slave, on the
    FMU extracted into `unzipped`)."""
    slave = fmpy.fmi2.FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier=md.coSimulation.modelIdentifier, instanceName="timing")
    slave.instantiate()
    slave.setupExperiment(startTime=start)
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    times = []
    steps = round((stop - start) / DT)
    for k in range(steps):
        clock = time.perf_counter()
        slave.doStep(currentCommunicationPoint=start + k * DT, communicationStepSize=DT)
        times.append(time.perf_counter() - clock)
    slave.terminate()
    slave.freeInstance()
    return sorted(times)[len(times) // 2]


def misuse(unzipped, md, start):
    """A host's mistakes through FMPy's FMU2Slave (on the FMU extracted into
    `unzipped`): each must end in an FMI error status (FMPy raises
    FMICallException) and leave an instance that can still be freed;
    returns the cases checked."""
    refs = {v.name: v.valueReference for v in md.modelVariables}
    cases = []

    def expect_error(name, parameters, steps):
        slave = fmpy.fmi2.FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
        slave.instantiate()
        try:
            slave.setupExperiment(startTime=start)
            slave.enterInitializationMode()
            for variable, value in parameters.items():
                slave.setReal([refs[variable]], [value])
            slave.exitInitializationMode()
            for t, h in steps:
                slave.doStep(currentCommunicationPoint=t, communicationStepSize=h)
        except fmpy.fmi1.FMICallException:
            cases.append(name)
        else:
            raise SystemExit(f"{md.modelName}: {name} was accepted")
        finally:
            slave.freeInstance()

    expect_error("g = -9.81", {"g": -9.81}, [(start, DT)])
    expect_error("dt = 1e-300", {"dt": 1e-300}, [(start, DT)])
    expect_error("doStep at t = NaN", {}, [(start, DT), (float("nan"), DT)])
    expect_error("doStep at t = inf", {}, [(float("inf"), DT)])
    expect_error("doStep with h = 0", {}, [(start, 0.0)])
    expect_error("doStep with h = -0.01", {}, [(start, -DT)])
    return cases


def audit(unzipped, md, summary, start, stop):
    """The `status` output through FMU2Slave against `TOOL run`'s summary:
    1 after initialisation for unstable internal dynamics (a warning), 0
    otherwise; at the end of the move 2 with an FMI error for a runaway
    input, else what it was."""
    status = next(v.valueReference for v in md.modelVariables if v.name == "status")
    internal = summary["internal_dynamics"]
    slave = fmpy.fmi2.FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier=md.coSimulation.modelIdentifier, instanceName="audit")
    slave.instantiate()
    try:
        slave.setupExperiment(startTime=start)
        slave.enterInitializationMode()
        slave.exitInitializationMode()
        at_start = slave.getInteger([status])[0]
        # a run by stable inversion is bounded: not warned of its dynamics
        expected = 0 if internal["stable"] or summary["formulation"] == "stable-inversion" else 1
        if at_start != expected:
            raise SystemExit(f"{md.modelName}: status {at_start} after initialisation, expected {expected}")
        failed = None
        for k in range(round((stop - start) / DT)):
            try:
                slave.doStep(currentCommunicationPoint=start + k * DT, communicationStepSize=DT)
            except fmpy.fmi1.FMICallException:
                failed = start + (k + 1) * DT
                break
        at_end = slave.getInteger([status])[0]
    finally:
        slave.freeInstance()
    if internal["runaway_at"] is not None:
        if failed is None or at_end != 2 or abs(failed - internal["runaway_at"]) > 1e-9:
            raise SystemExit(f"{md.modelName}: the runaway at t = {internal['runaway_at']} s gave an error at {failed}, status {at_end}")
        return f"status {at_start} at the start, error and status 2 at the runaway (t = {failed:.2f} s)"
    if failed is not None or at_end > 1:
        raise SystemExit(f"{md.modelName}: an FMI error at t = {failed}, status {at_end}")
    return f"status {at_start} at the start, {at_end} at the end"


def scenario_fmu(crane, host, out, model, scenario):
    """The FMU of `model` packaged with `scenario`'s run against `TOOL run
    MODEL --scenario`, through FMPy and through the C host (which passes
    the extracted FMU's resources folder); returns the largest relative
    difference of each."""
    fmu = out / f"{model}-scenario.fmu"
    run(crane, "fmu", model, "--scenario", scenario, "--out", str(fmu))
    problems = validate_fmu(str(fmu))
    if problems:
        raise SystemExit(f"{model} with {scenario}: validate_fmu: {problems}")
    md = fmpy.read_model_description(str(fmu))
    experiment = md.defaultExperiment
    start, stop, step = float(experiment.startTime), float(experiment.stopTime), float(experiment.stepSize)
    outputs = [v for v in md.modelVariables if v.causality == "output" and v.type == "Real" and not v.name.startswith("lambda")]
    names = [v.name for v in outputs]
    written = Path(run(crane, "run", model, "--scenario", scenario, "--quiet", "--out", str(out / f"{model}-scenario")).split("wrote ")[-1].strip())
    reference = columns(written / "results.csv")
    result = fmpy.simulate_fmu(str(fmu), start_time=start, stop_time=stop, output_interval=step, step_size=step, output=names)
    worst_fmpy = max(agree(f"{model} with {scenario}: FMPy {name}", reference[name], list(result[name])) for name in names if name in reference)
    unzipped = fmpy.extract(str(fmu))
    library = Path(unzipped) / "binaries" / "linux64" / f"{md.coSimulation.modelIdentifier}.so"
    refs = [str(v.valueReference) for v in outputs]
    hosted = subprocess.run([host, str(library), md.guid, str(start), str(stop), str(step), *refs], check=True, capture_output=True, text=True)
    rows = [list(map(float, line.split(","))) for line in hosted.stdout.splitlines()]
    worst_host = max(agree(f"{model} with {scenario}: C host {name}", reference[name], [r[i + 1] for r in rows]) for i, name in enumerate(names) if name in reference)
    return worst_fmpy, worst_host


def main():
    crane, host, out = sys.argv[1], sys.argv[2], Path(sys.argv[3])
    scenarios = [item.split("=", 1) for item in sys.argv[4:]]
    out.mkdir(parents=True, exist_ok=True)
    report = []
    for model in models(crane):
        fmu = out / f"{model}.fmu"
        run(crane, "fmu", model, "--out", str(fmu))
        problems = validate_fmu(str(fmu))
        if problems:
            raise SystemExit(f"{model}: validate_fmu: {problems}")
        md = fmpy.read_model_description(str(fmu))
        start, stop = float(md.defaultExperiment.startTime), float(md.defaultExperiment.stopTime)
        outputs = [v for v in md.modelVariables if v.causality == "output" and v.type == "Real"]
        compared = [v.name for v in outputs if not v.name.startswith("lambda")]

        written = Path(run(crane, "run", model, "--dt", str(DT), "--quiet", "--out", str(out / model)).split("wrote ")[-1].strip())
        summary = json.loads((written / "summary.json").read_text())
        # (a crane whose default is stable inversion: its FMU plays the
        # bounded solution back from the default experiment's start, t0 -
        # T_pre, where the run's results.csv starts too)
        reference = columns(written / "results.csv")
        unzipped = fmpy.extract(str(fmu))
        audited = audit(unzipped, md, summary, start, stop)
        runaway = summary["internal_dynamics"]["runaway_at"]
        if runaway is not None:
            # the FMU stops at the runaway: compare the move before it
            stop = round(runaway / DT - 1) * DT
            reference = {name: values[: round((stop - start) / DT) + 1] for name, values in reference.items()}

        result = fmpy.simulate_fmu(str(fmu), start_time=start, stop_time=stop, output_interval=DT, step_size=DT, output=compared)
        fmpy_step = fmpy_do_step(unzipped, md, start, stop)
        worst_fmpy = max(agree(f"{model} FMPy {name}", reference[name], list(result[name])) for name in compared if name in reference)

        # a negative mass: an FMI error, reported, and the process lives on
        mass = next(v.name for v in md.modelVariables if v.causality == "parameter" and v.name.startswith("m"))
        try:
            fmpy.simulate_fmu(str(fmu), start_time=start, stop_time=stop, output_interval=DT, start_values={mass: -1.0})
            raise SystemExit(f"{model}: {mass} = -1 was accepted")
        except fmpy.fmi1.FMICallException as e:
            bad_mass = str(e)
        # a communication step that is not a multiple of dt
        try:
            fmpy.simulate_fmu(str(fmu), start_time=start, stop_time=stop, output_interval=0.015, step_size=0.015)
            raise SystemExit(f"{model}: a step of 0.015 s with dt = 0.01 s was accepted")
        except fmpy.fmi1.FMICallException:
            pass
        misused = misuse(unzipped, md, start)

        # the C host on the FMU's own binary (from the extraction above)
        library = Path(unzipped) / "binaries" / "linux64" / f"{md.coSimulation.modelIdentifier}.so"
        refs = [str(v.valueReference) for v in outputs if v.name in compared]
        names = [v.name for v in outputs if v.name in compared]
        hosted = subprocess.run([host, str(library), md.guid, str(start), str(stop), str(DT), *refs], check=True, capture_output=True, text=True)
        rows = [list(map(float, line.split(","))) for line in hosted.stdout.splitlines()]
        worst_host = max(agree(f"{model} C host {name}", reference[name], [r[i + 1] for r in rows]) for i, name in enumerate(names) if name in reference)
        host_step = float(hosted.stderr.split("median fmi2DoStep ")[1].split()[0]) * 1e-6
        mass_vr = next(str(v.valueReference) for v in md.modelVariables if v.name == mass)
        subprocess.run([host, str(library), md.guid, str(start), "--bad", mass_vr, "-1"], check=True, capture_output=True, text=True)

        native = json.loads(run(crane, "bench", model, "--dt", str(DT), "--repeat", "5", "--json"))["median_step_s"]
        report.append((model, len(result) - 1, worst_fmpy, worst_host, native, host_step, fmpy_step))
        print(f"{model}: validated; FMPy and C host agree with {Path(crane).name} run to {worst_fmpy:.1e} and {worst_host:.1e} (relative); "
              f"{mass} = -1: {bad_mass.strip()}; FMI errors for {', '.join(misused)}; audit: {audited}", flush=True)

    for model, scenario in scenarios:
        worst_fmpy, worst_host = scenario_fmu(crane, host, out, model, scenario)
        print(f"{model} packaged with {scenario}: validated; FMPy and C host agree with {Path(crane).name} run --scenario "
              f"to {worst_fmpy:.1e} and {worst_host:.1e} (relative)", flush=True)

    print(f"\nper step (dt = 0.01 s): native stepper ({Path(crane).name} bench, median) | C host fmi2DoStep (median) | FMPy doStep (median, through ctypes)")
    for model, steps, _, _, native, host_step, fmpy_step in report:
        print(f"  {model:<20} {steps:>5} steps  {native * 1e6:8.2f} us | {host_step * 1e6:8.2f} us | {fmpy_step * 1e6:8.2f} us")


if __name__ == "__main__":
    main()
