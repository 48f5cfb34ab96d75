//! `crane`: run a crane's inverse dynamics and write results, summary and plots.
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

mod convergence;
mod output;
mod planning;
mod plot;
mod progress;
mod replay;
mod report;
mod scenario;
mod snapshots;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::{Parser, Subcommand};
use crane_models::registry::{self, Visit};
use crane_models::{CATALOG, Case, Crane};
use crane_runtime::{Options, Scheme};
use scenario::{Overrides, ScenarioFile};

/// Inverse dynamics of underactuated cranes: the torques that move the load
/// exactly along a prescribed path (backward Euler or BDF-k on the minimally
/// extended index-3 DAEs).
#[derive(Parser, Debug)]
#[command(name = "crane", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// List the built-in models with their sizes n, m, a, f.
    List,
    /// Run a model on its paper maneuver or a scenario; write results.csv, summary.json and SVG plots.
    Run {
        /// Model name (see `crane list`).
        model: String,
        /// Scenario file (TOML): load path, times, parameters, start, torque limits
        /// (see examples/); flags given on the command line override it.
        #[arg(long, value_name = "FILE.toml")]
        scenario: Option<PathBuf>,
        /// Time step in s (default 0.01).
        #[arg(long)]
        dt: Option<f64>,
        /// End time in s of the run (and of the motion unless the scenario sets t1;
        /// the paper uses 4 and 15 for navy-planar).
        #[arg(long)]
        tf: Option<f64>,
        /// Output directory (default out/MODEL).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Redundant coordinates (eqs. 22a-d) or minimal coordinates (eqs. 24a-e) (default redundant).
        #[arg(long, value_enum)]
        formulation: Option<Formulation>,
        /// Time-discretisation scheme: backward-euler (the paper's, default;
        /// also bdf1), bdf2, bdf3, bdf4 or bdf5 (order k).
        #[arg(long, value_name = "SCHEME")]
        scheme: Option<Scheme>,
        /// Exit non-zero if a rope goes slack, an input exceeds its limit or
        /// the internal dynamics are unstable (the results are still written).
        #[arg(long)]
        strict: bool,
        /// No progress bar (it is shown only on a terminal, for runs over a second).
        #[arg(long)]
        quiet: bool,
        /// Replay the computed torques on the crane's forward dynamics (dt/4,
        /// BDF-2, then a settling window with the torques held): writes
        /// replay.csv and replay.svg and adds "replay" to summary.json.
        #[arg(long)]
        replay: bool,
        /// With --replay: a plant parameter that differs from the planner's,
        /// NAME=VALUE (repeatable; adds to the scenario's [plant] table).
        #[arg(long = "plant", value_name = "NAME=VALUE")]
        plant: Vec<String>,
        /// With --replay: the settling window in s (default: twice the longest
        /// rope pendulum period 2 pi sqrt(L/g) at the end).
        #[arg(long, value_name = "SECONDS")]
        settle: Option<f64>,
        /// With --replay: add a PD law on the robot coordinates about the
        /// planned p(t): `default` (gains from the model) or `KP,KD` (the same
        /// stiffness and damping on every robot coordinate); the replay runs
        /// open loop too and replay.svg shows both.
        #[arg(long, value_name = "default|KP,KD")]
        feedback: Option<String>,
    },
    /// Time repeated runs without writing files; print median wall time per run and per step.
    Bench {
        /// Model name (see `crane list`).
        model: String,
        /// Time step in s.
        #[arg(long, default_value_t = 0.01)]
        dt: f64,
        /// Number of timed runs.
        #[arg(long, default_value_t = 20)]
        repeat: usize,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
        /// Redundant coordinates (eqs. 22a-d) or minimal coordinates (eqs. 24a-e).
        #[arg(long, value_enum, default_value_t = Formulation::Redundant)]
        formulation: Formulation,
        /// Time-discretisation scheme: backward-euler (the paper's, default;
        /// also bdf1), bdf2, bdf3, bdf4 or bdf5 (order k).
        #[arg(long, value_name = "SCHEME")]
        scheme: Option<Scheme>,
    },
    /// Convergence study: the relative error of u at t = 1.5 s (eq. 48) for
    /// dt = 0.1 ... 0.001 and the observed orders; writes convergence.svg
    /// (log-log, like Figs. 7 and 16, with the slope of the scheme's order)
    /// and convergence.csv.
    Convergence {
        /// Model name (see `crane list`); it needs an analytical reference.
        model: String,
        /// Scenario file (its dt is ignored).
        #[arg(long, value_name = "FILE.toml")]
        scenario: Option<PathBuf>,
        /// Redundant coordinates (eqs. 22a-d) or minimal coordinates (eqs. 24a-e) (default redundant).
        #[arg(long, value_enum)]
        formulation: Option<Formulation>,
        /// Time-discretisation scheme: backward-euler (the paper's, default;
        /// also bdf1), bdf2, bdf3, bdf4 or bdf5 (order k).
        #[arg(long, value_name = "SCHEME")]
        scheme: Option<Scheme>,
        /// Output directory (default out/MODEL).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// The shortest duration of the move's shape (start, end and profile of
    /// the scenario or the default manoeuvre, time scaled) for which every
    /// torque limit and tension floor holds; writes fastest.json and plots
    /// of u and the tensions with the limits.
    Fastest {
        /// Model name (see `crane list`).
        model: String,
        #[command(flatten)]
        plan: PlanFlags,
        /// Bisection tolerance on the duration, s.
        #[arg(long, default_value_t = 1e-3)]
        tolerance: f64,
        /// Print fastest.json on stdout instead of the summary.
        #[arg(long)]
        json: bool,
    },
    /// Peaks and feasibility over a grid of parameters (and durations), in
    /// parallel: sweep.csv, and for two swept quantities a heat map sweep.svg.
    Sweep {
        /// Model name (see `crane list`).
        model: String,
        /// A swept parameter, NAME=LOW:HIGH:COUNT (repeatable).
        #[arg(long = "param", value_name = "NAME=LOW:HIGH:COUNT")]
        param: Vec<String>,
        /// Swept durations of the move, LOW:HIGH:COUNT (default: its own).
        #[arg(long, value_name = "LOW:HIGH:COUNT")]
        duration: Option<String>,
        #[command(flatten)]
        plan: PlanFlags,
        /// Worker threads (default: one per core).
        #[arg(long)]
        threads: Option<usize>,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Write an FMI 2.0 co-simulation FMU of a built-in model (the inverse
    /// model: load target in, inputs, coordinates, multipliers and tensions
    /// out); see the README, "Using a crane in Simulink, Modelica or Python".
    Fmu {
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
    },
}

/// Which index-3 formulation to integrate.
#[derive(clap::ValueEnum, serde::Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum Formulation {
    /// Redundant coordinates, backward Euler on eqs. (22a-d).
    Redundant,
    /// Minimal coordinates, backward Euler on eqs. (24a-e).
    Minimal,
}

impl Formulation {
    /// The name used in `summary.json`.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::Redundant => "redundant",
            Formulation::Minimal => "minimal",
        }
    }

    /// Integrate `case` from `start` with this formulation.
    fn simulate<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
        self,
        case: &Case<C, N, M, A>,
        start: &crane_runtime::State<N, M, A>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<crane_runtime::Solution<N, M, A>, CliError> {
        match self {
            Formulation::Redundant => Ok(case.simulate_with_progress(start, options, progress)?),
            Formulation::Minimal => case
                .simulate_minimal_with_progress(start, options, progress)
                .ok_or_else(|| CliError::NoMinimalMap(C::NAME.to_string()))?
                .map_err(CliError::from),
        }
    }
}

