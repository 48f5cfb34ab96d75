//! `crane fmu`: package a crane as an FMI 2.0 co-simulation FMU.

use std::path::{Path, PathBuf};

use crane_models::Crane;
use crane_models::registry::{Registry, Visit};

use crate::{CliError, Tool};

/// The flags of `crane fmu`.
#[derive(clap::Args, Debug)]
pub struct FmuArgs {
    /// Model name (see `list`).
    model: String,
    /// The FMU to write (default out/MODEL.fmu).
    #[arg(long, value_name = "FILE.fmu")]
    out: Option<PathBuf>,
    /// The shared library that exports the crane's FMI functions (default:
    /// the tool's library next to this executable, libcrane_fmu.so for
    /// `crane`, as `cargo build --release` leaves it).
    #[arg(long, value_name = "FILE.so")]
    library: Option<PathBuf>,
}

/// Package the FMU of a crane.
struct Package<'a> {
    library: &'a Path,
    out: &'a Path,
}

impl Visit for Package<'_> {
    type Output = Result<(), CliError>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        Ok(crane_fmi::package::package::<C, N, M, A>(self.library, self.out)?)
    }
}

/// Write the FMU.
pub fn fmu<R: Registry>(tool: &Tool<R>, args: FmuArgs) -> Result<(), CliError> {
    let FmuArgs { model, out, library } = args;
    tool.entry(&model)?;
    let out = out.unwrap_or_else(|| PathBuf::from("out").join(format!("{model}.fmu")));
    let library = match library {
        Some(path) => path,
        None => std::env::current_exe()
            .map_err(|source| CliError::Io {
                context: "locating the crane executable".into(),
                source,
            })?
            .with_file_name(tool.library_name()),
    };
    if !library.is_file() {
        return Err(CliError::NoFmuLibrary(library.display().to_string()));
    }
    tool.dispatch(
        &model,
        Package {
            library: &library,
            out: &out,
        },
    )?;
    say!(
        "wrote {} (FMI 2.0 co-simulation, binaries/linux64/{}.so)",
        out.display(),
        crane_fmi::description::model_identifier(&model)
    )?;
    Ok(())
}
