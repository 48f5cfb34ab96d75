//! Inverse dynamics as a design tool: the shortest duration of a move
//! under torque limits and rope-tension floors ([`fastest`]), and grids
//! over parameters and durations ([`sweep`]).
//!
//! A duration `T` is *feasible* when the inverse dynamics of the case's
//! path shape, scaled to last `T` (start, end and profile fixed), keep every
//! limited `|u_k|` at or below its limit and every floored rope tension at
//! or above its floor over the whole run, and the run's
//! [`audit`](crate::study::audit()) finds nothing else wrong with it (states
//! off their constraints, unstable internal dynamics, a runaway input, many
//! singular steps, a crane beyond its formulation) ([`evaluate`]). [`fastest`]
//! brackets the shortest feasible duration by halving or doubling the
//! case's own duration, bisects to a tolerance, and checks on the bracket
//! that feasible durations form an interval there (the assumption that
//! makes bisection correct), saying so when they do not.
//!
//! ```
//! use crane_models::navy_planar;
//! use crane_models::plan::{Limits, Settings, fastest};
//!
//! let case = navy_planar::PaperCase::maneuver().unwrap();
//! // |u2| <= 150 N m, BDF-4 at dt <= 0.05 s
//! let limits = Limits { torque: vec![(1, 150.0)], tension: vec![] };
//! let best = fastest(&case, &limits, &Settings::default()).unwrap();
//! assert!(best.duration < 4.0 && best.interval.holds);
//! println!("{:.3} s in {} evaluations, bound by {}", best.duration, best.evaluations, best.binding.name);
//! ```

use rayon::prelude::*;
use serde::Serialize;
use std::sync::{Arc, Mutex};

use crane_runtime::cancel::Cancel;
use crane_runtime::error::{Number, Rounded};
use crane_runtime::{CraneModel, Options, Scheme, Solution};

use crate::case::Case;
use crate::crane::{Crane, LowerBound};
use crate::path::{Path, PathSpec};
use crate::study::summary::slack_allowance;

mod report;
mod shape;
pub use report::{Column, LimitReport, Report, ShapeReport, check_grid, check_points, sweep_columns};
pub use shape::{MAX_CONTROL_POINTS, ShapeProgress, ShapeSettings, Shaped, fastest_shape};

/// Torque limits `|u_k| <= limit` and tension floors `N_r >= floor`, by
/// input and rope index.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Limits {
    /// `(input index, limit)`, N m (or N).
    pub torque: Vec<(usize, f64)>,
    /// `(rope index, floor)`, N.
    pub tension: Vec<(usize, f64)>,
}

/// How a duration is evaluated and how close the search goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Largest time step; each run takes the largest step at most this
    /// that divides its length.
    pub dt: f64,
    /// The scheme.
    pub scheme: Scheme,
    /// Width of the final bracket, s.
    pub tolerance: f64,
    /// Durations evaluated evenly across the bracket to check that the
    /// feasible ones form an interval.
    pub interval_points: usize,
}

impl Default for Settings {
    /// BDF-4 at dt = 0.05 s (an evaluation of navy-planar's move is 80
    /// steps), 1 ms tolerance, 8 check points.
    fn default() -> Self {
        Self {
            dt: 0.05,
            scheme: Scheme::Bdf4,
            tolerance: 1e-3,
            interval_points: 8,
        }
    }
}

impl Settings {
    /// The defaults with what is given: `dt` a step a run can take
    /// ([`Options::stepping`]), `tolerance` positive.
    ///
    /// ```
    /// use crane_models::plan::Settings;
    /// let settings = Settings::with(Some(0.01), None, None).unwrap();
    /// assert_eq!((settings.dt, settings.tolerance), (0.01, 1e-3));
    /// assert!(Settings::with(Some(-0.01), None, None).is_err());
    /// assert!(Settings::with(None, None, Some(0.0)).is_err());
    /// ```
    pub fn with(dt: Option<f64>, scheme: Option<Scheme>, tolerance: Option<f64>) -> Result<Self, PlanError> {
        let defaults = Self::default();
        let dt = dt.unwrap_or(defaults.dt);
        Options::stepping(dt).map_err(|e| PlanError::Settings(format!("dt: {e}")))?;
        let tolerance = tolerance.unwrap_or(defaults.tolerance);
        if !(tolerance > 0.0 && tolerance.is_finite()) {
            return Err(PlanError::Settings(format!("tolerance {tolerance} must be positive")));
        }
        Ok(Self {
            dt,
            scheme: scheme.unwrap_or(defaults.scheme),
            tolerance,
            ..defaults
        })
    }
}

