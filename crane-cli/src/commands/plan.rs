//! `crane fastest` and `crane sweep`: the planning functions of
//! `crane_models::plan` on the command line, with their files.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use crane_models::PathSpec;
use crane_models::plan::{self, Limits, MAX_SWEEP_POINTS, Settings, ShapeSettings};
use crane_models::registry::{Registry, Visit};
use crane_models::study::Formulation;
use crane_models::{Case, Crane};
use crane_runtime::error::{Number, Rounded};
use crane_runtime::{CraneModel, Scheme};

use super::{name_values, out_dir};
use crate::output::{Claim, Staged};
use crate::plot;
use crate::scenario::{self, Overrides, ScenarioFile};
use crate::{CliError, Tool};

/// The most worker threads `crane sweep` starts: beyond the cores they gain
/// nothing, and tens of thousands once hung the process at exit.
pub const MAX_THREADS: usize = 256;

/// The flags `crane fastest` and `crane sweep` share.
#[derive(clap::Args, Debug)]
pub struct PlanFlags {
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
    #[arg(long, value_name = "SCHEME", help = super::scheme_help(Settings::default().scheme))]
    scheme: Option<Scheme>,
    /// Largest time step of the runs, s (default 0.05).
    #[arg(long)]
    dt: Option<f64>,
    /// Output directory (default out/MODEL).
    #[arg(long)]
    out: Option<PathBuf>,
}

/// The flags of `crane fastest`.
#[derive(clap::Args, Debug)]
// a negative number is a value to check, not a flag
#[command(allow_negative_numbers = true)]
pub struct FastestArgs {
    /// Model name (see `list`).
    model: String,
    #[command(flatten)]
    plan: PlanFlags,
    /// Bisection tolerance on the duration, s.
    #[arg(long, default_value_t = 1e-3)]
    tolerance: f64,
    /// The path's shape: `time-scaled` (the scenario's own path, scaled in
    /// time) or `optimal` (a spline's shape optimised with the duration).
    #[arg(long, value_enum, default_value_t = Shape::TimeScaled)]
    shape: Shape,
    /// Free control points per load coordinate of an optimal shape.
    #[arg(long, default_value_t = ShapeSettings::default().control_points)]
    control_points: usize,
    /// Print fastest.json on stdout instead of the summary.
    #[arg(long)]
    json: bool,
    /// No progress display.
    #[arg(long)]
    quiet: bool,
}

/// What `crane fastest` shapes.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// The path's own shape, scaled in time.
    TimeScaled,
    /// The shape optimised with the duration.
    Optimal,
}

/// The flags of `crane sweep`.
#[derive(clap::Args, Debug)]
// a negative number is a value to check, not a flag
#[command(allow_negative_numbers = true)]
pub struct SweepArgs {
    /// Model name (see `list`).
    model: String,
    /// A swept parameter, NAME=LOW:HIGH:COUNT (repeatable).
    #[arg(long = "param", value_name = "NAME=LOW:HIGH:COUNT")]
    param: Vec<String>,
    /// Swept durations of the move, LOW:HIGH:COUNT (default: its own).
    #[arg(long, value_name = "LOW:HIGH:COUNT", allow_hyphen_values = true)]
    duration: Option<String>,
    /// Any set of points instead of a grid: a CSV file whose columns are
    /// parameter names (and `duration`, else the move's own), a point per
    /// row.
    #[arg(long, value_name = "FILE.csv", conflicts_with_all = ["param", "duration"])]
    points: Option<PathBuf>,
    #[command(flatten)]
    plan: PlanFlags,
    /// Worker threads (default: one per core).
    #[arg(long)]
    threads: Option<usize>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

impl PlanFlags {
    /// The scenario file (loaded) and the output directory, claimed.
    fn files(&self, model: &str) -> Result<(Option<ScenarioFile>, PathBuf, Claim), CliError> {
        let file = self.scenario.as_deref().map(ScenarioFile::load).transpose()?;
        let (out, claim) = out_dir(self.out.as_deref(), model)?;
        Ok((file, out, claim))
    }

