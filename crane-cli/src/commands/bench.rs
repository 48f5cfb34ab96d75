//! `crane bench`: time repeated runs of a crane's default manoeuvre without
//! writing files: the simulation alone, or (`--study`) the whole run as
//! `crane run` and the Python package's `run` compute it (the simulation,
//! its summary and its audit).

use std::time::Instant;

use crane_models::registry::{Registry, Visit};
use crane_models::study::{self, DEFAULT_DT, Formulation, RunSettings};
use crane_models::{Case, Crane};
use crane_runtime::{Options, Scheme, Solution};

use super::{formulation_help, scheme_help};
use crate::scenario::{self, Overrides};
use crate::{CliError, Tool};

/// The most timed runs `crane bench` makes (each keeps its time; a median
/// of 1e5 runs is as good as it gets, and 1e9 would run for days).
pub const MAX_REPEAT: usize = 100_000;

/// The flags of `crane bench`.
#[derive(clap::Args, Debug)]
// a negative number is a value to check ("--dt -0.01"), not a flag
#[command(allow_negative_numbers = true)]
pub struct BenchArgs {
    /// Model name (see `list`).
    model: String,
    /// Time step in s.
    #[arg(long, default_value_t = DEFAULT_DT)]
    dt: f64,
    /// End time in s of the run (and of the motion), as for `crane run`.
    #[arg(long)]
    tf: Option<f64>,
    /// Number of timed runs.
    #[arg(long, default_value_t = 20)]
    repeat: usize,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    #[arg(long, value_name = "FORMULATION", help = formulation_help())]
    formulation: Option<Formulation>,
    #[arg(long, value_name = "SCHEME", help = scheme_help(Scheme::default()))]
    scheme: Option<Scheme>,
    /// Time the whole run: the simulation with its summary and audit, what
    /// `crane run` computes before it writes its files.
    #[arg(long)]
    study: bool,
}

struct Bench {
    overrides: Overrides,
    repeat: usize,
    json: bool,
    study: bool,
}

impl Visit for Bench {
    type Output = Result<(), CliError>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let (case, settings) = scenario::build::<C, N, M, A>(None, &self.overrides)?;
        time(&case, &settings, self.repeat, self.json, self.study)
    }
}

/// Time the runs.
pub fn bench<R: Registry>(tool: &Tool<R>, args: BenchArgs) -> Result<(), CliError> {
    let overrides = Overrides {
        dt: Some(args.dt),
        tf: args.tf,
        formulation: args.formulation,
        scheme: args.scheme,
    };
    tool.dispatch(
        &args.model,
        Bench {
            overrides,
            repeat: args.repeat,
            json: args.json,
            study: args.study,
        },
    )
}

/// Time `repeat` runs of one case (after one untimed run, whose audit's
/// findings are printed as warnings and listed in the JSON): the
/// simulation, or with `study` the whole run ([`study::run`]).
fn time<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    settings: &RunSettings,
    repeat: usize,
    json: bool,
    study: bool,
) -> Result<(), CliError> {
    if repeat == 0 {
        return Err(CliError::NoRepeats);
    }
    if repeat > MAX_REPEAT {
        return Err(CliError::TooManyRepeats(repeat));
    }
    let name = C::NAME;
    let (formulation, scheme, dt) = (settings.formulation, settings.scheme, settings.dt);
    let start = case.run_start()?;
    let options = Options::new(dt, case.tf())?.with_scheme(scheme);
    let run = || -> Result<Solution<N, M, A>, CliError> {
        Ok(if study {
            study::run(case, settings, &mut |_, _| {})?.solution
        } else {
            formulation.simulate(case, &start, &options, &mut |_, _| {})?
        })
    };
    let mut times = Vec::with_capacity(repeat);
    let mut steps = 0;
    let mut iterations = 0.0;
    // the warm-up, audited: a run whose numbers are not a result says so
    // (inputs of 1e29 N m were timed without a word)
    let findings = study::run(case, settings, &mut |_, _| {})?.findings;
    for _ in 0..repeat {
        let clock = Instant::now();
        let solution = run()?;
        times.push(clock.elapsed().as_secs_f64());
        steps = solution.steps();
        iterations = solution.mean_newton_iterations();
    }
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    let timed = if study { "run, summary and audit" } else { "simulation" };
    if json {
        let value = serde_json::json!({
            "model": name, "formulation": formulation.name(), "scheme": scheme.name(), "dt": dt, "tf": case.tf(), "steps": steps,
            "repeat": repeat, "timed": timed, "median_run_s": median, "median_step_s": median / steps as f64,
            "mean_newton_iterations": iterations,
            "findings": findings.iter().map(|f| f.to_string()).collect::<Vec<_>>(),
        });
        say!("{value}")?;
    } else {
        say!(
            "{name} ({}, {scheme}): dt = {dt} s, {steps} steps, {repeat} runs ({timed}): median {:.3} ms per run, \
             {:.2} us per step, {:.2} Newton iterations per step",
            formulation.name(),
            median * 1e3,
            median / steps as f64 * 1e6,
            iterations
        )?;
    }
    for finding in &findings {
        eprintln!("warning: {finding}");
    }
    Ok(())
}
