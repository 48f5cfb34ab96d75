//! `crane run`: a crane on its default manoeuvre or a scenario
//! (`crane_models::study::run`), written as results.csv, summary.json and
//! plots, with the highlights and warnings on the terminal.

use std::path::{Path, PathBuf};

use crane_models::registry::{Registry, Visit};
use crane_models::study::StudyError;
use crane_models::study::replay::{FeedbackSpec, ReplayOutcome};
use crane_models::study::{self, Formulation, ReplayRequest, Summary};
use crane_models::{Case, Crane};
use crane_runtime::error::{Number, Rounded, Seconds};
use crane_runtime::{Scheme, State};

use super::{formulation_help, name_values, out_dir, scheme_help};
use crate::scenario::{self, Overrides, ScenarioFile};
use crate::{CliError, Tool, output, plot, progress, snapshots};

/// The flags of `crane run`.
#[derive(clap::Args, Debug)]
// a negative number is a value to check ("--dt -0.01"), not a flag
#[command(allow_negative_numbers = true)]
pub struct RunArgs {
    /// Model name (see `list`).
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
    #[arg(long, value_name = "FORMULATION", help = formulation_help())]
    formulation: Option<Formulation>,
    #[arg(long, value_name = "SCHEME", help = scheme_help(Scheme::default()))]
    scheme: Option<Scheme>,
    /// Exit non-zero if the audit finds anything: states off their
    /// constraints, a rope that goes slack or of non-positive length, an
    /// input beyond its limit or running away, unstable internal dynamics,
    /// many singular steps, a path too rough or beyond the formulation, a
    /// replay that misses the path (the results are still written).
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
    #[arg(long = "plant", value_name = "NAME=VALUE", requires = "replay")]
    plant: Vec<String>,
    /// With --replay: the settling window in s (default: twice the longest
    /// rope pendulum period 2 pi sqrt(L/g) at the end).
    #[arg(long, value_name = "SECONDS", requires = "replay")]
    settle: Option<f64>,
    /// With --replay: add a PD law on the robot coordinates about the
    /// planned p(t): `default` (gains from the model) or `KP,KD` (the same
    /// stiffness and damping on every robot coordinate); the replay runs
    /// open loop too and replay.svg shows both.
    #[arg(long, value_name = "default|KP,KD", requires = "replay", allow_hyphen_values = true)]
    feedback: Option<String>,
}

/// `crane run`: the run, its files, and under `--strict` an error if it is
/// infeasible.
pub fn run<R: Registry>(tool: &Tool<R>, args: RunArgs) -> Result<(), CliError> {
    let file = args.scenario.as_deref().map(ScenarioFile::load).transpose()?;
    let (out, _claim) = out_dir(args.out.as_deref(), &args.model)?;
    let overrides = Overrides {
        dt: args.dt,
        tf: args.tf,
        formulation: args.formulation,
        scheme: args.scheme,
    };
    let plant = name_values("--plant", &args.plant, |item| CliError::Plant(item.to_string()))?;
    let feedback = args
        .feedback
        .as_deref()
        .map(|text| {
            text.parse::<FeedbackSpec>()
                .map_err(|e| CliError::Feedback(text.to_string(), e))
        })
        .transpose()?;
    if let Some(settle) = args.settle
        && !study::replay::valid_settle(settle)
    {
        return Err(CliError::Settle(settle));
    }
    let replay = args.replay.then_some(ReplayRequest {
        plant,
        settle: args.settle,
        feedback,
    });
    let job = Run {
        file: file.as_ref(),
        overrides,
        out: &out,
        quiet: args.quiet,
        replay,
    };
    let summary = tool.dispatch(&args.model, job)?;
    let findings = study::audit(&summary);
    if args.strict && !findings.is_empty() {
        let problems: Vec<String> = findings.iter().map(|f| f.to_string()).collect();
        return Err(CliError::Infeasible {
            problems: problems.join("; "),
            out: out.display().to_string(),
        });
    }
    Ok(())
}

/// An inconsistent start the scenario did not give: say that the crane's
/// default `p0` was checked (and no equilibrium found from it), and how to
/// give one.
fn default_start_hint<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    error: StudyError,
    file: Option<&ScenarioFile>,
) -> CliError {
    let defaulted = file.is_some_and(|f| f.p0.is_none());
    match error {
        StudyError::Runtime(e @ crane_runtime::Error::InconsistentStart { .. }) if defaulted => {
            CliError::Planning(format!(
                "{e}; the scenario gives no `p0`, so the start was checked with {}'s default p0 = {:?}, which \
                 fits its default manoeuvre, and no static equilibrium was found from it: give `p0` for this start",
                C::NAME,
                C::maneuver().p0
            ))
        }
        StudyError::Runtime(e @ crane_runtime::Error::InconsistentStart { .. }) => CliError::Planning(format!(
            "the scenario's `p0` is not a start of {}: {e}; give a `p0` that meets every constraint with the load \
             at the path's start, or leave `p0` out to start from the static equilibrium",
            C::NAME
        )),
        other => other.into(),
    }
}

