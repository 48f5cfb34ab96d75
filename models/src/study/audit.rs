//! The audit of a result: whether the numbers a run, a replay, a
//! convergence study or a planning evaluation report are a trustworthy
//! inverse dynamics of the crane, and a move it can make. One function
//! ([`audit`]) reads a run's [`Summary`] and returns every [`Finding`];
//! the command line prints them and fails on them under `--strict`, the
//! FMU reports them as `fmi2Warning` or `fmi2Error` by [`Severity`], and
//! planning counts a duration with a finding as infeasible.
//!
//! ```
//! use crane_models::navy_planar::PaperCase;
//! use crane_models::study::{self, RunSettings, audit::Severity};
//!
//! let case = PaperCase::new(4.0).unwrap();
//! let outcome = study::run(&case, &RunSettings::default(), &mut |_, _| {}).unwrap();
//! assert!(study::audit(&outcome.summary).is_empty());          // taut, flat, on its constraints
//! // one step of 1e6 s: Newton's scaled test is met, the constraints are not
//! let settings = RunSettings { dt: 1e6, ..RunSettings::default() };
//! let coarse = study::run(&PaperCase::new(1e6).unwrap(), &settings, &mut |_, _| {}).unwrap();
//! let findings = study::audit(&coarse.summary);
//! assert!(findings.iter().any(|f| f.severity() == Severity::Error));
//! ```

use std::fmt;

use crane_runtime::error::{Number, Rounded, Seconds};
use crane_runtime::internal::{RUNAWAY_FACTOR, internal_dynamics};
use crane_runtime::nalgebra::SVector;
use crane_runtime::{CraneModel, State};

use super::summary::{ConstraintResidual, InputSpike, LimitSummary, RopeSummary, Summary, below_floor};

/// How bad a finding is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// The numbers solve the crane's equations, but are not a move to make
    /// or not a result to trust as a feedforward: a rope that would push,
    /// a limit exceeded, unstable internal dynamics, a path too rough, a
    /// replay that does not bring the load to the path's end.
    Warning,
    /// The numbers are not a solution of the crane's equations: states off
    /// their constraints, a rope of non-positive length, a runaway input.
    Error,
}