/// The peaks of one run, or why it failed.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// Duration of the move, s.
    pub duration: f64,
    /// `(max |u_k|, time)` per input.
    pub peak_u: Vec<(f64, f64)>,
    /// `(min N_r, time)` per rope.
    pub min_tension: Vec<(f64, f64)>,
    /// The largest `|N|` of any rope over the run (the scale of the
    /// tensions' round-off, [`below_floor`](crate::study::below_floor)).
    pub largest_tension: f64,
    /// The run's error, if it failed (then infeasible).
    pub error: Option<String>,
    /// What the run's [`audit`](crate::study::audit()) found besides the
    /// limits and floors, which planning measures itself (each makes the
    /// duration infeasible).
    pub findings: Vec<String>,
}

/// A limit and how a run meets it.
#[derive(Debug, Clone, PartialEq)]
pub struct Binding {
    /// `u2`, `N1`, ... as the model declares it.
    pub name: String,
    /// The limit (torque) or the floor (tension).
    pub limit: f64,
    /// The run's peak `|u|` or minimum tension.
    pub value: f64,
    /// When it occurs, s.
    pub at: f64,
    /// How far past the limit, relative (`> 0`: past it).
    pub excess: f64,
    /// The excess still counted as within the limit: 0 for torques,
    /// for tensions the one slack rule's round-off
    /// ([`below_floor`](crate::study::below_floor)), in the units of `excess`.
    pub allowance: f64,
    /// A tension floor (`value` is then a minimum), not a torque limit.
    pub tension: bool,
}

impl Limits {
    /// Limits of crane `Mdl` by name: `torque` on the inputs `(name, |u|
    /// limit)` over `base` (by index; a name given again replaces it),
    /// `tension` floors on the ropes `(tension name, floor)`; every other
    /// rope taut (floor 0). Names are checked against the model, limits
    /// must be positive and floors finite.
    ///
    /// ```
    /// use crane_models::navy_planar::NavyPlanar;
    /// use crane_models::plan::Limits;
    /// let limits = Limits::by_name::<NavyPlanar, 7, 3, 2>(&[], &[("u2".into(), 150.0)], &[]).unwrap();
    /// assert_eq!(limits.torque, vec![(1, 150.0)]);
    /// assert_eq!(limits.tension, vec![(0, 0.0), (1, 0.0)]); // both ropes taut
    /// assert!(Limits::by_name::<NavyPlanar, 7, 3, 2>(&[], &[("u9".into(), 1.0)], &[]).is_err());
    /// ```
    pub fn by_name<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
        base: &[(usize, f64)],
        torque: &[(String, f64)],
        tension: &[(String, f64)],
    ) -> Result<Self, PlanError> {
        let info = Mdl::INFO;
        let mut out = Limits {
            torque: base.to_vec(),
            tension: Vec::new(),
        };
        for (name, value) in torque {
            let k = info.inputs.iter().position(|u| u == name).ok_or_else(|| {
                PlanError::TorqueLimit(format!(
                    "{name}: no such input; the inputs are {}",
                    info.inputs.join(", ")
                ))
            })?;
            if !(value.is_finite() && *value > 0.0) {
                return Err(PlanError::TorqueLimit(format!(
                    "{name}={value}: a limit on |{name}| must be positive"
                )));
            }
            out.torque.retain(|&(j, _)| j != k);
            out.torque.push((k, *value));
        }
        for (name, value) in tension {
            let r = info.ropes.iter().position(|r| r.tension == name).ok_or_else(|| {
                let ropes: Vec<&str> = info.ropes.iter().map(|r| r.tension).collect();
                PlanError::TensionFloor(format!(
                    "{name}: no such rope tension; the ropes are {}",
                    ropes.join(", ")
                ))
            })?;
            if !value.is_finite() {
                return Err(PlanError::TensionFloor(format!(
                    "{name}={value}: a tension floor must be finite"
                )));
            }
            out.tension.push((r, *value));
        }
        Ok(out.with_taut_ropes::<Mdl, N, M, A>())
    }

    /// The same limits with a floor of 0 (taut) on every rope of `Mdl`
    /// that has no floor yet.
    pub fn with_taut_ropes<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(mut self) -> Self {
        for r in 0..Mdl::INFO.ropes.len() {
            if !self.tension.iter().any(|&(j, _)| j == r) {
                self.tension.push((r, 0.0));
            }
        }
        self
    }
}

impl Evaluation {
    /// The evaluation of a run of `duration` that could not be made, and why.
    pub fn failed(duration: f64, error: String) -> Self {
        Evaluation {
            duration,
            peak_u: Vec::new(),
            min_tension: Vec::new(),
            largest_tension: 0.0,
            error: Some(error),
            findings: Vec::new(),
        }
    }

