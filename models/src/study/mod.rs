//! What a run means, in one place for the command line, the FMU, the tests
//! and API users: the formulation dispatch ([`Formulation`]), a run with
//! its summary and the audit of its results ([`run`], [`summary`],
//! [`audit`](mod@audit)), the convergence study ([`convergence`]) and the replay
//! policy ([`replay`]). A run is described as data by a [`RunSpec`]
//! ([`spec`]), which scenario files and FMU variables both fill in.
//!
//! ```
//! use crane_models::navy_planar::PaperCase;
//! use crane_models::study::{self, RunSettings};
//!
//! let case = PaperCase::new(4.0).unwrap();                 // sect. 5.1.3
//! let outcome = study::run(&case, &RunSettings::default(), &mut |_, _| {}).unwrap();
//! let summary = &outcome.summary;
//! assert_eq!(summary.steps, 400);
//! assert!(summary.reference.as_ref().unwrap().e_u_at_1_5s.unwrap() < 2e-3); // eq. (48)
//! assert!(outcome.findings.is_empty());                                     // ropes taut, flat
//! ```

pub mod audit;
pub mod convergence;
pub mod replay;
pub mod spec;
pub mod summary;

use std::fmt;
use std::str::FromStr;
use std::time::Instant;

use crane_runtime::error::Number;
use crane_runtime::internal::{diagnose, path_smoothness};
use crane_runtime::{CraneModel, Options, Scheme, Solution, State, dummy_derivative, state_selection};

use crate::case::Case;
use crate::crane::Crane;
pub use audit::{Finding, Severity, audit};
pub use replay::{FeedbackSpec, ReplayOutcome, ReplayRequest};
pub use spec::{RunSpec, SpecError};
pub use summary::{PathSmoothnessSummary, StableInversionSummary, StateSelectionSummary, Summary, below_floor};

/// Which formulation of the servo problem a run solves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Formulation {
    /// Redundant coordinates, eqs. (22a-d): a crane's default where it has
    /// internal dynamics (and so no reduced system), and `Default`'s, which
    /// knows no crane ([`default_for`](Self::default_for) gives a crane's).
    #[default]
    Redundant,
    /// Minimal coordinates, eqs. (24a-e), for a crane with a minimal map.
    Minimal,
    /// Eqs. (22a-d) reduced by dummy derivatives
    /// ([`crane_runtime::dummy_derivative`]), for a crane without internal
    /// dynamics: exact at every step time whatever the path order (the
    /// default of every such crane, [`default_for`](Self::default_for)).
    DummyDerivative,
    /// Stable inversion ([`crane_runtime::stable_inversion`]): the bounded
    /// solution of eqs. (22b-d) on the whole time axis, with pre- and
    /// post-actuation, for a crane whose internal dynamics are unstable
    /// (the default of such a crane, [`default_for`](Self::default_for));
    /// central differences of order 2 whatever the scheme.
    StableInversion,
    /// Eqs. (22a-d) reduced by dummy derivatives with state selection
    /// ([`crane_runtime::state_selection`]): the states the path leaves
    /// free integrated by the scheme, every other unknown algebraic at each
    /// step time (the default of a crane whose internal dynamics are
    /// stable, [`default_for`](Self::default_for)); a flat crane's run is
    /// the dummy-derivative one.
    StateSelection,
}

impl Formulation {
    /// All of them, in order.
    pub const ALL: [Formulation; 5] = [
        Formulation::Redundant,
        Formulation::Minimal,
        Formulation::DummyDerivative,
        Formulation::StateSelection,
        Formulation::StableInversion,
    ];