/// What the audit found.
#[derive(Debug, Clone, PartialEq)]
pub enum Finding {
    /// The internal dynamics along the path are unstable: the causal
    /// inverse grows without bound.
    UnstableInternalDynamics {
        /// The crane's name.
        model: String,
        /// Their dimension.
        dimension: usize,
        /// The largest real part of an eigenvalue, 1/s.
        max_real_part: f64,
        /// Where, s.
        at: f64,
    },
    /// The structure counts internal dynamics, but no sampled state of the
    /// run was resolved: whether they are stable is not known.
    InternalDynamicsUnknown {
        /// The crane's name.
        model: String,
        /// The structural count.
        dimension: usize,
        /// Why the first sampled state was not resolved.
        reason: String,
    },
    /// The inputs depend on derivatives of the path beyond its continuity.
    PathTooRough {
        /// The crane's name.
        model: String,
        /// The highest path derivative the inputs depend on.
        needed: usize,
        /// The highest continuous one.
        continuous: usize,
    },
    /// The crane's inputs need a higher derivative of the path than the
    /// formulation's index reduction covers: no convergence theorem bounds
    /// its errors (on the built-ins BDF-2..5 keep their order, backward
    /// Euler on the double pendulum does not).
    BeyondFormulation {
        /// The crane's name.
        model: String,
        /// The path order the crane needs.
        needed: usize,
        /// The path order the formulation covers.
        covered: usize,
    },
    /// A rope's length reaches zero or below during the run: the path
    /// leaves the crane's workspace, or the move is too fast for the crane
    /// (the start refuses such a state; along the run the equations still
    /// solve, on the mirror side of the rope).
    NonPositiveRopeLength {
        /// The crane's name.
        model: String,
        /// The rope's tension name, e.g. `N2`.
        rope: String,
        /// Its constraint's name.
        constraint: String,
        /// Its shortest length, m.
        length: f64,
        /// When, s.
        at: f64,
        /// Its length with the load at rest at the same point of the path
        /// ([`RopeSummary::length_at_rest`]), where known.
        at_rest: Option<f64>,
        /// The step, s, where it is too long for the path's shortest feature
        /// ([`resolves`](super::summary::resolves)) in a discretised
        /// formulation: its equations then also solve on the mirror side of
        /// a rope, and the step, not the move, may be the cause.
        long_step: Option<f64>,
    },
    /// The reported states leave their constraints
    /// ([`ConstraintResidual::violated`](super::summary::ConstraintResidual::violated)).
    ConstraintsViolated {
        /// The crane's name.
        model: String,
        /// How far, where, when.
        residual: super::summary::ConstraintResidual,
    },
    /// Many steps met a singular iteration matrix or held what a nearly
    /// slack rope leaves free ([`singular_steps`](super::summary::singular_steps)).
    SingularSteps {
        /// The crane's name.
        model: String,
        /// Steps with a minimum-norm Newton update.
        count: usize,
        /// All steps.
        steps: usize,
    },
    /// An input exceeds [`RUNAWAY_FACTOR`]
    /// times its size at the start.
    Runaway {
        /// The crane's name.
        model: String,
        /// From when, s.
        at: f64,
    },
    /// A rope whose tension falls below zero beyond round-off
    /// ([`below_floor`]): it would have to push.
    SlackRope(RopeSummary),
    /// An input beyond its limit.
    LimitExceeded {
        /// The limit and its first violation.
        limit: LimitSummary,
        /// The input's unit suffix (`" N m"`), empty where none is declared.
        unit: String,
    },
    /// An input turns between steps by more than its peak
    /// ([`InputSpike::spiky`]).
    InputSpike {
        /// The crane's name.
        model: String,
        /// Where and how much.
        spike: InputSpike,
    },
    /// Round-off makes up most of a discretised run's error against the
    /// exact inputs ([`RoundOff::dominates`](super::summary::RoundOff::dominates)):
    /// a finer step would be less accurate.
    RoundOffDominates {
        /// The crane's name.
        model: String,
        /// The time step, s.
        dt: f64,
        /// The error and the floor.
        round_off: super::summary::RoundOff,
    },
    /// The path's ramps are shorter than [`RAMP_STEPS`] steps.
    UnresolvedRamp {
        /// The ramp duration, s.
        tau0: f64,
        /// The step, s.
        dt: f64,
    },
    /// In the replay, a rope would have to push.
    ReplaySlack {
        /// The rope's tension name.
        rope: String,
        /// From when, s.
        at: f64,
    },
    /// The replayed load does not arrive: it ends, or sways after the move,
    /// farther from the path's end than [`REPLAY_TOLERANCE`] of its travel.
    ReplayMisses {
        /// `|x(tf) - gamma(tf)|`, m.
        deviation_at_tf: f64,
        /// The largest `|x(t) - gamma(tf)|` in the settling window, m.
        residual_sway: f64,
        /// `|gamma(t1) - gamma(t0)|`, m.
        travel: f64,
        /// Whether the replay was on a plant that differs from the planner's.
        mismatched: bool,
        /// Whether a feedback law acted.
        feedback: bool,
    },
}

/// The fewest steps a three-phase path's ramp must span: the difference
/// formulas of BDF-3 and above span more than a shorter ramp, and the
/// inputs' peaks inside it fall between the steps (ramps of tau0 = 0.01 s
/// on navy-planar at dt = 0.01 s give a peak |u2| of 98 N m; the exact
/// inputs there reach ~1e12 N m).
pub const RAMP_STEPS: f64 = 4.0;

/// How far from the path's end, relative to the load's travel, a replayed
/// load may end or sway and still count as arrived (at least 1 mm): the
/// nominal replays of BDF-2..5 torques stay below 1e-4 m on the paper's
/// 5 m move, torques that miss it leave metres (a backward Euler run
/// that ends with the move holds torques O(dt) off the static ones: 0.84
/// m of drift over the settling window at dt = 0.01 s; a 20 % heavier
/// load: 68 m).
pub const REPLAY_TOLERANCE: f64 = 1e-2;