    /// Each limited quantity's margin, largest relative excess first.
    pub fn bindings<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
        &self,
        limits: &Limits,
    ) -> Vec<Binding> {
        let info = Mdl::INFO;
        let mut out: Vec<Binding> = Vec::new();
        if self.error.is_some() {
            return out;
        }
        for &(k, limit) in &limits.torque {
            if let Some(&(value, at)) = self.peak_u.get(k) {
                out.push(Binding {
                    name: info.inputs[k].to_string(),
                    limit,
                    value,
                    at,
                    excess: (value - limit) / limit.abs().max(f64::MIN_POSITIVE),
                    allowance: 0.0,
                    tension: false,
                });
            }
        }
        for &(r, floor) in &limits.tension {
            if let Some(&(value, at)) = self.min_tension.get(r) {
                let peak = self.largest_tension;
                let scale = floor.abs().max(1.0);
                out.push(Binding {
                    name: info.ropes[r].tension.to_string(),
                    limit: floor,
                    value,
                    at,
                    excess: (floor - value) / scale,
                    allowance: slack_allowance(floor, peak) / scale,
                    tension: true,
                });
            }
        }
        out.sort_by(|a, b| (b.excess - b.allowance).total_cmp(&(a.excess - a.allowance)));
        out
    }

    /// Whether the run succeeded within every limit (a tension at its
    /// floor to within round-off counts as at it:
    /// [`below_floor`](crate::study::below_floor)).
    pub fn feasible<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
        &self,
        limits: &Limits,
    ) -> bool {
        self.error.is_none()
            && self.findings.is_empty()
            && self
                .bindings::<Mdl, N, M, A>(limits)
                .iter()
                .all(|b| b.excess <= b.allowance)
    }
}

/// The case with its motion scaled in time to last `duration`: start, end
/// and shape kept (the ramps of a three-phase profile scale with it), a
/// settling time after the motion kept too.
pub fn with_duration<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    model: C::Model,
    duration: f64,
) -> Result<Case<C, N, M, A>, String> {
    let spec = case.path().spec().clone();
    let settle = (case.tf() - spec.t1).max(0.0);
    let scale = duration / (spec.t1 - spec.t0);
    let profile = spec.profile.scaled(scale);
    let path = Path::new(PathSpec {
        profile,
        t1: spec.t0 + duration,
        ..spec
    })
    .map_err(|e| e.to_string())?;
    Ok(Case::from_parts(
        model,
        path,
        case.p0.clone(),
        spec.t0 + duration + settle,
    ))
}

/// The run of `case` (its own duration and model) under `settings`: the
/// largest step at most `settings.dt`, and at most a twentieth of the
/// path's shortest feature
/// ([`SPIKE_RESOLUTION`](crate::study::summary::SPIKE_RESOLUTION)), that
/// divides the run (the smallest
/// above it where that would fall below the runtime's smallest step,
/// [`MIN_DT`](crane_runtime::options::MIN_DT)), the start
/// from `p0` (or, where the parameters moved it, the static equilibrium
/// from it), in the crane's default formulation
/// ([`Formulation::default_for`](crate::study::Formulation::default_for)).
pub fn run<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    settings: &Settings,
) -> Result<Solution<N, M, A>, String> {
    let (t0, tf) = (case.t0(), case.tf());
    let span = tf - t0;
    if !(span > 0.0 && span.is_finite()) {
        return Err(format!("the run from t = {t0} s to {tf} s is empty"));
    }
    // at most the settings' step, and short enough to resolve the move: a
    // move of 2 ms in one step of 2 s has its inputs only at rest, and
    // passed every limit
    let feature = case.path().spec().shortest_feature();
    let resolved = feature / crate::study::summary::SPIKE_RESOLUTION;
    let dt = step_for(span, settings.dt.min(resolved));
    if dt < crane_runtime::options::MIN_DT {
        return Err(format!(
            "a move of {} s is too short to evaluate: resolving its shortest feature ({} s) takes steps of {} s, \
             below the smallest time step, {} s",
            Number(span),
            Number(feature),
            Number(dt),
            Number(crane_runtime::options::MIN_DT)
        ));
    }
    within_evaluation_steps(span, dt)?;
    let start = case.consistent_start(t0).map_err(|e| e.to_string())?;
    let options = Options::new(dt, tf)
        .map_err(|e| e.to_string())?
        .with_scheme(settings.scheme);
    crate::study::Formulation::default_for::<C, N, M, A>()
        .simulate(case, &start, &options, &mut |_, _| {})
        .map_err(|e| e.to_string())
}

/// The most steps a planning evaluation takes: a plan evaluates tens of
/// runs, each held whole (a million steps of navy-planar take about 2 s and
/// 0.3 GB; `--dt 1e-6` on its 4 s move grew to 12 GB in the bracket).
pub const MAX_EVALUATION_STEPS: usize = 1_000_000;