/// `crane run` on one crane.
struct Run<'a> {
    file: Option<&'a ScenarioFile>,
    overrides: Overrides,
    out: &'a Path,
    quiet: bool,
    /// `--replay` and its options (the scenario's `[plant]` goes first).
    replay: Option<ReplayRequest>,
}

impl Visit for Run<'_> {
    type Output = Result<Summary, CliError>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let (case, settings) = scenario::build::<C, N, M, A>(self.file, &self.overrides)?;
        if self.replay.is_none() && !settings.plant.is_empty() {
            let names: Vec<&str> = settings.plant.iter().map(|(name, _)| name.as_str()).collect();
            return Err(CliError::PlantWithoutReplay(names.join(", ")));
        }
        let replay = self.replay.map(|request| ReplayRequest {
            plant: settings.plant.iter().cloned().chain(request.plant).collect(),
            ..request
        });
        // the plant is checked before any work: a refused plant leaves no
        // inverse run written
        if let Some(request) = &replay {
            study::replay::plant(&case, request)?;
            study::replay::check_step(settings.dt)?;
        }
        let mut progress = progress::Progress::new(C::NAME, self.quiet);
        let outcome = study::run(&case, &settings, &mut |step, steps| progress.tick(step, steps));
        progress.finish();
        let mut outcome = outcome.map_err(|e| default_start_hint::<C, N, M, A>(e, self.file))?;
        let replayed = replay
            .as_ref()
            .map(|request| outcome.replay(&case, request).map(|_| ()));
        // the inverse run is a result of its own: written whether or not
        // its replay succeeded, and a failed replay says where it went
        write(&case, &outcome, self.out)?;
        if let Some(Err(error)) = replayed {
            return Err(CliError::ReplayFailed {
                source: error,
                out: self.out.display().to_string(),
            });
        }
        let (solution, summary) = (&outcome.solution, &outcome.summary);
        say!(
            "{} ({}, {}): {} steps of dt = {} s in {:.1} ms ({:.2} Newton iterations per step)",
            C::NAME,
            settings.formulation.name(),
            summary.scheme,
            solution.steps(),
            settings.dt,
            summary.wall_time_s * 1e3,
            solution.mean_newton_iterations()
        )?;
        if settings.formulation == Formulation::StableInversion && settings.scheme != Scheme::default() {
            say!(
                "  {} is not used: stable inversion solves the whole move at once, by central differences of \
                 order 2",
                settings.scheme
            )?;
        }
        if !settings.formulation.discretised() && settings.scheme != Scheme::default() {
            say!(
                "  {} discretises nothing here: the {} system is algebraic at each step (a scheme serves only steps \
                 of eqs. 22a-d at a nearly slack rope); --formulation redundant runs eqs. (22a-d) on it",
                settings.scheme,
                settings.formulation
            )?;
        }
        if solution.redundant_start_steps > 0 && settings.formulation == Formulation::DummyDerivative {
            say!(
                "  {} steps in redundant coordinates (eqs. 22a-d): a rope carried under {:e} of the largest tension \
                 (a nearly slack rope leaves directions the reduced system does not fix)",
                solution.redundant_start_steps,
                crane_runtime::minimal::DEGENERATE_TENSION_RATIO
            )?;
        } else if solution.redundant_start_steps > 0 {
            let k = solution.redundant_start_steps;
            say!(
                "  first {k} steps (to t = {} s) in redundant coordinates: a rope carries under {:e} of the largest \
                 tension (degenerate start)",
                Seconds(solution.states[k].t),
                crane_runtime::minimal::DEGENERATE_TENSION_RATIO
            )?;
        }
        if solution.continued_steps > 0 {
            say!(
                "  {} of {} steps followed the path in shorter steps: from the prediction, Newton failed or found \
                 another root of the same equations (a mirror configuration); the inputs at the step times are \
                 exact",
                solution.continued_steps,
                solution.steps()
            )?;
        }
        if let Some(t) = solution.first_crossing {
            say!(
                "  the path passes a singular configuration at t = {} s{}: a rope's length or a taut rope's tension \
                 changes sign there (a rope going slack), and the step takes the solution beyond it as found",
                Seconds(t),
                if solution.crossings > 1 {
                    format!(" and {} more times", solution.crossings - 1)
                } else {
                    String::new()
                }
            )?;
        }
        if solution.held_steps > 0 {
            say!(
                "  {} of {} steps held what a nearly slack rope leaves free (a rope under {:e} of the largest \
                 tension places nothing on it; held where the last steps put it, the limit of a vanishing tension)",
                solution.held_steps,
                solution.steps(),
                crane_runtime::stepper::HOLD_TENSION_RATIO
            )?;
        }
        for line in highlights(summary) {
            say!("  {line}")?;
        }
        for finding in &outcome.findings {
            eprintln!("warning: {finding}");
        }
        say!("wrote {}", self.out.display())?;
        Ok(outcome.summary)
    }
}