impl Finding {
    /// How bad it is.
    pub fn severity(&self) -> Severity {
        match self {
            Finding::ConstraintsViolated { .. } | Finding::NonPositiveRopeLength { .. } | Finding::Runaway { .. } => {
                Severity::Error
            }
            _ => Severity::Warning,
        }
    }
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Finding::UnstableInternalDynamics {
                model,
                dimension,
                max_real_part,
                at,
            } => write!(
                f,
                "{model} has unstable internal dynamics along this path (dimension {dimension}, largest real part \
                 {max_real_part:.4} 1/s at t = {} s): the computed inputs grow without bound; see docs/internal-dynamics.md \
                 in the guide",
                Seconds(*at)
            ),
            Finding::InternalDynamicsUnknown {
                model,
                dimension,
                reason,
            } => write!(
                f,
                "{model} has internal dynamics of dimension {dimension} by its structure, but the diagnosis resolved \
                 none of the run's sampled states ({reason}): whether they are stable, and so whether its inputs \
                 stay bounded, is not known; look at the inputs before using them"
            ),
            Finding::PathTooRough {
                model,
                needed,
                continuous,
            } => {
                write!(
                    f,
                    "the inputs of {model} depend on the load path's derivatives up to order {needed}, but this path \
                     is continuous only up to order {continuous}: the exact inputs jump or carry impulses where its \
                     derivative {} jumps, and the computed ones grow there as dt shrinks ",
                    continuous + 1
                )?;
                let smoothest = crane_runtime::trajectory::SMOOTH_THREE_PHASE_CONTINUITY;
                if *needed <= smoothest && *continuous < smoothest {
                    f.write_str("(use a smoother path: trajectory = \"smooth-three-phase\")")
                } else {
                    write!(
                        f,
                        "(no built-in path is that smooth, the smoothest, \"smooth-three-phase\", to order \
                         {smoothest}: give a path of your own, continuous to order {needed})"
                    )
                }
            }
            Finding::NonPositiveRopeLength {
                model,
                rope,
                constraint,
                length,
                at,
                at_rest,
                long_step,
            } => {
                write!(
                    f,
                    "rope {rope} of {model} (constraint `{constraint}`) has the length {length:.4} m at t = {} s: the \
                     computed motion is not one the crane can make; ",
                    Seconds(*at)
                )?;
                if let Some(dt) = long_step {
                    return write!(
                        f,
                        "the step of {} s is too long for the path (a twentieth of its shortest feature at most): the \
                         scheme's equations at such a step also solve on the mirror side of a rope, so the step, not \
                         the move, may be the cause (a shorter step tells; the dummy-derivative formulation stays on \
                         the crane's branch at any step)",
                        Seconds(*dt)
                    );
                }
                match at_rest {
                    Some(rest) if *rest > 0.0 => write!(
                        f,
                        "with the load at rest at the same point of the path the rope is {rest:.4} m long, so the \
                         path is inside the crane's workspace and the move is too fast for the crane: following it, \
                         the load swings the rope through zero length (a slower move, or `crane fastest` under \
                         limits, finds one the crane can make)"
                    ),
                    Some(_) => f.write_str(
                        "the path leaves the crane's workspace (with the load at rest there, a rope would be shorter \
                         than zero)",
                    ),
                    None => f.write_str(
                        "the path leaves the crane's workspace, or the move is too fast for the crane (no \
                         equilibrium with the load at rest there was found to tell which: try the same path slower)",
                    ),
                }
            }
            Finding::ConstraintsViolated { model, residual } => write!(f, "{model}: {residual}"),
            Finding::SingularSteps { model, count, steps } => write!(
                f,
                "{count} of {steps} steps of {model} met an iteration matrix singular to working precision or held \
                 what a rope under {:e} of the largest tension leaves free (a rope without tension leaves a \
                 coordinate free, as when the load hangs straight below the boom tip): the path does not determine \
                 the inputs there, and they are not a reliable result",
                crane_runtime::stepper::HOLD_TENSION_RATIO
            ),
            Finding::BeyondFormulation { model, needed, covered } => write!(
                f,
                "the inputs of {model} depend on the load path's derivatives up to order {needed}, but this \
                 formulation (the paper's minimal extension, eqs. 22 and 24) covers order {covered}: the \
                 discretised system's index is beyond what the schemes are known to converge on, so no error bound \
                 holds for the computed inputs (measured on the built-in cranes of path order 6: BDF-2 to BDF-5 \
                 in eqs. 22 reach their order, backward Euler on the double pendulum does not); the \
                 dummy-derivative formulation, where the crane has it, gives them exactly"
            ),
            Finding::Runaway { model, at } => write!(
                f,
                "an input of {model} exceeds 1e6 times its size at the start from t = {} s: not a physical result",
                Seconds(*at)
            ),
            Finding::SlackRope(rope) => match rope.slack() {
                Some(slack) => write!(f, "{slack} (min tension {:.3e} N)", rope.min_tension),
                None => write!(f, "rope {} goes slack", rope.name),
            },
            Finding::LimitExceeded { limit, unit } => write!(
                f,
                "|{}| exceeds its limit {}{unit} first at t = {} s (peak {}{unit})",
                limit.name,
                Number(limit.limit),
                Seconds(limit.first_violation.unwrap_or(f64::NAN)),
                Rounded(limit.peak)
            ),
            Finding::RoundOffDominates { model, dt, round_off } => write!(
                f,
                "round-off makes up most of the error of {model}'s inputs at dt = {} s: {:.3e} against the exact \
                 inputs over the middle of the run, where the step-to-step noise is {:.3e} (the scheme's second \
                 differences of the rounded coordinates grow like 1/dt^2): a finer step is less accurate, a larger \
                 one as accurate; the dummy-derivative formulation gives the exact inputs",
                Seconds(*dt),
                round_off.error,
                round_off.floor
            ),
            Finding::InputSpike { model, spike } => write!(
                f,
                "input {} of {model} turns by {:.4e} between the steps around t = {} s, more than its largest value \
                 elsewhere, {:.4e}: no smooth input does that; a direction the path does not determine (a rope without \
                 tension leaves a massless pulley free, and round-off, differentiated by the scheme, moves it) or a \
                 path feature shorter than the step; the inputs there are not a result (a longer step, or a faster \
                 move, determines them better)",
                spike.input,
                spike.second_difference,
                Seconds(spike.t),
                spike.peak
            ),
            Finding::UnresolvedRamp { tau0, dt } => write!(
                f,
                "the path's ramps last tau0 = {tau0} s, fewer than {RAMP_STEPS} steps of dt = {dt} s: the steps do \
                 not resolve them, and the inputs' peaks inside them are missed (take dt <= {} s, or longer ramps)",
                tau0 / RAMP_STEPS
            ),
            Finding::ReplaySlack { rope, at } => write!(
                f,
                "in the replay rope {rope} would have to push from t = {} s",
                Seconds(*at)
            ),
            Finding::ReplayMisses {
                deviation_at_tf,
                residual_sway,
                travel,
                mismatched,
                feedback,
            } => {
                let why = match (mismatched, feedback) {
                    (true, true) => "the plant differs from the planner's and the feedback law does not make up for it",
                    (true, false) => "the plant differs from the planner's (add --feedback)",
                    (false, _) => {
                        "the torques at the end differ from the static ones (a scheme of order 1, or a run that \
                         ends with the move: run beyond it, or take a higher-order scheme or a smaller dt)"
                    }
                };
                write!(
                    f,
                    "the replayed load does not arrive: it ends {deviation_at_tf:.3e} m from the path's end and \
                     sways by {residual_sway:.3e} m after the move, more than {} % of its {travel:.3} m travel: {why}",
                    REPLAY_TOLERANCE * 100.0
                )
            }
        }
    }
}