    /// The planner's settings from the flags (BDF-4, dt 0.05 s, 1 ms by default).
    fn settings(&self, tolerance: Option<f64>) -> Result<Settings, CliError> {
        Settings::with(self.dt, self.scheme, tolerance).map_err(|e| CliError::Planning(format!("--{e}")))
    }
}

/// The limits of a planning command for crane `C`: the scenario's and the flags'.
fn case_and_limits<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    file: Option<&ScenarioFile>,
    flags: &PlanFlags,
) -> Result<(Case<C, N, M, A>, Limits), CliError> {
    let (case, settings) = scenario::build::<C, N, M, A>(file, &Overrides::default())?;
    let limits = limits::<C::Model, N, M, A>(&settings.limits, &flags.limit, &flags.min_tension)?;
    Ok((case, limits))
}

struct Fastest<'a> {
    file: Option<&'a ScenarioFile>,
    flags: &'a PlanFlags,
    settings: Settings,
    out: &'a Path,
    json: bool,
    /// `Some`: optimise the shape with these settings.
    shape: Option<ShapeSettings>,
    quiet: bool,
}

impl Visit for Fastest<'_> {
    type Output = Result<(), CliError>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let (case, limits) = case_and_limits::<C, N, M, A>(self.file, self.flags)?;
        match self.shape {
            Some(shape) => search_shape(&case, &limits, &self.settings, &shape, self.out, self.json, self.quiet),
            None => search(&case, &limits, &self.settings, self.out, self.json),
        }
    }
}

/// `crane fastest`.
pub fn fastest<R: Registry>(tool: &Tool<R>, args: FastestArgs) -> Result<(), CliError> {
    let (file, out, _claim) = args.plan.files(&args.model)?;
    let settings = args.plan.settings(Some(args.tolerance))?;
    let shape = (args.shape == Shape::Optimal).then_some(ShapeSettings {
        control_points: args.control_points,
        ..ShapeSettings::default()
    });
    tool.dispatch(
        &args.model,
        Fastest {
            file: file.as_ref(),
            flags: &args.plan,
            settings,
            out: &out,
            json: args.json,
            shape,
            quiet: args.quiet,
        },
    )
}

struct Sweep<'a> {
    file: Option<&'a ScenarioFile>,
    flags: &'a PlanFlags,
    settings: Settings,
    out: &'a Path,
    params: &'a [String],
    durations: Vec<f64>,
    /// A point set read from `--points`: the column names and the rows.
    points: Option<(Vec<String>, Vec<Vec<f64>>)>,
    quiet: bool,
}

impl Visit for Sweep<'_> {
    type Output = Result<(), CliError>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let (case, limits) = case_and_limits::<C, N, M, A>(self.file, self.flags)?;
        let spec = case.path().spec();
        let own = spec.t1 - spec.t0;
        let planning = |e: plan::PlanError| CliError::Planning(e.to_string());
        let (names, points, axes) = match self.points {
            Some((columns, rows)) => {
                // a `duration` column gives each point's duration
                let at = columns.iter().position(|c| c == "duration");
                let names: Vec<String> = columns.iter().filter(|c| *c != "duration").cloned().collect();
                let points: Vec<(Vec<f64>, f64)> = rows
                    .into_iter()
                    .map(|row| {
                        let duration = at.map_or(own, |k| row[k]);
                        let values = row.iter().enumerate().filter(|(k, _)| Some(*k) != at).map(|(_, v)| *v);
                        (values.collect(), duration)
                    })
                    .collect();
                plan::check_points::<C::Model, N, M, A>(&names, &points)
                    .map_err(|e| CliError::Planning(format!("--points: {e}")))?;
                (names, points, Vec::new())
            }
            None => {
                let params = self
                    .params
                    .iter()
                    .map(|p| range("--param", p))
                    .collect::<Result<Vec<_>, _>>()?;
                plan::check_grid::<C::Model, N, M, A>(&params, &self.durations).map_err(planning)?;
                // the heat map's axes: the quantities swept over more than one value
                let mut axes: Vec<(String, Vec<f64>)> = params.iter().filter(|(_, v)| v.len() > 1).cloned().collect();
                if self.durations.len() > 1 {
                    axes.push(("duration".into(), self.durations.clone()));
                }
                let names = params.iter().map(|(n, _)| n.clone()).collect();
                (names, plan::grid_points(own, &params, &self.durations), axes)
            }
        };
        grid(
            &case,
            &names,
            points,
            &axes,
            &limits,
            &self.settings,
            self.out,
            self.quiet,
        )
    }
}

