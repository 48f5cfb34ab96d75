//! A run written as a scenario file: the path, the parameters and the
//! limits of an answer (`crane fastest`'s `fastest.toml`), which `crane run
//! --scenario`, planning and Python read back to the same numbers (every
//! value written as the shortest decimal that reads back to the same f64).

use std::fmt::Write;

use crane_models::path::Profile;
use crane_models::plan::Limits;
use crane_models::{Crane, PathSpec};
use crane_runtime::CraneModel;

/// A number as TOML reads it back exactly (`5.0`, `0.1`, `1e-5`).
fn number(value: f64) -> String {
    format!("{value:?}")
}

fn list(values: impl IntoIterator<Item = f64>) -> String {
    let items: Vec<String> = values.into_iter().map(number).collect();
    format!("[{}]", items.join(", "))
}

/// The scenario of crane `C` with `model`'s parameters moving on `path`
/// under the torque `limits` (by input name), headed by `comment` lines; the
/// run ends at the first whole step of the default `dt` at or after the
/// motion (`tf`), so that it runs as written.
pub fn scenario_text<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &C::Model,
    path: &PathSpec<A>,
    limits: &Limits,
    comment: &[String],
) -> String {
    let dt = crane_models::study::DEFAULT_DT;
    let steps = ((path.t1 - path.t0) / dt - 1e-9).ceil();
    let info = <C::Model as CraneModel<N, M, A>>::INFO;
    let mut text = String::new();
    for line in comment {
        let _ = writeln!(text, "# {line}");
    }
    let _ = writeln!(text, "model = \"{}\"", C::NAME);
    let _ = writeln!(text, "trajectory = \"{}\"", path.profile.kind().name());
    let _ = writeln!(text, "t0 = {}", number(path.t0));
    let _ = writeln!(text, "t1 = {}", number(path.t1));
    let _ = writeln!(
        text,
        "tf = {}  # the motion's end, rounded up to a whole step of dt = {dt} s",
        number(path.t0 + steps * dt)
    );
    match &path.profile {
        Profile::Spline(shape) => {
            let _ = writeln!(text, "degree = {}", shape.degree());
            let _ = writeln!(text, "knots = {}", list(shape.knots().iter().copied()));
            let rows: Vec<String> = shape
                .control()
                .iter()
                .map(|p| format!("    {},", list(p.iter().copied())))
                .collect();
            let _ = writeln!(text, "control = [\n{}\n]", rows.join("\n"));
        }
        profile => {
            if let Some(tau0) = profile.tau0() {
                let _ = writeln!(text, "tau0 = {}", number(tau0));
            }
            let _ = writeln!(text, "start = {}", list(path.start.iter().copied()));
            let _ = writeln!(text, "end = {}", list(path.end.iter().copied()));
        }
    }
    let _ = writeln!(text, "\n[parameters]");
    for (name, value) in info.parameters.iter().zip(model.parameter_values()) {
        let _ = writeln!(text, "{name} = {}", number(value));
    }
    if !limits.torque.is_empty() {
        let _ = writeln!(text, "\n[limits]");
        for &(k, value) in &limits.torque {
            let _ = writeln!(text, "{} = {}", info.inputs[k], number(value));
        }
    }
    text
}