/// The run's step where it is too long for the path's shortest feature in a
/// formulation that discretises the path (eqs. 22 or 24): a rope of
/// non-positive length may then be the step's mirror root, not the move's.
fn long_step(summary: &Summary) -> Option<f64> {
    let discretised = summary.formulation != super::Formulation::DummyDerivative.name();
    (discretised && !super::summary::resolves(summary.shortest_feature, summary.dt)).then_some(summary.dt)
}

/// Every finding on a run's summary, in this order: a crane beyond the
/// formulation, states off their constraints, unstable internal dynamics,
/// internal dynamics the diagnosis could not resolve, a path too rough, ropes of non-positive length, a runaway input, many
/// singular steps, ramps the steps do not resolve, a spiking input, slack
/// ropes, exceeded limits, and the replay's, if the summary has one.
pub fn audit(summary: &Summary) -> Vec<Finding> {
    let model = summary.model.clone();
    let internal = &summary.internal_dynamics;
    let mut out = Vec::new();
    if let Some(p) = internal.path_order.filter(|p| !p.is_covered()) {
        out.push(Finding::BeyondFormulation {
            model: model.clone(),
            needed: p.needed,
            covered: p.covered,
        });
    }
    if let Some(residual) = summary.constraint_residual.as_ref().filter(|r| r.violated()) {
        out.push(Finding::ConstraintsViolated {
            model: model.clone(),
            residual: residual.clone(),
        });
    }
    // stable inversion's inputs are the bounded ones whatever the internal
    // dynamics do
    let inverted = summary.formulation == super::Formulation::StableInversion.name();
    if internal.stable == Some(false) && !inverted {
        out.push(Finding::UnstableInternalDynamics {
            model: model.clone(),
            dimension: internal.dimension,
            max_real_part: internal.max_real_part.unwrap_or(f64::NAN),
            at: internal.at.unwrap_or(f64::NAN),
        });
    }
    // (stability is unknown only where every sampled state was unresolved,
    // each with its reason)
    if let (None, Some(reason)) = (internal.stable, internal.unresolved_reason.as_ref()) {
        out.push(Finding::InternalDynamicsUnknown {
            model: model.clone(),
            dimension: internal.dimension,
            reason: reason.to_string(),
        });
    }
    if let Some(smooth) = summary.path_smoothness.as_ref().filter(|s| !s.sufficient) {
        out.push(Finding::PathTooRough {
            model: model.clone(),
            needed: smooth.needed,
            continuous: smooth.continuous,
        });
    }
    for r in summary.ropes.iter().filter(|r| r.leaves_workspace()) {
        out.push(Finding::NonPositiveRopeLength {
            model: model.clone(),
            rope: r.name.clone(),
            constraint: r.constraint.clone(),
            length: r.min_length,
            at: r.t_min_length,
            at_rest: r.length_at_rest,
            long_step: long_step(summary),
        });
    }
    if let Some(at) = internal.runaway_at {
        out.push(Finding::Runaway {
            model: model.clone(),
            at,
        });
    }
    if super::summary::singular_steps(summary) {
        out.push(Finding::SingularSteps {
            model,
            count: summary.newton.min_norm_steps + summary.newton.held_steps,
            steps: summary.steps,
        });
    }
    out.extend(unresolved_ramp(summary.ramp, summary.dt));
    // steps too long for the path's features turn smooth inputs by as much
    // as their peak: no sign of a wrong input there
    let resolved = super::summary::resolves(summary.shortest_feature, summary.dt);
    if let Some(spike) = summary.input_spike.as_ref().filter(|s| resolved && s.spiky()) {
        out.push(Finding::InputSpike {
            model: summary.model.clone(),
            spike: spike.clone(),
        });
    }
    if let Some(round_off) = summary.round_off.as_ref().filter(|r| r.dominates()) {
        out.push(Finding::RoundOffDominates {
            model: summary.model.clone(),
            dt: summary.dt,
            round_off: round_off.clone(),
        });
    }
    let workspace_left = |r: &&RopeSummary| r.leaves_workspace();
    out.extend(
        (summary.ropes.iter())
            .filter(|r| !workspace_left(r) && r.first_slack.is_some())
            .map(|r| Finding::SlackRope(r.clone())),
    );
    out.extend(
        (summary.torque_limits.iter())
            .filter(|l| l.first_violation.is_some())
            .map(|l| Finding::LimitExceeded {
                limit: l.clone(),
                unit: summary.unit_suffix(&l.name),
            }),
    );
    if let Some(replay) = &summary.replay {
        out.extend(
            replay
                .first_slack
                .iter()
                .map(|(rope, &at)| Finding::ReplaySlack { rope: rope.clone(), at }),
        );
        if replay.misses() {
            out.push(Finding::ReplayMisses {
                deviation_at_tf: replay.deviation_at_tf,
                residual_sway: replay.residual_sway,
                travel: replay.travel,
                mismatched: !replay.plant.is_empty(),
                feedback: replay.feedback.is_some(),
            });
        }
    }
    out
}