/// The flags `crane fastest` and `crane sweep` share.
#[derive(clap::Args, Debug)]
struct PlanFlags {
    /// Scenario file: the path shape, parameters and [limits].
    #[arg(long, value_name = "FILE.toml")]
    scenario: Option<PathBuf>,
    /// A limit |u| <= VALUE on an input, NAME=VALUE (repeatable).
    #[arg(long = "limit", value_name = "NAME=VALUE")]
    limit: Vec<String>,
    /// A floor N >= VALUE on a rope tension, NAME=VALUE (repeatable; ropes
    /// without one must stay taut).
    #[arg(long = "min-tension", value_name = "NAME=VALUE")]
    min_tension: Vec<String>,
    /// Scheme of the runs (default bdf4).
    #[arg(long, value_name = "SCHEME")]
    scheme: Option<Scheme>,
    /// Largest time step of the runs, s (default 0.05).
    #[arg(long)]
    dt: Option<f64>,
    /// Output directory (default out/MODEL).
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Errors the command reports (then exits non-zero).
#[derive(Debug, thiserror::Error)]
enum CliError {
    #[error("unknown model `{0}`; `crane list` shows the built-in models")]
    UnknownModel(String),
    #[error(transparent)]
    Runtime(#[from] crane_runtime::Error),
    #[error(transparent)]
    Trajectory(#[from] crane_runtime::trajectory::TrajectoryError),
    #[error("{context}: {source}")]
    Io { context: String, source: std::io::Error },
    #[error("writing {what}: {message}")]
    Output { what: String, message: String },
    #[error("model `{0}` declares no minimal-coordinate map; use --formulation redundant")]
    NoMinimalMap(String),
    #[error("--repeat must be at least 1")]
    NoRepeats,
    #[error("--plant `{0}`: expected NAME=VALUE, e.g. --plant m_l=110")]
    Plant(String),
    #[error("--feedback `{0}`: expected `default` or KP,KD (two numbers >= 0), e.g. --feedback 5000,2000")]
    Feedback(String),
    #[error("plant parameter `{name}`: {message}")]
    PlantParameter { name: String, message: String },
    #[error(transparent)]
    Scenario(#[from] scenario::ScenarioError),
    #[error("infeasible (--strict): {problems}; the results were still written to {out}")]
    Infeasible { problems: String, out: String },
    #[error("{0}")]
    Convergence(String),
    #[error("{0}")]
    Planning(String),
    #[error("no FMU library at {0}: build it with `cargo build --release -p crane-fmu` or give --library")]
    NoFmuLibrary(String),
    #[error(transparent)]
    Package(#[from] crane_fmi::package::PackageError),
}

/// A command on one crane, run by [`registry::visit`] with the crane's
/// description and sizes.
enum Job<'a> {
    Run {
        settings: RunSettings<'a>,
        file: Option<&'a ScenarioFile>,
        overrides: Overrides,
    },
    Bench {
        overrides: Overrides,
        repeat: usize,
        json: bool,
    },
    Convergence {
        file: Option<&'a ScenarioFile>,
        overrides: Overrides,
        out: &'a std::path::Path,
    },
    Fastest {
        file: Option<&'a ScenarioFile>,
        plan: PlanArgs<'a>,
        json: bool,
    },
    Sweep {
        file: Option<&'a ScenarioFile>,
        plan: PlanArgs<'a>,
        params: &'a [String],
        durations: Vec<f64>,
        quiet: bool,
    },
}

/// What `crane fastest` and `crane sweep` share.
struct PlanArgs<'a> {
    limit: &'a [String],
    min_tension: &'a [String],
    settings: crane_models::plan::Settings,
    out: &'a std::path::Path,
}

impl Visit for Job<'_> {
    type Output = Result<Option<report::Summary>, CliError>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        match self {
            Job::Run {
                settings,
                file,
                overrides,
            } => {
                let (case, run_settings) = scenario::build::<C, N, M, A>(file, &overrides)?;
                run(&case, &settings, &run_settings).map(Some)
            }
            Job::Bench {
                overrides,
                repeat,
                json,
            } => {
                let (case, settings) = scenario::build::<C, N, M, A>(None, &overrides)?;
                bench(&case, settings.formulation, settings.scheme, settings.dt, repeat, json).map(|()| None)
            }
            Job::Convergence { file, overrides, out } => {
                let (case, settings) = scenario::build::<C, N, M, A>(file, &overrides)?;
                convergence::run(&case, settings.formulation, settings.scheme, out).map(|()| None)
            }
            Job::Fastest { file, plan, json } => {
                let (case, settings) = scenario::build::<C, N, M, A>(file, &Overrides::default())?;
                let limits = planning::limits::<C::Model, N, M, A>(&settings.limits, plan.limit, plan.min_tension)?;
                planning::fastest(&case, &limits, &plan.settings, plan.out, json).map(|()| None)
            }
            Job::Sweep {
                file,
                plan,
                params,
                durations,
                quiet,
            } => {
                let (case, settings) = scenario::build::<C, N, M, A>(file, &Overrides::default())?;
                let limits = planning::limits::<C::Model, N, M, A>(&settings.limits, plan.limit, plan.min_tension)?;
                let params = params
                    .iter()
                    .map(|p| planning::range("--param", p))
                    .collect::<Result<Vec<_>, _>>()?;
                planning::sweep(&case, &params, &durations, &limits, &plan.settings, plan.out, quiet).map(|()| None)
            }
        }
    }
}

/// The internal dynamics at the start of a crane's default manoeuvre, for
/// `crane list`: `0 (flat)`, `2 stable`, `2 unstable`, or `?` where the
/// diagnosis cannot tell.
struct InternalAtStart;

impl Visit for InternalAtStart {
    type Output = String;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> String {
        let diagnosis = Case::<C, N, M, A>::maneuver().ok().and_then(|case| {
            let start = case.start().ok()?;
            crane_runtime::internal::internal_dynamics(case.model(), &start).ok()
        });
        match diagnosis {
            Some(d) if d.dimension == 0 => "0 (flat)".into(),
            Some(d) => format!("{} {}", d.dimension, if d.is_stable() { "stable" } else { "unstable" }),
            None => "?".into(),
        }
    }
}

/// Package the FMU of a crane.
struct Package<'a> {
    library: &'a std::path::Path,
    out: &'a std::path::Path,
}