/// The rows of a `--points` file: its header (the column names) and its
/// numbers, every row as long as the header.
fn read_points(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>), CliError> {
    let bad = |message: String| CliError::Planning(format!("--points {}: {message}", path.display()));
    if !std::fs::metadata(path).map_err(|e| bad(e.to_string()))?.is_file() {
        return Err(bad("not a regular file".into()));
    }
    let mut reader = csv::Reader::from_path(path).map_err(|e| bad(e.to_string()))?;
    let names: Vec<String> = reader
        .headers()
        .map_err(|e| bad(e.to_string()))?
        .iter()
        .map(|h| h.trim().to_string())
        .collect();
    let mut rows = Vec::new();
    for (i, record) in reader.records().enumerate() {
        let record = record.map_err(|e| bad(e.to_string()))?;
        let row = record
            .iter()
            .enumerate()
            .map(|(k, v)| {
                v.trim()
                    .parse::<f64>()
                    .map_err(|_| bad(format!("row {}, column `{}`: `{v}` is not a number", i + 1, names[k])))
            })
            .collect::<Result<Vec<f64>, _>>()?;
        rows.push(row);
        if rows.len() > MAX_SWEEP_POINTS {
            return Err(bad(format!("more than {MAX_SWEEP_POINTS} points (split the set)")));
        }
    }
    Ok((names, rows))
}

/// `crane sweep`.
pub fn sweep<R: Registry>(tool: &Tool<R>, args: SweepArgs) -> Result<(), CliError> {
    let (file, out, _claim) = args.plan.files(&args.model)?;
    let settings = args.plan.settings(None)?;
    let durations = match args.duration.as_deref() {
        Some(spec) => values(spec).filter(|d| d.iter().all(|&x| x > 0.0)).ok_or_else(|| {
            CliError::Planning(format!(
                "--duration `{spec}`: expected LOW:HIGH:COUNT of positive durations, 1 <= COUNT <= {}, e.g. 3:5:5",
                plan::MAX_SWEEP_POINTS
            ))
        })?,
        None => Vec::new(),
    };
    let points = args.points.as_deref().map(read_points).transpose()?;
    if points.is_none() && args.param.is_empty() && durations.len() < 2 {
        return Err(CliError::Planning(match args.duration.as_deref() {
            Some(spec) => format!(
                "--duration `{spec}` is one duration, and no --param is given: nothing to sweep (give COUNT >= 2, \
                 or --param NAME=LOW:HIGH:COUNT)"
            ),
            None => {
                "nothing to sweep: give --param NAME=LOW:HIGH:COUNT, --duration LOW:HIGH:COUNT or --points FILE.csv"
                    .into()
            }
        }));
    }
    let job = || {
        let job = Sweep {
            file: file.as_ref(),
            flags: &args.plan,
            settings,
            out: &out,
            params: &args.param,
            durations,
            points,
            quiet: args.quiet,
        };
        tool.dispatch(&args.model, job)
    };
    match args.threads {
        Some(0) => Err(CliError::Planning("--threads must be at least 1".into())),
        Some(n) if n > MAX_THREADS => Err(CliError::Planning(format!(
            "--threads {n}: at most {MAX_THREADS} (one per core is the default; more than the cores gain nothing)"
        ))),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| CliError::Planning(format!("--threads {n}: {e}")))?
            .install(job),
        None => job(),
    }
}