    /// The default of crane `C`: [`DummyDerivative`](Self::DummyDerivative)
    /// where it has the reduced system (no internal dynamics: every flat
    /// crane), which gives the exact inputs at every step time whatever the
    /// path order and, solved stage by stage, costs less per step than
    /// eqs. (22a-d) with backward Euler on every flat built-in;
    /// [`StateSelection`](Self::StateSelection) where every eigenvalue of
    /// the selected states' equations at the start of the crane's default
    /// manoeuvre has a negative real part (stable internal dynamics: the
    /// scheme's error in the free states only);
    /// [`StableInversion`](Self::StableInversion) where the internal
    /// dynamics there are unstable and have no eigenvalue on the imaginary
    /// axis (the causal inverse explodes, the bounded one exists); else
    /// [`Redundant`](Self::Redundant).
    pub fn default_for<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>() -> Self {
        if dummy_derivative::system_size::<C::Model, N, M, A>().is_ok() {
            return Formulation::DummyDerivative;
        }
        let Some((case, start)) = Case::<C, N, M, A>::maneuver()
            .ok()
            .and_then(|case| case.run_start().ok().map(|start| (case, start)))
        else {
            return Formulation::Redundant;
        };
        let stable = state_selection::eigenvalues_at(case.model(), case.path(), &start)
            .is_some_and(|eigenvalues| eigenvalues.iter().all(|lambda| lambda.re < 0.0));
        if stable {
            return Formulation::StateSelection;
        }
        let hyperbolic_and_unstable = crane_runtime::internal::internal_dynamics(&case.model, &start).is_ok_and(|d| {
            d.dimension > 0 && !d.is_stable() && crane_runtime::stable_inversion::horizons(&d, &d).is_ok()
        });
        if hyperbolic_and_unstable {
            Formulation::StableInversion
        } else {
            Formulation::Redundant
        }
    }

    /// The name in scenario files, on the command line and in `summary.json`.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::Redundant => "redundant",
            Formulation::Minimal => "minimal",
            Formulation::DummyDerivative => "dummy-derivative",
            Formulation::StableInversion => "stable-inversion",
            Formulation::StateSelection => "state-selection",
        }
    }

    /// What it is, in a few words.
    pub fn description(self) -> &'static str {
        match self {
            Formulation::Redundant => "redundant coordinates, eqs. (22a-d)",
            Formulation::Minimal => "minimal coordinates, eqs. (24a-e)",
            Formulation::DummyDerivative => {
                "eqs. (22a-d) reduced by dummy derivatives, exact for flat cranes of any path order"
            }
            Formulation::StableInversion => {
                "the bounded solution on the whole time axis, with pre- and post-actuation, for unstable internal \
                 dynamics (central differences, order 2)"
            }
            Formulation::StateSelection => {
                "eqs. (22a-d) reduced by dummy derivatives, the states the path leaves free integrated by the \
                 scheme, for stable internal dynamics"
            }
        }
    }

    /// Whether the scheme discretises it: `false` for the dummy-derivative
    /// formulation, whose system is algebraic at each step (every
    /// derivative is an unknown of its own), so its results do not depend
    /// on the scheme or the step size.
    pub fn discretised(self) -> bool {
        !matches!(self, Formulation::DummyDerivative)
    }

    /// The order of the run's inputs in dt: the scheme's for eqs. (22) and
    /// (24) and for the states of state selection, 2 for stable
    /// inversion's central differences, none for the dummy-derivative
    /// formulation (exact at each step).
    pub fn order(self, scheme: Scheme) -> Option<usize> {
        match self {
            Formulation::Redundant | Formulation::Minimal | Formulation::StateSelection => Some(scheme.order()),
            Formulation::DummyDerivative => None,
            Formulation::StableInversion => Some(2),
        }
    }

    /// How a run of it is made, in a few words: the formulation with the
    /// scheme where one applies (`redundant, bdf4`), with its own
    /// discretisation (`stable-inversion, central differences`), or alone.
    pub fn method(self, scheme: Scheme) -> String {
        match self {
            Formulation::Redundant | Formulation::Minimal | Formulation::StateSelection => {
                format!("{}, {scheme}", self.name())
            }
            Formulation::DummyDerivative => self.name().to_string(),
            Formulation::StableInversion => format!("{}, central differences", self.name()),
        }
    }

    /// The names, "redundant, minimal, dummy-derivative, state-selection or
    /// stable-inversion".
    pub fn names() -> String {
        let names: Vec<&str> = Self::ALL.iter().map(|f| f.name()).collect();
        let (last, first) = names.split_last().expect("formulations");
        format!("{} or {last}", first.join(", "))
    }

    /// The choices as one line of help.
    pub fn help() -> String {
        Self::ALL
            .iter()
            .map(|f| format!("{} ({})", f.name(), f.description()))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Integrate `case` from `start` with this formulation, calling
    /// `progress(step, steps)` after every step.
    pub fn simulate<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
        self,
        case: &Case<C, N, M, A>,
        start: &State<N, M, A>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Solution<N, M, A>, StudyError> {
        match self {
            Formulation::Redundant => Ok(case.simulate_with_progress(start, options, progress)?),
            Formulation::Minimal => Ok(case
                .simulate_minimal_with_progress(start, options, progress)
                .ok_or_else(|| StudyError::NoMinimalMap {
                    model: C::NAME.to_string(),
                    default: Formulation::default_for::<C, N, M, A>(),
                })??),
            Formulation::DummyDerivative => case
                .simulate_dummy_derivative(start, options, progress)
                .map_err(|error| StudyError::of_crane(C::NAME, error)),
            Formulation::StateSelection => {
                state_selection::simulate(case.model(), case.path(), start, options, progress)
                    .map_err(|error| StudyError::of_crane(C::NAME, error))
            }
            Formulation::StableInversion => {
                let inversion = case.simulate_stable_inversion(start, options)?;
                let nodes = inversion.solution.states.len();
                progress(nodes, nodes);
                Ok(inversion.solution)
            }
        }
    }
}