impl Visit for Package<'_> {
    type Output = Result<(), CliError>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        Ok(crane_fmi::package::package::<C, N, M, A>(self.library, self.out)?)
    }
}

/// Run `job` on the built-in crane `name`.
fn dispatch(name: &str, job: Job) -> Result<Option<report::Summary>, CliError> {
    registry::visit(name, job).unwrap_or_else(|| Err(CliError::UnknownModel(name.to_string())))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match execute(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

fn execute(command: Command) -> Result<(), CliError> {
    match command {
        Command::List => {
            let width = CATALOG.iter().map(|e| e.name.len()).max().unwrap_or(5);
            println!(
                "{:<width$} {:>3} {:>3} {:>3} {:>3}  {:<9} {:<7} {:<10} description",
                "model", "n", "m", "a", "f", "reference", "minimal", "internal"
            );
            let yes = |b: bool| if b { "yes" } else { "no" };
            for e in CATALOG {
                let internal = registry::visit(e.name, InternalAtStart).unwrap_or_else(|| "?".into());
                println!(
                    "{:<width$} {:>3} {:>3} {:>3} {:>3}  {:<9} {:<7} {:<10} {}",
                    e.name,
                    e.n,
                    e.m,
                    e.a,
                    e.dof(),
                    yes(e.reference),
                    yes(e.minimal),
                    internal,
                    e.description
                );
            }
            Ok(())
        }
        Command::Run {
            model,
            scenario,
            dt,
            tf,
            out,
            formulation,
            scheme,
            strict,
            quiet,
            replay,
            plant,
            settle,
            feedback,
        } => {
            let file = scenario.as_deref().map(ScenarioFile::load).transpose()?;
            let out = out.unwrap_or_else(|| PathBuf::from("out").join(&model));
            let overrides = Overrides {
                dt,
                tf,
                formulation,
                scheme,
            };
            let plant = plant
                .iter()
                .map(|item| {
                    let (name, value) = item.split_once('=').ok_or_else(|| CliError::Plant(item.clone()))?;
                    let value: f64 = value.trim().parse().map_err(|_| CliError::Plant(item.clone()))?;
                    Ok((name.trim().to_string(), value))
                })
                .collect::<Result<Vec<_>, CliError>>()?;
            let settings = RunSettings {
                name: &model,
                out: &out,
                quiet,
                replay: replay.then_some(ReplayRequest {
                    plant,
                    settle,
                    feedback: feedback.as_deref().map(replay::FeedbackSpec::parse).transpose()?,
                }),
            };
            let summary = dispatch(
                &model,
                Job::Run {
                    settings,
                    file: file.as_ref(),
                    overrides,
                },
            )?
            .expect("a run returns its summary");
            let problems = report::infeasibilities(&summary);
            if strict && !problems.is_empty() {
                return Err(CliError::Infeasible {
                    problems: problems.join("; "),
                    out: out.display().to_string(),
                });
            }
            Ok(())
        }
        Command::Bench {
            model,
            dt,
            repeat,
            json,
            formulation,
            scheme,
        } => {
            let overrides = Overrides {
                dt: Some(dt),
                tf: None,
                formulation: Some(formulation),
                scheme,
            };
            dispatch(
                &model,
                Job::Bench {
                    overrides,
                    repeat,
                    json,
                },
            )
            .map(|_| ())
        }
        Command::Fastest {
            model,
            plan,
            tolerance,
            json,
        } => {
            let (file, out) = plan.files(&model)?;
            let plan = plan.args(plan.settings(Some(tolerance))?, &out);
            dispatch(
                &model,
                Job::Fastest {
                    file: file.as_ref(),
                    plan,
                    json,
                },
            )
            .map(|_| ())
        }
        Command::Sweep {
            model,
            param,
            duration,
            plan,
            threads,
            quiet,
        } => {
            let (file, out) = plan.files(&model)?;
            let settings = plan.settings(None)?;
            let durations = match duration.as_deref() {
                Some(spec) => planning::values(spec)
                    .filter(|d| d.iter().all(|&x| x > 0.0))
                    .ok_or_else(|| {
                        CliError::Planning(format!(
                            "--duration `{spec}`: expected LOW:HIGH:COUNT of positive durations, e.g. 3:5:5"
                        ))
                    })?,
                None => Vec::new(),
            };
            if param.is_empty() && durations.len() < 2 {
                return Err(CliError::Planning(
                    "nothing to sweep: give --param NAME=LOW:HIGH:COUNT or --duration LOW:HIGH:COUNT".into(),
                ));
            }
            let plan = plan.args(settings, &out);
            let job = || {
                dispatch(
                    &model,
                    Job::Sweep {
                        file: file.as_ref(),
                        plan,
                        params: &param,
                        durations,
                        quiet,
                    },
                )
                .map(|_| ())
            };
            match threads {
                Some(0) => Err(CliError::Planning("--threads must be at least 1".into())),
                Some(n) => rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .map_err(|e| CliError::Planning(format!("--threads {n}: {e}")))?
                    .install(job),
                None => job(),
            }
        }
        Command::Fmu { model, out, library } => {
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
            registry::visit(
                &model,
                Package {
                    library: &library,
                    out: &out,
                },
            )
            .unwrap_or_else(|| Err(CliError::UnknownModel(model.clone())))?;
            println!(
                "wrote {} (FMI 2.0 co-simulation, binaries/linux64/{}.so)",
                out.display(),
                crane_fmi::description::model_identifier(&model)
            );
            Ok(())
        }
        Command::Convergence {
            model,
            scenario,
            formulation,
            scheme,
            out,
        } => {
            let file = scenario.as_deref().map(ScenarioFile::load).transpose()?;
            let out = out.unwrap_or_else(|| PathBuf::from("out").join(&model));
            let overrides = Overrides {
                dt: None,
                tf: None,
                formulation,
                scheme,
            };
            dispatch(
                &model,
                Job::Convergence {
                    file: file.as_ref(),
                    overrides,
                    out: &out,
                },
            )
            .map(|_| ())
        }
    }
}

impl PlanFlags {
    /// The scenario file (loaded) and the output directory.
    fn files(&self, model: &str) -> Result<(Option<ScenarioFile>, PathBuf), CliError> {
        let file = self.scenario.as_deref().map(ScenarioFile::load).transpose()?;
        Ok((
            file,
            self.out.clone().unwrap_or_else(|| PathBuf::from("out").join(model)),
        ))
    }

    /// The planner's settings from the flags (BDF-4, dt 0.05 s, 1 ms by default).
    fn settings(&self, tolerance: Option<f64>) -> Result<crane_models::plan::Settings, CliError> {
        let defaults = crane_models::plan::Settings::default();
        let dt = self.dt.unwrap_or(defaults.dt);
        let tolerance = tolerance.unwrap_or(defaults.tolerance);
        if !(dt > 0.0 && dt.is_finite() && tolerance > 0.0 && tolerance.is_finite()) {
            return Err(CliError::Planning(format!(
                "--dt {dt} and --tolerance {tolerance} must be positive"
            )));
        }
        Ok(crane_models::plan::Settings {
            dt,
            scheme: self.scheme.unwrap_or(defaults.scheme),
            tolerance,
            ..defaults
        })
    }

    /// What the jobs need of the flags.
    fn args<'a>(&'a self, settings: crane_models::plan::Settings, out: &'a std::path::Path) -> PlanArgs<'a> {
        PlanArgs {
            limit: &self.limit,
            min_tension: &self.min_tension,
            settings,
            out,
        }
    }
}

/// What `crane run` was asked to do.
struct RunSettings<'a> {
    name: &'a str,
    out: &'a std::path::Path,
    quiet: bool,
    /// `--replay` and its options.
    replay: Option<ReplayRequest>,
}

/// What `--replay` asks for.
struct ReplayRequest {
    /// `--plant NAME=VALUE` overrides (after the scenario's `[plant]`).
    plant: Vec<(String, f64)>,
    /// `--settle`.
    settle: Option<f64>,
    /// `--feedback`.
    feedback: Option<replay::FeedbackSpec>,
}

/// Run one case and write its outputs.
fn run<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    settings: &RunSettings,
    scenario: &scenario::Settings,
) -> Result<report::Summary, CliError> {
    let RunSettings { name, out, quiet, .. } = *settings;
    let (dt, formulation) = (scenario.dt, scenario.formulation);
    let start = case.start()?;
    let options = Options::new(dt, case.tf())?.with_scheme(scenario.scheme);
    let clock = Instant::now();
    let mut progress = progress::Progress::new(name, quiet);
    let solution = formulation.simulate(case, &start, &options, &mut |step, steps| progress.tick(step, steps));
    progress.finish();
    let solution = solution?;
    let wall = clock.elapsed().as_secs_f64();
    // the reference is evaluated where it is needed, never stored per step
    let (t0, tf) = (case.t0(), case.tf());
    let reference_at = |t: f64| case.reference(t);
    let has_reference = C::HAS_REFERENCE && case.reference(t0).is_some();
    let summary = report::summarize(
        name,
        formulation.name(),
        &solution,
        has_reference.then_some(&reference_at as &dyn Fn(f64) -> Option<crane_runtime::State<N, M, A>>),
        &scenario.limits,
        wall,
    );
    // the reference curves of the plots on a grid as fine as the plot shows
    let samples = solution.steps().clamp(800, plot::MAX_POINTS);
    let fine: Option<Vec<_>> = has_reference
        .then(|| {
            (0..=samples)
                .map(|i| case.reference(t0 + (tf - t0) * i as f64 / samples as f64))
                .collect()
        })
        .flatten();
    let snapshots = snapshots::svg(C::drawing(case.model()), &solution)?.map(|svg| ("snapshots.svg".to_string(), svg));
    let derived = output::Derived {
        names: case.derived_outputs(),
        values: &|s| case.derived(s),
    };
    let mut summary = summary;
    summary.internal_dynamics = report::internal_summary(case.model(), &solution);
    let internal = &summary.internal_dynamics;
    if !internal.stable {
        eprintln!(
            "warning: {name} has unstable internal dynamics along this path (dimension {}, largest real part {:.4} 1/s at t = {} s): the computed inputs grow without bound; see the README, \"Flat and non-flat cranes\"",
            internal.dimension,
            internal.max_real_part.unwrap_or(f64::NAN),
            crane_runtime::error::Seconds(internal.at.unwrap_or(f64::NAN)),
        );
    }
    if let Some(smooth) = crane_runtime::internal::path_smoothness::<C::Model, _, N, M, A>(case.path()) {
        summary.path_smoothness = Some(report::PathSmoothnessSummary {
            needed: smooth.needed,
            continuous: smooth.continuous,
            sufficient: smooth.is_sufficient(),
        });
        if !smooth.is_sufficient() {
            eprintln!(
                "warning: the inputs of {name} depend on the load path's derivatives up to order {}, but this path is continuous only up to order {}: the exact inputs jump or carry impulses where its derivative {} jumps, and the computed ones grow there as dt shrinks (use a smoother path, e.g. trajectory = \"smooth-three-phase\")",
                smooth.needed,
                smooth.continuous,
                smooth.continuous + 1
            );
        }
    }
    let internal = &summary.internal_dynamics;
    if let Some(t) = internal.runaway_at {
        eprintln!(
            "warning: an input of {name} exceeds 1e6 times its size at the start from t = {} s: not a physical result",
            crane_runtime::error::Seconds(t)
        );
    }
    let mut extra: Vec<(String, String)> = snapshots.into_iter().collect();
    if let Some(request) = &settings.replay {
        let plant_values = scenario
            .plant
            .iter()
            .cloned()
            .chain(request.plant.iter().cloned())
            .collect::<Vec<_>>();
        let (replay_summary, files) = replay::run(case, &solution, &plant_values, request.settle, request.feedback)?;
        extra.extend(files);
        summary.replay = Some(replay_summary);
    }
    output::write_all(out, &solution, fine.as_deref(), &summary, &derived, &extra)?;
    println!(
        "{name} ({}, {}): {} steps of dt = {dt} s in {:.1} ms ({:.2} Newton iterations per step)",
        formulation.name(),
        scenario.scheme,
        solution.steps(),
        wall * 1e3,
        solution.mean_newton_iterations()
    );
    if solution.redundant_start_steps > 0 {
        let k = solution.redundant_start_steps;
        println!(
            "  first {k} steps (to t = {} s) in redundant coordinates: a rope carries under {:e} of the largest tension (degenerate start)",
            crane_runtime::error::Seconds(solution.states[k].t),
            crane_runtime::minimal::DEGENERATE_TENSION_RATIO
        );
    }
    for line in report::highlights(&summary) {
        println!("  {line}");
    }
    println!("wrote {}", out.display());
    Ok(summary)
}