/// The limits of the scenario (`[limits]`, by input index) and of the flags
/// `--limit NAME=VALUE` and `--min-tension NAME=VALUE` (a rope without one
/// must stay taut), checked against crane `Mdl`.
fn limits<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    scenario: &[(usize, f64)],
    torque: &[String],
    tension: &[String],
) -> Result<Limits, CliError> {
    // the example names what the flag takes: an input of the crane, a rope
    let input = Mdl::INFO.inputs.first().copied().unwrap_or("u1");
    let rope = Mdl::INFO.ropes.first().map_or("N1", |r| r.tension);
    let parse = |flag: &'static str, example: String, items: &[String]| -> Result<Vec<(String, f64)>, CliError> {
        name_values(flag, items, |item| {
            CliError::Planning(format!("{flag} `{item}`: expected NAME=VALUE, e.g. {flag} {example}"))
        })
    };
    let (torque, tension) = (
        parse("--limit", format!("{input}=150"), torque)?,
        parse("--min-tension", format!("{rope}=10"), tension)?,
    );
    Limits::by_name::<Mdl, N, M, A>(scenario, &torque, &tension).map_err(|e| match e {
        plan::PlanError::TensionFloor(message) => CliError::Planning(format!("--min-tension {message}")),
        other => CliError::Planning(format!("--limit {other}")),
    })
}

/// `NAME=LOW:HIGH:COUNT` as the name and `COUNT` evenly spaced values.
fn range(flag: &str, item: &str) -> Result<(String, Vec<f64>), CliError> {
    let bad = || {
        CliError::Planning(format!(
            "{flag} `{item}`: expected NAME=LOW:HIGH:COUNT with 1 <= COUNT <= {}, e.g. {flag} m_l=80:120:5",
            plan::MAX_SWEEP_POINTS
        ))
    };
    let (name, spec) = item.split_once('=').ok_or_else(bad)?;
    Ok((name.trim().to_string(), values(spec).ok_or_else(bad)?))
}

/// `LOW:HIGH:COUNT` as values (`COUNT = 1`: `LOW`).
fn values(spec: &str) -> Option<Vec<f64>> {
    let parts: Vec<&str> = spec.split(':').collect();
    let [low, high, count] = parts[..] else { return None };
    let (low, high): (f64, f64) = (low.trim().parse().ok()?, high.trim().parse().ok()?);
    let count: usize = count.trim().parse().ok()?;
    if count == 0 || count > MAX_SWEEP_POINTS || !low.is_finite() || !high.is_finite() {
        return None;
    }
    Some(
        (0..count)
            .map(|i| {
                if count == 1 {
                    low
                } else {
                    low + (high - low) * i as f64 / (count - 1) as f64
                }
            })
            .collect(),
    )
}

/// `f(x, y)` for every cell of the grid `xs` by `ys`, a row per `y`.
fn over_cells<T>(xs: &[f64], ys: &[f64], f: impl Fn(f64, f64) -> T) -> Vec<Vec<T>> {
    ys.iter().map(|&y| xs.iter().map(|&x| f(x, y)).collect()).collect()
}