/// Refuse a run of `span` at `dt` longer than [`MAX_EVALUATION_STEPS`].
fn within_evaluation_steps(span: f64, dt: f64) -> Result<(), String> {
    let steps = (span / dt).round();
    if steps > MAX_EVALUATION_STEPS as f64 {
        return Err(format!(
            "a run of {} s at dt = {} s is {steps:e} steps, more than planning takes per evaluation \
             ({MAX_EVALUATION_STEPS:e}: one plan evaluates tens of runs): give dt >= {} s",
            Number(span),
            Number(dt),
            Number(span / MAX_EVALUATION_STEPS as f64)
        ));
    }
    Ok(())
}

/// The largest step at most `dt` that divides `span` into whole steps, or
/// where that falls below [`MIN_DT`](crane_runtime::options::MIN_DT) (a
/// `dt` at the minimum), the smallest above it.
fn step_for(span: f64, dt: f64) -> f64 {
    let steps = (span / dt - 1e-9).ceil().max(1.0);
    if span / steps < crane_runtime::options::MIN_DT && steps > 1.0 {
        span / (steps - 1.0)
    } else {
        span / steps
    }
}

/// The extremum of the parabola through three equally spaced samples
/// `(t - h, a), (t, b), (t + h, c)` with `b` the sampled extremum: the
/// peak between the steps, `(value, time)`.
fn vertex(t: f64, h: f64, a: f64, b: f64, c: f64) -> (f64, f64) {
    let curvature = a - 2.0 * b + c;
    if curvature == 0.0 || !curvature.is_finite() {
        return (b, t);
    }
    let offset = (0.5 * (a - c) / curvature).clamp(-1.0, 1.0);
    (b - 0.25 * (a - c) * offset, t + offset * h)
}

/// The peaks of a run: the largest `|u_k|` and the smallest tension of
/// each rope, between the steps where the extreme sample is interior (the
/// parabola through it and its neighbours: on a coarse step the samples
/// miss a smooth peak by O(dt^2), 1e-3 relative at dt = 0.05 s on the
/// paper's move; the vertex by O(dt^3)).
pub fn peaks<const N: usize, const M: usize, const A: usize>(duration: f64, run: &Solution<N, M, A>) -> Evaluation {
    let states = &run.states;
    let ropes = run.info.ropes.len();
    let extreme = |value: &dyn Fn(usize) -> f64| -> (f64, f64) {
        // the sample with the largest value (NaN counts as +inf)
        let v = |i: usize| {
            let x = value(i);
            if x.is_nan() { f64::INFINITY } else { x }
        };
        let best = (0..states.len()).fold(0, |b, i| if v(i) > v(b) { i } else { b });
        if best > 0 && best + 1 < states.len() && v(best).is_finite() {
            let h = states[best + 1].t - states[best].t;
            vertex(states[best].t, h, v(best - 1), v(best), v(best + 1))
        } else {
            (v(best), states[best].t)
        }
    };
    let peak_u = (0..A).map(|k| extreme(&|i| states[i].u[k].abs())).collect();
    let min_tension = (0..ropes)
        .map(|r| {
            let (value, at) = extreme(&|i| -run.tensions_at(i)[r]);
            (-value, at)
        })
        .collect();
    Evaluation {
        duration,
        peak_u,
        min_tension,
        largest_tension: run.largest_tension(),
        error: None,
        findings: Vec::new(),
    }
}

/// Evaluate `case` scaled to `duration`.
pub fn evaluate<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    duration: f64,
    settings: &Settings,
) -> (Evaluation, Option<Solution<N, M, A>>) {
    evaluate_model(case, case.model().clone(), duration, settings)
}

/// The most points a sweep may have (each is a run of the inverse
/// dynamics; a million take about a quarter of an hour on two cores).
pub const MAX_SWEEP_POINTS: usize = 1_000_000;

/// Evaluate `case` with `model` instead of its own, scaled to `duration`.
fn evaluate_model<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    model: C::Model,
    duration: f64,
    settings: &Settings,
) -> (Evaluation, Option<Solution<N, M, A>>) {
    let failed = |error: String| (Evaluation::failed(duration, error), None);
    let scaled = match with_duration(case, model, duration) {
        Ok(c) => c,
        Err(e) => return failed(e),
    };
    match run(&scaled, settings) {
        Ok(solution) => {
            let mut evaluation = peaks(duration, &solution);
            evaluation.findings = findings(&scaled, &solution);
            (evaluation, Some(solution))
        }
        Err(e) => failed(e),
    }
}

