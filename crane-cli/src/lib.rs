//! The command line of a crane tool as a library: `crane` is this with the
//! built-in cranes, and a user's binary of a few lines is the same tool for
//! the cranes of its own [`Registry`] (see [`Tool`]):
//!
//! ```text
//! crane list
//! crane run navy-planar [--scenario FILE.toml] [--dt 0.01] [--tf 4] [--scheme bdf4] [--out out/navy-planar] [--strict]
//! crane convergence navy-planar [--formulation minimal] [--scheme bdf4]
//! crane bench navy-planar [--dt 0.01] [--scheme bdf4] [--repeat 20] [--json]
//! crane fmu navy-planar [--out out/navy-planar.fmu] [--library target/release/libcrane_fmu.so]
//! crane fastest navy-planar --limit u2=150 [--min-tension N1=0] [--scenario FILE] [--json]
//! crane sweep navy-planar --param m_l=80:120:5 [--duration 3:5:5] [--limit u2=150]
//! ```
//!
//! This file holds the command line (clap) and the dispatch; each command
//! lives in `commands/`, what a run means in `crane_models::study`.
#![warn(missing_docs)]

/// `println!` that returns the error of a closed or full standard output
/// instead of panicking: `say!("wrote {}", out.display())?;`.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::output::say(format_args!($($arg)*))
    };
}

mod commands;
mod error;
mod output;
mod plot;
mod progress;
pub mod scenario;
mod snapshots;

use std::ffi::OsString;
use std::path::Path;
use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use crane_models::registry::{Entry, Registry, Visit};

use error::CliError;

/// Inverse dynamics of underactuated cranes: the torques that move the load
/// exactly along a prescribed path (backward Euler or BDF-k on the minimally
/// extended index-3 DAEs).
#[derive(Parser, Debug)]
#[command(name = "crane")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// List the models with their sizes n, m, a, f.
    List,
    /// Run a model on its paper maneuver or a scenario; write results.csv, summary.json and SVG plots.
    Run(commands::run::RunArgs),
    /// Time repeated runs without writing files; print median wall time per run and per step.
    Bench(commands::bench::BenchArgs),
    /// Convergence study: the relative error of u at t = 1.5 s (eq. 48) for
    /// dt = 0.1 ... 0.001 and the observed orders; writes convergence.svg
    /// (log-log, like Figs. 7 and 16, with the slope of the scheme's order)
    /// and convergence.csv.
    Convergence(commands::convergence::ConvergenceArgs),
    /// The shortest duration of the move's shape (start, end and profile of
    /// the scenario or the default manoeuvre, time scaled) for which every
    /// torque limit and tension floor holds; writes fastest.json and plots
    /// of u and the tensions with the limits.
    Fastest(commands::plan::FastestArgs),
    /// Peaks and feasibility over a grid of parameters (and durations), in
    /// parallel: sweep.csv, and for two swept quantities a heat map sweep.svg.
    Sweep(commands::plan::SweepArgs),
    /// Write an FMI 2.0 co-simulation FMU of a model (the inverse
    /// model: load target in, inputs, coordinates, multipliers and tensions
    /// out); see docs/fmi.md in the guide.
    Fmu(commands::fmu::FmuArgs),
}

/// A crane tool's command line: `list | run | bench | convergence |
/// fastest | sweep | fmu` over the cranes of a [`Registry`], with the flags,
/// scenario files, outputs and plots of `crane`.
///
/// A user's binary (`src/main.rs` of a crate whose library declares the
/// cranes, lists them with `registry!` and exports the same registry with
/// `export_fmu!(registry = (MyCranes, BuiltIn))`, so that `fmu` packages a
/// library that has every crane the binary lists):
///
/// ```no_run
/// use crane_models::{BuiltIn, gantry_3d};
///
/// crane_models::registry! {
///     /// The cranes of this tool.
///     pub struct MyCranes { gantry_3d::Description }
/// }
///
/// fn main() -> std::process::ExitCode {
///     // the user's cranes first, then the built-in ones
///     crane_cli::Tool::new((MyCranes, BuiltIn)).main()
/// }
/// ```
#[derive(Debug, Clone)]
pub struct Tool<R> {
    registry: R,
    program: Option<String>,
    fmu_library: Option<String>,
}