/// The audit of a run step by step, for a host that steps it itself (the
/// FMU): the checks of [`audit`] that a single state can answer, on each
/// state as it comes, and those of the start. A step makes no allocation
/// unless it finds something.
///
/// ```
/// use crane_models::navy_planar::PaperCase;
/// use crane_models::study::audit::StepAudit;
/// use crane_runtime::{Advance, Options, Scheme, Stepper, redundant::Redundant};
///
/// let case = PaperCase::new(4.0).unwrap();
/// let start = case.start().unwrap();
/// let (mut audit, findings) = StepAudit::start("navy-planar", case.model(), &start, Some(4));
/// assert!(findings.is_empty());
/// let options = Options::stepping(0.01).unwrap().with_scheme(Scheme::Bdf2);
/// let problem = Redundant::new(Box::new(case.model().clone()), case.path().clone());
/// let mut stepper = Stepper::new(problem, &start, &options).unwrap();
/// for _ in 0..400 {
///     let report = stepper.step().unwrap();
///     assert_eq!(audit.step(case.model(), stepper.state(), report.left_free()), None);
/// }
/// ```
#[derive(Debug, Clone)]
pub struct StepAudit {
    model: &'static str,
    /// The largest input at the start (at least 1): the runaway's scale.
    scale: f64,
    /// The largest rope tension so far (the slack rule's scale).
    peak_tension: f64,
    /// Steps, and those with a minimum-norm Newton update.
    steps: usize,
    singular: usize,
    /// What was reported already: each warning once.
    slack_reported: bool,
    singular_reported: bool,
    /// Scratch: rope lengths and tensions.
    lengths: Vec<f64>,
    tensions: Vec<f64>,
}