/// The states at which an evaluation diagnoses the internal dynamics of a
/// crane that has them structurally: 11 (a run of
/// [`study::run`](crate::study::run) has 101; an evaluation is one of many,
/// and unstable internal dynamics show at every state). A crane without
/// them by structure is not sampled
/// ([`summarize_run`](crate::study::summarize_run)).
pub const DIAGNOSIS_SAMPLES: usize = 10;

/// What the [`audit`](crate::study::audit()) of `solution`, a run of `case`,
/// finds besides slack ropes and exceeded limits (planning measures those
/// itself, between the steps and against its own floors) and a path
/// smoothness planning has checked before ([`impulses`]).
fn findings<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    solution: &Solution<N, M, A>,
) -> Vec<String> {
    use crate::study::{self, Finding, RunSettings};
    let settings = RunSettings {
        dt: solution.dt,
        formulation: study::Formulation::default_for::<C, N, M, A>(),
        ..RunSettings::default()
    };
    let summary = study::summarize_run(case, &settings, solution, 0.0, DIAGNOSIS_SAMPLES);
    study::audit(&summary)
        .iter()
        .filter(|f| !matches!(f, Finding::SlackRope(_) | Finding::PathTooRough { .. }))
        .map(|f| f.to_string())
        .collect()
}

/// What the interval check found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct IntervalCheck {
    /// Durations checked across the bracket.
    pub points: usize,
    /// Every checked duration below the answer infeasible and every one
    /// above feasible.
    pub holds: bool,
    /// A checked duration that breaks it, if any.
    pub counterexample: Option<f64>,
}

/// The shortest feasible duration.
#[derive(Debug, Clone)]
pub struct Fastest<const N: usize, const M: usize, const A: usize> {
    /// The duration, s (feasible; the bracket's lower end is not).
    pub duration: f64,
    /// The answer's path: the case's own shape, lasting `duration`.
    pub path: PathSpec<A>,
    /// The final bracket `(infeasible, feasible)`.
    pub bracket: (f64, f64),
    /// The limit that binds: the one most violated just below the answer
    /// (`at`: when, there; `excess`: by how much), with its value at the
    /// answer (`value`).
    pub binding: Binding,
    /// Every limit at the answer.
    pub at_answer: Vec<Binding>,
    /// Evaluations of the search (bracketing and bisection).
    pub evaluations: usize,
    /// The check that feasible durations form an interval on the first
    /// bracket (`interval_points` more evaluations).
    pub interval: IntervalCheck,
    /// The run at the answer.
    pub solution: Solution<N, M, A>,
    /// The crane's lower bound on any move's duration under the torque
    /// limits, where it has one ([`Crane::lower_bound`]).
    pub lower_bound: Option<LowerBound>,
}

/// Why there is no answer.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlanError {
    /// Nothing to search for.
    #[error("no limits given: every duration is feasible")]
    NoLimits,
    /// Settings out of range.
    #[error("{0}")]
    Settings(String),
    /// A torque limit on an input the crane does not have, or not positive.
    #[error("{0}")]
    TorqueLimit(String),
    /// A tension floor on a rope the crane does not have, or not finite.
    #[error("{0}")]
    TensionFloor(String),
    /// A sweep's grid that cannot be run ([`check_grid`]).
    #[error("{0}")]
    Grid(String),
    /// Even `duration` (the longest tried) violates a limit.
    #[error("no feasible duration up to {duration:.3} s: {reason}")]
    NoFeasibleDuration {
        /// The longest duration tried, s.
        duration: f64,
        /// Why it is infeasible.
        reason: String,
    },
    /// No limit binds before the inverse dynamics itself fails: below
    /// `duration` the runs fail, or give results the audit finds are no
    /// solution or no move to make (a rope of negative length), so the
    /// answer would be the solver's limit, not the crane's.
    #[error(
        "no limit binds down to {duration:.4} s, and below it {error}; the limits do not decide the fastest move \
         (tighten them, or check the crane's parameters)"
    )]
    RunFailsFirst {
        /// The shortest duration whose run succeeded, s.
        duration: f64,
        /// Why the run just below it failed, or what its audit found.
        error: String,
    },
    /// The path is too rough for the crane: its inputs carry impulses.
    #[error(
        "the path is continuous only up to its derivative {continuous}, but the inputs of {crane} need derivative \
         {needed}: they carry impulses where derivative {jump} jumps, which no torque limit admits (use a smoother \
         profile, e.g. smooth-three-phase)",
        jump = continuous + 1
    )]
    PathTooRough {
        /// The crane.
        crane: &'static str,
        /// The derivative of the path its inputs need.
        needed: usize,
        /// The highest continuous derivative of the path.
        continuous: usize,
    },
    /// Even `duration` (the shortest tried) meets every limit.
    #[error("every duration down to {duration:.3e} s is feasible; the limits do not bind")]
    Unbounded {
        /// The shortest duration tried, s.
        duration: f64,
    },
}