/// Search, write fastest.json and the plots, print.
fn search<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    limits: &Limits,
    settings: &Settings,
    out: &Path,
    print_json: bool,
) -> Result<(), CliError> {
    let clock = Instant::now();
    let best = plan::fastest(case, limits, settings).map_err(|e| CliError::Planning(e.to_string()))?;
    let wall = clock.elapsed().as_secs_f64();
    let info = <C::Model as CraneModel<N, M, A>>::INFO;
    let report = best.report::<C>(settings, wall);
    // a reduced run is exact at each step and uses no scheme, stable
    // inversion its own
    let method = Formulation::default_for::<C, N, M, A>().method(settings.scheme);
    let text = serde_json::to_string_pretty(&report).map_err(|e| CliError::Output {
        what: "fastest.json".into(),
        message: e.to_string(),
    })?;
    let solution = &best.solution;
    let mut staged = Staged::new(out)?;
    staged.text("fastest.json", text.clone() + "\n")?;
    let command = answer_scenario(case, &best.path, limits, out, &mut staged, "the time-scaled path")?;
    let inputs: Vec<(&str, Vec<(f64, f64)>)> = info
        .inputs
        .iter()
        .enumerate()
        .map(|(k, name)| (*name, solution.states.iter().map(|s| (s.t, s.u[k])).collect()))
        .collect();
    let levels: Vec<(usize, f64)> = limits.torque.iter().flat_map(|&(k, l)| [(k, l), (k, -l)]).collect();
    let title = format!("{}: inputs of the fastest move, T* = {:.3} s", C::NAME, best.duration);
    staged.text(
        "fastest-inputs.svg",
        plot::curves_with_levels(&title, "u [N m]", &inputs, &levels)?,
    )?;
    if !info.ropes.is_empty() {
        let tensions: Vec<(&str, Vec<(f64, f64)>)> = info
            .ropes
            .iter()
            .enumerate()
            .map(|(r, rope)| {
                (
                    rope.tension,
                    (0..solution.states.len())
                        .map(|i| (solution.states[i].t, solution.tensions_at(i)[r]))
                        .collect(),
                )
            })
            .collect();
        let floors: Vec<(usize, f64)> = limits.tension.clone();
        let title = format!("{}: rope tensions of the fastest move", C::NAME);
        staged.text(
            "fastest-tensions.svg",
            plot::curves_with_levels(&title, "N [N]", &tensions, &floors)?,
        )?;
    }
    staged.commit()?;
    if print_json {
        say!("{text}")?;
    } else {
        let b = &best.binding;
        let bound = if b.tension {
            format!(
                "rope tension {} >= {} N (a faster move takes it below at t = {:.3} s)",
                b.name, b.limit, b.at
            )
        } else if b.limit.is_nan() {
            b.name.clone()
        } else {
            format!(
                "|{}| <= {} (peak {} at the answer; a faster move exceeds it at t = {:.3} s)",
                b.name,
                Number(b.limit),
                Rounded(b.value),
                b.at
            )
        };
        say!(
            "{}: fastest feasible duration T* = {:.4} s (bracket {:.4} .. {:.4} s), bound by {bound}",
            C::NAME,
            best.duration,
            best.bracket.0,
            best.bracket.1
        )?;
        say!(
            "  {} evaluations ({method}, dt <= {} s and a twentieth of the move or its ramps) and {} for the interval \
             check in {:.1} ms; {}",
            best.evaluations,
            settings.dt,
            best.interval.points,
            wall * 1e3,
            if best.interval.holds {
                "feasible durations form an interval on the bracket".to_string()
            } else {
                format!(
                    "WARNING: feasible durations are not an interval on the bracket (at {:.4} s): the answer \
                        may not be the shortest",
                    best.interval.counterexample.unwrap_or(f64::NAN)
                )
            }
        )?;
        say!("  run it: {command}")?;
        say!("wrote {}", out.display())?;
    }
    Ok(())
}

/// Stage `fastest.toml`, the scenario of the answer's `path` (with the
/// case's parameters and the torque limits), and return the command that
/// runs it.
fn answer_scenario<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    path: &PathSpec<A>,
    limits: &Limits,
    out: &Path,
    staged: &mut Staged,
    what: &str,
) -> Result<String, CliError> {
    let command = format!(
        "crane run {} --scenario {}",
        C::NAME,
        out.join("fastest.toml").display()
    );
    let comment = [
        format!(
            "The fastest move of {} found by `crane fastest` ({what}), {} s.",
            C::NAME,
            Number(path.t1 - path.t0)
        ),
        format!("Run it: {command}"),
    ];
    staged.text(
        "fastest.toml",
        scenario::scenario_text::<C, N, M, A>(case.model(), path, limits, &comment),
    )?;
    Ok(command)
}