/// results.csv, summary.json, the plots (the reference dashed, on a grid as
/// fine as the plot shows), the snapshots and the replay's files.
fn write<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    outcome: &study::Outcome<N, M, A>,
    out: &Path,
) -> Result<(), CliError> {
    let solution = &outcome.solution;
    let (t0, tf) = (case.t0(), case.tf());
    let has_reference = outcome.summary.reference.is_some();
    let samples = solution.steps().clamp(800, plot::MAX_POINTS);
    let fine: Option<Vec<State<N, M, A>>> = has_reference
        .then(|| {
            (0..=samples)
                .map(|i| case.reference(t0 + (tf - t0) * i as f64 / samples as f64))
                .collect()
        })
        .flatten();
    let mut extra: Vec<(String, String)> = snapshots::svg(C::drawing(case.model()), solution)?
        .map(|svg| ("snapshots.svg".to_string(), svg))
        .into_iter()
        .collect();
    if let Some(replay) = &outcome.replay {
        extra.extend(replay_files(case, replay)?);
    }
    let derived = output::Derived {
        names: case.derived_outputs(),
        values: &|s| case.derived(s),
    };
    output::write_all(out, solution, fine.as_deref(), &outcome.summary, &derived, &extra)
}

/// replay.csv (the states of the replay the summary describes, with the
/// load's deviation) and replay.svg (the deviation, open loop and with
/// feedback).
fn replay_files<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    replay: &ReplayOutcome<N, M, A>,
) -> Result<Vec<(String, String)>, CliError> {
    let (open, closed, result) = (&replay.open_loop, replay.closed_loop.as_ref(), replay.result());
    let (info, tf) = (result.solution.info, replay.end);
    let deviation = |s: &State<N, M, A>| crane_runtime::replay::load_deviation(case.path(), tf, s);
    let mut writer = csv::Writer::from_writer(Vec::new());
    let mut header = vec!["t".to_string()];
    header.extend(info.coordinates.iter().map(|s| s.to_string()));
    header.extend((1..=M).map(|i| format!("lambda{i}")));
    header.extend(info.ropes.iter().map(|r| r.tension.to_string()));
    header.push("load_deviation".into());
    let failed = |e: csv::Error| CliError::Output {
        what: "replay.csv".into(),
        message: e.to_string(),
    };
    writer.write_record(&header).map_err(failed)?;
    let mut row = Vec::new();
    for (i, s) in result.solution.states.iter().enumerate() {
        row.clear();
        row.push(format!("{}", s.t));
        row.extend(s.q.iter().chain(s.lambda.iter()).map(|v| format!("{v:e}")));
        row.extend(result.solution.tensions_at(i).iter().map(|v| format!("{v:e}")));
        row.push(format!("{:e}", deviation(s)));
        writer.write_record(&row).map_err(failed)?;
    }
    let csv = writer.into_inner().map_err(|e| CliError::Output {
        what: "replay.csv".into(),
        message: e.to_string(),
    })?;
    let curve = |r: &crane_runtime::replay::Replay<N, M, A>| -> Vec<(f64, f64)> {
        r.solution.states.iter().map(|s| (s.t, deviation(s))).collect()
    };
    let changed = &replay.summary.plant;
    let plant_label = if changed.is_empty() {
        "the planned plant".to_string()
    } else {
        changed
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let title = format!(
        "{} - replay on {plant_label}: load deviation (torques held after {tf} s)",
        info.name
    );
    let svg = match closed {
        None => plot::curves_over_time(&title, "|x - gamma| [m]", &[("open loop", curve(open))])?,
        Some(c) => plot::curves_over_time(
            &title,
            "|x - gamma| [m]",
            &[("open loop", curve(open)), ("with feedback", curve(c))],
        )?,
    };
    Ok(vec![
        ("replay.csv".into(), String::from_utf8_lossy(&csv).into_owned()),
        ("replay.svg".into(), svg),
    ])
}

/// A few lines for the terminal.
pub fn highlights(summary: &Summary) -> Vec<String> {
    let mut lines = Vec::new();
    for p in &summary.peak_torque {
        lines.push(format!(
            "peak |{}| = {}{} at t = {:.3} s",
            p.name,
            Rounded(p.value.abs()),
            summary.unit_suffix(&p.name),
            p.t
        ));
    }
    // what the audit finds is said once, as a warning; states off their
    // constraints say nothing of their ropes
    let solved = !summary.constraint_residual.as_ref().is_some_and(|r| r.violated());
    for r in summary
        .ropes
        .iter()
        .filter(|r| solved && !r.leaves_workspace() && r.first_slack.is_none())
    {
        // a rope that stays taut is below zero only by round-off (the slack
        // rule's 1e-9 of the largest tension: -2.6e125 N of a 7.7e140 N
        // tension under a load of 1e140 kg), and round-off below the
        // printed digits is none either: no negative tension is printed
        // beside "taut" (summary.json keeps the number)
        lines.push(format!(
            "rope {} stays taut: min tension {} N at t = {:.3} s",
            r.name,
            Rounded(if r.min_tension < 0.0 || r.min_tension.abs() < 5e-4 {
                0.0
            } else {
                r.min_tension
            }),
            r.t_min
        ));
    }
    for l in summary.torque_limits.iter().filter(|l| l.first_violation.is_none()) {
        lines.push(format!(
            "|{}| stays within its limit {}{unit} (peak {}{unit})",
            l.name,
            Number(l.limit),
            Rounded(l.peak),
            unit = summary.unit_suffix(&l.name)
        ));
    }
    if let Some(reference) = &summary.reference {
        lines.push(match reference.e_u_at_1_5s {
            Some(e) => format!("relative error of u at t = 1.5 s against the analytical reference (eq. 48): {e:.3e}"),
            None => "no step lands at t = 1.5 s, so eq. (48)'s error is not reported (summary.json has the largest \
                     errors against the reference over the run)"
                .to_string(),
        });
    }
    let internal = &summary.internal_dynamics;
    lines.push(match (internal.dimension, internal.stable) {
        (k, None) => format!(
            "internal dynamics: dimension {k} by the structure, not resolved at any of the {} sampled states: \
             whether they are stable is not known (see the warning)",
            internal.samples
        ),
        (0, _) if internal.unresolved == 0 => {
            "internal dynamics: none (flat), the torques are the unique ones".to_string()
        }
        (0, _) => format!(
            "internal dynamics: not resolved at {} of {} sampled states",
            internal.unresolved, internal.samples
        ),
        (k, Some(true)) => format!("internal dynamics: dimension {k}, stable"),
        (k, Some(false)) => match &summary.stable_inversion {
            Some(inversion) => format!(
                "internal dynamics: dimension {k}, unstable: the bounded inputs by stable inversion, acting {} s \
                 before the move (pre-actuation) and settling {} s after it (post-actuation)",
                Seconds(inversion.t_pre),
                Seconds(inversion.t_post)
            ),
            None => format!("internal dynamics: dimension {k}, unstable (see the warning)"),
        },
    });
    if let Some(selection) = &summary.state_selection {
        let eigenvalues: Vec<String> = (selection.eigenvalues_start.iter())
            .map(|&(re, im)| match im {
                0.0 => format!("{re:.4}"),
                _ => format!("{re:.4} {} {:.4}i", if im < 0.0 { "-" } else { "+" }, im.abs()),
            })
            .collect();
        lines.push(format!(
            "state selection: {} integrated by the scheme (eigenvalues at the start {} 1/s), every other unknown \
             exact at each step",
            selection.states.join(", "),
            eigenvalues.join(", ")
        ));
        // the first few; summary.json has them all
        const SHOWN: usize = 4;
        for reselection in selection.reselections.iter().take(SHOWN) {
            lines.push(format!(
                "  selected anew at t = {} s, where the selection degenerated: {}",
                Seconds(reselection.t),
                reselection.states.join(", ")
            ));
        }
        if selection.reselections.len() > SHOWN {
            lines.push(format!(
                "  and {} times more (summary.json: state_selection.reselections)",
                selection.reselections.len() - SHOWN
            ));
        }
    }
    if let Some(replay) = &summary.replay {
        // what the torques do on the plant, where the files say it in full
        let plant = if replay.plant.is_empty() {
            "the model".to_string()
        } else {
            let changed: Vec<String> = replay
                .plant
                .iter()
                .map(|(name, value)| format!("{name} = {value}"))
                .collect();
            format!("the plant with {}", changed.join(", "))
        };
        let with = replay
            .feedback
            .as_ref()
            .map_or(String::new(), |law| format!(" with feedback {law}"));
        lines.push(format!(
            "replay on {plant}{with}: the load leaves its path by at most {:.3e} m, {:.3e} m at the end, and sways \
             by {:.3e} m over the {:.3} s after it (replay.csv, replay.svg)",
            replay.max_load_deviation, replay.deviation_at_tf, replay.residual_sway, replay.settle_time
        ));
    }
    lines
}