impl fmt::Display for Formulation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A formulation name that is not one of [`Formulation::ALL`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown formulation `{0}`; expected {names}", names = Formulation::names())]
pub struct UnknownFormulation(pub String);

impl<'de> serde::Deserialize<'de> for Formulation {
    /// By [`name`](Self::name).
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

impl FromStr for Formulation {
    type Err = UnknownFormulation;
    fn from_str(s: &str) -> Result<Self, UnknownFormulation> {
        Self::ALL
            .into_iter()
            .find(|f| f.name() == s)
            .ok_or_else(|| UnknownFormulation(s.to_string()))
    }
}

/// Why a study could not be made.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// The runtime refused the run or a step failed.
    #[error(transparent)]
    Runtime(#[from] crane_runtime::Error),
    /// The load path leaves the crane's workspace ([`Case::check_workspace`]).
    #[error(transparent)]
    OutsideWorkspace(#[from] crate::case::OutsideWorkspace),
    /// The minimal formulation of a crane without a minimal map.
    #[error("model `{model}` declares no minimal-coordinate map; run it in its default formulation, {default}")]
    NoMinimalMap {
        /// The crane's name.
        model: String,
        /// The formulation its declaration supports by default (the
        /// redundant one, or the reduced one where its inputs need more
        /// than the path's 4th derivative).
        default: Formulation,
    },
    /// The dummy-derivative formulation of a crane that has none (internal
    /// dynamics, or a path order beyond what the runtime carries).
    #[error(
        "model `{model}` has no dummy-derivative formulation: {reason}; run it {}",
        if matches!(reason, crane_runtime::NoDummyDerivatives::InternalDynamics { .. }) {
            "with state selection (formulation `state-selection`) or in the redundant formulation"
        } else {
            "in the redundant formulation"
        }
    )]
    NoDummyDerivatives {
        /// The crane's name.
        model: &'static str,
        /// Why.
        reason: crane_runtime::NoDummyDerivatives,
    },
    /// The convergence study cannot measure its error.
    #[error("{0}")]
    Convergence(String),
    /// A replay of inputs that are not a result (an audit finding of
    /// [`Severity::Error`]: a runaway input, states off their constraints,
    /// a rope of non-positive length).
    #[error("nothing to replay: {0}")]
    NotAResult(String),
    /// A run's step too short for its replay's forward steps.
    #[error(
        "a replay steps the plant {refine} times per step of the run: dt = {} s would step it at {} s, below the \
         smallest time step, {} s; take dt >= {} s for a replay",
        Number(*.dt),
        Number(*.dt / *.refine as f64),
        Number(crane_runtime::options::MIN_DT),
        Number(crane_runtime::options::MIN_DT * *.refine as f64)
    )]
    ReplayStep {
        /// The run's step, s.
        dt: f64,
        /// Forward steps per step of the run.
        refine: usize,
    },
    /// A plant parameter of a replay is unknown or not finite.
    #[error("plant parameter `{name}`: {message}")]
    PlantParameter {
        /// The parameter.
        name: String,
        /// What is wrong with it.
        message: String,
    },
}

