//! `crane fmu`: package a built-in crane as an FMI 2.0 co-simulation FMU.

use std::path::{Path, PathBuf};

use crane_models::Crane;
use crane_models::registry::Visit;

use super::dispatch;
use crate::CliError;

/// The flags of `crane fmu`.
#[derive(clap::Args, Debug)]
pub struct FmuArgs {
    /// Model name (see `crane list`).
    model: String,
    /// The FMU to write (default out/MODEL.fmu).
    #[arg(long, value_name = "FILE.fmu")]
    out: Option<PathBuf>,
    /// The shared library of the built-in FMUs (default: libcrane_fmu.so
    /// next to this executable, as `cargo build --release --workspace`
    /// leaves it).
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
pub fn fmu(args: FmuArgs) -> Result<(), CliError> {
    let FmuArgs { model, out, library } = args;
    let out = out.unwrap_or_else(|| PathBuf::from("out").join(format!("{model}.fmu")));
    let library = match library {
        Some(path) => path,
        None => std::env::current_exe()
            .map_err(|source| CliError::Io {
                context: "locating the crane executable".into(),
                source,
            })?
            .with_file_name("libcrane_fmu.so"),
    };
    if !library.is_file() {
        return Err(CliError::NoFmuLibrary(library.display().to_string()));
    }
    dispatch(
        &model,
        Package {
            library: &library,
            out: &out,
        },
    )?;
    println!(
        "wrote {} (FMI 2.0 co-simulation, binaries/linux64/{}.so)",
        out.display(),
        crane_fmi::description::model_identifier(&model)
    );
    Ok(())
}
