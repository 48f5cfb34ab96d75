//! One module per command: its flags (`clap::Args`) and what it does with
//! them. A command on one crane is a [`Visit`](crane_models::Visit) that
//! [`Tool::dispatch`](crate::Tool) runs on the crane of that name with its
//! sizes.

pub mod bench;
pub mod convergence;
pub mod fmu;
pub mod list;
pub mod plan;
pub mod run;

use std::path::{Path, PathBuf};

use crane_models::study::Formulation;
use crane_runtime::Scheme;

use crate::CliError;
use crate::output::Claim;

/// The output directory: `out` if given, else `out/MODEL`, claimed for the
/// command ([`Claim`]: keep it until the command ends).
pub fn out_dir(out: Option<&Path>, model: &str) -> Result<(PathBuf, Claim), CliError> {
    let dir = out.map_or_else(|| PathBuf::from("out").join(model), Path::to_path_buf);
    // before any computation: a folder that cannot be written, or that
    // another run is writing into, is an error now, not after a long run
    crate::output::check_writable(&dir)?;
    let claim = Claim::new(&dir)?;
    Ok((dir, claim))
}

/// The help of a `--scheme` flag, from the one list of schemes.
pub fn scheme_help(default: Scheme) -> String {
    format!("Time-discretisation scheme: {} (default {default})", Scheme::help())
}

/// The help of a `--formulation` flag, from the one list of formulations.
pub fn formulation_help() -> String {
    format!(
        "Formulation: {} (default {} for a crane without internal dynamics, {} for stable ones, {} for unstable \
         ones, {} for the others)",
        Formulation::help(),
        Formulation::DummyDerivative,
        Formulation::StateSelection,
        Formulation::StableInversion,
        Formulation::Redundant
    )
}

/// Every `NAME=VALUE` of a repeatable flag (`--limit`, `--min-tension`,
/// `--plant`), each name once: a second value for a name is an error, not
/// a silent override (`--limit u2=100 --limit u2=150` once kept 150).
pub fn name_values(
    flag: &'static str,
    items: &[String],
    bad: impl Fn(&str) -> CliError,
) -> Result<Vec<(String, f64)>, CliError> {
    let mut pairs: Vec<(String, f64)> = Vec::with_capacity(items.len());
    for item in items {
        let (name, value) = name_value(item, || bad(item))?;
        if let Some(&(_, first)) = pairs.iter().find(|(other, _)| *other == name) {
            return Err(CliError::Repeated {
                flag,
                name,
                first,
                second: value,
            });
        }
        pairs.push((name, value));
    }
    Ok(pairs)
}

/// `NAME=VALUE` of a flag such as `--plant m_l=110` or `--limit u2=150`,
/// or the error `bad()` makes (what the value may be is the library's to say).
pub fn name_value(item: &str, bad: impl Fn() -> CliError) -> Result<(String, f64), CliError> {
    let (name, value) = item.split_once('=').ok_or_else(&bad)?;
    let value: f64 = value.trim().parse().map_err(|_| bad())?;
    Ok((name.trim().to_string(), value))
}