impl StudyError {
    /// A runtime error of crane `model`, the missing dummy-derivative
    /// system named by the crane's name.
    pub fn of_crane(model: &'static str, error: crane_runtime::Error) -> Self {
        match error {
            crane_runtime::Error::NoDummyDerivatives { reason, .. } => StudyError::NoDummyDerivatives { model, reason },
            error => StudyError::Runtime(error),
        }
    }
}

/// How a case is run: the settings a scenario file or the command line
/// gives besides the case itself.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSettings {
    /// Time step, s.
    pub dt: f64,
    /// The formulation.
    pub formulation: Formulation,
    /// The scheme.
    pub scheme: Scheme,
    /// `(input index, limit)`: limits on `|u|`.
    pub limits: Vec<(usize, f64)>,
    /// Parameters of a replay's plant that differ from the planner's.
    pub plant: Vec<(String, f64)>,
}

/// The time step when neither a scenario nor the command line gives one, s.
pub const DEFAULT_DT: f64 = 0.01;

impl Default for RunSettings {
    /// `dt = 0.01 s`, redundant coordinates, backward Euler, no limits.
    fn default() -> Self {
        Self {
            dt: DEFAULT_DT,
            formulation: Formulation::default(),
            scheme: Scheme::default(),
            limits: Vec::new(),
            plant: Vec::new(),
        }
    }
}

/// A run and what it means.
#[derive(Debug, Clone)]
pub struct Outcome<const N: usize, const M: usize, const A: usize> {
    /// The states of every step.
    pub solution: Solution<N, M, A>,
    /// Its summary (with the replay's, once [`replay`](Self::replay) made one).
    pub summary: Summary,
    /// What the [`audit()`] of the summary found (the replay's included,
    /// once there is one).
    pub findings: Vec<Finding>,
    /// The replay, once [`replay`](Self::replay) made one.
    pub replay: Option<ReplayOutcome<N, M, A>>,
}

impl<const N: usize, const M: usize, const A: usize> Outcome<N, M, A> {
    /// Replay the run's torques as `request` asks ([`replay::replay_run`])
    /// and add the replay to the outcome and its summary.
    pub fn replay<C: Crane<N, M, A>>(
        &mut self,
        case: &Case<C, N, M, A>,
        request: &ReplayRequest,
    ) -> Result<&ReplayOutcome<N, M, A>, StudyError> {
        // a runaway's end state would size the settling window too (a
        // pendulum of 1e16 m)
        if let Some(finding) = self.findings.iter().find(|f| f.severity() == Severity::Error) {
            return Err(StudyError::NotAResult(finding.to_string()));
        }
        let replay = replay::replay_run(case, &self.solution, request)?;
        self.summary.replay = Some(replay.summary.clone());
        self.findings = audit(&self.summary);
        Ok(self.replay.insert(replay))
    }
}