/// Refuse a path continuous two or more derivatives below what the crane's
/// inputs need: they carry impulses there (a path one derivative short
/// gives finite jumps, which a limit can judge). [`fastest`] and the
/// sweeps ask it before any run.
pub fn impulses<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
) -> Result<(), PlanError> {
    match crane_runtime::internal::path_smoothness::<C::Model, _, N, M, A>(case.path()) {
        Some(s) if s.continuous + 2 <= s.needed => Err(PlanError::PathTooRough {
            crane: C::NAME,
            needed: s.needed,
            continuous: s.continuous,
        }),
        _ => Ok(()),
    }
}

/// Why an evaluation is infeasible, in words.
fn reason<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    e: &Evaluation,
    limits: &Limits,
) -> String {
    if let Some(error) = &e.error {
        return format!("the inverse dynamics failed: {error}");
    }
    if let Some(finding) = e.findings.first() {
        return finding.clone();
    }
    match e.bindings::<Mdl, N, M, A>(limits).first() {
        Some(b) if b.excess > b.allowance => {
            format!(
                "{} = {} against {} at t = {:.3} s",
                b.name,
                Rounded(b.value),
                Number(b.limit),
                b.at
            )
        }
        _ => "feasible".into(),
    }
}

/// The shortest duration of `case`'s path shape for which every limit
/// holds (see the module docs).
pub fn fastest<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    limits: &Limits,
    settings: &Settings,
) -> Result<Fastest<N, M, A>, PlanError> {
    if limits.torque.is_empty() && limits.tension.is_empty() {
        return Err(PlanError::NoLimits);
    }
    if !(settings.tolerance > 0.0 && settings.dt > 0.0) {
        return Err(PlanError::Settings(format!(
            "tolerance {} and dt {} must be positive",
            settings.tolerance, settings.dt
        )));
    }
    let spec = case.path().spec();
    let own = spec.t1 - spec.t0;
    // below this the bracket cannot shrink (durations are f64): the
    // bisection would not end
    let resolvable = 1e-12 * own.abs();
    if !(settings.tolerance >= resolvable) {
        return Err(PlanError::Settings(format!(
            "tolerance {:e} s is below what the bisection resolves on a {own} s move: give at least {resolvable:e} s",
            settings.tolerance
        )));
    }
    impulses(case)?;
    // the move's own duration first: a step too small for it is said so
    // before the bracket grows
    within_evaluation_steps(case.tf() - case.t0(), settings.dt).map_err(PlanError::Settings)?;
    let mut evaluations = 0;
    // one evaluation, kept: the last infeasible (`below`) and feasible
    // (`above`, with its run) ones end as the bracket's
    let mut probe = |duration: f64| {
        evaluations += 1;
        let (evaluation, solution) = evaluate(case, duration, settings);
        let ok = evaluation.feasible::<C::Model, N, M, A>(limits);
        (ok, evaluation, solution)
    };
    // bracket: (infeasible lo, feasible hi)
    let (mut lo, mut hi, mut below, mut above) = match probe(own) {
        (true, evaluation, solution) => {
            let mut above = (evaluation, solution);
            let mut hi = own;
            let mut lo = own / 2.0;
            loop {
                let (ok, evaluation, solution) = probe(lo);
                if !ok {
                    break (lo, hi, evaluation, above);
                }
                above = (evaluation, solution);
                hi = lo;
                lo /= 2.0;
                if lo < settings.tolerance {
                    return Err(PlanError::Unbounded { duration: hi });
                }
            }
        }
        (false, evaluation, _) => {
            let at_own = reason::<C::Model, N, M, A>(&evaluation, limits);
            let mut below = evaluation;
            let mut lo = own;
            let mut hi = 2.0 * own;
            loop {
                let (ok, evaluation, solution) = probe(hi);
                if ok {
                    break (lo, hi, below, (evaluation, solution));
                }
                if hi > 64.0 * own {
                    let last = reason::<C::Model, N, M, A>(&evaluation, limits);
                    return Err(PlanError::NoFeasibleDuration {
                        duration: hi,
                        reason: if last == at_own {
                            last
                        } else {
                            format!(
                                "at the move's own {} s: {at_own}; at {} s: {last}",
                                Number(own),
                                Number(hi)
                            )
                        },
                    });
                }
                below = evaluation;
                lo = hi;
                hi *= 2.0;
            }
        }
    };
    let first_bracket = (lo, hi);
    while hi - lo > settings.tolerance {
        let mid = 0.5 * (lo + hi);
        let (ok, evaluation, solution) = probe(mid);
        if ok {
            hi = mid;
            above = (evaluation, solution);
        } else {
            lo = mid;
            below = evaluation;
        }
    }
    if let Some(error) = &below.error {
        return Err(PlanError::RunFailsFirst {
            duration: hi,
            error: error.clone(),
        });
    }
    // infeasible by the audit alone: no limit decides
    let binds = |e: &Evaluation| (e.bindings::<C::Model, N, M, A>(limits).iter()).any(|b| b.excess > b.allowance);
    if let Some(finding) = below.findings.first()
        && !binds(&below)
    {
        return Err(PlanError::RunFailsFirst {
            duration: hi,
            error: finding.clone(),
        });
    }
    let (answer, solution) = above;
    let at_answer = answer.bindings::<C::Model, N, M, A>(limits);
    // the limit most violated just below the answer, with its value at the
    // answer and the time it is violated just below it
    let violated = below.bindings::<C::Model, N, M, A>(limits).into_iter().next();
    let binding = match violated {
        Some(b) => {
            let value = at_answer
                .iter()
                .find(|a| a.name == b.name)
                .map_or(f64::NAN, |a| a.value);
            Binding { value, ..b }
        }
        None => at_answer.first().cloned().unwrap_or(Binding {
            name: String::new(),
            limit: f64::NAN,
            value: f64::NAN,
            at: f64::NAN,
            excess: f64::NAN,
            allowance: 0.0,
            tension: false,
        }),
    };
    // feasible durations an interval on the first bracket?
    let points = settings.interval_points;
    let mut counterexample = None;
    for i in 1..=points {
        let d = first_bracket.0 + (first_bracket.1 - first_bracket.0) * i as f64 / (points + 1) as f64;
        let ok = evaluate(case, d, settings).0.feasible::<C::Model, N, M, A>(limits);
        if ok != (d >= hi) && (d - hi).abs() > settings.tolerance {
            counterexample.get_or_insert(d);
        }
    }
    let solution = solution.ok_or_else(|| PlanError::NoFeasibleDuration {
        duration: hi,
        reason: reason::<C::Model, N, M, A>(&answer, limits),
    })?;
    Ok(Fastest {
        duration: hi,
        path: PathSpec {
            profile: spec.profile.scaled(hi / own),
            t1: spec.t0 + hi,
            ..spec.clone()
        },
        bracket: (lo, hi),
        binding,
        at_answer,
        evaluations,
        interval: IntervalCheck {
            points,
            holds: counterexample.is_none(),
            counterexample,
        },
        solution,
        lower_bound: C::lower_bound(case.model(), &spec.start, &spec.end, &limits.torque),
    })
}