impl<R: Registry> Tool<R> {
    /// The tool of the cranes of `registry`, named as its executable.
    pub fn new(registry: R) -> Self {
        Tool {
            registry,
            program: None,
            fmu_library: None,
        }
    }

    /// The program name in help and messages (default: the executable's file name).
    pub fn program(mut self, name: &str) -> Self {
        self.program = Some(name.to_string());
        self
    }

    /// The file name of the shared library `fmu` packages, looked for next
    /// to the executable (default `lib<program>.so` with `-` as `_`, the
    /// `cdylib` of a crate named like the program; `--library` overrides).
    pub fn fmu_library(mut self, file_name: &str) -> Self {
        self.fmu_library = Some(file_name.to_string());
        self
    }

    /// The registry.
    pub fn registry(&self) -> &R {
        &self.registry
    }

    /// The program name.
    fn name(&self) -> String {
        self.program.clone().unwrap_or_else(|| {
            std::env::args_os()
                .next()
                .and_then(|arg0| Path::new(&arg0).file_stem().map(|s| s.to_string_lossy().into_owned()))
                .unwrap_or_else(|| "crane".into())
        })
    }

    /// The file name of the FMU library.
    fn library_name(&self) -> String {
        self.fmu_library
            .clone()
            .unwrap_or_else(|| format!("lib{}.so", self.name().replace('-', "_")))
    }

    /// The registry's entry of the crane `name`.
    fn entry(&self, name: &str) -> Result<Entry, CliError> {
        self.registry
            .entries()
            .into_iter()
            .find(|e| e.name == name)
            .ok_or_else(|| self.unknown(name))
    }

    /// Run `job` on the crane `name`.
    fn dispatch<V: Visit<Output = Result<T, CliError>>, T>(&self, name: &str, job: V) -> Result<T, CliError> {
        self.registry
            .visit(name, job)
            .unwrap_or_else(|| Err(self.unknown(name)))
    }

    /// The error for a name the registry does not know.
    fn unknown(&self, name: &str) -> CliError {
        CliError::UnknownModel {
            name: name.to_string(),
            program: self.name(),
        }
    }

    /// Parse the process's arguments, run the command, print its error:
    /// the whole `main` of a crane tool.
    pub fn main(&self) -> ExitCode {
        self.main_from(std::env::args_os())
    }

    /// [`main`](Self::main) on the arguments given (the first is the program).
    pub fn main_from<I: IntoIterator<Item = T>, T: Into<OsString> + Clone>(&self, args: I) -> ExitCode {
        let name = self.name();
        let matches = Cli::command()
            .name(name.clone())
            .bin_name(name)
            .version(env!("CARGO_PKG_VERSION"))
            .get_matches_from(args);
        let cli = match Cli::from_arg_matches(&matches) {
            Ok(cli) => cli,
            Err(error) => error.exit(),
        };
        output::remove_partials_on_signals();
        match self.execute(cli.command) {
            Ok(()) => ExitCode::SUCCESS,
            // the reader has all it wanted (`crane list | head -1`)
            Err(CliError::Stdout(error)) if error.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
            Err(error) => {
                eprintln!("error: {error}");
                ExitCode::FAILURE
            }
        }
    }

    /// Run one command.
    fn execute(&self, command: Command) -> Result<(), CliError> {
        match command {
            Command::List => commands::list::list(self),
            Command::Run(args) => commands::run::run(self, args),
            Command::Bench(args) => commands::bench::bench(self, args),
            Command::Convergence(args) => commands::convergence::convergence(self, args),
            Command::Fastest(args) => commands::plan::fastest(self, args),
            Command::Sweep(args) => commands::plan::sweep(self, args),
            Command::Fmu(args) => commands::fmu::fmu(self, args),
        }
    }
}