/// Run `case` from its checked start with `settings` (a path that leaves
/// the crane's workspace refused first, [`Case::check_workspace`]), calling
/// `progress(step, steps)` after every step: the solution, its summary
/// (peaks, ropes, limits, errors against the reference, the internal
/// dynamics at 101 states, the path's smoothness) and the warnings; a
/// replay is added by [`Outcome::replay`].
pub fn run<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    settings: &RunSettings,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Outcome<N, M, A>, StudyError> {
    let start = case.run_start()?;
    case.check_workspace()?;
    let options = Options::new(settings.dt, case.tf())?.with_scheme(settings.scheme);
    let clock = Instant::now();
    let solution = settings.formulation.simulate(case, &start, &options, progress)?;
    let wall = clock.elapsed().as_secs_f64();
    let mut summary = summarize_run(case, settings, &solution, wall, DIAGNOSIS_SAMPLES);
    if settings.formulation.discretised() {
        summary.round_off = round_off(case, &start, &options, &solution);
    }
    let findings = audit(&summary);
    Ok(Outcome {
        solution,
        summary,
        findings,
        replay: None,
    })
}

/// A discretised run's inputs against the exact ones of the reduced
/// formulation at the same steps, and their round-off
/// ([`summary::RoundOff`]); `None` for a crane without the reduced system,
/// or where its run fails.
fn round_off<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    start: &State<N, M, A>,
    options: &Options,
    solution: &Solution<N, M, A>,
) -> Option<summary::RoundOff> {
    dummy_derivative::system_size::<C::Model, N, M, A>().ok()?;
    let exact = case.simulate_dummy_derivative(start, options, &mut |_, _| {}).ok()?;
    let (t0, tf) = (case.t0(), case.tf());
    let window = (t0 + 0.2 * (tf - t0), tf - 0.2 * (tf - t0));
    let error = (solution.states.iter().zip(&exact.states))
        .filter(|(s, _)| s.t >= window.0 && s.t <= window.1)
        .map(|(s, e)| (s.u - e.u).amax())
        .fold(0.0f64, f64::max);
    let peak = exact.states.iter().map(|e| e.u.amax()).fold(0.0f64, f64::max);
    Some(summary::RoundOff {
        error,
        floor: convergence::round_off_floor(&solution.states, window.0, window.1),
        peak,
    })
}

/// The states at which [`run`] diagnoses the internal dynamics of a crane
/// that has them by structure: 101.
pub const DIAGNOSIS_SAMPLES: usize = 100;

/// The summary of `solution`, a run of `case` under `settings` that took
/// `wall` seconds: peaks, ropes, limits, errors against the reference, the
/// internal dynamics at `samples + 1` states, the path's smoothness and
/// the distance from the constraints; what [`audit()`] reads.
///
/// A crane flat by structure (internal dynamics of dimension 0, Pryce's
/// count) is not sampled: where its system Jacobian is regular a sample can
/// only confirm dimension 0, and where it is singular the frozen-time
/// projection reports spurious eigenvalues, so the samples would cost
/// (more than the run itself for a small crane) and say nothing the audit
/// uses.
pub fn summarize_run<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    settings: &RunSettings,
    solution: &Solution<N, M, A>,
    wall: f64,
    samples: usize,
) -> Summary {
    // the reference is evaluated where it is needed, never stored per step
    let reference_at = |t: f64| case.reference(t);
    let has_reference = C::HAS_REFERENCE && case.reference(case.t0()).is_some();
    let mut summary = summary::summarize(
        C::NAME,
        settings.formulation.name(),
        solution,
        has_reference.then_some(&reference_at as &dyn Fn(f64) -> Option<State<N, M, A>>),
        &settings.limits,
        wall,
    );
    for (unit, declared) in summary.input_units.iter_mut().zip(C::input_units()) {
        *unit = declared.to_string();
    }
    let flat = <C::Model as CraneModel<N, M, A>>::STRUCTURE.is_some_and(|s| s.dimension == 0);
    summary.internal_dynamics = diagnose(case.model(), solution, if flat { 0 } else { samples });
    summary.path_smoothness =
        path_smoothness::<C::Model, _, N, M, A>(case.path()).map(|smooth| PathSmoothnessSummary {
            needed: smooth.needed,
            continuous: smooth.continuous,
            sufficient: smooth.is_sufficient(),
        });
    summary.constraint_residual = Some(summary::constraint_residual(case.model(), solution));
    let spec = case.path().spec();
    summary.ramp = spec.profile.tau0();
    summary.shortest_feature = Some(spec.shortest_feature());
    for (r, rope) in summary.ropes.iter_mut().enumerate() {
        if rope.leaves_workspace() {
            rope.length_at_rest = length_at_rest(case, r, rope.t_min_length);
        }
    }
    if settings.formulation == Formulation::StableInversion {
        summary.stable_inversion = stable_inversion_summary(case, solution);
    }
    if !solution.selected_states.is_empty() {
        summary.state_selection = solution.states.first().map(|start| StateSelectionSummary {
            states: solution.selected_states.clone(),
            eigenvalues_start: state_selection::eigenvalues_at(case.model(), case.path(), start)
                .unwrap_or_default()
                .iter()
                .map(|lambda| (lambda.re, lambda.im))
                .collect(),
            reselections: (solution.reselected_states.iter())
                .map(|(t, states)| summary::Reselection {
                    t: *t,
                    states: states.clone(),
                })
                .collect(),
        });
    }
    summary
}