/// One point of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepPoint {
    /// The swept parameter values, in the order of the sweep's parameters.
    pub values: Vec<f64>,
    /// The duration (the case's own if durations are not swept).
    pub duration: f64,
    /// The run's peaks (or its error).
    pub evaluation: Evaluation,
    /// Within every limit.
    pub feasible: bool,
}

/// The grid of `params` (each `(name, values)`) and `durations` (the
/// case's own if empty), row-major with the last parameter fastest and the
/// duration fastest of all, as [`sweep_points`] evaluates it: in parallel
/// and in grid order, so the result does not depend on the number of
/// threads. `progress` is called once per finished point. A point that
/// fails records its error; the sweep goes on.
pub fn sweep<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    params: &[(String, Vec<f64>)],
    durations: &[f64],
    limits: &Limits,
    settings: &Settings,
    progress: &(dyn Fn() + Sync),
) -> Vec<SweepPoint> {
    let spec = case.path().spec();
    let points = grid_points(spec.t1 - spec.t0, params, durations);
    let names: Vec<String> = params.iter().map(|(name, _)| name.clone()).collect();
    sweep_points(case, &names, points, limits, settings, progress)
}

/// The points of the grid of `params` and `durations` (`own` if empty),
/// row-major with the last parameter fastest and the duration fastest of
/// all: each the parameters' values and a duration.
pub fn grid_points(own: f64, params: &[(String, Vec<f64>)], durations: &[f64]) -> Vec<(Vec<f64>, f64)> {
    let own = [own];
    let durations: &[f64] = if durations.is_empty() { &own } else { durations };
    let mut grid: Vec<Vec<f64>> = vec![Vec::new()];
    for (_, values) in params {
        grid = grid
            .into_iter()
            .flat_map(|prefix| values.iter().map(move |&v| [prefix.clone(), vec![v]].concat()))
            .collect();
    }
    grid.into_iter()
        .flat_map(|values| durations.iter().map(move |&d| (values.clone(), d)))
        .collect()
}