impl StepAudit {
    /// The audit of a run of `model` (called `name`) from `start`, whose
    /// formulation covers the path's derivatives up to `covered` (`None`
    /// where it needs no such bound), and what the start shows: unstable
    /// internal dynamics there, a crane beyond the formulation.
    pub fn start<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
        name: &'static str,
        model: &Mdl,
        start: &State<N, M, A>,
        covered: Option<usize>,
    ) -> (Self, Vec<Finding>) {
        let ropes = Mdl::INFO.ropes.len();
        let mut audit = Self {
            model: name,
            scale: start.u.amax().max(1.0),
            peak_tension: 0.0,
            steps: 0,
            singular: 0,
            slack_reported: false,
            singular_reported: false,
            lengths: vec![0.0; ropes],
            tensions: vec![0.0; ropes],
        };
        let mut findings = Vec::new();
        if let (Some(needed), Some(covered)) = (Mdl::STRUCTURE.map(|s| s.path_order(A)), covered)
            && needed > covered
        {
            findings.push(Finding::BeyondFormulation {
                model: name.to_string(),
                needed,
                covered,
            });
        }
        let flat = Mdl::STRUCTURE.is_some_and(|s| s.dimension == 0);
        if !flat
            && let Ok(d) = internal_dynamics(model, start)
            && !d.is_stable()
        {
            findings.push(Finding::UnstableInternalDynamics {
                model: name.to_string(),
                dimension: d.dimension,
                max_real_part: d.max_real_part,
                at: start.t,
            });
        }
        model.rope_tensions(&start.q, &start.lambda, &mut audit.tensions);
        audit.peak_tension = audit.tensions.iter().fold(0.0, |m, n| m.max(n.abs()));
        (audit, findings)
    }

    /// Audit `state`, reached by a step that did (`singular`) or did not
    /// take a minimum-norm Newton update: the first finding, errors first
    /// (states off their constraints, a rope of non-positive length, a
    /// runaway input), then the warnings not reported before (a rope that
    /// would push, many singular steps).
    pub fn step<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
        &mut self,
        model: &Mdl,
        state: &State<N, M, A>,
        singular: bool,
    ) -> Option<Finding> {
        self.steps += 1;
        self.singular += usize::from(singular);
        let (k, distance) = constraint_distance(model, &state.q);
        let scale = state.q.amax().max(1.0);
        let residual = ConstraintResidual {
            constraint: String::new(),
            distance,
            t: state.t,
            scale,
        };
        if residual.violated() {
            return Some(Finding::ConstraintsViolated {
                model: self.model.to_string(),
                residual: ConstraintResidual {
                    constraint: Mdl::INFO.constraints.get(k).copied().unwrap_or("").to_string(),
                    ..residual
                },
            });
        }
        model.rope_lengths(&state.q, &mut self.lengths);
        if let Some(r) = self.lengths.iter().position(|length| !(*length > 0.0)) {
            let rope = &Mdl::INFO.ropes[r];
            return Some(Finding::NonPositiveRopeLength {
                model: self.model.to_string(),
                rope: rope.tension.to_string(),
                constraint: Mdl::INFO
                    .constraints
                    .get(rope.constraint)
                    .copied()
                    .unwrap_or("")
                    .to_string(),
                length: self.lengths[r],
                at: state.t,
                at_rest: None,
                long_step: None,
            });
        }
        if !(state.u.amax() <= RUNAWAY_FACTOR * self.scale) {
            return Some(Finding::Runaway {
                model: self.model.to_string(),
                at: state.t,
            });
        }
        model.rope_tensions(&state.q, &state.lambda, &mut self.tensions);
        self.peak_tension = self.tensions.iter().fold(self.peak_tension, |m, n| m.max(n.abs()));
        if !self.slack_reported
            && let Some(r) = (self.tensions.iter()).position(|&n| below_floor(n, 0.0, self.peak_tension))
        {
            self.slack_reported = true;
            return Some(Finding::SlackRope(RopeSummary {
                name: Mdl::INFO.ropes[r].tension.to_string(),
                min_tension: self.tensions[r],
                t_min: state.t,
                max_tension: self.peak_tension,
                first_slack: Some(state.t),
                constraint: (Mdl::INFO.constraints.get(Mdl::INFO.ropes[r].constraint).copied())
                    .unwrap_or("")
                    .to_string(),
                min_length: self.lengths[r],
                t_min_length: state.t,
                length_at_rest: None,
            }));
        }
        if !self.singular_reported && super::summary::too_many_singular(self.singular, self.steps) {
            self.singular_reported = true;
            return Some(Finding::SingularSteps {
                model: self.model.to_string(),
                count: self.singular,
                steps: self.steps,
            });
        }
        None
    }
}