/// The horizons of a run by stable inversion, from its first and last
/// states (the rest states at `t0 - t_pre` and `tf + t_post`), and the
/// eigenvalues at them.
fn stable_inversion_summary<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    solution: &Solution<N, M, A>,
) -> Option<StableInversionSummary> {
    let (first, last) = (solution.states.first()?, solution.states.last()?);
    let eigenvalues = |state: &State<N, M, A>| {
        crane_runtime::internal::internal_dynamics(case.model(), state)
            .map(|d| d.eigenvalues)
            .unwrap_or_default()
    };
    let move_end = case.move_end(case.tf());
    Some(StableInversionSummary {
        discretisation: "central differences, order 2".to_string(),
        t_pre: case.t0() - first.t,
        t_post: last.t - move_end,
        eigenvalues_start: eigenvalues(first),
        eigenvalues_end: eigenvalues(last),
        boundary_residual: crane_runtime::stable_inversion::boundary_residual(solution),
    })
}

/// The length of rope `r` with the load at rest at the point of `case`'s
/// path at time `t` ([`Case::rest_along`] in [`REST_MARCH`] steps); zero
/// where the march needs some rope shorter than zero (the path leaves the
/// workspace), `None` where an equilibrium is not found.
fn length_at_rest<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    r: usize,
    t: f64,
) -> Option<f64> {
    match case.rest_along(t, REST_MARCH) {
        Ok(rest) => {
            let mut lengths = vec![0.0; <C::Model as CraneModel<N, M, A>>::INFO.ropes.len()];
            case.model().rope_lengths(&rest.q, &mut lengths);
            lengths.get(r).copied()
        }
        Err(crane_runtime::Error::NonPositiveRopeLength { .. }) => Some(0.0),
        Err(_) => None,
    }
}