/// The load coordinates of `solution` over time, one curve each, named
/// with `suffix`.
fn load_curves<'a, const N: usize, const M: usize, const A: usize>(
    names: &'a [&'a str],
    solution: &crane_runtime::Solution<N, M, A>,
    suffix: &str,
) -> Vec<(String, Vec<(f64, f64)>)> {
    names
        .iter()
        .enumerate()
        .map(|(k, name)| {
            (
                format!("{name}{suffix}"),
                solution.states.iter().map(|s| (s.t, s.q[N - A + k])).collect(),
            )
        })
        .collect()
}

/// Named curves as the plots take them.
fn as_refs(curves: &[(String, Vec<(f64, f64)>)]) -> Vec<(&str, Vec<(f64, f64)>)> {
    curves.iter().map(|(n, c)| (n.as_str(), c.clone())).collect()
}

/// `crane fastest --shape optimal`: the time-scaled answer first (what the
/// shape improves on), then the shape's optimisation with a progress line;
/// fastest.json, fastest.toml and plots of both moves side by side.
fn search_shape<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    limits: &Limits,
    settings: &Settings,
    shape: &ShapeSettings,
    out: &Path,
    print_json: bool,
    quiet: bool,
) -> Result<(), CliError> {
    let clock = Instant::now();
    let scaled = plan::fastest(case, limits, settings).map_err(|e| CliError::Planning(e.to_string()))?;
    let bar = (!quiet && !print_json && std::io::IsTerminal::is_terminal(&std::io::stdout())).then(|| {
        let bar = indicatif::ProgressBar::new_spinner();
        bar.set_message(format!("time-scaled {:.4} s; optimising the shape", scaled.duration));
        bar
    });
    let shaped = plan::fastest_shape(case, limits, settings, shape, &mut |p| {
        if let Some(bar) = &bar {
            bar.set_message(format!(
                "iteration {}: T = {:.4} s, worst violation {:.1e}, trust radius {:.1e}",
                p.iteration, p.duration, p.violation, p.radius
            ));
            bar.tick();
        }
    })
    .map_err(|e| CliError::Planning(e.to_string()))?;
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let wall = clock.elapsed().as_secs_f64();
    let info = <C::Model as CraneModel<N, M, A>>::INFO;
    let report = shaped.report::<C>(settings, shape.control_points, scaled.duration, wall);
    let text = serde_json::to_string_pretty(&report).map_err(|e| CliError::Output {
        what: "fastest.json".into(),
        message: e.to_string(),
    })?;
    let mut staged = Staged::new(out)?;
    staged.text("fastest.json", text.clone() + "\n")?;
    let command = answer_scenario(case, &shaped.path, limits, out, &mut staged, "the optimised shape")?;
    // inputs, tensions and the load path of both moves side by side
    let inputs: Vec<(String, Vec<(f64, f64)>)> = (0..A)
        .flat_map(|k| {
            [(&shaped.solution, ""), (&scaled.solution, " (time-scaled)")].map(|(run, suffix)| {
                (
                    format!("{}{suffix}", info.inputs[k]),
                    run.states.iter().map(|s| (s.t, s.u[k])).collect(),
                )
            })
        })
        .collect();
    let levels: Vec<(usize, f64)> = limits
        .torque
        .iter()
        .flat_map(|&(k, l)| [(2 * k, l), (2 * k, -l)])
        .collect();
    let title = format!(
        "{}: inputs of the shaped move, T* = {:.3} s, and the time-scaled, {:.3} s",
        C::NAME,
        shaped.duration,
        scaled.duration
    );
    staged.text(
        "fastest-inputs.svg",
        plot::curves_with_levels(&title, "u [N m]", &as_refs(&inputs), &levels)?,
    )?;
    if !info.ropes.is_empty() {
        let tensions: Vec<(String, Vec<(f64, f64)>)> = (0..info.ropes.len())
            .flat_map(|r| {
                [(&shaped.solution, ""), (&scaled.solution, " (time-scaled)")].map(|(run, suffix)| {
                    (
                        format!("{}{suffix}", info.ropes[r].tension),
                        (0..run.states.len())
                            .map(|i| (run.states[i].t, run.tensions_at(i)[r]))
                            .collect(),
                    )
                })
            })
            .collect();
        let floors: Vec<(usize, f64)> = limits.tension.iter().map(|&(r, f)| (2 * r, f)).collect();
        let title = format!("{}: rope tensions of the shaped and the time-scaled move", C::NAME);
        staged.text(
            "fastest-tensions.svg",
            plot::curves_with_levels(&title, "N [N]", &as_refs(&tensions), &floors)?,
        )?;
    }
    let loads = &info.coordinates[N - A..];
    let mut path = load_curves(loads, &shaped.solution, "");
    path.extend(load_curves(loads, &scaled.solution, " (time-scaled)"));
    let title = format!(
        "{}: the load's coordinates on the shaped and the time-scaled move",
        C::NAME
    );
    staged.text(
        "fastest-path.svg",
        plot::curves_over_time(&title, "[m]", &as_refs(&path))?,
    )?;
    staged.commit()?;
    if print_json {
        say!("{text}")?;
        return Ok(());
    }
    say!(
        "{}: fastest shaped move T* = {:.4} s (time-scaled {}: {:.4} s), {} free control points per coordinate",
        C::NAME,
        shaped.duration,
        case.path().spec().profile.kind(),
        scaled.duration,
        shape.control_points
    )?;
    if let Some(bound) = &shaped.lower_bound {
        say!(
            "  lower bound {:.4} s ({}): the answer is {:.2} % above it",
            bound.duration,
            bound.derivation,
            100.0 * (shaped.duration / bound.duration - 1.0)
        )?;
    }
    for b in &shaped.at_answer {
        say!(
            "  {} {} {}: {} at t = {:.3} s",
            b.name,
            if b.tension { ">=" } else { "<=" },
            Number(b.limit),
            Rounded(b.value),
            b.at
        )?;
    }
    say!(
        "  {} iterations, {} inverse runs in {:.2} s (the samples kept {:.0e} below each limit)",
        shaped.iterations,
        shaped.runs,
        wall,
        shaped.margin
    )?;
    say!("  run it: {command}")?;
    say!("wrote {}", out.display())?;
    Ok(())
}

