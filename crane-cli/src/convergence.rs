//! `crane convergence`: the relative error of `u` at t = 1.5 s (eq. 48)
//! against the analytical reference for a range of time steps, the observed
//! orders, and a log-log plot like the paper's Figs. 7 and 16.

use std::fmt::Write as _;
use std::path::Path;

use crane_models::{Case, Crane};
use crane_runtime::{Options, Scheme};

use crate::{CliError, Formulation, plot};

/// The time steps of the study, s.
pub const DTS: [f64; 6] = [0.1, 0.05, 0.02, 0.01, 0.005, 0.001];

/// Time of the error measure (eq. 48), s.
pub const T_ERROR: f64 = 1.5;

/// Run the study on `case` and write `convergence.svg` and `convergence.csv` into `out`.
pub fn run<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    formulation: Formulation,
    scheme: Scheme,
    out: &Path,
) -> Result<(), CliError> {
    if !(case.t0() < T_ERROR && T_ERROR <= case.tf()) {
        return Err(CliError::Convergence(format!(
            "the error is measured at t = {T_ERROR} s, outside the run [{}, {}] s",
            case.t0(),
            case.tf()
        )));
    }
    let name = C::NAME;
    let no_reference = || {
        CliError::Convergence(format!(
            "{name} has no analytical reference at t = {T_ERROR} s to measure the error against"
        ))
    };
    case.reference(T_ERROR).ok_or_else(no_reference)?;
    let start = case.start()?;
    let mut rows: Vec<(f64, f64)> = Vec::new();
    println!(
        "{name} ({}, {scheme}, order {}): relative error of u at t = {T_ERROR} s, eq. (48)",
        formulation.name(),
        scheme.order()
    );
    println!("{:>8}  {:>12}  {:>8}", "dt [s]", "e_u", "order");
    for dt in DTS {
        // the state at 1.5 s does not depend on later steps: stop there
        let options = Options::new(dt, T_ERROR)?.with_scheme(scheme);
        let solution = formulation.simulate(case, &start, &options, &mut |_, _| {})?;
        let state = solution
            .states
            .iter()
            .find(|s| (s.t - T_ERROR).abs() < 0.5 * dt)
            .ok_or_else(|| CliError::Convergence(format!("dt = {dt} s: no step at t = {T_ERROR} s")))?;
        let error = case.relative_input_error(state).ok_or_else(no_reference)?;
        let order = rows.last().map(|&(dt0, e0)| (e0 / error).ln() / (dt0 / dt).ln());
        match order {
            Some(p) => println!("{dt:>8}  {error:>12.4e}  {p:>8.3}"),
            None => println!("{dt:>8}  {error:>12.4e}  {:>8}", "-"),
        }
        rows.push((dt, error));
    }
    let mut staged = crate::output::Staged::new(out)?;
    let mut csv = String::from("dt,e_u,order\n");
    for (i, &(dt, e)) in rows.iter().enumerate() {
        let order = if i == 0 {
            String::new()
        } else {
            format!("{}", (rows[i - 1].1 / e).ln() / (rows[i - 1].0 / dt).ln())
        };
        let _ = writeln!(csv, "{dt},{e:e},{order}");
    }
    let title = format!(
        "{name} ({}, {scheme}) - relative error of u at t = {T_ERROR} s, eq. (48)",
        formulation.name()
    );
    let svg = plot::convergence(&title, &rows, scheme.order())?;
    staged.text("convergence.csv", csv)?;
    staged.text("convergence.svg", svg)?;
    staged.commit()?;
    println!("wrote {}", out.join("convergence.svg").display());
    Ok(())
}
