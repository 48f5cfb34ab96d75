//! `crane fmu`: package a crane as an FMI 2.0 co-simulation FMU.

use std::path::{Path, PathBuf};

use crane_fmi::start::Start;
use crane_models::Crane;
use crane_models::registry::{Registry, Visit};

use crate::scenario::{self, Overrides, ScenarioFile};
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
    /// A scenario file whose run the FMU starts from: its parameters,
    /// move (a spline move included: `path` = 4), step, scheme and
    /// formulation become the FMU's start values, packaged as
    /// resources/start.toml (limits and a replay's plant play no part).
    #[arg(long, value_name = "FILE.toml")]
    scenario: Option<PathBuf>,
}

/// Package the FMU of a crane.
struct Package<'a> {
    library: &'a Path,
    scenario: Option<&'a ScenarioFile>,
}

impl Visit for Package<'_> {
    /// The archive, and what the FMU starts from in words if not the
    /// crane's default.
    type Output = Result<(Vec<u8>, Option<String>), CliError>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let Some(file) = self.scenario else {
            let start = Start::default_for::<C, N, M>();
            return Ok((crane_fmi::package::archive::<C, N, M, A>(self.library, &start)?, None));
        };
        let spec = scenario::checked_spec::<C, N, M, A>(Some(file), &Overrides::default())?;
        let start = Start::packaged::<C, N, M>(&spec)?;
        let bytes = crane_fmi::package::archive::<C, N, M, A>(self.library, &start)?;
        let path = &start.spec.path;
        let mut words = match path.profile.kind().code() {
            Some(code) => format!(
                "a {} move (path = {code}) from t0 = {} s for {} s",
                path.profile.kind(),
                path.t0,
                path.t1 - path.t0
            ),
            None => format!(
                "the spline move (path = {}) from t0 = {} s for {} s",
                crane_fmi::variables::SPLINE_PATH,
                path.t0,
                path.t1 - path.t0
            ),
        };
        if !spec.limits.is_empty() {
            let limits: Vec<String> = spec.limits.iter().map(|(u, l)| format!("|{u}| <= {l}")).collect();
            words.push_str(&format!(
                "; the scenario's limits ({}) are not the FMU's: it computes the inputs, `crane run` checks them",
                limits.join(", ")
            ));
        }
        Ok((bytes, Some(words)))
    }
}

/// Write the FMU.
pub fn fmu<R: Registry>(tool: &Tool<R>, args: FmuArgs) -> Result<(), CliError> {
    let FmuArgs {
        model,
        out,
        library,
        scenario,
    } = args;
    tool.entry(&model)?;
    let scenario_path = scenario;
    let scenario = scenario_path.as_deref().map(ScenarioFile::load).transpose()?;
    if let Some(file) = &scenario
        && !file.plant.is_empty()
    {
        let names: Vec<&str> = file.plant.keys().map(String::as_str).collect();
        return Err(CliError::FmuPlant(names.join(", ")));
    }
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
    // refused before any work, as the packager refuses it
    if let Some(kind) = crane_models::files::not_a_regular_file(&out) {
        return Err(crane_fmi::package::PackageError::NotAFile { path: out, kind }.into());
    }
    if let Some(path) = &scenario_path
        && same_file(path, &out)
    {
        return Err(CliError::Output {
            what: out.display().to_string(),
            message: "it is the scenario itself: choose another --out".into(),
        });
    }
    let (bytes, packaged) = tool.dispatch(
        &model,
        Package {
            library: &library,
            scenario: scenario.as_ref(),
        },
    )?;
    crate::output::write_whole(&out, &bytes)?;
    say!(
        "wrote {} (FMI 2.0 co-simulation, binaries/linux64/{}.so)",
        out.display(),
        crane_fmi::description::model_identifier(&model)
    )?;
    if let Some(words) = packaged {
        say!(
            "  starting from the scenario's run (resources/{}): {words}",
            crane_fmi::start::RESOURCE
        )?;
    }
    Ok(())
}

/// Whether `a` and `b` name one existing file.
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}