/// Steps of the march of static equilibria in [`length_at_rest`].
const REST_MARCH: usize = 16;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coupled_trolley::CoupledTrolley;
    use crane_runtime::nalgebra::vector;
    use crane_runtime::trajectory::Poly9;
    use crane_runtime::{init, simulate};

    fn run(c: f64) -> (CoupledTrolley, Solution<4, 1, 2>) {
        let crane = CoupledTrolley {
            c,
            ..CoupledTrolley::default()
        };
        let path = Poly9::new(0.0, 5.0, vector![0.0, -5.0], vector![4.0, -3.0]).unwrap();
        let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0]).unwrap();
        let run = simulate(&crane, &path, &start, &Options::new(0.01, 5.0).unwrap()).unwrap();
        (crane, run)
    }

    /// The coupled crane: the run "succeeds", the diagnosis says why its
    /// torques are not a result: unstable internal dynamics of dimension 2
    /// from the start (sqrt(lambda/c) = 9.9045 1/s there, larger where the
    /// load rises and accelerates), and an input beyond 1e6 times its size
    /// at the start before t = 2.5 s (3.4e12 N there); both are warnings
    /// and make the run infeasible.
    #[test]
    fn an_unstable_crane_is_reported_as_such() {
        let (crane, solution) = run(2.0);
        let mut summary = summary::summarize("coupled-trolley", "redundant", &solution, None, &[], 0.0);
        summary.internal_dynamics = diagnose(&crane, &solution, 100);
        let d = &summary.internal_dynamics;
        assert_eq!(d.structural_dimension, Some(2), "{d:?}");
        assert_eq!(d.dimension, 2, "{d:?}");
        assert_eq!(d.stable, Some(false), "{d:?}");
        assert!(d.max_real_part.unwrap() >= 9.9, "{d:?}");
        assert!(d.runaway_at.is_some_and(|t| t < 2.5), "{d:?}");
        // diagnosed up to the runaway (1.8 s of 5 s: 37 of the 101 samples)
        assert!(d.samples >= 30 && d.unresolved == 0, "{d:?}");
        let findings = audit(&summary);
        // (past the runaway Newton's matrix is singular at most steps, which
        // is reported too)
        assert!(matches!(
            findings[..],
            [Finding::UnstableInternalDynamics { .. }, Finding::Runaway { .. }, ..]
        ));
        assert_eq!(
            findings[0].severity(),
            Severity::Warning,
            "a solution, not a feedforward"
        );
        assert_eq!(findings[1].severity(), Severity::Error, "not a physical result");
    }

    /// Without the coupling: flat, nothing to report.
    #[test]
    fn a_flat_crane_is_reported_flat() {
        let (crane, solution) = run(0.0);
        let d = diagnose(&crane, &solution, 100);
        // structurally 2 (c is a parameter), numerically 0 at c = 0
        assert_eq!(d.structural_dimension, Some(2), "{d:?}");
        assert_eq!(d.dimension, 0, "{d:?}");
        assert!(d.stable == Some(true) && d.runaway_at.is_none(), "{d:?}");
    }

    /// A crane whose inputs need the path's 6th derivative (navy-3d-pulley)
    /// is beyond the paper's formulation, which covers the 4th: the run is
    /// not usable, warned of and infeasible; the paper's planar crane is
    /// covered and none of that.
    #[test]
    fn a_crane_beyond_the_formulation_is_not_reported_usable() {
        let beyond = crate::navy_3d_pulley::PaperCase::smooth(crate::navy_3d_pulley::TF).unwrap();
        let settings = RunSettings {
            dt: 0.1,
            ..RunSettings::default()
        };
        let outcome = super::run(&beyond, &settings, &mut |_, _| {}).unwrap();
        let d = &outcome.summary.internal_dynamics;
        assert_eq!(
            d.path_order,
            Some(crane_runtime::internal::PathOrder { needed: 6, covered: 4 }),
            "{d:?}"
        );
        assert!(d.stable == Some(true) && !d.is_usable(), "{d:?}");
        assert!(
            matches!(
                outcome.findings[..],
                [Finding::BeyondFormulation {
                    needed: 6,
                    covered: 4,
                    ..
                }]
            ),
            "{:?}",
            outcome.findings
        );
        assert!(outcome.findings[0].to_string().contains("covers order 4"));
        let covered = crate::navy_planar::PaperCase::new(4.0).unwrap();
        let outcome = super::run(&covered, &RunSettings::default(), &mut |_, _| {}).unwrap();
        let d = &outcome.summary.internal_dynamics;
        assert_eq!(
            d.path_order,
            Some(crane_runtime::internal::PathOrder { needed: 4, covered: 4 })
        );
        assert!(d.is_usable() && outcome.findings.is_empty());
    }

    /// One slack rule: round-off around a rope that carries nothing is not
    /// slack, anything beyond 1e-9 of the rope's peak is.
    #[test]
    fn the_slack_rule_allows_round_off_only() {
        assert!(!below_floor(-2.6e-13, 0.0, 1000.0), "the paper's start");
        assert!(below_floor(-2e-6, 0.0, 1000.0));
        assert!(!below_floor(99.9999999, 100.0, 1000.0));
        assert!(below_floor(99.99, 100.0, 1000.0));
        assert!(below_floor(f64::NEG_INFINITY, 0.0, 1.0));
    }
}
