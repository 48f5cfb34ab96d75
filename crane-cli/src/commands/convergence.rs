//! `crane convergence`: the convergence study of `crane_models::study` on
//! the terminal, with convergence.csv and a log-log plot like the paper's
//! Figs. 7 and 16.

use std::path::{Path, PathBuf};

use crane_models::registry::{Registry, Visit};
use crane_models::study::Formulation;
use crane_models::study::convergence::{DTS, T_ERROR, reference_inputs, study_against};
use crane_models::{Case, Crane};
use crane_runtime::Scheme;

use super::{formulation_help, out_dir, scheme_help};
use crate::scenario::{self, Overrides, ScenarioFile};
use crate::{CliError, Tool, plot};

/// The flags of `crane convergence`.
#[derive(clap::Args, Debug)]
// a negative number is a value to check ("--dt -0.01"), not a flag
#[command(allow_negative_numbers = true)]
pub struct ConvergenceArgs {
    /// Model name (see `list`); errors are measured against its analytical
    /// reference, or the exact inputs of its dummy-derivative formulation.
    model: String,
    /// Scenario file (its dt is ignored).
    #[arg(long, value_name = "FILE.toml")]
    scenario: Option<PathBuf>,
    #[arg(long, value_name = "FORMULATION", help = formulation_help())]
    formulation: Option<Formulation>,
    #[arg(long, value_name = "SCHEME", help = scheme_help(Scheme::default()))]
    scheme: Option<Scheme>,
    /// Output directory (default out/MODEL).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Exit non-zero if the audit finds a run of the study that is not a
    /// trustworthy inverse dynamics (the results are still written).
    #[arg(long)]
    strict: bool,
}

struct Convergence<'a> {
    file: Option<&'a ScenarioFile>,
    overrides: Overrides,
    out: &'a Path,
}

impl Visit for Convergence<'_> {
    /// The study's findings, `dt = ...: what`.
    type Output = Result<Vec<String>, CliError>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let (case, settings) = scenario::build::<C, N, M, A>(self.file, &self.overrides)?;
        write(&case, settings.formulation, settings.scheme, self.out)
    }
}

/// Run the study.
pub fn convergence<R: Registry>(tool: &Tool<R>, args: ConvergenceArgs) -> Result<(), CliError> {
    let file = args.scenario.as_deref().map(ScenarioFile::load).transpose()?;
    let (out, _claim) = out_dir(args.out.as_deref(), &args.model)?;
    let overrides = Overrides {
        dt: None,
        tf: None,
        formulation: args.formulation,
        scheme: args.scheme,
    };
    let findings = tool.dispatch(
        &args.model,
        Convergence {
            file: file.as_ref(),
            overrides,
            out: &out,
        },
    )?;
    if args.strict && !findings.is_empty() {
        return Err(CliError::Infeasible {
            problems: findings.join("; "),
            out: out.display().to_string(),
        });
    }
    Ok(())
}

/// Print the rows as they come (a row whose run the audit flags marked
/// `!`, what it found a warning), write `convergence.svg` and
/// `convergence.csv` into `out`, and return the findings.
fn write<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    formulation: Formulation,
    scheme: Scheme,
    out: &Path,
) -> Result<Vec<String>, CliError> {
    let name = C::NAME;
    let method = if let Some(order) = formulation.order(scheme) {
        format!("{}, order {order}", formulation.method(scheme))
    } else {
        format!(
            "{}: algebraic at each step, {scheme} discretises nothing; errors at round-off have no order",
            formulation.name()
        )
    };
    let (reference, against) = reference_inputs(case)?;
    let mut header = Some(format!(
        "{name} ({method}): relative error of u at t = {T_ERROR} s against {}, eq. (48)\n{:>8}  {:>12}  {:>8}",
        against.describe(),
        "dt [s]",
        "e_u",
        "order"
    ));
    // the first failure to print stops the printing and is reported after
    let mut printed: Result<(), CliError> = Ok(());
    let rows = study_against(case, &reference, formulation, scheme, &DTS, |row| {
        if printed.is_err() {
            return;
        }
        printed = header.take().map_or(Ok(()), |header| say!("{header}")).and_then(|()| {
            let grew = row.order.is_some_and(|p| p < 0.0);
            let mark = if !row.findings.is_empty() {
                "  !"
            } else if grew {
                "  (round-off: the run's step-to-step noise; a smaller dt does not help)"
            } else {
                ""
            };
            match row.order {
                Some(p) => say!("{:>8}  {:>12.4e}  {p:>8.3}{mark}", row.dt, row.e_u),
                None => say!("{:>8}  {:>12.4e}  {:>8}{mark}", row.dt, row.e_u, "-"),
            }
        });
        for finding in &row.findings {
            eprintln!("warning: dt = {} s: {finding}", row.dt);
        }
    })?;
    printed?;
    let mut staged = crate::output::Staged::new(out)?;
    let failed = |e: csv::Error| CliError::Output {
        what: "convergence.csv".into(),
        message: e.to_string(),
    };
    let mut csv = csv::Writer::from_writer(Vec::new());
    csv.write_record(["dt", "e_u", "order", "audit"]).map_err(failed)?;
    for row in &rows {
        let order = row.order.map(|p| format!("{p}")).unwrap_or_default();
        let record = [
            format!("{}", row.dt),
            format!("{:e}", row.e_u),
            order,
            row.findings.join("; "),
        ];
        csv.write_record(&record).map_err(failed)?;
    }
    let csv = csv.into_inner().map_err(|e| CliError::Output {
        what: "convergence.csv".into(),
        message: e.to_string(),
    })?;
    let title = format!(
        "{name} ({}, {scheme}) - relative error of u at t = {T_ERROR} s, eq. (48)",
        formulation.name()
    );
    let points: Vec<(f64, f64)> = rows.iter().map(|r| (r.dt, r.e_u)).collect();
    let guide = formulation.order(scheme);
    let svg = plot::convergence(&title, &points, guide)?;
    staged.text("convergence.csv", csv)?;
    staged.text("convergence.svg", svg)?;
    staged.commit()?;
    say!("wrote {}", out.join("convergence.svg").display())?;
    let findings = rows
        .iter()
        .flat_map(|row| row.findings.iter().map(move |f| format!("dt = {} s: {f}", row.dt)))
        .collect();
    Ok(findings)
}