/// Time `repeat` runs of one case.
fn bench<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    formulation: Formulation,
    scheme: Scheme,
    dt: f64,
    repeat: usize,
    json: bool,
) -> Result<(), CliError> {
    if repeat == 0 {
        return Err(CliError::NoRepeats);
    }
    let name = C::NAME;
    let start = case.start()?;
    let options = Options::new(dt, case.tf())?.with_scheme(scheme);
    let mut times = Vec::with_capacity(repeat);
    let mut steps = 0;
    let mut iterations = 0.0;
    formulation.simulate(case, &start, &options, &mut |_, _| {})?; // warm-up
    for _ in 0..repeat {
        let clock = Instant::now();
        let solution = formulation.simulate(case, &start, &options, &mut |_, _| {})?;
        times.push(clock.elapsed().as_secs_f64());
        steps = solution.steps();
        iterations = solution.mean_newton_iterations();
    }
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    if json {
        let value = serde_json::json!({
            "model": name, "formulation": formulation.name(), "scheme": scheme.name(), "dt": dt, "steps": steps, "repeat": repeat,
            "median_run_s": median, "median_step_s": median / steps as f64,
            "mean_newton_iterations": iterations,
        });
        println!("{value}");
    } else {
        println!(
            "{name} ({}, {scheme}): dt = {dt} s, {steps} steps, {repeat} runs: median {:.3} ms per run, {:.2} us per step, {:.2} Newton iterations per step",
            formulation.name(),
            median * 1e3,
            median / steps as f64 * 1e6,
            iterations
        );
    }
    Ok(())
}