/// [`Finding::UnresolvedRamp`] where a three-phase path's ramps, lasting
/// `tau0` (`None`: not a three-phase path), are shorter than
/// [`RAMP_STEPS`] steps of `dt`: known before the run, so a stepping host
/// (the FMU) hears it at the start.
///
/// ```
/// use crane_models::study::audit::{Finding, unresolved_ramp};
///
/// assert!(matches!(unresolved_ramp(Some(0.01), 0.01), Some(Finding::UnresolvedRamp { .. })));
/// assert_eq!(unresolved_ramp(Some(0.04), 0.01), None);
/// assert_eq!(unresolved_ramp(None, 0.01), None);
/// ```
pub fn unresolved_ramp(tau0: Option<f64>, dt: f64) -> Option<Finding> {
    tau0.filter(|&tau0| !(tau0 >= RAMP_STEPS * dt))
        .map(|tau0| Finding::UnresolvedRamp { tau0, dt })
}

/// The constraint of `model` farthest from holding at `q`, and its
/// distance `|g_k(q)| / |dg_k/dq|` (the first-order distance from the
/// constraint's surface; `|g_k|` where the gradient vanishes; NaN counts as
/// the farthest).
pub fn constraint_distance<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    q: &SVector<f64, N>,
) -> (usize, f64) {
    let (g, jacobian) = (model.constraints(q), model.constraint_jacobian(q));
    let mut worst = (0, 0.0);
    for k in 0..M {
        let slope = jacobian.row(k).norm();
        let distance = if slope > 0.0 { g[k].abs() / slope } else { g[k].abs() };
        if !(distance <= worst.1) {
            worst = (k, distance);
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::navy_planar::PaperCase;

    /// What [`StepAudit::step`] finds in one state of navy-planar's start,
    /// changed by `change`, from a fresh audit.
    fn step_finding(change: impl Fn(&mut State<7, 3, 2>)) -> Option<Finding> {
        let case = PaperCase::new(4.0).unwrap();
        let start = case.start().unwrap();
        let (mut audit, _) = StepAudit::start("navy-planar", case.model(), &start, Some(4));
        let mut state = start;
        change(&mut state);
        audit.step(case.model(), &state, false)
    }

    /// Each check of a step from both sides of its threshold: the load
    /// lowered off its rope by 1e-3 of the coordinates' scale (10 m here) is
    /// flagged, by 1e-9 not (Newton's tolerance is 1e-10 relative; the
    /// threshold, `CONSTRAINT_TOLERANCE`, 1e-6); a rope of negative length
    /// (its constraint, written in squares, still holds) is flagged, as is
    /// an input a billion times its size at the start, and the start itself
    /// is clean.
    #[test]
    fn a_step_audit_flags_each_fault_and_not_its_absence() {
        assert_eq!(step_finding(|_| {}), None);
        let off = |by: f64| move |s: &mut State<7, 3, 2>| s.q[6] += by * 10.0;
        assert!(matches!(
            step_finding(off(1e-3)),
            Some(Finding::ConstraintsViolated { .. })
        ));
        assert_eq!(step_finding(off(1e-9)), None);
        let negative = step_finding(|s| s.q[0] = -s.q[0]);
        assert!(
            matches!(&negative, Some(Finding::NonPositiveRopeLength { rope, .. }) if rope == "N1"),
            "{negative:?}"
        );
        let runaway = step_finding(|s| s.u[1] *= 1e9);
        assert!(matches!(runaway, Some(Finding::Runaway { .. })), "{runaway:?}");
        assert_eq!(step_finding(|s| s.u[1] *= 10.0), None);
    }

    /// A path too rough for the crane points to the smooth three-phase path
    /// only where that one is smooth enough and is not the path already: a
    /// crane of path order 8 on it was told to use it.
    #[test]
    fn a_rough_path_is_told_of_a_smoother_one_only_where_there_is_one() {
        let rough = |needed, continuous| {
            Finding::PathTooRough {
                model: "crane".into(),
                needed,
                continuous,
            }
            .to_string()
        };
        let three_phase = rough(6, 4);
        assert!(
            three_phase.contains("use a smoother path: trajectory = \"smooth-three-phase\""),
            "{three_phase}"
        );
        let order_8 = rough(8, 6);
        assert!(!order_8.contains("use a smoother path"), "{order_8}");
        assert!(
            order_8.contains("no built-in path is that smooth") && order_8.contains("continuous to order 8"),
            "{order_8}"
        );
    }
}
