//! End-to-end tests of the `crane` binary: scenario errors, an example
//! scenario's outputs, `--strict`, `convergence`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn crane(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_crane"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run crane")
}

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples").join(name)
}

/// Run `crane run MODEL --scenario` on `toml`; expect a failure whose message
/// contains every one of `needles` and no results written.
fn expect_error(model: &str, toml: &str, needles: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scenario.toml");
    std::fs::write(&file, toml).unwrap();
    let out = dir.path().join("out");
    let result = crane(&[
        "run",
        model,
        "--scenario",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        !result.status.success(),
        "expected failure for {toml:?}; stderr: {stderr}"
    );
    for needle in needles {
        assert!(
            stderr.contains(needle),
            "stderr for {toml:?} lacks {needle:?}: {stderr}"
        );
    }
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
    assert!(
        !out.join("results.csv").exists(),
        "results.csv written despite the error"
    );
    stderr.into_owned()
}

#[test]
fn unknown_key_is_named() {
    expect_error(
        "navy-planar",
        "dt = 0.01\nspeed = 3.0\n",
        &["`speed`", "unknown field", "line 2"],
    );
}

#[test]
fn unknown_key_in_a_table_is_named() {
    expect_error(
        "navy-planar",
        "[limits]\nu1 = 100.0\n[extra]\nx = 1\n",
        &["`extra`", "unknown field"],
    );
}

#[test]
fn wrong_type_is_named() {
    expect_error("navy-planar", "dt = \"fast\"\n", &["key `dt`", "invalid type"]);
    expect_error(
        "navy-planar",
        "[parameters]\nm_l = \"heavy\"\n",
        &["key `parameters.m_l`", "invalid type"],
    );
}

#[test]
fn wrong_coordinate_count_is_named() {
    expect_error(
        "navy-planar",
        "start = [1.0, 2.0, 3.0]\n",
        &["`start` needs 2 numbers for navy-planar (x, z), got 3"],
    );
    expect_error(
        "navy-3d",
        "end = [1.0, 2.0]\n",
        &["`end` needs 3 numbers for navy-3d", "got 2"],
    );
    expect_error(
        "navy-planar",
        "p0 = [1.0]\n",
        &["`p0` needs 5 numbers for navy-planar (L1, L2, L0, x0, z0), got 1"],
    );
}

#[test]
fn non_positive_dt_is_an_error() {
    expect_error("navy-planar", "dt = 0.0\n", &["`dt` must be a positive"]);
    expect_error("navy-planar", "dt = -0.01\n", &["`dt` must be a positive"]);
}

#[test]
fn tf_not_after_t0_is_an_error() {
    expect_error(
        "navy-planar",
        "t0 = 2.0\ntf = 1.0\n",
        &["`tf` = 1 s must be after the start time t0 = 2 s"],
    );
    expect_error("navy-planar", "tf = 0.0\n", &["`tf`", "must be after"]);
}

#[test]
fn unknown_parameter_is_named() {
    expect_error(
        "navy-planar",
        "[parameters]\nmass = 3.0\n",
        &["`parameters.mass`", "unknown parameter `mass`", "m_l"],
    );
}

#[test]
fn unknown_limit_input_is_named() {
    expect_error("navy-planar", "[limits]\nu7 = 3.0\n", &["`limits.u7`", "u1, u2"]);
}

#[test]
fn inconsistent_start_names_the_constraint() {
    // L1 = 8 instead of 5 sqrt 3: rope 1 cannot reach the pulley
    expect_error(
        "navy-planar",
        "p0 = [8.0, 10.0, 5.0, 0.0, -5.0]\n",
        &[
            "the scenario's `p0` is not a start of navy-planar",
            "inconsistent start",
            "constraint `rope1`",
            "leave `p0` out to start from the static equilibrium",
        ],
    );
}

#[test]
fn example_scenario_end_to_end() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fig5");
    let scenario = example("navy-planar-fig5-8.toml");
    let result = crane(&[
        "run",
        "navy-planar",
        "--scenario",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert_eq!(
        header,
        [
            "t", "L1", "L2", "L0", "x0", "z0", "x", "z", "u1", "u2", "lambda1", "lambda2", "lambda3", "N1", "N2"
        ]
    );
    assert_eq!(
        csv.lines().count(),
        1 + 401,
        "header and 401 rows (t = 0..4 s, dt = 0.01 s)"
    );
    for name in ["inputs.svg", "coordinates.svg", "multipliers.svg", "tensions.svg"] {
        let svg = std::fs::read_to_string(out.join(name)).unwrap();
        assert!(svg.len() > 1024 && svg.contains("<svg"), "{name} is trivial");
    }
    let summary = summary_json(&out);
    let limits = summary["torque_limits"].as_array().unwrap();
    assert_eq!(limits.len(), 2);
    assert!(limits.iter().all(|l| l["first_violation"].is_null()));
    // same as the paper case without a scenario (eq. 48 at dt = 0.01)
    let e_u = summary["reference"]["e_u_at_1_5s"].as_f64().unwrap();
    assert!((e_u - 1.471e-3).abs() < 1e-5, "e_u = {e_u}");
    // the paper's crane is flat by structure: no internal dynamics, and no
    // state sampled to say so
    let internal = &summary["internal_dynamics"];
    assert_eq!(internal["structural_dimension"], 0, "{internal}");
    assert_eq!(internal["dimension"], 0, "{internal}");
    assert_eq!(internal["stable"], true, "{internal}");
    assert_eq!(internal["unresolved"], 0, "{internal}");
    assert_eq!(internal["samples"], 0, "{internal}");
}

#[test]
fn command_line_overrides_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let scenario = example("navy-planar-fig5-8.toml");
    let result = crane(&[
        "run",
        "navy-planar",
        "--scenario",
        scenario.to_str().unwrap(),
        "--dt",
        "0.02",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let summary = summary_json(&out);
    assert_eq!(summary["dt"].as_f64(), Some(0.02));
    assert_eq!(summary["steps"].as_u64(), Some(200));
}

#[test]
fn strict_fails_on_a_violated_limit_but_writes_results() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("low.toml");
    std::fs::write(&file, "dt = 0.01\n[limits]\nu2 = 50.0\n").unwrap();
    let out = dir.path().join("out");
    let args = [
        "run",
        "navy-planar",
        "--scenario",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ];
    // without --strict: a warning, exit 0
    let lenient = crane(&args);
    assert!(lenient.status.success());
    let stderr = String::from_utf8_lossy(&lenient.stderr);
    assert!(
        stderr.contains("warning: |u2| exceeds its limit 50 N m first at t = "),
        "{stderr}"
    );
    let summary = summary_json(&out);
    assert!(summary["torque_limits"][0]["first_violation"].as_f64().is_some());
    std::fs::remove_dir_all(&out).unwrap();
    // with --strict: non-zero, results still written, and the message says so
    let strict = crane(&[&args[..], &["--strict"]].concat());
    let stderr = String::from_utf8_lossy(&strict.stderr);
    assert!(!strict.status.success());
    assert!(
        stderr.contains("infeasible (--strict): |u2| exceeds its limit 50 N m"),
        "{stderr}"
    );
    assert!(stderr.contains("results were still written"), "{stderr}");
    assert!(out.join("results.csv").exists());
}

#[test]
fn strict_passes_a_feasible_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let scenario = example("navy-planar-pulley-fig14-17.toml");
    let result = crane(&[
        "run",
        "navy-planar-pulley",
        "--scenario",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--strict",
        "--quiet",
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
}

#[test]
fn every_example_parses_and_builds() {
    // a cheap check of all examples: a coarse dt override and a short run
    for entry in std::fs::read_dir(example("")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        // a paper figure's scenario names it; another says how to run it
        let name = path.file_name().unwrap().to_str().unwrap();
        assert!(
            text.starts_with('#') && (text.contains("Fig") || text.contains(&format!("--scenario examples/{name}"))),
            "{}: comment header naming the figure or the command",
            path.display()
        );
        let model = text
            .lines()
            .find_map(|l| l.strip_prefix("model = "))
            .unwrap()
            .trim_matches('"');
        let dir = tempfile::tempdir().unwrap();
        let result = crane(&[
            "run",
            model,
            "--scenario",
            path.to_str().unwrap(),
            "--dt",
            "0.05",
            "--out",
            dir.path().to_str().unwrap(),
            "--quiet",
        ]);
        assert!(
            result.status.success(),
            "{}: {}",
            path.display(),
            String::from_utf8_lossy(&result.stderr)
        );
    }
}

#[test]
fn convergence_reports_first_order_and_writes_the_plot() {
    let dir = tempfile::tempdir().unwrap();
    let result = crane(&[
        "convergence",
        "navy-planar",
        "--formulation",
        "redundant",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let csv = std::fs::read_to_string(dir.path().join("convergence.csv")).unwrap();
    let last: Vec<&str> = csv.lines().last().unwrap().split(',').collect();
    assert_eq!(last[0], "0.001");
    let order: f64 = last[2].parse().unwrap();
    assert!((order - 1.0).abs() < 0.05, "order {order}");
    let svg = std::fs::read_to_string(dir.path().join("convergence.svg")).unwrap();
    assert!(svg.len() > 1024 && svg.contains("<svg") && svg.contains("time step dt [s]"));
}

/// `--scheme` and the scenario key `scheme` select the scheme: summary.json
/// names it and its e_u(1.5 s) is the one of the same run through the API
/// (navy-planar, BDF-4, dt = 0.02: about 1e-6 against 2.9e-3 for backward
/// Euler); an unknown scheme is an error naming the key.
#[test]
fn the_scheme_takes_effect_from_the_flag_and_the_file() {
    use crane_runtime::{Options, Scheme, simulate};
    let case = crane_models::navy_planar::PaperCase::new(4.0).unwrap();
    let api = |scheme: Scheme| {
        let run = simulate(
            case.model(),
            case.path(),
            &case.start().unwrap(),
            &Options::new(0.02, 4.0).unwrap().with_scheme(scheme),
        )
        .unwrap();
        let state = run.state_near(1.5).unwrap();
        let reference = case.reference(state.t).unwrap();
        (state.u - reference.u).norm() / reference.u.norm()
    };
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scenario.toml");
    std::fs::write(&file, "scheme = \"bdf3\"\ndt = 0.02\n").unwrap();
    let summary = |args: &[&str], out: &str| {
        let out = dir.path().join(out);
        let mut all = vec![
            "run",
            "navy-planar",
            "--formulation",
            "redundant",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ];
        all.extend_from_slice(args);
        let result = crane(&all);
        assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
        let json = summary_json(&out);
        (
            json["scheme"].as_str().unwrap().to_string(),
            json["reference"]["e_u_at_1_5s"].as_f64().unwrap(),
        )
    };
    let (name, e) = summary(&["--dt", "0.02", "--scheme", "bdf4"], "flag");
    assert_eq!(name, "bdf4");
    assert!(
        (e - api(Scheme::Bdf4)).abs() <= 1e-12 * e,
        "{e} vs {}",
        api(Scheme::Bdf4)
    );
    assert!(e < 2e-6, "{e}");
    let (name, e) = summary(&["--scenario", file.to_str().unwrap()], "file");
    assert_eq!(name, "bdf3");
    assert!((e - api(Scheme::Bdf3)).abs() <= 1e-12 * e);
    // the flag overrides the file; the default is backward Euler
    let (name, _) = summary(&["--scenario", file.to_str().unwrap(), "--scheme", "bdf1"], "both");
    assert_eq!(name, "backward-euler");
    let (name, e) = summary(&["--dt", "0.02"], "default");
    assert_eq!(name, "backward-euler");
    assert!((e - api(Scheme::BackwardEuler)).abs() <= 1e-12 * e && e > 1e-3);
    expect_error(
        "navy-planar",
        "scheme = \"rk4\"\n",
        &["`scheme`", "unknown scheme `rk4`", "bdf5"],
    );
}

/// A scheme given to the default formulation of a flat crane, the reduced
/// system, says that it discretises nothing there: the run is the
/// reduced system's whatever the scheme (results.csv byte for byte that of
/// the default run; navy-planar's move takes no step of eqs. 22 at dt =
/// 0.01 s).
#[test]
fn a_scheme_under_the_reduced_formulation_says_it_discretises_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bdf4");
    let result = crane(&["run", "navy-planar", "--scheme", "bdf4", "--out", out.to_str().unwrap()]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(
        stdout.contains("bdf4 discretises nothing here: the dummy-derivative system is algebraic at each step"),
        "{stdout}"
    );
    let default = run_ok("navy-planar", &[], dir.path(), "default");
    assert_eq!(
        std::fs::read(out.join("results.csv")).unwrap(),
        std::fs::read(default.join("results.csv")).unwrap()
    );
    let result = crane(&[
        "run",
        "navy-planar",
        "--out",
        dir.path().join("plain").to_str().unwrap(),
    ]);
    assert!(!String::from_utf8_lossy(&result.stdout).contains("discretises nothing"));
}

/// `crane convergence --scheme bdf2` measures order 2 and draws the slope-2
/// guide; `crane bench --json` names the scheme.
#[test]
fn convergence_and_bench_take_the_scheme() {
    let dir = tempfile::tempdir().unwrap();
    let result = crane(&[
        "convergence",
        "navy-planar",
        "--formulation",
        "redundant",
        "--scheme",
        "bdf2",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let csv = std::fs::read_to_string(dir.path().join("convergence.csv")).unwrap();
    // dt = 0.01 -> 0.005: e_u 3.6e-5 -> 8.7e-6, order 2.05
    let row = csv.lines().find(|l| l.starts_with("0.005,")).unwrap();
    let order: f64 = row.split(',').nth(2).unwrap().parse().unwrap();
    assert!((order - 2.0).abs() < 0.1, "order {order}");
    let svg = std::fs::read_to_string(dir.path().join("convergence.svg")).unwrap();
    assert!(svg.contains("order 2 (slope 2)") && svg.contains("bdf2"));
    let result = crane(&[
        "bench",
        "navy-planar",
        "--formulation",
        "redundant",
        "--scheme",
        "bdf4",
        "--repeat",
        "2",
        "--json",
    ]);
    assert!(result.status.success());
    let json: serde_json::Value = serde_json::from_slice(&result.stdout).unwrap();
    assert_eq!(json["scheme"], "bdf4");
    assert_eq!(json["steps"], 400);
    assert_eq!(json["timed"], "simulation");
    assert!(json["median_step_s"].as_f64().unwrap() > 0.0);
    // the whole run: the same 400 steps with their summary and audit
    let result = crane(&["bench", "navy-planar", "--study", "--repeat", "2", "--json"]);
    assert!(result.status.success());
    let json: serde_json::Value = serde_json::from_slice(&result.stdout).unwrap();
    assert_eq!(json["timed"], "run, summary and audit");
    assert_eq!(json["steps"], 400);
    // a run of its own length, as `crane run --tf` makes it
    let result = crane(&["bench", "navy-planar", "--tf", "2", "--repeat", "2", "--json"]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let json: serde_json::Value = serde_json::from_slice(&result.stdout).unwrap();
    assert_eq!((json["steps"].as_u64(), json["tf"].as_f64()), (Some(200), Some(2.0)));
    let result = crane(&["bench", "navy-planar", "--tf", "-1", "--repeat", "2"]);
    assert!(!result.status.success());
}

/// `results.csv` of a run, as (header, rows of numbers).
fn results(dir: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut reader = csv::Reader::from_path(dir.join("results.csv")).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let rows = reader
        .records()
        .map(|r| r.unwrap().iter().map(|v| v.parse::<f64>().unwrap()).collect())
        .collect();
    (header, rows)
}

/// The `summary.json` a command wrote into `out`.
fn summary_json(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

/// Run `crane run MODEL ARGS --out DIR/NAME --quiet`; expect success.
fn run_ok(model: &str, args: &[&str], dir: &Path, name: &str) -> std::path::PathBuf {
    let out = dir.join(name);
    let mut all = vec!["run", model, "--quiet", "--out", out.to_str().unwrap()];
    all.extend_from_slice(args);
    let result = crane(&all);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    out
}

/// Every value of `column` equals the API's `value(state, tension)` (the CSV
/// holds the shortest decimal that reads back to the same f64).
fn assert_column<const N: usize, const M: usize, const A: usize>(
    header: &[String],
    rows: &[Vec<f64>],
    column: &str,
    run: &crane_runtime::Solution<N, M, A>,
    value: impl Fn(&crane_runtime::State<N, M, A>, &[f64]) -> f64,
) {
    let c = header
        .iter()
        .position(|h| h == column)
        .unwrap_or_else(|| panic!("no column {column}: {header:?}"));
    assert_eq!(rows.len(), run.states.len());
    for (i, (row, state)) in rows.iter().zip(&run.states).enumerate() {
        assert_eq!(row[c], value(state, run.tensions_at(i)), "{column} at row {i}");
    }
}

/// results.csv holds, column by name, exactly what the same run through the
/// API gives: time, coordinates, inputs, multipliers, tensions (a swapped or
/// shifted column fails).
#[test]
fn results_csv_columns_are_the_api_s_values() {
    use crane_runtime::{Options, Scheme};
    let dir = tempfile::tempdir().unwrap();
    let out = run_ok(
        "navy-planar",
        &["--formulation", "redundant", "--dt", "0.02", "--scheme", "bdf2"],
        dir.path(),
        "csv",
    );
    let (header, rows) = results(&out);
    assert_eq!(
        header,
        [
            "t", "L1", "L2", "L0", "x0", "z0", "x", "z", "u1", "u2", "lambda1", "lambda2", "lambda3", "N1", "N2"
        ]
    );
    let case = crane_models::navy_planar::PaperCase::new(4.0).unwrap();
    let run = case
        .simulate(
            &case.start().unwrap(),
            &Options::new(0.02, 4.0).unwrap().with_scheme(Scheme::Bdf2),
        )
        .unwrap();
    assert_column(&header, &rows, "t", &run, |s, _| s.t);
    for (k, name) in ["L1", "L2", "L0", "x0", "z0", "x", "z"].iter().enumerate() {
        assert_column(&header, &rows, name, &run, |s, _| s.q[k]);
    }
    assert_column(&header, &rows, "u1", &run, |s, _| s.u[0]);
    assert_column(&header, &rows, "u2", &run, |s, _| s.u[1]);
    for k in 0..3 {
        assert_column(&header, &rows, &format!("lambda{}", k + 1), &run, |s, _| s.lambda[k]);
    }
    assert_column(&header, &rows, "N1", &run, |_, n| n[0]);
    assert_column(&header, &rows, "N2", &run, |_, n| n[1]);
}

/// Each scenario key changes what it should: `[parameters]` the model, the
/// path kind the path, `formulation` the scheme of eqs. (24); each run equals
/// the API's run of the case the key describes and differs from the default.
#[test]
fn scenario_keys_take_effect() {
    use crane_models::navy_3d_pulley;
    use crane_runtime::{CraneModel, Options};
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let file = dir.path().join(name);
        std::fs::write(&file, text).unwrap();
        file
    };
    let u_column = |out: &Path, name: &str| {
        let (header, rows) = results(out);
        let c = header.iter().position(|h| h == name).unwrap();
        rows.iter().map(|r| r[c]).collect::<Vec<f64>>()
    };
    let default = run_ok("navy-planar", &["--dt", "0.02"], dir.path(), "default");
    // [parameters]: the load mass
    let file = write("mass.toml", "dt = 0.02\n[parameters]\nm_l = 120.0\n");
    let heavy = run_ok(
        "navy-planar",
        &["--scenario", file.to_str().unwrap()],
        dir.path(),
        "heavy",
    );
    let mut case = crane_models::navy_planar::PaperCase::new(4.0).unwrap();
    case.model.set_parameter("m_l", 120.0).unwrap();
    // (the default formulation: the reduced system)
    let api = case
        .simulate_dummy_derivative(
            &case.start().unwrap(),
            &Options::new(0.02, 4.0).unwrap(),
            &mut |_, _| {},
        )
        .unwrap();
    assert_eq!(
        u_column(&heavy, "u2"),
        api.states.iter().map(|s| s.u[1]).collect::<Vec<_>>()
    );
    assert_ne!(u_column(&heavy, "u2"), u_column(&default, "u2"));
    // formulation
    let file = write("minimal.toml", "dt = 0.02\nformulation = \"minimal\"\n");
    let minimal = run_ok(
        "navy-planar",
        &["--scenario", file.to_str().unwrap()],
        dir.path(),
        "minimal",
    );
    let case = crane_models::navy_planar::PaperCase::new(4.0).unwrap();
    let api = case
        .simulate_minimal(&case.start().unwrap(), &Options::new(0.02, 4.0).unwrap())
        .unwrap()
        .unwrap();
    assert_eq!(
        u_column(&minimal, "u1"),
        api.states.iter().map(|s| s.u[0]).collect::<Vec<_>>()
    );
    assert_ne!(u_column(&minimal, "u1"), u_column(&default, "u1"));
    // path kind: the C6 profile of the 3D crane with pulley mass
    let file = write("smooth.toml", "dt = 0.1\ntrajectory = \"smooth-three-phase\"\n");
    let smooth = run_ok(
        "navy-3d-pulley",
        &["--scenario", file.to_str().unwrap()],
        dir.path(),
        "smooth",
    );
    let paper = run_ok("navy-3d-pulley", &["--dt", "0.1"], dir.path(), "paper");
    // (its default formulation: dummy derivatives, the inputs need gamma^(6))
    let case = navy_3d_pulley::PaperCase::smooth(navy_3d_pulley::TF).unwrap();
    let api = case
        .simulate_dummy_derivative(
            &case.start().unwrap(),
            &Options::new(0.1, case.tf()).unwrap(),
            &mut |_, _| {},
        )
        .unwrap();
    assert_eq!(
        u_column(&smooth, "u4"),
        api.states.iter().map(|s| s.u[3]).collect::<Vec<_>>()
    );
    assert_ne!(u_column(&smooth, "u4"), u_column(&paper, "u4"));
}

/// `crane list` shows every model of the registry with its sizes.
#[test]
fn list_shows_the_registry() {
    let result = crane(&["list"]);
    assert!(result.status.success());
    let text = String::from_utf8_lossy(&result.stdout);
    assert_eq!(crane_models::CATALOG.len(), 9);
    // a header and a line per crane on standard output (scripts read it);
    // why the defaults are what they are on standard error
    assert_eq!(text.lines().count(), 1 + 9, "{text}");
    let note = String::from_utf8_lossy(&result.stderr);
    assert!(
        note.contains("note: the formulation column is the default: dummy-derivative for a crane without internal")
            && note.contains("redundant (eqs. 22a-d) for the others"),
        "{note}"
    );
    for e in crane_models::CATALOG {
        let line = text
            .lines()
            .find(|l| l.split_whitespace().next() == Some(e.name))
            .unwrap_or_else(|| panic!("{}: {text}", e.name));
        let fields: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(fields[1..5], [e.n, e.m, e.a, e.dof()].map(|v| v.to_string()), "{line}");
    }
}

/// `crane convergence --formulation minimal` measures backward Euler's
/// order 1 in minimal coordinates (0.996 between the two smallest steps).
#[test]
fn convergence_in_minimal_coordinates() {
    let dir = tempfile::tempdir().unwrap();
    let result = crane(&[
        "convergence",
        "navy-planar",
        "--formulation",
        "minimal",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let csv = std::fs::read_to_string(dir.path().join("convergence.csv")).unwrap();
    let order: f64 = csv.lines().last().unwrap().split(',').nth(2).unwrap().parse().unwrap();
    assert!((order - 1.0).abs() < 0.05, "order {order}");
}

/// The paper's move in 2.5 s instead of 4 makes rope 1 push (at t =
/// 1.38 s, down to -294 N) with every rope length positive (rope 1 at
/// least 1.9 m): summary.json says so, the results are written, and
/// `--strict` fails. (In 2 s the path leaves the workspace: rope 1's length
/// goes negative from t = 0.43 s, which is its own error.)
#[test]
fn a_slack_rope_is_reported_and_strict_fails_on_it() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("fast.toml");
    std::fs::write(&file, "duration = 2.5\n").unwrap();
    let out = run_ok(
        "navy-planar",
        &["--scenario", file.to_str().unwrap()],
        dir.path(),
        "fast",
    );
    let summary = summary_json(&out);
    let rope = summary["ropes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["name"] == "N1")
        .unwrap();
    let slack = rope["first_slack"].as_f64().expect("rope N1 goes slack");
    assert!((slack - 1.38).abs() < 0.02, "{slack}");
    assert!(rope["min_tension"].as_f64().unwrap() < -100.0);
    let strict_out = dir.path().join("strict");
    let result = crane(&[
        "run",
        "navy-planar",
        "--scenario",
        file.to_str().unwrap(),
        "--strict",
        "--quiet",
        "--out",
        strict_out.to_str().unwrap(),
    ]);
    assert!(!result.status.success());
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(stderr.contains("rope N1 goes slack at t = 1.380 s"), "{stderr}");
    assert!(!stderr.contains("non-positive length"), "{stderr}");
    assert!(
        strict_out.join("results.csv").exists(),
        "--strict still writes the results"
    );
}

/// A run's folder holding a symbolic link or a FIFO at an output's name:
/// refused in one line, the link and its target and the FIFO left as they
/// were (they were replaced by regular files), as `crane fmu` does.
#[test]
fn special_files_in_the_output_folder_are_not_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("od");
    std::fs::create_dir(&out).unwrap();
    let target = dir.path().join("elsewhere.csv");
    std::fs::write(&target, "mine\n").unwrap();
    std::os::unix::fs::symlink(&target, out.join("results.csv")).unwrap();
    let result = crane(&["run", "navy-planar", "--quiet", "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(!result.status.success());
    assert!(
        stderr.contains("results.csv: it exists and is a symbolic link, which crane does not replace"),
        "{stderr}"
    );
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        std::fs::symlink_metadata(out.join("results.csv"))
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "mine\n");
    std::fs::remove_file(out.join("results.csv")).unwrap();
    let fifo = out.join("summary.json");
    assert!(
        std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let result = crane(&["run", "navy-planar", "--quiet", "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains("summary.json: it exists and is a device, a FIFO or a socket"),
        "{stderr}"
    );
    assert!(!std::fs::symlink_metadata(&fifo).unwrap().file_type().is_file());
    assert!(
        !out.join("results.csv").exists(),
        "nothing written: the files are committed together"
    );
}

/// Messages that name what was given: the default ramps on a move the
/// command line shortened (it read "scenario: the load path (keys ...)"
/// with no scenario), an infinite `t1` (it read "must be after `t0`"), a
/// sweep of one duration ("nothing to sweep" with `--duration` given), a
/// parameter declared positive out of range (it offered "or be 0", which
/// the positive check refuses).
#[test]
fn messages_name_what_was_given() {
    let result = crane(&["run", "navy-3d", "--tf", "2"]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(!result.status.success());
    assert!(
        stderr.contains("the move lasts 2 s, but its ramps last tau0 = 5 s by default, more than half of it")
            && stderr.contains("`tau0` <= 1 s")
            && !stderr.contains("scenario:"),
        "{stderr}"
    );
    expect_error("navy-planar", "t1 = inf\n", &["`t1` must be finite, got inf"]);
    let result = crane(&["sweep", "navy-planar", "--duration", "5:5:1"]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains("--duration `5:5:1` is one duration, and no --param is given"),
        "{stderr}"
    );
    expect_error(
        "navy-3d-pulley",
        "[parameters]\nJ_b = -1e-9\n",
        &["`parameters.J_b` = -1e-9 must be positive"],
    );
    let result = expect_error(
        "navy-3d-pulley",
        "[parameters]\nJ_b = 1e-300\n",
        &["between 1e-150 and 1e150"],
    );
    assert!(!result.contains("or be 0"), "{result}");
}

/// Numbers at the ends of the range: a limit of 1e308 (its plot's axis
/// would span more than a double: plotters looped on it) is left out of the
/// plot and the answer is the tension's; a load of 1e140 kg prints its
/// peaks in scientific notation, not as 141 digits.
#[test]
fn extreme_numbers_neither_hang_nor_print_every_digit() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fastest");
    let result = crane(&[
        "fastest",
        "navy-planar",
        "--limit",
        "u2=1e308",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    assert!(out.join("fastest.json").exists());
    let file = dir.path().join("heavy.toml");
    std::fs::write(&file, "[parameters]\nm_l = 1e140\n").unwrap();
    let result = crane(&[
        "run",
        "navy-planar",
        "--scenario",
        file.to_str().unwrap(),
        "--out",
        dir.path().join("heavy").to_str().unwrap(),
    ]);
    // the exact inputs of a load 1e137 times the paper's (the crane's own
    // inertia negligible beside it): against the analytical reference to
    // round-off, the peaks in scientific notation
    let stdout = String::from_utf8_lossy(&result.stdout);
    let peak = stdout
        .lines()
        .find_map(|line| line.trim().strip_prefix("peak |u2| = "))
        .unwrap_or_else(|| panic!("{stdout}"));
    assert!(peak.ends_with("e140 N m at t = 2.760 s"), "{stdout}");
    let error: f64 = stdout
        .lines()
        .find_map(|line| line.split("against the analytical reference (eq. 48): ").nth(1))
        .unwrap_or_else(|| panic!("{stdout}"))
        .parse()
        .unwrap();
    assert!(error < 1e-13, "{stdout}");
    assert!(stdout.lines().all(|line| line.len() < 200), "{stdout}");
    // rope N1 is slack at the start: its tension there is round-off of
    // zero, -2.6e125 N of 7.7e140 N, which "stays taut" does not print
    assert!(stdout.contains("rope N1 stays taut: min tension 0.000 N"), "{stdout}");
    assert!(!stdout.contains("min tension -"), "{stdout}");
}

/// A scenario that changes the crane or the path's start but gives no `p0`
/// runs from the static equilibrium found from the crane's default `p0`
/// (a guess made for the default manoeuvre), or where that equilibrium is
/// a family, from the member the crane's flatness solution starts at; a
/// `p0` the user gave is never moved (`inconsistent_start_names_the_constraint`).
#[test]
fn a_changed_crane_without_p0_starts_from_its_equilibrium() {
    let dir = tempfile::tempdir().unwrap();
    // the double pendulum's sling of 2.1 m instead of 2 m: at rest the hook
    // hangs 2.1 m above the load at (0, -6), the hoist rope vertical below
    // the trolley at s = 0; q = [s, L, xh, zh, x, z]
    let file = dir.path().join("sling.toml");
    std::fs::write(&file, "[parameters]\nl_s = 2.1\n").unwrap();
    let out = run_ok(
        "double-pendulum",
        &["--scenario", file.to_str().unwrap()],
        dir.path(),
        "sling",
    );
    let (header, rows) = results(&out);
    assert_eq!(header[1..7], ["s", "L", "xh", "zh", "x", "z"]);
    for (q, expected) in rows[0][1..7].iter().zip([0.0, 3.9, 0.0, -3.9, 0.0, -6.0]) {
        // Newton's tolerance on the start, 1e-11 of the block's size
        assert!((q - expected).abs() < 1e-9, "{:?}", &rows[0][1..7]);
    }
    // navy-planar's load starting at (1, -10): the pulley hangs above it
    let file = dir.path().join("start.toml");
    std::fs::write(&file, "start = [1, -10]\n").unwrap();
    let out = run_ok(
        "navy-planar",
        &["--scenario", file.to_str().unwrap()],
        dir.path(),
        "start",
    );
    let (header, rows) = results(&out);
    assert_eq!(header[4..8], ["x0", "z0", "x", "z"]);
    assert!(
        (rows[0][4] - 1.0).abs() < 1e-9 && rows[0][6] == 1.0 && rows[0][7] == -10.0,
        "{:?}",
        rows[0]
    );
    // navy-planar's boom of 12 m at 0.8 rad: at rest its pulley is free
    // (rope L1 slack), and the run starts where the flatness solution does,
    // level with winch A: L1 = l sin(alpha), L0 = l cos(alpha), z0 = -L0
    let file = dir.path().join("boom.toml");
    std::fs::write(&file, "[parameters]\nl = 12\nalpha = 0.8\n").unwrap();
    let out = run_ok(
        "navy-planar",
        &["--scenario", file.to_str().unwrap()],
        dir.path(),
        "boom",
    );
    let (header, rows) = results(&out);
    assert_eq!(header[1..6], ["L1", "L2", "L0", "x0", "z0"]);
    let (s, c) = 0.8f64.sin_cos();
    for (q, expected) in rows[0][1..6].iter().zip([12.0 * s, 10.0, 12.0 * c, 0.0, -12.0 * c]) {
        // the flatness formulas at t0, to round-off of 10 m
        assert!((q - expected).abs() < 1e-12, "{:?}", &rows[0][1..6]);
    }
}

/// A run that fails in its middle (an unreachable end point: Newton fails at
/// t = 0.23 s) leaves no results.csv and no partial files.
#[test]
fn a_failure_in_mid_run_leaves_no_results() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("far.toml");
    std::fs::write(&file, "end = [8.0, -14.0]\nduration = 2.0\n").unwrap();
    let out = dir.path().join("far");
    let result = crane(&[
        "run",
        "navy-planar",
        "--scenario",
        file.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!result.status.success());
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(stderr.contains("did not converge at t = 0.23 s"), "{stderr}");
    let left: Vec<_> = std::fs::read_dir(&out)
        .map(|d| d.map(|e| e.unwrap().file_name()).collect())
        .unwrap_or_default();
    assert!(left.is_empty(), "files left behind: {left:?}");
}

/// A negative mass in `[parameters]` is refused before the run, naming the
/// key (the built-in models declare their masses `positive`).
#[test]
fn a_negative_mass_in_the_scenario_names_the_key() {
    expect_error(
        "navy-planar",
        "[parameters]\nm_l = -100.0\n",
        &["`parameters.m_l` = -100 must be positive"],
    );
    expect_error(
        "gantry-3d",
        "[parameters]\nm_t = 0.0\n",
        &["`parameters.m_t` = 0 must be positive"],
    );
}

/// `--replay` drives the forward dynamics with the computed torques: on the
/// planned plant the load follows the path (BDF-4's torques at dt = 0.01:
/// 2.8e-5 m), on a 10 % heavier load (`--plant m_l=110` or a `[plant]`
/// table) it does not; replay.csv has a row per forward step (dt/4) and the
/// deviation column, replay.svg is written.
#[test]
fn replay_reports_how_the_torques_do_on_the_plant() {
    let dir = tempfile::tempdir().unwrap();
    let exact = run_ok(
        "navy-planar-pulley",
        &["--scheme", "bdf4", "--replay", "--settle", "9"],
        dir.path(),
        "exact",
    );
    let replay = &summary_json(&exact)["replay"];
    assert!(replay["max_load_deviation"].as_f64().unwrap() < 1e-4, "{replay}");
    assert_eq!(replay["settle_time"].as_f64(), Some(9.0));
    assert_eq!(replay["scheme"], "bdf2");
    assert!(replay["first_slack"].as_object().unwrap().is_empty());
    let (header, rows) = results(&exact);
    assert_eq!(header.len(), 19, "results.csv itself is unchanged: {header:?}");
    let text = std::fs::read_to_string(exact.join("replay.csv")).unwrap();
    assert!(text.lines().next().unwrap().ends_with(",load_deviation"));
    assert_eq!(
        text.lines().count(),
        1 + 4 * 400 + 4 * 900 + 1,
        "dt/4 over 4 + 9 s, and the header"
    );
    assert!(std::fs::metadata(exact.join("replay.svg")).unwrap().len() > 1024);
    assert_eq!(rows.len(), 401, "one row per inverse step");
    let heavy = run_ok(
        "navy-planar-pulley",
        &["--scheme", "bdf4", "--replay", "--plant", "m_l=110"],
        dir.path(),
        "heavy",
    );
    let replay = &summary_json(&heavy)["replay"];
    assert!(replay["max_load_deviation"].as_f64().unwrap() > 1.0, "{replay}");
    assert_eq!(replay["plant"]["m_l"].as_f64(), Some(110.0));
    let file = dir.path().join("plant.toml");
    std::fs::write(&file, "scheme = \"bdf4\"\n[plant]\nm_l = 110.0\n").unwrap();
    let from_file = run_ok(
        "navy-planar-pulley",
        &["--scenario", file.to_str().unwrap(), "--replay"],
        dir.path(),
        "file",
    );
    assert_eq!(
        summary_json(&from_file)["replay"]["max_load_deviation"],
        replay["max_load_deviation"]
    );
    // a lighter load that the planned torques over-lift: rope N1 would have
    // to push during the settling window, and the replay says so
    let light = run_ok(
        "navy-planar-pulley",
        &["--scheme", "bdf4", "--replay", "--plant", "m_l=90", "--settle", "9"],
        dir.path(),
        "light",
    );
    let slack = summary_json(&light)["replay"]["first_slack"]["N1"]
        .as_f64()
        .expect("N1 pushes");
    assert!((9.0..10.5).contains(&slack), "{slack}");
    // --feedback default at least halves the heavier load's deviation
    let fed = run_ok(
        "navy-planar-pulley",
        &[
            "--scheme",
            "bdf4",
            "--replay",
            "--plant",
            "m_l=110",
            "--feedback",
            "default",
        ],
        dir.path(),
        "fed",
    );
    let with = &summary_json(&fed)["replay"];
    assert!(with["feedback"].as_str().unwrap().starts_with("default"));
    assert_eq!(with["open_loop_max_load_deviation"], replay["max_load_deviation"]);
    assert!(
        with["max_load_deviation"].as_f64().unwrap() <= 0.5 * replay["max_load_deviation"].as_f64().unwrap(),
        "{with}"
    );
    let bad = crane(&[
        "run",
        "navy-planar-pulley",
        "--replay",
        "--plant",
        "mass=3",
        "--quiet",
        "--out",
        dir.path().join("bad").to_str().unwrap(),
    ]);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("plant parameter `mass`: unknown parameter"));
    // a plant parameter out of its range is refused before the inverse run:
    // nothing is written
    let negative = dir.path().join("negative");
    let refused = crane(&[
        "run",
        "navy-planar",
        "--replay",
        "--plant",
        "m_l=-1",
        "--quiet",
        "--out",
        negative.to_str().unwrap(),
    ]);
    assert!(!refused.status.success());
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains("plant parameter `m_l`: parameter `m_l` = -1 must be positive"),
        "{stderr}"
    );
    assert!(
        !negative.exists(),
        "the inverse run was written before the plant was refused"
    );
    // what the forward dynamics cannot follow is named, not the step: a
    // lighter load reeled into its pulley by the torques of a heavier one
    // (rope N2's length passes zero at 4.215 s; Newton fails at 4.5825 s),
    // a longer boom that moves the start off the planner's
    for (plant, needle) in [
        (
            "m_l=90",
            "rope N2 of the plant reaches zero length at t = 4.215 s in the replay",
        ),
        (
            "l=10.5",
            "the plant cannot start where the inverse run starts: its constraint `rope1` (g = 0, eq. 22d) is violated",
        ),
    ] {
        let out = dir.path().join(plant);
        let result = crane(&[
            "run",
            "navy-planar",
            "--replay",
            "--plant",
            plant,
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(!result.status.success(), "{plant}");
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(
            stderr.contains(needle) && !stderr.contains("smaller dt"),
            "{plant}: {stderr}"
        );
    }
    // runaway inputs are not replayed: their end state sized a settling
    // window of 3.4e10 steps (the causal inverse of coupled-trolley: eqs. 22)
    let runaway = dir.path().join("runaway");
    let result = crane(&[
        "run",
        "coupled-trolley",
        "--formulation",
        "redundant",
        "--replay",
        "--quiet",
        "--out",
        runaway.to_str().unwrap(),
    ]);
    assert!(!result.status.success());
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains("nothing to replay: an input of coupled-trolley exceeds 1e6 times its size"),
        "{stderr}"
    );
}

/// The built-in crane that is not flat (`coupled-trolley`, unstable
/// internal dynamics with growth rate sqrt(lambda/c) = 9.9045 1/s at its
/// start), run causally (eqs. 22): `crane run` writes the results but warns
/// on stderr and in summary.json, and `--strict` fails on it.
#[test]
fn unstable_internal_dynamics_are_reported_and_strict_fails_on_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("coupled");
    let causal = ["--formulation", "redundant"];
    let result = crane(
        &[
            &["run", "coupled-trolley", "--quiet", "--out", out.to_str().unwrap()],
            &causal[..],
        ]
        .concat(),
    );
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(stderr.contains("unstable internal dynamics"), "{stderr}");
    assert!(stderr.contains("exceeds 1e6 times its size at the start"), "{stderr}");
    let summary = summary_json(&out);
    let internal = &summary["internal_dynamics"];
    assert_eq!(internal["structural_dimension"], 2, "{internal}");
    assert_eq!(internal["dimension"], 2, "{internal}");
    assert_eq!(internal["stable"], false, "{internal}");
    assert!(internal["max_real_part"].as_f64().unwrap() >= 9.9045, "{internal}");
    assert!(internal["runaway_at"].as_f64().is_some_and(|t| t < 2.5), "{internal}");
    // sampled (it has internal dynamics by structure) up to the runaway:
    // 37 of the 101 states lie before t = 1.8 s
    assert!(internal["samples"].as_u64().unwrap() >= 30, "{internal}");
    let strict_out = dir.path().join("strict");
    let result = crane(
        &[
            &[
                "run",
                "coupled-trolley",
                "--strict",
                "--quiet",
                "--out",
                strict_out.to_str().unwrap(),
            ],
            &causal[..],
        ]
        .concat(),
    );
    assert!(!result.status.success());
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains("infeasible (--strict): coupled-trolley has unstable internal dynamics"),
        "{stderr}"
    );
    assert!(
        strict_out.join("results.csv").exists(),
        "--strict still writes the results"
    );
}

/// `crane fmu MODEL` zips the model description with the given library as
/// `binaries/linux64/<identifier>.so`; without a library it says how to
/// build one, and writes nothing.
#[test]
fn fmu_packages_the_description_and_the_library() {
    let dir = tempfile::tempdir().unwrap();
    // a stand-in with what the packager checks: ELF magic and the FMI names
    let library = dir.path().join("libfake.so");
    std::fs::write(&library, b"\x7fELF stand-in naming fmi2Instantiate and fmi2DoStep").unwrap();
    let out = dir.path().join("fmus").join("gantry-3d.fmu");
    let result = crane(&[
        "fmu",
        "gantry-3d",
        "--library",
        library.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let bytes = std::fs::read(&out).unwrap();
    // a zip archive holding both entries (names are stored uncompressed)
    assert_eq!(&bytes[..4], b"PK\x03\x04");
    let text = String::from_utf8_lossy(&bytes);
    assert!(
        text.contains("modelDescription.xml") && text.contains("binaries/linux64/gantry_3d.so"),
        "{text}"
    );
    let missing = dir.path().join("none.fmu");
    let result = crane(&[
        "fmu",
        "gantry-3d",
        "--library",
        dir.path().join("absent.so").to_str().unwrap(),
        "--out",
        missing.to_str().unwrap(),
    ]);
    assert!(!result.status.success());
    assert!(String::from_utf8_lossy(&result.stderr).contains("cargo build --release -p crane-fmu"));
    assert!(!missing.exists());
    let result = crane(&["fmu", "no-such-crane", "--library", library.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&result.stderr).contains("unknown model"));
}

/// `crane fmu MODEL --scenario FILE` packages the scenario's run with the
/// description and the library (`resources/start.toml`) and says what the
/// FMU starts from; a scenario for another crane or one its crane cannot
/// run is refused with the key's error, and no FMU is written.
#[test]
fn fmu_packages_a_scenarios_run() {
    let dir = tempfile::tempdir().unwrap();
    let library = dir.path().join("libfake.so");
    std::fs::write(&library, b"\x7fELF stand-in naming fmi2Instantiate and fmi2DoStep").unwrap();
    let out = dir.path().join("spline.fmu");
    let fmu = |scenario: &std::path::Path| {
        crane(&[
            "fmu",
            "gantry-3d",
            "--scenario",
            scenario.to_str().unwrap(),
            "--library",
            library.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
    };
    let example = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/gantry-3d-spline.toml");
    let result = fmu(&example);
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    assert!(
        stdout.contains("the spline move (path = 4) from t0 = 0 s for 9 s"),
        "{stdout}"
    );
    let bytes = std::fs::read(&out).unwrap();
    assert!(String::from_utf8_lossy(&bytes).contains("resources/start.toml"));
    std::fs::remove_file(&out).unwrap();
    // the scenario itself as --out: refused, the scenario left as it was
    let copy = dir.path().join("copy.toml");
    std::fs::copy(&example, &copy).unwrap();
    let result = crane(&[
        "fmu",
        "gantry-3d",
        "--scenario",
        copy.to_str().unwrap(),
        "--library",
        library.to_str().unwrap(),
        "--out",
        copy.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        !result.status.success() && stderr.contains("the scenario itself"),
        "{stderr}"
    );
    assert_eq!(std::fs::read(&copy).unwrap(), std::fs::read(&example).unwrap());
    for (text, needle) in [
        ("model = \"navy-planar\"\n", "navy-planar"),
        ("[plant]\nm_l = 600.0\n", "applies only to a replay"),
        ("p0 = [0.0, 0.0, 4.0]\n", "give a `p0` that meets every constraint"),
        ("dt = 0.03\ntf = 8.0\n", "not a whole number of steps"),
        (
            "trajectory = \"spline\"\ntimes = [0.0, 9.0]\nwaypoints = [[0.0, 0.0, -5.0], [6.0, 3.0, -3.0]]\ndegree = 5\n",
            "degree",
        ),
    ] {
        let scenario = dir.path().join("bad.toml");
        std::fs::write(&scenario, text).unwrap();
        let result = fmu(&scenario);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(!result.status.success() && stderr.contains(needle), "{stderr}");
        assert!(!out.exists());
    }
}

/// `crane fastest`: the shortest duration under |u2| <= 150 N m (rope 1
/// allowed to push, so that the torque binds): 2.95 s, bound by u2; the
/// JSON has `duration` and `binding`, and the files are written. With the
/// default floor (every rope taut) rope N1 binds instead, later.
#[test]
fn fastest_finds_the_binding_limit() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fast");
    let result = crane(&[
        "fastest",
        "navy-planar",
        "--limit",
        "u2=150",
        "--min-tension",
        "N1=-1e9",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let json: serde_json::Value = serde_json::from_slice(&result.stdout).unwrap();
    let duration = json["duration"].as_f64().unwrap();
    assert!((duration - 2.951).abs() < 0.002, "{json}");
    assert_eq!(json["binding"]["name"], "u2", "{json}");
    assert_eq!(json["interval"]["holds"], true, "{json}");
    for file in ["fastest.json", "fastest-inputs.svg", "fastest-tensions.svg"] {
        assert!(out.join(file).exists(), "{file}");
    }
    let taut = dir.path().join("taut");
    let result = crane(&[
        "fastest",
        "navy-planar",
        "--limit",
        "u2=150",
        "--json",
        "--out",
        taut.to_str().unwrap(),
    ]);
    let json: serde_json::Value = serde_json::from_slice(&result.stdout).unwrap();
    assert_eq!(json["binding"]["name"], "N1", "{json}");
    assert!(json["duration"].as_f64().unwrap() > duration + 0.1, "{json}");
    let result = crane(&["fastest", "navy-planar", "--limit", "u9=150"]);
    assert!(!result.status.success());
    assert!(String::from_utf8_lossy(&result.stderr).contains("no such input; the inputs are u1, u2"));
}

/// `crane sweep`: one row per grid point with the swept values, peaks,
/// minimum tensions and feasibility, a heat map for two swept quantities,
/// and a point that cannot run (a negative mass) recorded, not fatal.
#[test]
fn sweep_writes_a_row_per_point_and_survives_a_failure() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sweep");
    let result = crane(&[
        "sweep",
        "navy-planar",
        "--param",
        "m_l=-10:110:3",
        "--duration",
        "3:5:3",
        "--limit",
        "u2=150",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "m_l,duration,peak_u1,peak_u2,min_N1,min_N2,feasible,error,audit"
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 9);
    for row in &rows {
        if row[0] == "-10.0" {
            assert!(row[7].contains("m_l") && row[6] == "false", "{row:?}");
        } else {
            assert!(row[3].parse::<f64>().unwrap() > 0.0 && row[7].is_empty(), "{row:?}");
        }
    }
    assert!(out.join("sweep.svg").exists());
    let result = crane(&["sweep", "navy-planar", "--param", "mass=1:2:2"]);
    assert!(String::from_utf8_lossy(&result.stderr).contains("no such parameter"));
}

/// A crane whose inputs need the path's 6th derivative run through the
/// paper's formulation (which covers the 4th) is warned of, its summary says
/// so, and `--strict` fails on it (the results are still written); in its
/// default formulation (dummy derivatives) none of this happens.
#[test]
fn a_crane_beyond_the_formulation_is_warned_of_and_strict_fails() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("smooth.toml");
    std::fs::write(&file, "dt = 0.1\ntrajectory = \"smooth-three-phase\"\n").unwrap();
    let reduced = dir.path().join("reduced");
    let default = crane(&[
        "run",
        "navy-3d-pulley",
        "--scenario",
        file.to_str().unwrap(),
        "--quiet",
        "--strict",
        "--out",
        reduced.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&default.stderr);
    assert!(default.status.success() && !stderr.contains("covers order"), "{stderr}");
    let summary = summary_json(&reduced);
    assert_eq!(summary["formulation"], "dummy-derivative");
    assert_eq!(summary["internal_dynamics"]["path_order"]["covered"], 6);
    let out = dir.path().join("smooth");
    let args = [
        "run",
        "navy-3d-pulley",
        "--scenario",
        file.to_str().unwrap(),
        "--formulation",
        "redundant",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ];
    let result = crane(&args);
    assert!(result.status.success());
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains("derivatives up to order 6, but this formulation (the paper's minimal extension, eqs. 22 and 24) covers order 4"),
        "{stderr}"
    );
    let summary = summary_json(&out);
    assert_eq!(summary["internal_dynamics"]["path_order"]["needed"], 6);
    assert_eq!(summary["internal_dynamics"]["path_order"]["covered"], 4);
    let strict = crane(&[&args[..], &["--strict"]].concat());
    assert!(!strict.status.success());
    let stderr = String::from_utf8_lossy(&strict.stderr);
    assert!(
        stderr.contains("infeasible (--strict): the inputs of navy-3d-pulley depend on the load path's derivatives up to order 6, but this formulation (the paper's minimal extension, eqs. 22 and 24) covers order 4"),
        "{stderr}"
    );
    assert!(out.join("results.csv").exists(), "--strict still writes the results");
}

/// A path too rough for the crane is reported: navy-3d-pulley's inputs
/// need the path's 6th derivative, the paper's three-phase profile is
/// continuous only to the 4th (a warning and `path_smoothness` in
/// summary.json); the smooth profile is enough.
#[test]
fn a_path_too_rough_for_the_crane_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rough");
    let result = crane(&[
        "run",
        "navy-3d-pulley",
        "--dt",
        "0.1",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success());
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains("derivatives up to order 6, but this path is continuous only up to order 4"),
        "{stderr}"
    );
    let summary = summary_json(&out);
    assert_eq!(
        summary["path_smoothness"]["sufficient"], false,
        "{}",
        summary["path_smoothness"]
    );
    let file = dir.path().join("smooth.toml");
    std::fs::write(&file, "dt = 0.1\ntrajectory = \"smooth-three-phase\"\n").unwrap();
    let smooth = run_ok(
        "navy-3d-pulley",
        &["--scenario", file.to_str().unwrap()],
        dir.path(),
        "smooth",
    );
    let summary = summary_json(&smooth);
    assert_eq!(summary["path_smoothness"]["needed"], 6);
    assert_eq!(summary["path_smoothness"]["sufficient"], true);
}

/// A run that crosses t = 8192 s at dt = 0.001 (where an ulp of the time
/// exceeds 1e-9 of the step) goes through: the move starts at 8191.5 s, so
/// the crossing costs 1000 steps, not 8 million; its last row is at
/// t1 = 8192.5 s.
#[test]
fn a_run_across_t_8192_goes_through() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("late.toml");
    std::fs::write(&file, "t0 = 8191.5\nduration = 1.0\ndt = 0.001\n").unwrap();
    let out = run_ok(
        "navy-planar",
        &["--scenario", file.to_str().unwrap()],
        dir.path(),
        "late",
    );
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let last: f64 = csv.lines().last().unwrap().split(',').next().unwrap().parse().unwrap();
    assert!((last - 8192.5).abs() < 1e-9, "{last}");
    assert_eq!(csv.lines().count(), 1 + 1001);
}

/// The relative error of eq. (48) is reported only where a step lands at
/// t = 1.5 s: at dt = 0.8 (steps at 0.8, 1.6, ...) the run says so and
/// summary.json has null, at dt = 0.5 it is there.
#[test]
fn the_error_at_1_5_s_needs_a_step_there() {
    let dir = tempfile::tempdir().unwrap();
    for (dt, expected) in [("0.8", false), ("0.5", true)] {
        let out = dir.path().join(dt);
        let result = crane(&["run", "navy-planar", "--dt", dt, "--out", out.to_str().unwrap()]);
        assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
        let stdout = String::from_utf8_lossy(&result.stdout);
        assert_eq!(
            stdout.contains("relative error of u at t = 1.5 s"),
            expected,
            "{stdout}"
        );
        assert_eq!(stdout.contains("no step lands at t = 1.5 s"), !expected, "{stdout}");
        let summary = summary_json(&out);
        assert_eq!(summary["reference"]["e_u_at_1_5s"].is_null(), !expected);
    }
}

/// Gravity points down in every built-in crane's frame (z up, forces
/// `-m g`): each declares `g` positive, so a flipped sign is refused before
/// a run, not reported as slack ropes with 148 % error.
#[test]
fn gravity_with_the_wrong_sign_is_refused() {
    for e in crane_models::CATALOG {
        expect_error(
            e.name,
            "[parameters]\ng = -9.81\n",
            &["`parameters.g` = -9.81 must be positive"],
        );
    }
}

/// The replay's options do nothing without `--replay`, so they are refused
/// without it (the scenario's `[plant]` too), and a settling window must be
/// positive; a negative number after a flag is a value to check, not a flag.
#[test]
fn replay_options_without_replay_and_negative_values_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x");
    let out = out.to_str().unwrap();
    let stderr = |args: &[&str]| {
        let result = crane(&[&["run", "navy-planar", "--quiet", "--out", out], args].concat());
        assert!(!result.status.success(), "{args:?} was accepted");
        String::from_utf8_lossy(&result.stderr).to_string()
    };
    for args in [
        &["--plant", "m_l=110"][..],
        &["--settle", "5"],
        &["--feedback", "default"],
    ] {
        assert!(stderr(args).contains("--replay"), "{args:?}");
    }
    // 1e308 s ended as "the replay failed: invalid end time tf = inf"
    for settle in ["-5", "0", "inf", "1e308"] {
        assert!(
            stderr(&["--replay", "--settle", settle]).contains("the settling window must be a positive number"),
            "{settle}"
        );
    }
    let file = dir.path().join("plant.toml");
    std::fs::write(&file, "[plant]\nm_l = 110\n").unwrap();
    assert!(stderr(&["--scenario", file.to_str().unwrap()]).contains("[plant] table (m_l) applies only to a replay"));
    // a flag's mistake is named as the flag, not as a scenario key
    assert!(stderr(&["--dt", "-0.01"]).contains("--dt -0.01: the time step must be at least 1e-6 s and finite"));
    assert!(stderr(&["--tf", "-4"]).contains("--tf -4: the end time must be finite and after the start time t0 = 0 s"));
    assert!(stderr(&["--tf", "inf"]).contains("--tf inf: the end time must be finite"));
    let file = dir.path().join("endless.toml");
    std::fs::write(&file, "tf = inf\n").unwrap();
    assert!(stderr(&["--scenario", file.to_str().unwrap()]).contains("scenario: `tf` must be finite, got inf"));
    assert!(!std::path::Path::new(out).join("results.csv").exists());
}

/// `crane fmu --library` takes only an FMU's shared library: an empty file
/// or another program is refused and no .fmu is written.
#[test]
fn an_fmu_needs_an_fmu_library() {
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("empty.so");
    std::fs::write(&empty, b"").unwrap();
    let not_fmu = dir.path().join("text.so");
    std::fs::write(&not_fmu, b"\x7fELF but nothing else").unwrap();
    for (library, needle) in [
        (&empty, "the file is empty"),
        (&not_fmu, "does not export the FMI 2.0 functions"),
    ] {
        let out = dir.path().join("crane.fmu");
        let result = crane(&[
            "fmu",
            "navy-planar",
            "--library",
            library.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(!result.status.success() && stderr.contains(needle), "{stderr}");
        assert!(!out.exists());
    }
}

/// Planning that could not end is refused up front: a sweep larger than
/// `plan::MAX_SWEEP_POINTS` (one axis or the product), a parameter swept
/// twice, and a bisection tolerance below what f64 durations resolve.
#[test]
fn planning_that_cannot_end_is_refused() {
    let stderr = |args: &[&str]| {
        let result = crane(args);
        assert!(!result.status.success(), "{args:?} was accepted");
        String::from_utf8_lossy(&result.stderr).to_string()
    };
    assert!(stderr(&["sweep", "navy-planar", "--param", "m_l=1:2:100000000"]).contains("1 <= COUNT <= 1000000"));
    assert!(
        stderr(&[
            "sweep",
            "navy-planar",
            "--param",
            "m_l=1:2:1000",
            "--param",
            "l=5:10:1001"
        ])
        .contains("the sweep has 1001000 points")
    );
    assert!(stderr(&["sweep", "navy-planar", "--param", "m_l=1:2:3", "--param", "m_l=2:3:3"]).contains("given twice"));
    for tolerance in ["1e-300", "1e-16"] {
        assert!(
            stderr(&["fastest", "navy-planar", "--limit", "u2=150", "--tolerance", tolerance])
                .contains("below what the bisection resolves"),
            "{tolerance}"
        );
    }
}

/// A load path through the pulley (navy-planar to `end = [-3, 5]`, above
/// the boom tip) leaves the crane's workspace: the run is refused before it
/// starts, naming the rope, its length with the load held at rest and the
/// time, and writes nothing; a path inside the workspace driven too fast
/// swings a rope through zero length, and the run warns naming the rope,
/// its length and the time, summary.json has the shortest lengths, and
/// `--strict` fails; the default run's ropes stay positive and its
/// round-off tension of -2.6e-13 N prints as 0.000.
#[test]
fn a_rope_of_non_positive_length_is_reported_and_infeasible() {
    let dir = tempfile::tempdir().unwrap();
    let stderr = expect_error(
        "navy-planar",
        "end = [-3, 5]\n",
        &["the load path leaves navy-planar's workspace: with the load held at rest at the path's point of t = "],
    );
    assert!(
        stderr.contains("rope N2 would be -") || stderr.contains("rope N1 would be -"),
        "{stderr}"
    );
    let default = crane(&[
        "run",
        "navy-planar",
        "--out",
        dir.path().join("default").to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&default.stdout);
    assert!(stdout.contains("rope N1 stays taut: min tension 0.000 N"), "{stdout}");
    assert!(!String::from_utf8_lossy(&default.stderr).contains("length"));
    // the paper's path in 2 s: rope N1 swings through zero length on a path
    // inside the workspace (at rest at that point it is 8.3 m long, where
    // L1 is 8.66 m at the start): the run says the move is too fast, and
    // a tower crane's likewise (its equilibria along the path once
    // balanced the move's acceleration too, swung the jib round and blamed
    // the workspace)
    let fast = crane(&[
        "run",
        "navy-planar",
        "--tf",
        "2",
        "--quiet",
        "--out",
        dir.path().join("fast").to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&fast.stderr);
    assert!(
        stderr.contains("rope N1 of navy-planar (constraint `rope1`) has the length -141.3128 m at t = 0.63 s")
            && stderr.contains(
                "with the load at rest at the same point of the path the rope is 8.3102 m long, so the path is \
                 inside the crane's workspace and the move is too fast for the crane"
            ),
        "{stderr}"
    );
    let summary = summary_json(&dir.path().join("fast"));
    assert!(summary["ropes"][0]["min_length"].as_f64().unwrap() < 0.0);
    let at_rest = summary["ropes"][0]["length_at_rest"].as_f64().unwrap();
    assert!((at_rest - 8.3102).abs() < 1e-4, "N1 at rest: {at_rest}");
    let strict = crane(&[
        "run",
        "navy-planar",
        "--tf",
        "2",
        "--strict",
        "--quiet",
        "--out",
        dir.path().join("strict").to_str().unwrap(),
    ]);
    assert!(!strict.status.success());
    assert!(
        String::from_utf8_lossy(&strict.stderr)
            .contains("rope N1 of navy-planar (constraint `rope1`) has the length -141.3128 m")
    );
    let tower = crane(&[
        "run",
        "tower-crane",
        "--tf",
        "2",
        "--quiet",
        "--out",
        dir.path().join("tower").to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&tower.stderr);
    assert!(
        stderr.contains("the rope is 11.1311 m long, so the path is inside the crane's workspace"),
        "{stderr}"
    );
}

/// A folder holds one run's complete output: of two runs into the same
/// `--out` at once one finishes and the other, if it started while the
/// first held the folder, is refused; they leave a results.csv and a
/// summary.json of the same run, no partial file; a run
/// of another kind removes what the earlier one wrote and it does not
/// (replay.csv, replay.svg), and leaves other files alone.
#[test]
fn an_output_folder_holds_one_runs_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shared");
    let out_str = out.to_str().unwrap().to_string();
    let spawn = |dt: &str| {
        Command::new(env!("CARGO_BIN_EXE_crane"))
            .args([
                "run",
                "navy-planar",
                "--tf",
                "40",
                "--dt",
                dt,
                "--quiet",
                "--out",
                &out_str,
            ])
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap()
    };
    let (a, b) = (spawn("0.001"), spawn("0.002"));
    let ends = [a.wait_with_output().unwrap(), b.wait_with_output().unwrap()];
    assert!(ends.iter().any(|end| end.status.success()));
    for end in ends.iter().filter(|end| !end.status.success()) {
        let stderr = String::from_utf8_lossy(&end.stderr);
        assert!(
            stderr.contains("another run of crane is writing into this folder"),
            "{stderr}"
        );
    }
    let rows = std::fs::read_to_string(out.join("results.csv"))
        .unwrap()
        .lines()
        .count()
        - 1;
    let summary = summary_json(&out);
    assert_eq!(
        rows as u64,
        summary["steps"].as_u64().unwrap() + 1,
        "results.csv and summary.json of one run"
    );
    let partial = |dir: &Path| {
        std::fs::read_dir(dir)
            .unwrap()
            .any(|e| e.unwrap().file_name().to_string_lossy().ends_with(".partial"))
    };
    assert!(!partial(&out));
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    assert!(
        crane(&["run", "navy-planar", "--replay", "--quiet", "--out", &out_str])
            .status
            .success()
    );
    assert!(out.join("replay.csv").exists());
    assert!(
        crane(&["run", "navy-planar", "--quiet", "--out", &out_str])
            .status
            .success()
    );
    assert!(!out.join("replay.csv").exists() && !out.join("replay.svg").exists());
    assert!(out.join("notes.txt").exists() && out.join("results.csv").exists());
}

/// SIGINT at any moment of a run (computing, writing a 60 MB results.csv,
/// or the plots after it) ends it with status 130 and no partial file left;
/// a signal while the handler removes files must not race a file being
/// created (seen once at 800 ms: `.inputs.svg.partial` left behind).
#[test]
fn an_interrupted_run_leaves_no_partial_file() {
    let dir = tempfile::tempdir().unwrap();
    let interrupted = interrupt_after(&[200, 500, 700, 800, 900, 1000, 1100, 1200, 1400], |k| {
        let out = dir.path().join(format!("run{k}"));
        let mut command = Command::new(env!("CARGO_BIN_EXE_crane"));
        command
            .args([
                "run",
                "navy-planar",
                "--tf",
                "100",
                "--dt",
                "0.0005",
                "--quiet",
                "--out",
            ])
            .arg(&out);
        (command, out)
    });
    assert!(interrupted > 0, "no run was interrupted: the test tested nothing");
}

/// SIGINT to the command `make(k)` gives (with the folder it writes in)
/// after each of `delays` ms: every one ends with status 130 or success,
/// and no `.partial` file is left in its folder; returns how many were
/// interrupted.
fn interrupt_after(delays: &[u64], make: impl Fn(usize) -> (Command, PathBuf)) -> usize {
    let mut interrupted = 0;
    for (k, &delay) in delays.iter().enumerate() {
        let (mut command, folder) = make(k);
        let mut child = command
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(delay));
        let _ = Command::new("kill").args(["-INT", &child.id().to_string()]).status();
        let status = child.wait().unwrap();
        assert!(status.success() || status.code() == Some(130), "{delay} ms: {status:?}");
        interrupted += usize::from(status.code() == Some(130));
        if folder.exists() {
            for entry in std::fs::read_dir(&folder).unwrap() {
                let name = entry.unwrap().file_name().to_string_lossy().to_string();
                assert!(!name.ends_with(".partial"), "{delay} ms: {name} left behind");
            }
        }
    }
    interrupted
}

/// SIGINT at any moment of `crane fmu` (zipping a 48 MB library, writing
/// the archive) ends it with status 130 or a whole FMU, and no partial file
/// beside it.
#[test]
fn an_interrupted_fmu_leaves_no_partial_file() {
    let dir = tempfile::tempdir().unwrap();
    // a stand-in library that deflate cannot shrink much: xorshift bytes
    let library = dir.path().join("libbig.so");
    let mut bytes = b"\x7fELF stand-in naming fmi2Instantiate and fmi2DoStep".to_vec();
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    bytes.extend((0..48 << 20).map(|_| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x as u8
    }));
    std::fs::write(&library, &bytes).unwrap();
    let fmu = |k: usize| dir.path().join(format!("fmu{k}")).join("gantry-3d.fmu");
    let interrupted = interrupt_after(&[100, 300, 600, 900, 1200, 1600, 2000], |k| {
        let mut command = Command::new(env!("CARGO_BIN_EXE_crane"));
        command
            .args(["fmu", "gantry-3d", "--library"])
            .arg(&library)
            .arg("--out")
            .arg(fmu(k));
        (command, dir.path().join(format!("fmu{k}")))
    });
    // an FMU is whole or absent: a written one is a zip archive to its end
    for k in 0..7 {
        if let Ok(bytes) = std::fs::read(fmu(k)) {
            assert!(
                bytes.starts_with(b"PK\x03\x04") && bytes.windows(4).any(|w| w == b"PK\x05\x06"),
                "fmu{k}"
            );
        }
    }
    assert!(interrupted > 0, "no packaging was interrupted: the test tested nothing");
}

/// Messages that name the real problem: a start beyond 1e100 m (whose
/// squares overflow), a scenario start that the crane's default `p0` does
/// not fit and no equilibrium from it does (said so, with that p0), `--min-tension` with an example of a
/// rope, a step below a microsecond.
#[test]
fn messages_name_the_real_problem() {
    expect_error(
        "navy-planar",
        "start = [1e308, -10]\n",
        &["`x` = 1e308 is beyond 1e100"],
    );
    // a path end beyond 1e100 ended as a non-finite Newton iterate
    expect_error(
        "navy-planar",
        "end = [1e300, -5.0]\n",
        &[
            "the load path's `x` = 1.2202477546958927e289 at t = 0.01 s is beyond 1e100",
            "`start` and `end`",
        ],
    );
    // the boom does not reach a load 100 m out: no equilibrium from the default p0
    expect_error(
        "navy-planar",
        "start = [100, -10]\n",
        &[
            "constraint `hoist`",
            "the scenario gives no `p0`",
            "default p0 = [8.66",
            "no static equilibrium was found from it",
        ],
    );
    let result = crane(&["fastest", "navy-planar", "--min-tension", "garbage"]);
    assert!(String::from_utf8_lossy(&result.stderr).contains("e.g. --min-tension N1=10"));
    let result = crane(&["run", "navy-planar", "--dt", "1e-300"]);
    assert!(String::from_utf8_lossy(&result.stderr).contains("--dt 1e-300: the time step must be at least 1e-6 s"));
}

/// The paper's crane on a 2000 s move, run for its first 2 s at dt = 0.001:
/// the load barely moves (1e-14 m), rope N1 carries 5e-11 N, the pulley is
/// free along the hoist rope; Newton's matrix was singular at 1818 of 2000
/// steps and the inputs there round-off (a spike of 82159 N m in u1 where
/// the reference has 0). The steps now hold what the rope leaves free (u1
/// stays 0), but the path still does not determine the inputs at any of
/// them: the run says so and `--strict` fails; the
/// default run (one singular step at the degenerate start) does not. The
/// round-off N1 = -2.6e-13 N at the start is not a slack rope.
#[test]
fn a_run_of_singular_steps_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("slow.toml");
    std::fs::write(&file, "duration = 2000.0\ntf = 2.0\ndt = 0.001\n").unwrap();
    let out = dir.path().join("slow");
    let args = [
        "run",
        "navy-planar",
        "--scenario",
        file.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ];
    let result = crane(&args);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        result.status.success() && stderr.contains("steps of navy-planar met an iteration matrix singular"),
        "{stderr}"
    );
    // N1 = -2.6e-13 N at the start is round-off of the crane's 981 N, not
    // of N1's own peak (below 1e-6 N over these 2 s): not slack
    let summary = summary_json(&out);
    assert!(summary["ropes"][0]["min_tension"].as_f64().unwrap() < 0.0);
    assert!(summary["ropes"][0]["first_slack"].is_null(), "{}", summary["ropes"][0]);
    let strict = crane(&[&args[..], &["--strict"]].concat());
    assert!(!strict.status.success());
    assert!(String::from_utf8_lossy(&strict.stderr).contains("met an iteration matrix singular"));
    let default = crane(&[
        "run",
        "navy-planar",
        "--dt",
        "0.001",
        "--quiet",
        "--strict",
        "--out",
        dir.path().join("d").to_str().unwrap(),
    ]);
    assert!(default.status.success() && !String::from_utf8_lossy(&default.stderr).contains("singular"));
}

/// Each input is printed with the unit its crane declares: the 3D gantry's
/// bridge and trolley forces in N, its winch torque in N m (summary.json
/// carries the units too).
#[test]
fn inputs_are_printed_in_their_own_units() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("gantry");
    let result = crane(&[
        "run",
        "gantry-3d",
        "--dt",
        "0.1",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let stdout = String::from_utf8_lossy(&result.stdout);
    let line = |input: &str| {
        stdout
            .lines()
            .find(|l| l.trim_start().starts_with(&format!("peak |{input}|")))
            .unwrap_or_else(|| panic!("no peak line of {input}: {stdout}"))
            .to_string()
    };
    assert!(line("u1").contains(" N at t ="), "{}", line("u1"));
    assert!(line("u2").contains(" N at t ="), "{}", line("u2"));
    assert!(line("u3").contains(" N m at t ="), "{}", line("u3"));
    let summary = summary_json(&out);
    assert_eq!(summary["input_units"], serde_json::json!(["N", "N", "N m"]));
}

/// Every input is bounded and every repeat decided: a repeated `--limit`,
/// `--min-tension` or `--plant` is refused naming both values (a sweep once
/// kept the last, `u2=150`, and marked a peak of 125 feasible against 100);
/// `--threads` and `--repeat` have caps, checked before any work; a
/// scenario that is a device or too large is refused before it is read
/// (`/dev/zero` once grew to 4.7 GB); a negative inertia is refused
/// however small (`J_b = -1e-9` once passed on navy-3d-pulley).
#[test]
fn every_input_is_bounded_and_every_repeat_decided() {
    let refused = |args: &[&str]| {
        let result = crane(args);
        let stderr = String::from_utf8_lossy(&result.stderr).to_string();
        assert!(!result.status.success(), "{args:?} was accepted: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
        stderr
    };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let twice = refused(&[
        "fastest",
        "navy-planar",
        "--limit",
        "u2=100",
        "--limit",
        "u2=150",
        "--out",
        out,
    ]);
    assert!(
        twice.contains("--limit `u2` is given twice (100 and 150): give each name once"),
        "{twice}"
    );
    let twice = refused(&[
        "sweep",
        "navy-planar",
        "--param",
        "m_l=90:110:3",
        "--min-tension",
        "N2=10",
        "--min-tension",
        "N2=20",
        "--out",
        out,
    ]);
    assert!(
        twice.contains("--min-tension `N2` is given twice (10 and 20)"),
        "{twice}"
    );
    let twice = refused(&[
        "run",
        "navy-planar",
        "--replay",
        "--plant",
        "m_l=110",
        "--plant",
        "m_l=120",
        "--out",
        out,
    ]);
    assert!(twice.contains("--plant `m_l` is given twice (110 and 120)"), "{twice}");
    let threads = refused(&[
        "sweep",
        "navy-planar",
        "--param",
        "m_l=90:110:3",
        "--threads",
        "100000",
        "--out",
        out,
    ]);
    assert!(threads.contains("--threads 100000: at most 256"), "{threads}");
    let repeat = refused(&["bench", "navy-planar", "--repeat", "1000000000"]);
    assert!(
        repeat.contains("--repeat 1000000000: at most 100000 timed runs"),
        "{repeat}"
    );
    let overflow = refused(&["bench", "navy-planar", "--repeat", "18446744073709551615"]);
    assert!(overflow.contains("at most 100000 timed runs"), "{overflow}");
    if Path::new("/dev/zero").exists() {
        let device = refused(&["run", "navy-planar", "--scenario", "/dev/zero", "--out", out]);
        assert!(device.contains("scenario /dev/zero: not a regular file"), "{device}");
    }
    // a FIFO without a writer: refused by its type, not opened (which
    // would block for ever)
    let fifo = dir.path().join("fifo.toml");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|status| status.success()) {
        let pipe = refused(&["run", "navy-planar", "--scenario", fifo.to_str().unwrap(), "--out", out]);
        assert!(pipe.contains("fifo.toml: not a regular file"), "{pipe}");
    }
    // times double precision cannot tell apart at the step (0.0156 s at
    // 1e14 s): refused before the run, which repeated its time stamps
    let late = dir.path().join("late.toml");
    std::fs::write(&late, "t0 = 1e14\n").unwrap();
    let times = refused(&["run", "navy-planar", "--scenario", late.to_str().unwrap(), "--out", out]);
    assert!(times.contains("resolves times only to 1.562e-2 s"), "{times}");
    let big = dir.path().join("big.toml");
    std::fs::write(&big, format!("# {}\ndt = 0.01\n", "x".repeat(2 << 20))).unwrap();
    let large = refused(&["run", "navy-planar", "--scenario", big.to_str().unwrap(), "--out", out]);
    assert!(large.contains("larger than 1024 KiB"), "{large}");
    let small = dir.path().join("negative.toml");
    std::fs::write(&small, "[parameters]\nJ_b = -1e-9\n").unwrap();
    let negative = refused(&[
        "run",
        "navy-3d-pulley",
        "--scenario",
        small.to_str().unwrap(),
        "--out",
        out,
    ]);
    assert!(negative.contains("J_b"), "{negative}");
    assert!(!Path::new(out).join("results.csv").exists());
}

/// Every output goes where it should or fails in one line: a closed pipe
/// (`crane list | head -1`) ends quietly and a full disk behind stdout is
/// an error, where both once panicked (status 101 and a backtrace); an FMU
/// is never written over a symbolic link, a FIFO or a device (`--out
/// /dev/full` once replaced the device with a file); an output folder that
/// cannot be created is refused before the computation, with nothing left
/// behind.
#[test]
fn outputs_go_where_they_should_or_fail_in_one_line() {
    use std::io::Read;
    use std::process::Stdio;
    // a reader that closes the pipe at once
    let mut child = Command::new(env!("CARGO_BIN_EXE_crane"))
        .arg("list")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let mut stderr = String::new();
    child.stderr.take().unwrap().read_to_string(&mut stderr).unwrap();
    let status = child.wait().unwrap();
    assert!(status.success(), "{status:?}: {stderr}");
    assert!(stderr.is_empty(), "{stderr}");
    if let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") {
        let result = Command::new(env!("CARGO_BIN_EXE_crane"))
            .arg("list")
            .stdout(full)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(1), "{stderr}");
        assert_eq!(
            stderr.trim_end(),
            "error: writing to standard output: No space left on device (os error 28)"
        );
    }
    let dir = tempfile::tempdir().unwrap();
    let library = Path::new(env!("CARGO_BIN_EXE_crane")).with_file_name("libcrane_fmu.so");
    let target = dir.path().join("target.txt");
    std::fs::write(&target, "mine").unwrap();
    let link = dir.path().join("link.fmu");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    if library.is_file() {
        let result = crane(&[
            "fmu",
            "navy-planar",
            "--out",
            link.to_str().unwrap(),
            "--library",
            library.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(!result.status.success());
        assert!(
            stderr.contains("exists and is a symbolic link, not a regular file"),
            "{stderr}"
        );
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "mine");
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        if Path::new("/dev/full").exists() {
            let result = crane(&[
                "fmu",
                "navy-planar",
                "--out",
                "/dev/full",
                "--library",
                library.to_str().unwrap(),
            ]);
            let stderr = String::from_utf8_lossy(&result.stderr);
            assert!(
                stderr.contains("/dev/full exists and is a device, a FIFO or a socket"),
                "{stderr}"
            );
        }
    }
    // a folder below a regular file cannot be made: refused at once
    let out = target.join("out");
    let result = crane(&[
        "sweep",
        "navy-planar",
        "--param",
        "m_l=90:110:3",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(!result.status.success());
    assert!(stderr.contains("target.txt is not a folder"), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 2, "nothing left behind: {names:?}");
}

/// A replay that fails (a load of 1 mg that the torques reel into the
/// pulley: the forward dynamics cannot go on past it) is an error of one
/// line, but the inverse run
/// is a result of its own and is written (it once wrote nothing), without
/// replay files or a replay section.
#[test]
fn a_failed_replay_still_writes_the_inverse_results() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let result = crane(&[
        "run",
        "navy-planar",
        "--replay",
        "--plant",
        "m_l=1e-6",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(!result.status.success());
    assert!(
        stderr.starts_with("error: the replay failed: rope N2 of the plant reaches zero length"),
        "{stderr}"
    );
    assert!(stderr.contains("the inverse run's results were written to"), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(out.join("results.csv").exists() && out.join("summary.json").exists());
    assert!(!out.join("replay.csv").exists());
    let summary = summary_json(&out);
    assert!(summary["replay"].is_null(), "{}", summary["replay"]);
}

/// One step of 1e6 s in eqs. (22): it once passed Newton's scaled test with
/// states metres off the ropes (the iteration matrix, in mixed units, was
/// taken for singular), which the check of the reported states named. Now
/// Newton solves the step: on the mirror side of the hoist rope (length
/// -7.7 m), a root of the scheme's equations at a step far too long for the
/// path. The warning names the step, not the move, as the cause, and
/// `--strict` fails. A regular run's states are on their constraints to
/// round-off (measured 1.1e-13 m on navy-planar at dt = 0.1; the threshold
/// is 1e-6 of the largest coordinate); the check itself is tested from both
/// sides of its threshold on the run's audit.
#[test]
fn states_off_their_constraints_are_reported() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("huge");
    let args = [
        "run",
        "navy-planar",
        "--formulation",
        "redundant",
        "--tf",
        "1e6",
        "--dt",
        "1e6",
        "--out",
        out.to_str().unwrap(),
    ];
    let result = crane(&args);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success());
    assert!(
        stderr.contains("warning: rope N2 of navy-planar (constraint `hoist`) has the length -7.7178 m"),
        "{stderr}"
    );
    assert!(
        stderr.contains("the step of 1000000 s is too long for the path") && !stderr.contains("too fast"),
        "{stderr}"
    );
    let summary = summary_json(&out);
    let distance = summary["constraint_residual"]["distance"].as_f64().unwrap();
    assert!(distance < 1e-6, "the step's states are on the constraints: {distance}");
    let strict = crane(&[&args[..], &["--strict", "--quiet"]].concat());
    assert!(!strict.status.success());
    assert!(
        String::from_utf8_lossy(&strict.stderr).contains("infeasible (--strict): rope N2 of navy-planar"),
        "{}",
        String::from_utf8_lossy(&strict.stderr)
    );
    let regular = dir.path().join("regular");
    assert!(
        crane(&[
            "run",
            "navy-planar",
            "--dt",
            "0.1",
            "--out",
            regular.to_str().unwrap(),
            "--quiet"
        ])
        .status
        .success()
    );
    let summary = summary_json(&regular);
    let distance = summary["constraint_residual"]["distance"].as_f64().unwrap();
    assert!(distance < 1e-10, "{distance}");
}

/// A crane without a minimal map is pointed at its own default formulation:
/// the reduced one for the flat double-pendulum and navy-3d, stable
/// inversion for coupled-trolley (unstable internal dynamics: no reduced
/// system), where the message once advised the redundant formulation to
/// every crane.
#[test]
fn a_missing_minimal_map_points_at_the_default_formulation() {
    let dir = tempfile::tempdir().unwrap();
    for (model, default) in [
        ("double-pendulum", "dummy-derivative"),
        ("navy-3d", "dummy-derivative"),
        ("coupled-trolley", "stable-inversion"),
    ] {
        let out = dir.path().join(model);
        let result = crane(&[
            "run",
            model,
            "--formulation",
            "minimal",
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ]);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(!result.status.success());
        assert!(
            stderr.contains(&format!(
                "model `{model}` declares no minimal-coordinate map; run it in its default formulation, {default}"
            )),
            "{stderr}"
        );
        assert!(!out.join("results.csv").exists());
    }
}

/// The replay says on the console what the torques do on the plant (it
/// printed nothing there: the numbers were only in summary.json).
#[test]
fn the_replay_is_summed_up_on_the_console() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("heavy");
    let result = crane(&[
        "run",
        "navy-planar-pulley",
        "--scheme",
        "bdf4",
        "--replay",
        "--plant",
        "m_l=110",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success());
    let stdout = String::from_utf8_lossy(&result.stdout);
    let line = stdout
        .lines()
        .find(|line| line.contains("replay on the plant with m_l = 110: the load leaves its path by at most"))
        .unwrap_or_else(|| panic!("no replay line: {stdout}"));
    let summary = summary_json(&out);
    let deviation = summary["replay"]["max_load_deviation"].as_f64().unwrap();
    assert!(
        line.contains(&format!("at most {deviation:.3e} m")),
        "{line} vs {deviation}"
    );
}

/// The audit of a replay: backward Euler's torques (eqs. 22a-d) on the
/// paper's move, held after it, drift the load 0.84 m over the settling
/// window (its end torques are O(dt) off the static ones), and a 20 %
/// heavier plant leaves 68 m: `--replay` warns, `--replay --strict` fails on
/// both, where it passed with any sway. BDF-4's torques on the planned plant
/// arrive (7.7e-5 m of sway) and pass, and so do the default's exact ones.
/// The forward replay's start, where rope N1 carries nothing and dips to
/// -1.2e-5 N, is not a rope that pushes.
#[test]
fn a_replay_that_misses_the_path_fails_strict() {
    let dir = tempfile::tempdir().unwrap();
    for (name, extra) in [
        ("be", &["--formulation", "redundant"][..]),
        (
            "heavy",
            &["--formulation", "redundant", "--scheme", "bdf4", "--plant", "m_l=1200"][..],
        ),
    ] {
        let out = dir.path().join(name);
        let mut args = vec![
            "run",
            "navy-planar",
            "--replay",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let lenient = crane(&args);
        assert!(lenient.status.success(), "{name}");
        let stderr = String::from_utf8_lossy(&lenient.stderr);
        assert!(
            stderr.contains("warning: the replayed load does not arrive: it ends ")
                && stderr.contains("more than 1 % of its 5.000 m travel"),
            "{name}: {stderr}"
        );
        assert!(!stderr.contains("would have to push from t = 0.003 s"), "{stderr}");
        let strict = crane(&[&args[..], &["--strict"]].concat());
        let stderr = String::from_utf8_lossy(&strict.stderr);
        assert!(!strict.status.success(), "{name}");
        assert!(
            stderr.contains("infeasible (--strict): ") && stderr.contains("the replayed load does not arrive"),
            "{name}: {stderr}"
        );
        let why = if name == "be" {
            "the torques at the end differ from the static ones"
        } else {
            "the plant differs from the planner's (add --feedback)"
        };
        assert!(stderr.contains(why), "{name}: {stderr}");
    }
    for (name, formulation) in [("bdf4", "redundant"), ("default", "dummy-derivative")] {
        let out = dir.path().join(name);
        let args = ["run", "navy-planar", "--replay", "--strict", "--quiet", "--out"];
        let scheme: &[&str] = if name == "bdf4" {
            &["--formulation", "redundant", "--scheme", "bdf4"]
        } else {
            &[]
        };
        let exact = crane(&[&args[..], &[out.to_str().unwrap()], scheme].concat());
        assert!(exact.status.success(), "{}", String::from_utf8_lossy(&exact.stderr));
        let summary = summary_json(&out);
        assert_eq!(summary["formulation"], formulation);
        assert!(summary["replay"]["residual_sway"].as_f64().unwrap() < 1e-3);
    }
}

/// The audit of a convergence study: the load straight below the boom tip
/// (end (0, -5)) leaves rope N1 without tension and Newton's matrix
/// singular at almost every step; each row says so (marked `!`, a warning
/// naming its dt, an `audit` column in convergence.csv) and `--strict`
/// fails, where the study printed orders of -3 to 0.08 as if measured.
#[test]
fn a_convergence_study_on_unreliable_runs_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("below.toml");
    std::fs::write(&file, "end = [0.0, -5.0]\n").unwrap();
    let out = dir.path().join("study");
    let args = [
        "convergence",
        "navy-planar",
        "--scenario",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    let result = crane(&args);
    assert!(result.status.success());
    let (stdout, stderr) = (
        String::from_utf8_lossy(&result.stdout),
        String::from_utf8_lossy(&result.stderr),
    );
    assert!(stdout.lines().filter(|l| l.ends_with("  !")).count() >= 5, "{stdout}");
    assert!(
        stderr.contains(
            "warning: dt = 0.001 s: 1500 of 1500 steps of navy-planar met an iteration matrix singular to working \
             precision or held"
        ),
        "{stderr}"
    );
    let csv = std::fs::read_to_string(out.join("convergence.csv")).unwrap();
    assert!(csv.starts_with("dt,e_u,order,audit\n"), "{csv}");
    assert!(csv.lines().skip(1).all(|l| l.contains("singular")), "{csv}");
    let strict = crane(&[&args[..], &["--strict"]].concat());
    assert!(!strict.status.success());
    assert!(String::from_utf8_lossy(&strict.stderr).contains("infeasible (--strict): dt = 0.1 s: "));
    // the paper's move: nothing found, nothing marked
    let clean = crane(&[
        "convergence",
        "navy-planar",
        "--strict",
        "--out",
        dir.path().join("paper").to_str().unwrap(),
    ]);
    assert!(clean.status.success(), "{}", String::from_utf8_lossy(&clean.stderr));
    assert!(!String::from_utf8_lossy(&clean.stdout).contains('!'));
}

/// The coupled trolley by default: stable inversion. From the results
/// files at dt = 0.02, 0.01 and 0.005: rows from t <= -1 s (pre-actuation,
/// 2.33 s from the rest state's eigenvalue) to t >= 6 s, peak |u1| below
/// 200 N (the causal inverse: 1.4e18 N at dt = 0.01), u converging at order 2 (the
/// differences of successive halvings at the coarse rows fall by 4), the
/// trolley's pre-actuation growing at the unstable eigenvalue 9.9045 1/s
/// (fitted on [-1, -0.3] s at dt = 0.01 and 0.005, within the central
/// differences' (k dt)^2 / 24 = 4e-4 at dt = 0.01), summary.json's horizons and eigenvalues, and the
/// replay keeping the load within 1e-3 m of its path.
#[test]
fn coupled_trolley_gets_bounded_inputs_by_stable_inversion() {
    let dir = tempfile::tempdir().unwrap();
    let mut runs = Vec::new();
    for dt in ["0.02", "0.01", "0.005"] {
        let out = run_ok("coupled-trolley", &["--dt", dt], dir.path(), dt);
        let (header, rows) = results(&out);
        assert_eq!(header[..7], ["t", "s", "L", "x", "z", "u1", "u2"]);
        let (first, last) = (rows[0][0], rows[rows.len() - 1][0]);
        assert!(first <= -1.0 && last >= 6.0, "rows from {first} to {last} s");
        let peak = rows.iter().map(|r| r[5].abs()).fold(0.0, f64::max);
        assert!(peak < 200.0, "dt = {dt}: peak |u1| = {peak}");
        let at = |t: f64| rows.iter().find(|r| (r[0] - t).abs() < 1e-9).unwrap();
        let rate = (at(-0.3)[1] / at(-1.0)[1]).ln() / 0.7;
        // (k dt)^2 / 24 = 1.6e-3 at dt = 0.02: the rate is checked below
        if dt != "0.02" {
            assert!((rate - 9.9045).abs() < 1e-3 * 9.9045, "dt = {dt}: rate {rate}");
        }
        let summary = summary_json(&out);
        assert_eq!(summary["formulation"], "stable-inversion");
        let inversion = &summary["stable_inversion"];
        assert!(
            (inversion["t_pre"].as_f64().unwrap() - 2.33).abs() < 0.02,
            "{inversion}"
        );
        let k = inversion["eigenvalues_start"][1][0].as_f64().unwrap().abs();
        assert!((k - 9.904_544).abs() < 1e-5, "{inversion}");
        assert!(inversion["boundary_residual"].as_f64().unwrap() < 1e-9, "{inversion}");
        runs.push(rows);
    }
    // |u(dt) - u(dt/2)| at the coarse rows both hold
    let difference = |coarse: &Vec<Vec<f64>>, fine: &Vec<Vec<f64>>| {
        coarse
            .iter()
            .filter_map(|r| {
                let other = fine.iter().find(|f| (f[0] - r[0]).abs() < 1e-9)?;
                Some((r[5] - other[5]).abs().max((r[6] - other[6]).abs()))
            })
            .fold(0.0, f64::max)
    };
    let order = (difference(&runs[0], &runs[1]) / difference(&runs[1], &runs[2])).log2();
    assert!(order >= 1.8, "order {order}");
    let out = run_ok("coupled-trolley", &["--replay"], dir.path(), "replay");
    // the plots mark where the load moves, in the pre- and post-actuation
    for plot in ["inputs.svg", "coordinates.svg", "tensions.svg"] {
        let svg = std::fs::read_to_string(out.join(plot)).unwrap();
        assert!(
            svg.contains("the load moves (before: pre-, after: post-actuation)"),
            "{plot}"
        );
    }
    // and only there: a causal run has no such mark
    let causal = run_ok(
        "coupled-trolley",
        &["--formulation", "redundant", "--tf", "1"],
        dir.path(),
        "causal",
    );
    let svg = std::fs::read_to_string(causal.join("inputs.svg")).unwrap();
    assert!(!svg.contains("the load moves"));
    let replay = &summary_json(&out)["replay"];
    let deviation = replay["max_load_deviation"].as_f64().unwrap();
    assert!(deviation < 1e-3, "{replay}");
}

/// The audit of planning: navy-planar's move squeezed into 1 s swings its
/// hoist rope through zero length; that sweep point is infeasible with the
/// audit's words in sweep.csv's `audit` column (the paper's 4 s is
/// feasible with the column empty), and `fastest` under a limit no
/// duration meets finds none, saying why. The coupled trolley, whose causal
/// inverse runs away (1.4e18 N), is planned by stable inversion: feasible at
/// c = 2 with bounded inputs as at c = 0.
#[test]
fn planning_counts_what_the_audit_finds_as_infeasible() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sweep");
    let result = crane(&[
        "sweep",
        "navy-planar",
        "--duration",
        "1:4:2",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let mut reader = csv::Reader::from_path(out.join("sweep.csv")).unwrap();
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!((&rows[0][0], &rows[0][5]), ("1.0", "false"));
    assert!(
        rows[0][7].starts_with("rope N2 of navy-planar (constraint `hoist`) has the length"),
        "{:?}",
        &rows[0]
    );
    assert_eq!((&rows[1][0], &rows[1][5], &rows[1][7]), ("4.0", "true", ""));
    let result = crane(&[
        "fastest",
        "navy-planar",
        "--limit",
        "u2=50",
        "--out",
        dir.path().join("f").to_str().unwrap(),
    ]);
    assert!(!result.status.success());
    assert!(
        String::from_utf8_lossy(&result.stderr)
            .contains("no feasible duration up to 512.000 s: at the move's own 4 s: u2 = 125.068 against 50"),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let coupled = dir.path().join("coupled");
    let result = crane(&[
        "sweep",
        "coupled-trolley",
        "--param",
        "c=0:2:2",
        "--quiet",
        "--out",
        coupled.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let mut reader = csv::Reader::from_path(coupled.join("sweep.csv")).unwrap();
    for row in reader.records().map(Result::unwrap) {
        let peak_u1: f64 = row[2].parse().unwrap();
        assert!(&row[5] == "true" && row[7].is_empty() && peak_u1 < 200.0, "{row:?}");
    }
}

/// A parameter beyond what double precision can evaluate the equations
/// with (`m_l = 1e300`, whose products overflow) is refused by name, where
/// the run used to stop at its first step with "singular iteration matrix
/// (LU pivot ratio 0.0e0)"; so is one too small to be told from zero.
#[test]
fn a_parameter_beyond_double_precision_is_named() {
    for (value, shown) in [("1e300", "1e300"), ("1e-200", "1e-200")] {
        expect_error(
            "navy-planar",
            &format!("[parameters]\nm_l = {value}\n"),
            &[
                &format!("parameter `m_l` = {shown} is beyond what the equations can be evaluated with"),
                "between 1e-150 and 1e150",
            ],
        );
    }
    // a mass is declared positive: that is said first, whatever the size
    expect_error(
        "navy-planar",
        "[parameters]\nm_l = -1e200\n",
        &["`parameters.m_l` = -1e200 must be positive"],
    );
}

/// Numbers in messages are as short as they read back: `1e300`, not the
/// 301 digits `{}` prints for it; parameters too.
#[test]
fn numbers_in_messages_are_short() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let result = crane(&[
        "run",
        "navy-planar",
        "--dt",
        "1e300",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains("not a whole number of steps of dt = 1e300 s"),
        "{stderr}"
    );
    expect_error(
        "navy-planar",
        "t0 = 1e300\n",
        &["`t1` = 1e300 s must be after `t0` = 1e300 s"],
    );
    expect_error(
        "navy-planar",
        "[parameters]\nr1 = -1e100\n",
        &["`parameters.r1` = -1e100 must be positive"],
    );
    assert!(!stderr.contains("0000000000"), "{stderr}");
}

/// A long step stays on its branch: the paper's move at dt = 0.5 s and in
/// one step of 100 s (the move slowed to 100 s) ends with the inputs and
/// tensions of the fine step (navy-planar's end, Appendix A: u1 = -43.345
/// N m, N1 = +433.45 N, u2 = -98.1 N m, N2 = +981 N; the prediction's other
/// root had u1 = +133.2 N m and N1 = -1332 N at dt = 0.5, u2 = +98.1 N m
/// and a rope of length -14.68 m at dt = 100), says that it followed the
/// path in shorter steps, and warns of nothing; `--strict` passes.
#[test]
fn a_long_step_ends_on_the_branch_the_move_is_on() {
    let dir = tempfile::tempdir().unwrap();
    for (name, args) in [("half", &["--dt", "0.5"][..]), ("one", &["--tf", "100", "--dt", "100"])] {
        let out = dir.path().join(name);
        let mut all = vec!["run", "navy-planar", "--strict", "--out", out.to_str().unwrap()];
        all.extend_from_slice(args);
        let result = crane(&all);
        let (stdout, stderr) = (
            String::from_utf8_lossy(&result.stdout),
            String::from_utf8_lossy(&result.stderr),
        );
        assert!(result.status.success(), "{name}: {stderr}");
        assert!(!stderr.contains("warning"), "{name}: {stderr}");
        assert!(
            stdout.contains("steps followed the path in shorter steps"),
            "{name}: {stdout}"
        );
        let (header, rows) = results(&out);
        let column = |c: &str| header.iter().position(|h| h == c).unwrap();
        let end = rows.last().unwrap();
        // the same equations solved at the same time: round-off of 1e2
        for (c, exact) in [
            ("u1", -43.345_043_319_952),
            ("N1", 433.450_433_199_52),
            ("u2", -98.1),
            ("N2", 981.0),
        ] {
            assert!(
                (end[column(c)] - exact).abs() < 1e-9 * exact.abs(),
                "{name}: {c} = {}",
                end[column(c)]
            );
        }
        assert!(
            summary_json(&out)["newton"]["continued_steps"].as_u64().unwrap() >= 1,
            "{name}"
        );
    }
}

/// Exact inputs at steps too long for the move's features are no spike:
/// tower-crane's 10 s move at dt = 1 s turns u2 by 455 N between steps
/// where its peak elsewhere is 233 N (the same inputs as dt = 0.001 s to
/// 1e-15 of their peak), and navy-planar's 4 s move in two steps; neither
/// warns and `--strict` passes. `summary.json` gives the feature the steps
/// are judged against.
#[test]
fn exact_inputs_at_long_steps_are_not_called_spikes() {
    let dir = tempfile::tempdir().unwrap();
    for (model, dt, feature) in [("tower-crane", "1.0", 10.0), ("navy-planar", "2", 4.0)] {
        let out = dir.path().join(model);
        let result = crane(&["run", model, "--dt", dt, "--strict", "--out", out.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(result.status.success(), "{model}: {stderr}");
        assert!(!stderr.contains("turns by"), "{model}: {stderr}");
        let summary = summary_json(&out);
        assert_eq!(summary["shortest_feature"].as_f64(), Some(feature), "{model}");
        // the turn is there: it is the step, not the input, that is coarse
        let spike = &summary["input_spike"];
        let ratio = spike["second_difference"].as_f64().unwrap() / spike["peak"].as_f64().unwrap();
        assert!(ratio > 1.0, "{model}: {ratio}");
    }
}

/// `crane bench` says what it timed is not a result: the paper's move in
/// 0.5 s (ropes through zero length, inputs of 1e6 N m and more) warns on
/// stderr and lists the findings in its JSON; the default move has none.
#[test]
fn bench_reports_the_findings_of_what_it_times() {
    let fast = crane(&["bench", "navy-planar", "--tf", "0.5", "--repeat", "1", "--json"]);
    assert!(fast.status.success(), "{}", String::from_utf8_lossy(&fast.stderr));
    let json: serde_json::Value = serde_json::from_slice(&fast.stdout).unwrap();
    let findings = json["findings"].as_array().unwrap();
    assert!(
        findings
            .iter()
            .any(|f| f.as_str().unwrap().contains("has the length -")),
        "{findings:?}"
    );
    assert!(String::from_utf8_lossy(&fast.stderr).contains("warning: rope N2 of navy-planar"));
    let default = crane(&["bench", "navy-planar", "--repeat", "1", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&default.stdout).unwrap();
    assert_eq!(json["findings"].as_array().map(Vec::len), Some(0), "{json}");
}

/// A folder that another run is writing into is refused at once, before
/// any computation (two runs into one `--out` once both ran, and the one
/// that finished last replaced the other's results without a word); the
/// first run's results are its own. A refused or failed run leaves no
/// folder it created.
#[test]
fn a_folder_another_run_writes_into_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shared");
    // a run of a few seconds (the paper's move slowed to 400 s at 1 ms)
    let mut first = Command::new(env!("CARGO_BIN_EXE_crane"))
        .args(["run", "navy-planar", "--tf", "400", "--dt", "0.001", "--quiet", "--out"])
        .arg(&out)
        .spawn()
        .unwrap();
    // wait until it holds the folder (its lock file exists), then try
    let lock = out.join(".crane.lock");
    while !lock.exists() {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let second = crane(&["run", "navy-planar", "--quiet", "--out", out.to_str().unwrap()]);
    let still_running = first.try_wait().unwrap().is_none();
    assert!(first.wait().unwrap().success());
    // (a second run let through would have ended long before the first)
    assert!(
        still_running,
        "the first run ended before the second: the test needs a longer one"
    );
    assert!(!second.status.success());
    let stderr = String::from_utf8_lossy(&second.stderr);
    assert!(
        stderr.contains("another run of crane is writing into this folder"),
        "{stderr}"
    );
    assert_eq!(
        summary_json(&out)["tf"].as_f64(),
        Some(400.0),
        "the first run's results"
    );
    // a run that fails after claiming its folder leaves none behind
    let scenario = dir.path().join("inconsistent.toml");
    std::fs::write(&scenario, "p0 = [8.0, 10.0, 5.0, 0.0, -5.0]\n").unwrap();
    let fresh = dir.path().join("a").join("b");
    let failed = crane(&[
        "run",
        "navy-planar",
        "--scenario",
        scenario.to_str().unwrap(),
        "--out",
        fresh.to_str().unwrap(),
    ]);
    assert!(String::from_utf8_lossy(&failed.stderr).contains("inconsistent start"));
    assert!(!dir.path().join("a").exists());
}

/// `crane sweep` refuses a path whose inputs carry impulses before any run,
/// as `crane fastest` does (navy-3d-pulley on the paper's three-phase
/// profile: it exited 0 with every point "failed"), and writes nothing.
#[test]
fn sweep_refuses_a_path_whose_inputs_carry_impulses() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sweep");
    let result = crane(&[
        "sweep",
        "navy-3d-pulley",
        "--param",
        "m_l=90:110:3",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!result.status.success());
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains("they carry impulses where derivative 5 jumps"),
        "{stderr}"
    );
    assert!(!out.exists());
}

/// Winch drums of 1e-6 m (torques a million times the paper's) at dt =
/// 0.001 s give the inputs of dt = 0.01 s: peak |u1| 4.87674531e5 N m at
/// t = 1.33 s both (a long run of singular steps once reached 3.6e49 N m).
#[test]
fn tiny_drums_at_a_fine_step_give_the_inputs_of_a_coarse_one() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("drums.toml");
    std::fs::write(&scenario, "[parameters]\nr1 = 1e-6\nr2 = 1e-6\n").unwrap();
    let peak = |dt: &str| {
        let out = run_ok(
            "navy-planar",
            &["--scenario", scenario.to_str().unwrap(), "--dt", dt],
            dir.path(),
            dt,
        );
        let summary = summary_json(&out);
        assert_eq!(summary["newton"]["min_norm_steps"].as_u64(), Some(0), "dt = {dt}");
        summary["peak_torque"][0]["value"].as_f64().unwrap()
    };
    let (coarse, fine) = (peak("0.01"), peak("0.001"));
    // both sample u1 at t = 1.33 s, its peak: the same equations there
    assert!((coarse - 4.876_745_31e5).abs() < 1.0, "{coarse}");
    assert!((fine - coarse).abs() < 1e-9 * coarse, "{fine} against {coarse}");
}

/// Where the path itself passes a singular configuration (the paper's move
/// in 3 s: rope N1 goes slack at t = 1.76 s, its tension through zero,
/// where the reduced system is singular), the run says so in one line with
/// the time and `summary.json` counts it; the paper's own move has none.
#[test]
fn a_singular_configuration_on_the_path_is_named_with_its_time() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fast");
    let result = crane(&["run", "navy-planar", "--tf", "3", "--out", out.to_str().unwrap()]);
    assert!(result.status.success());
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(
        stdout.contains("the path passes a singular configuration at t = 1.76 s"),
        "{stdout}"
    );
    let newton = &summary_json(&out)["newton"];
    assert_eq!(newton["crossings"].as_u64(), Some(1), "{newton}");
    assert_eq!(newton["first_crossing"].as_f64(), Some(1.76), "{newton}");
    let paper = run_ok("navy-planar", &[], dir.path(), "paper");
    assert_eq!(summary_json(&paper)["newton"]["crossings"].as_u64(), Some(0));
}

/// `--replay` with a step whose replay would step the plant below the
/// smallest time step is refused before the run (nothing written), naming
/// the step given; it failed after the whole run, naming dt = 2.5e-7.
#[test]
fn a_replay_step_below_the_smallest_is_refused_before_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("short");
    let started = std::time::Instant::now();
    let result = crane(&[
        "run",
        "navy-planar",
        "--dt",
        "1e-6",
        "--replay",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!result.status.success());
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        stderr.contains("dt = 1e-6 s would step it at 2.5e-7 s") && stderr.contains("take dt >= 4e-6 s"),
        "{stderr}"
    );
    assert!(!out.exists(), "nothing written");
    // a run of 4e6 steps takes seconds; the refusal comes before it
    assert!(started.elapsed().as_secs_f64() < 2.0, "{:?}", started.elapsed());
}

/// A spline scenario through four waypoints: the load is at each waypoint
/// at its time, at rest at the ends, and its inputs are continuous (their
/// largest step-to-step change halves with the step); a spline's mistakes
/// are one-line errors naming the key, and a spline that leaves the
/// crane's workspace is refused before the run.
#[test]
fn a_spline_scenario_passes_its_waypoints_with_continuous_inputs() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = example("gantry-3d-spline.toml");
    let largest_change = |dt: &str| {
        let out = run_ok(
            "gantry-3d",
            &["--scenario", scenario.to_str().unwrap(), "--dt", dt],
            dir.path(),
            dt,
        );
        let (header, rows) = results(&out);
        let column = |name: &str| header.iter().position(|h| h == name).unwrap();
        let (x, y, z) = (column("x"), column("y"), column("z"));
        for (t, point) in [
            (0.0, [0.0, 0.0, -5.0]),
            (2.0, [0.0, 0.0, -3.0]),
            (7.0, [6.0, 3.0, -3.0]),
            (9.0, [6.0, 3.0, -5.0]),
        ] {
            let row = rows.iter().find(|r| (r[0] - t).abs() < 1e-9).unwrap();
            for (k, c) in [x, y, z].into_iter().enumerate() {
                assert!((row[c] - point[k]).abs() < 1e-12, "t = {t}: {} = {}", header[c], row[c]);
            }
        }
        let inputs: Vec<usize> = ["u1", "u2", "u3"].iter().map(|u| column(u)).collect();
        rows.windows(2)
            .map(|w| inputs.iter().map(|&c| (w[1][c] - w[0][c]).abs()).fold(0.0, f64::max))
            .fold(0.0, f64::max)
    };
    let ratio = largest_change("0.005") / largest_change("0.01");
    assert!((0.45..0.55).contains(&ratio), "ratio {ratio}");

    let spline = "trajectory = \"spline\"\n";
    let two = "waypoints = [[0, 0, -5], [6, 3, -3]]\ntimes = [0, 5]\n";
    expect_error("gantry-3d", spline, &["`waypoints`", "`times`"]);
    expect_error(
        "gantry-3d",
        &format!("{two}degree = 7\n"),
        &["`degree`", "too low", "degree 9 or more"],
    );
    expect_error("gantry-3d", &format!("{two}degree = 10\n"), &["`degree`", "odd"]);
    expect_error("gantry-3d", &format!("{two}end = [1, 2, 3]\n"), &["`end`", "last"]);
    expect_error("gantry-3d", &format!("{two}t1 = 3\n"), &["`t1`", "`times`"]);
    expect_error(
        "gantry-3d",
        &format!("trajectory = \"poly9\"\n{two}"),
        &["`waypoints`", "only to trajectory = \"spline\""],
    );
    expect_error(
        "gantry-3d",
        "waypoints = [[0, 0, -5], [6, 3]]\ntimes = [0, 5]\n",
        &["`waypoints`", "waypoint 2 needs 3 numbers", "(x, y, z)"],
    );
    expect_error(
        "gantry-3d",
        "waypoints = [[0, 0, -5], [6, 3, -3]]\ntimes = [5, 0]\n",
        &["`times`", "increasing"],
    );
    expect_error(
        "gantry-3d",
        "waypoints = [[0, 0, -5]]\ntimes = [0]\n",
        &["`times`", "at least two"],
    );
    // through points 1 m above the trolley (at height 0): held there the
    // rope would push with the load's weight
    expect_error(
        "gantry-3d",
        "trajectory = \"spline\"\ntimes = [0, 2, 7, 9]\n\
         waypoints = [[0, 0, -5], [0, 0, 1], [6, 3, 1], [6, 3, -5]]\n",
        &[
            "the load path leaves gantry-3d's workspace",
            "every rope would have to push (N = -4.9050e3 N)",
        ],
    );
    // a cubic Bezier from rest is not at rest to order 4 at its ends
    expect_error(
        "gantry-3d",
        "knots = [0, 0, 0, 0, 1, 1, 1, 1]\ncontrol = [[0, 0, -5], [0, 0, -5], [6, 3, -3], [6, 3, -3]]\n",
        &["`control`", "only to order 1", "order 4"],
    );
}

/// The peak |u| of input `name` in a run's results.csv.
fn peak_of(out: &Path, name: &str) -> f64 {
    let (header, rows) = results(out);
    let c = header.iter().position(|h| h == name).unwrap();
    rows.iter().map(|r| r[c].abs()).fold(0.0, f64::max)
}

/// `crane fastest` writes its answer as a scenario, `fastest.toml`, and
/// prints the command that runs it: a three-phase move, whose ramps the
/// search scales with the duration, peaks at the limit when run as
/// written (double-pendulum under |u1| <= 500 N: 499.88 N at T* = 9.1003 s,
/// within 0.1 % of the limit; `--tf 9.1003` alone keeps the ramps and
/// peaks at 445.8).
#[test]
fn fastest_writes_its_answer_as_a_scenario_that_reproduces_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fast");
    let result = crane(&[
        "fastest",
        "double-pendulum",
        "--limit",
        "u1=500",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&result.stdout);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let command = format!(
        "crane run double-pendulum --scenario {}",
        out.join("fastest.toml").display()
    );
    assert!(stdout.contains(&command), "{stdout}");
    let scenario = out.join("fastest.toml");
    let run = run_ok(
        "double-pendulum",
        &["--scenario", scenario.to_str().unwrap()],
        dir.path(),
        "run",
    );
    let peak = peak_of(&run, "u1");
    assert!(peak <= 500.0 && peak > 499.5, "{peak}");
}

/// `crane fastest --shape optimal`: gantry-3d under |u1| <= 1000 N, the
/// shaped move within 5 % of the rigid-body bound 4.899 s (the time-scaled
/// poly9: 6.553 s), reported in fastest.json with the bound and the gap;
/// its fastest.toml, run by `crane run` at dt = 0.5 ms, stays within the
/// limit with the rope taut and the load at rest at both ends; the plots
/// show both moves.
#[test]
fn fastest_with_an_optimal_shape_comes_near_the_bound_and_runs_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("shaped");
    let result = crane(&[
        "fastest",
        "gantry-3d",
        "--limit",
        "u1=1000",
        "--shape",
        "optimal",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
    let json: serde_json::Value = serde_json::from_slice(&result.stdout).unwrap();
    let duration = json["duration"].as_f64().unwrap();
    let bound = json["shape"]["lower_bound"]["duration"].as_f64().unwrap();
    assert!((bound - 4.898979485566356).abs() < 1e-12, "{json}");
    assert!(duration >= bound && duration <= 1.05 * bound, "{json}");
    assert_eq!(json["shape"]["kind"], "optimal", "{json}");
    assert!(
        (json["shape"]["time_scaled"].as_f64().unwrap() - 6.553).abs() < 0.002,
        "{json}"
    );
    assert!((json["shape"]["gap"].as_f64().unwrap() - (duration / bound - 1.0)).abs() < 1e-12);
    for file in [
        "fastest.json",
        "fastest.toml",
        "fastest-inputs.svg",
        "fastest-tensions.svg",
        "fastest-path.svg",
    ] {
        assert!(out.join(file).exists(), "{file}");
    }
    let scenario = out.join("fastest.toml");
    let tf = format!("{}", (duration / 0.0005).ceil() * 0.0005);
    let run = run_ok(
        "gantry-3d",
        &["--scenario", scenario.to_str().unwrap(), "--dt", "0.0005", "--tf", &tf],
        dir.path(),
        "run",
    );
    let peak = peak_of(&run, "u1");
    assert!(peak <= 1000.0 && peak > 995.0, "{peak}");
    let summary = summary_json(&run);
    let rope = &summary["ropes"][0];
    assert!(
        rope["first_slack"].is_null() && rope["min_tension"].as_f64().unwrap() > 0.0,
        "{summary}"
    );
    let (header, rows) = results(&run);
    let x = header.iter().position(|h| h == "x").unwrap();
    let (first, last) = (&rows[0], rows.last().unwrap());
    assert_eq!((first[x], last[x]), (0.0, 6.0));
}

/// `crane sweep --points FILE.csv`: any set of points, a `duration` column
/// giving each point's; every row equals the grid's row with the same
/// values bit for bit, and a bad set is one error line before any run.
#[test]
fn a_sweep_of_a_point_set_equals_the_grid_s_rows() {
    let dir = tempfile::tempdir().unwrap();
    let points = dir.path().join("pts.csv");
    std::fs::write(&points, "m_l,duration\n120,4\n80,3\n100,3.5\n").unwrap();
    let sweep = |args: &[&str], name: &str| -> Vec<Vec<String>> {
        let out = dir.path().join(name);
        let mut all = vec![
            "sweep",
            "navy-planar",
            "--limit",
            "u2=150",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ];
        all.extend_from_slice(args);
        let result = crane(&all);
        assert!(result.status.success(), "{}", String::from_utf8_lossy(&result.stderr));
        let mut reader = csv::Reader::from_path(out.join("sweep.csv")).unwrap();
        reader
            .records()
            .map(|r| r.unwrap().iter().map(String::from).collect())
            .collect()
    };
    let set = sweep(&["--points", points.to_str().unwrap()], "set");
    let grid = sweep(&["--param", "m_l=80:120:3", "--duration", "3:4:3"], "grid");
    assert_eq!(set.len(), 3);
    for row in &set {
        assert!(grid.contains(row), "{row:?} not in the grid's rows");
    }
    assert_eq!((set[0][0].as_str(), set[0][1].as_str()), ("120.0", "4.0"));
    for (text, needle) in [
        ("m_x\n1\n", "no such parameter"),
        ("m_l\nnan\n", "not finite"),
        ("m_l\n", "no points"),
        ("m_l,duration\n100,-1\n", "positive"),
        ("m_l\nheavy\n", "not a number"),
    ] {
        std::fs::write(&points, text).unwrap();
        let result = crane(&[
            "sweep",
            "navy-planar",
            "--points",
            points.to_str().unwrap(),
            "--out",
            dir.path().join("bad").to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(
            !result.status.success() && stderr.contains(needle),
            "{text:?}: {stderr}"
        );
        assert!(!dir.path().join("bad").join("sweep.csv").exists());
    }
}