/// Any set of points: each the values of the parameters `names` (in that
/// order) and a duration, evaluated as [`evaluate`] does with the
/// parameters set by name, in parallel (rayon) and returned in the order
/// given. `progress` is called once per finished point. A point that fails
/// records its error; the sweep goes on ([`check_points`] refuses a set
/// that cannot run before any run).
pub fn sweep_points<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    names: &[String],
    points: Vec<(Vec<f64>, f64)>,
    limits: &Limits,
    settings: &Settings,
    progress: &(dyn Fn() + Sync),
) -> Vec<SweepPoint> {
    // a flag in scope here stops the points on the pool's threads too: a
    // point not started once it is set is not evaluated
    let cancel = Cancel::current();
    let run = move || {
        points
            .into_par_iter()
            .map(|(values, duration)| {
                let point = match &cancel {
                    Some(cancel) if cancel.is_set() => SweepPoint {
                        evaluation: Evaluation::failed(duration, crane_runtime::Error::Cancelled.to_string()),
                        values,
                        duration,
                        feasible: false,
                    },
                    Some(cancel) => cancel.scope(|| sweep_point(case, names, &values, duration, limits, settings)),
                    None => sweep_point(case, names, &values, duration, limits, settings),
                };
                progress();
                point
            })
            .collect()
    };
    match sweep_pool() {
        Some(pool) => pool.install(run),
        None => run(),
    }
}

/// The thread pool sweeps run on, built by this process: a process forked
/// from one that swept inherits the pool's handles but none of its threads,
/// and rayon's global pool then waits for ever in the child (a Python
/// sweep, `os.fork()`, a sweep in the child). `None` where no pool can be
/// built (the sweep then runs on the global one).
fn sweep_pool() -> Option<Arc<rayon::ThreadPool>> {
    static POOL: Mutex<Option<(u32, Arc<rayon::ThreadPool>)>> = Mutex::new(None);
    let pid = std::process::id();
    let mut pool = POOL.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some((owner, built)) = pool.as_ref()
        && *owner == pid
    {
        return Some(Arc::clone(built));
    }
    let built = Arc::new(rayon::ThreadPoolBuilder::new().build().ok()?);
    // the parent's pool, in a forked child: its threads are not here, so
    // it is left alone rather than dropped (dropping signals them)
    if let Some(inherited) = pool.replace((pid, Arc::clone(&built))) {
        std::mem::forget(inherited);
    }
    Some(built)
}

/// One sweep point: the model with the parameters `names` set to
/// `values`, scaled to `duration`.
pub fn sweep_point<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    names: &[String],
    values: &[f64],
    duration: f64,
    limits: &Limits,
    settings: &Settings,
) -> SweepPoint {
    let mut model = case.model().clone();
    let mut error = impulses(case).err().map(|e| e.to_string());
    for (name, &value) in names.iter().zip(values) {
        if let Err(e) = model.set_parameter(name, value) {
            error.get_or_insert(e.to_string());
        }
    }
    let evaluation = match error {
        Some(e) => Evaluation::failed(duration, e),
        None => evaluate_model(case, model, duration, settings).0,
    };
    let feasible = evaluation.feasible::<C::Model, N, M, A>(limits);
    SweepPoint {
        values: values.to_vec(),
        duration,
        evaluation,
        feasible,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crane_runtime::options::MIN_DT;

    /// The step of an evaluation divides its run, stays at most the asked
    /// `dt`, and never falls below the runtime's smallest step: `fastest
    /// --dt 1e-6` on a move of 3.3281 s chose 9.999998e-7 s, which the
    /// runtime refuses, and reported that as the inverse dynamics failing.
    #[test]
    fn the_step_divides_the_run_and_respects_the_minimum() {
        let whole = |span: f64, dt: f64| ((span / dt) - (span / dt).round()).abs() < 1e-6;
        for span in [4.0, 3.3281, 3.328_123_456_7, 1.0 + 1e-9, 0.5e-6] {
            for dt in [0.05, 0.01, 1e-3, MIN_DT] {
                let step = step_for(span, dt);
                assert!(whole(span, step), "{span} / {step}");
                assert!(step >= MIN_DT || span < MIN_DT, "{span}, {dt}: {step}");
                assert!(step <= dt || dt == MIN_DT || span < dt, "{span}, {dt}: {step}");
            }
        }
        // durations of a bisection at the minimum: never below it
        for span in [3.328_123_456_7, std::f64::consts::PI, 2.385_742_187_5] {
            let step = step_for(span, MIN_DT);
            assert!((MIN_DT..MIN_DT * (1.0 + 1e-6)).contains(&step), "{span}: {step}");
        }
        assert_eq!(step_for(4.0, 0.05), 0.05);
    }
}