/// The points (a grid's or a set's, checked), in parallel; sweep.csv and
/// (two swept quantities of a grid, `axes`) a heat map.
#[allow(clippy::too_many_arguments)]
fn grid<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    names: &[String],
    points: Vec<(Vec<f64>, f64)>,
    axes: &[(String, Vec<f64>)],
    limits: &Limits,
    settings: &Settings,
    out: &Path,
    quiet: bool,
) -> Result<(), CliError> {
    let info = <C::Model as CraneModel<N, M, A>>::INFO;
    let count = points.len();
    plan::impulses(case).map_err(|e| CliError::Planning(e.to_string()))?;
    let spec = case.path().spec();
    let bar = (!quiet && std::io::IsTerminal::is_terminal(&std::io::stdout())).then(|| {
        let bar = indicatif::ProgressBar::new(count as u64);
        if let Ok(style) = indicatif::ProgressStyle::with_template("sweep [{bar:40}] {pos}/{len} points, {eta} left") {
            bar.set_style(style.progress_chars("=> "));
        }
        bar
    });
    let done = AtomicUsize::new(0);
    let clock = Instant::now();
    let points = plan::sweep_points(case, names, points, limits, settings, &|| {
        let n = done.fetch_add(1, Ordering::Relaxed) + 1;
        if let Some(bar) = &bar {
            bar.set_position(n as u64);
        }
    });
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let wall = clock.elapsed().as_secs_f64();
    let columns = plan::sweep_columns::<C::Model, N, M, A>(names, &points);
    let mut writer = csv::Writer::from_writer(Vec::new());
    let failed_csv = |e: csv::Error| CliError::Output {
        what: "sweep.csv".into(),
        message: e.to_string(),
    };
    writer
        .write_record(columns.iter().map(|(name, _)| name))
        .map_err(failed_csv)?;
    for i in 0..points.len() {
        let row = columns.iter().map(|(_, column)| match column {
            plan::Column::Numbers(values) => values[i].map(|x| format!("{x:?}")).unwrap_or_default(),
            plan::Column::Flags(values) => values[i].to_string(),
            plan::Column::Texts(values) => values[i].clone(),
        });
        writer.write_record(row).map_err(failed_csv)?;
    }
    let bytes = writer.into_inner().map_err(|e| CliError::Output {
        what: "sweep.csv".into(),
        message: e.to_string(),
    })?;
    let mut staged = Staged::new(out)?;
    staged.text("sweep.csv", bytes)?;
    // two swept quantities: a heat map of the largest |u| relative to its
    // limit (or of the first input's peak without limits)
    let measure = |e: &plan::Evaluation| -> Option<f64> {
        if e.error.is_some() {
            return None;
        }
        if limits.torque.is_empty() {
            e.peak_u.first().map(|p| p.0)
        } else {
            limits.torque.iter().map(|&(k, l)| e.peak_u[k].0 / l).reduce(f64::max)
        }
    };
    if axes.len() == 2 {
        let (ax, ay) = (&axes[0], &axes[1]);
        // each axis's column among the swept parameters (none: the
        // duration, which is no parameter)
        let column = |name: &str| names.iter().position(|n| n == name);
        let (cx, cy) = (column(&ax.0), column(&ay.0));
        let value = |c: Option<usize>, p: &plan::SweepPoint| c.map_or(p.duration, |k| p.values[k]);
        // per cell (rows: the second axis), the points of the sweep there
        let at = |x: f64, y: f64| points.iter().filter(move |p| value(cx, p) == x && value(cy, p) == y);
        let grid = over_cells(&ax.1, &ay.1, |x, y| {
            at(x, y).next().and_then(|p| measure(&p.evaluation))
        });
        let marked = over_cells(&ax.1, &ay.1, |x, y| at(x, y).any(|p| !p.feasible));
        let label = if limits.torque.is_empty() {
            format!("peak |{}|", info.inputs[0])
        } else {
            "max |u|/limit".to_string()
        };
        let title = format!("{}: {label} over {} and {}", C::NAME, ax.0, ay.0);
        staged.text(
            "sweep.svg",
            plot::heat_map(&title, &ax.0, &ay.0, &ax.1, &ay.1, &grid, &marked, &label)?,
        )?;
    }
    staged.commit()?;
    let failed = points.iter().filter(|p| p.evaluation.error.is_some()).count();
    let feasible = points.iter().filter(|p| p.feasible).count();
    // every point is one of the three: ran and feasible, ran and
    // infeasible, failed to run
    let infeasible = (points.iter())
        .filter(|p| !p.feasible && p.evaluation.error.is_none())
        .count();
    say!(
        "{}: {} points in {:.2} s ({:.0} points/s on {} threads): {feasible} feasible, {infeasible} infeasible, \
            {failed} failed; the move's own duration is {:.3} s",
        C::NAME,
        points.len(),
        wall,
        points.len() as f64 / wall,
        rayon::current_num_threads(),
        spec.t1 - spec.t0
    )?;
    say!("wrote {}", out.display())?;
    Ok(())
}
