//! One module per command: its flags (`clap::Args`) and what it does with
//! them. A command on one crane is a [`Visit`] that [`dispatch`] runs on
//! the crane of that name with its sizes.

pub mod bench;
pub mod convergence;
pub mod fmu;
pub mod list;
pub mod plan;
pub mod run;

use std::path::{Path, PathBuf};

use crane_models::registry::{self, Visit};
use crane_models::study::Formulation;
use crane_runtime::Scheme;

use crate::CliError;

/// Run `job` on the built-in crane `name`.
pub fn dispatch<V: Visit<Output = Result<T, CliError>>, T>(name: &str, job: V) -> Result<T, CliError> {
    registry::visit(name, job).unwrap_or_else(|| Err(CliError::UnknownModel(name.to_string())))
}

/// The output directory: `out` if given, else `out/MODEL`.
pub fn out_dir(out: Option<&Path>, model: &str) -> PathBuf {
    out.map_or_else(|| PathBuf::from("out").join(model), Path::to_path_buf)
}

/// The help of a `--scheme` flag, from the one list of schemes.
pub fn scheme_help(default: Scheme) -> String {
    format!("Time-discretisation scheme: {} (default {default})", Scheme::help())
}

/// The help of a `--formulation` flag, from the one list of formulations.
pub fn formulation_help() -> String {
    format!("Formulation: {} (default redundant)", Formulation::help())
}
