//! The run summary (`summary.json`): feasibility and accuracy at a glance,
//! and the one slack rule of every study ([`below_floor`]).

use crane_runtime::error::Seconds;
use crane_runtime::internal::RunDiagnosis;
use crane_runtime::{CraneModel, Solution, State};
use serde::Serialize;

/// Extreme value of a column and when it occurs.
#[derive(Debug, Clone, Serialize)]
pub struct Extreme {
    /// The column, as the model names it.
    pub name: String,
    /// The value of largest magnitude (signed).
    pub value: f64,
    /// When, s.
    pub t: f64,
}

/// A rope's tension over the run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RopeSummary {
    /// The tension's name, e.g. `N1`.
    pub name: String,
    /// The smallest tension, N.
    pub min_tension: f64,
    /// When, s.
    pub t_min: f64,
    /// The largest tension, N (below zero: the rope pushes the whole run).
    pub max_tension: f64,
    /// First time the rope is slack ([`below_floor`] 0; ropes only pull, a
    /// negative tension is infeasible).
    pub first_slack: Option<f64>,
    /// The name of the rope's constraint, e.g. `hoist`.
    pub constraint: String,
    /// The rope's shortest length over the run, m (at or below 0: the path
    /// leaves the crane's workspace).
    pub min_length: f64,
    /// When, s.
    pub t_min_length: f64,
    /// Of a rope whose length reached zero or below: its length with the
    /// load at rest at the path's point of `t_min_length` (the static
    /// equilibrium there), where one is found: above zero, the path is
    /// inside the crane's workspace and the move is too fast for it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length_at_rest: Option<f64>,
}

impl RopeSummary {
    /// What a slack rope tells the user, if it goes slack: when, or, for a
    /// rope that pushes all along (a load hanging on it would pull it
    /// taut: almost surely gravity declared upward), what to check.
    pub fn slack(&self) -> Option<String> {
        let t = self.first_slack?;
        Some(if self.max_tension < 0.0 {
            format!(
                "rope {} pushes for the whole run (its tension stays between {:.1} and {:.1} N): a rope only \
                 pulls, and a load hanging on it pulls it taut, so check the sign of gravity in the crane's \
                 forces (with z up, `z: -m_l*g`)",
                self.name, self.min_tension, self.max_tension
            )
        } else {
            format!("rope {} goes slack at t = {t:.3} s", self.name)
        })
    }

    /// Whether the rope's length reached zero or below: the path left the
    /// crane's workspace.
    pub fn leaves_workspace(&self) -> bool {
        !(self.min_length > 0.0)
    }
}

/// Errors against the analytical reference.
#[derive(Debug, Clone, Serialize)]
pub struct ReferenceErrors {
    /// Relative error of u at t = 1.5 s, eq. (48): |u - u_ref| / |u_ref|,
    /// if a step lands there (to 1e-9 of the step); `None` otherwise.
    pub e_u_at_1_5s: Option<f64>,
    /// Largest `|u - u_ref|` per input.
    pub max_abs_error_u: Vec<Extreme>,
    /// Largest `|q - q_ref|` per coordinate.
    pub max_abs_error_q: Vec<Extreme>,
    /// Largest `|lambda - lambda_ref|` per multiplier.
    pub max_abs_error_lambda: Vec<Extreme>,
}

/// Newton's work over the run.
#[derive(Debug, Clone, Serialize)]
pub struct NewtonSummary {
    /// Iterations (linear solves) of all steps.
    pub total_iterations: usize,
    /// Mean per step.
    pub mean_per_step: f64,
    /// Most in one step.
    pub max_per_step: usize,
    /// Time steps that took a minimum-norm Newton update on a singular
    /// iteration matrix (at most `steps`).
    pub min_norm_steps: usize,
    /// Steps taken in redundant coordinates: of a minimal run, the first
    /// ones, at a degenerate start (a rope nearly slack); of a reduced run,
    /// those at a degenerate start or wherever a rope was nearly slack.
    pub redundant_start_steps: usize,
    /// Time steps that held the directions a nearly slack rope leaves free
    /// where the predictor put them (a rope under 1e-11 of the largest
    /// tension; the limit of a vanishing tension).
    pub held_steps: usize,
    /// Time steps of the reduced formulation taken by continuation: their
    /// solution left its branch (a mirror configuration, a rope of negative
    /// length) or Newton failed from the prediction, and shorter steps
    /// followed the path to the step time (only the step times are
    /// reported).
    pub continued_steps: usize,
    /// Of those, the steps in which the solution changed branch where the
    /// path does (a rope's length or a taut rope's tension changed sign
    /// within 2^-20 of a step, or across a singular configuration), and
    /// the first one's time, s.
    pub crossings: usize,
    /// The time of the first crossing, s.
    pub first_crossing: Option<f64>,
}

/// A torque limit from the scenario's `[limits]` and when it is first exceeded.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LimitSummary {
    /// The input.
    pub name: String,
    /// The limit on `|u|`.
    pub limit: f64,
    /// The largest `|u|` of the run.
    pub peak: f64,
    /// First time `|u| > limit`, if ever.
    pub first_violation: Option<f64>,
}

/// A run at a glance (`summary.json`).
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// The crane's name, e.g. `navy-planar`.
    pub model: String,
    /// One line on it.
    pub description: String,
    /// `redundant` or `minimal`.
    pub formulation: String,
    /// The time-discretisation scheme, e.g. `backward-euler` or `bdf4`.
    pub scheme: String,
    /// Time step, s.
    pub dt: f64,
    /// First and last time, s.
    pub t0: f64,
    /// Last time, s.
    pub tf: f64,
    /// Steps taken.
    pub steps: usize,
    /// Newton's work.
    pub newton: NewtonSummary,
    /// Wall time of the integration, s.
    pub wall_time_s: f64,
    /// Largest `|u|` per input.
    pub peak_torque: Vec<Extreme>,
    /// Each input's unit as the crane declares it (`N m`, `N`), empty where
    /// it declares none.
    pub input_units: Vec<String>,
    /// Each rope's tension.
    pub ropes: Vec<RopeSummary>,
    /// Each limit's first violation.
    pub torque_limits: Vec<LimitSummary>,
    /// Errors against the analytical reference, where there is one.
    pub reference: Option<ReferenceErrors>,
    /// `--replay`: the computed torques on the crane's forward dynamics.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub replay: Option<ReplaySummary>,
    /// The internal dynamics along the run (`crane_runtime::internal`).
    pub internal_dynamics: RunDiagnosis,
    /// How smooth the path must be (the inputs depend on its derivatives
    /// up to `needed`) and is (`continuous`), where both are known.
    pub path_smoothness: Option<PathSmoothnessSummary>,
    /// How far the reported states are from the constraints, where
    /// measured ([`constraint_residual`]).
    pub constraint_residual: Option<ConstraintResidual>,
    /// Of a discretised run (eqs. 22 or 24) of a crane with the reduced
    /// system: its inputs against the exact ones, and the round-off in them
    /// ([`RoundOff`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub round_off: Option<RoundOff>,
    /// The input's sharpest turn between steps ([`InputSpike`]).
    pub input_spike: Option<InputSpike>,
    /// The ramp duration `tau0` of a three-phase path, s (`None` for a
    /// polynomial path): the shortest feature the steps must resolve.
    pub ramp: Option<f64>,
    /// The shortest feature of the path, s: the ramps of a three-phase
    /// path, the move of a polynomial one (`None` where the path is not
    /// known, as a host's): spikes are judged only where the steps resolve
    /// it ([`SPIKE_RESOLUTION`]).
    pub shortest_feature: Option<f64>,
    /// Of a run by stable inversion: its horizons and the internal
    /// dynamics they come from ([`StableInversionSummary`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stable_inversion: Option<StableInversionSummary>,
    /// Of a run with state selection: the states and the eigenvalues of
    /// their equations at the start ([`StateSelectionSummary`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub state_selection: Option<StateSelectionSummary>,
}

/// A run with state selection (`crane_runtime::state_selection`): the jets
/// the path leaves free, integrated by the run's scheme, and the
/// linearisation of their equations at the start.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StateSelectionSummary {
    /// The states (`x2`, `x2'`), selected at the start.
    pub states: Vec<String>,
    /// The eigenvalues `(re, im)` of the states' equations linearised at
    /// the start, 1/s (all with negative real part: stable internal
    /// dynamics, which the scheme integrates forward in time).
    pub eigenvalues_start: Vec<(f64, f64)>,
    /// Where the selection degenerated along the move and the states were
    /// selected anew: when, and the new states.
    pub reselections: Vec<Reselection>,
}

/// The states selected anew at one time of a run with state selection.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reselection {
    /// When, s.
    pub t: f64,
    /// The new states.
    pub states: Vec<String>,
}

/// A run by stable inversion (`crane_runtime::stable_inversion`): the bounded
/// inputs act from `t0 - t_pre` (pre-actuation) and settle by `tf + t_post`
/// (post-actuation).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StableInversionSummary {
    /// The discretisation: central differences, order 2.
    pub discretisation: String,
    /// Pre-actuation before the move starts, s.
    pub t_pre: f64,
    /// Post-actuation after the move ends, s.
    pub t_post: f64,
    /// The eigenvalues `(re, im)` of the internal dynamics at the start's
    /// rest state, 1/s (`t_pre` decays the slowest to 1e-10).
    pub eigenvalues_start: Vec<(f64, f64)>,
    /// The same at the end's rest state (`t_post`).
    pub eigenvalues_end: Vec<(f64, f64)>,
    /// The robot coordinates' rate next to the two end nodes, relative to
    /// their largest rate: how far from rest the solution is where rest
    /// was imposed.
    pub boundary_residual: f64,
}

/// The largest second difference of an input between steps, `|u_{k+1} -
/// 2 u_k + u_{k-1}|`, against the input's peak: smooth inputs turn by
/// `dt^2 |u''|` from step to step, and where the path's derivative that
/// the inputs need last jumps, by `dt |[u']|`, both far below the peak
/// ([`spiky`](Self::spiky)).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InputSpike {
    /// The input.
    pub input: String,
    /// At which step, s.
    pub t: f64,
    /// `|u_{k+1} - 2 u_k + u_{k-1}|`.
    pub second_difference: f64,
    /// The input's peak over the run's other steps, those outside the
    /// three of the second difference (at least 1e-6 of the largest input,
    /// so that an input that stays at round-off is no scale): a spike is
    /// judged against the input elsewhere, also where it is the peak
    /// (one wild last step of 1.2e5 N m after 43 N m).
    pub peak: f64,
}

/// Above this ratio of an input's second difference to its peak elsewhere
/// the input spikes: measured at most 0.29 on every built-in's default move
/// at dt = 0.1, 0.01 and 0.001 s, in its default formulation and, for those
/// of path order 4, in eqs. (22) (the largest at backward Euler's first step
/// on navy-planar-pulley with dt = 0.1 s; it falls with dt), 2.8 on the
/// paper's move slowed to 1000 s at dt = 0.001 s when the steps did not
/// yet hold what a nearly slack rope leaves free (the place of a massless
/// pulley whose rope carries 3e-11 N, fixed only to round-off, jumped, and
/// the scheme's second differences turned the winch by +-600 N m where the
/// quasi-static torque is 43 N m).
pub const SPIKE_LIMIT: f64 = 1.0;

/// The fewest steps the path's shortest feature must span for a turn of
/// an input between steps to be judged against [`SPIKE_LIMIT`]: over fewer,
/// the steps sample a smooth input too sparsely for their second
/// differences to stay below its peak (exact inputs in the reduced
/// formulation, each built-in's default move: the ratio is at most 0.70 at
/// 20 steps, tower-crane's 10 s move at dt = 0.5 s; 1.09 at 10 steps,
/// navy-planar-pulley at dt = 0.4 s; 1.96 at 10 steps, tower-crane at dt =
/// 1 s; up to 2.6e5 at two steps, where the input elsewhere is its value at
/// rest).
pub const SPIKE_RESOLUTION: f64 = 20.0;

impl InputSpike {
    /// Whether the second difference exceeds [`SPIKE_LIMIT`] times the peak.
    pub fn spiky(&self) -> bool {
        !(self.second_difference <= SPIKE_LIMIT * self.peak)
    }
}

/// Whether steps of `dt` resolve a path whose shortest feature lasts
/// `feature` (unknown: yes) well enough for their inputs' turns to be
/// judged ([`SPIKE_RESOLUTION`]).
pub fn resolves(feature: Option<f64>, dt: f64) -> bool {
    feature.is_none_or(|feature| !(feature < SPIKE_RESOLUTION * dt))
}

/// The [`InputSpike`] of `solution`: the largest second difference of any
/// input against its peak, `None` for a run of fewer than three states or
/// inputs that are all zero.
pub fn input_spike<const N: usize, const M: usize, const A: usize>(solution: &Solution<N, M, A>) -> Option<InputSpike> {
    let states = &solution.states;
    let n = states.len();
    let largest = states.iter().fold(0.0f64, |m, s| m.max(s.u.amax()));
    let mut worst: Option<InputSpike> = None;
    for k in 0..A {
        // the peak over the steps before and after each three of a second
        // difference: a spike is judged against the input elsewhere, also
        // where it is the run's peak itself (one wild last step)
        let magnitudes: Vec<f64> = states.iter().map(|s| s.u[k].abs()).collect();
        let mut before = magnitudes.clone();
        let mut after = magnitudes.clone();
        for i in 1..n {
            before[i] = before[i].max(before[i - 1]);
            after[n - 1 - i] = after[n - 1 - i].max(after[n - i]);
        }
        for (i, w) in states.windows(3).enumerate() {
            let outside = match (i.checked_sub(1), after.get(i + 3)) {
                (Some(b), Some(&a)) => before[b].max(a),
                (Some(b), None) => before[b],
                (None, Some(&a)) => a,
                (None, None) => 0.0,
            };
            let peak = outside.max(1e-6 * largest);
            if !(peak > 0.0) {
                continue;
            }
            let second_difference = (w[2].u[k] - 2.0 * w[1].u[k] + w[0].u[k]).abs();
            let ratio = second_difference / peak;
            if worst.as_ref().is_none_or(|s| !(s.second_difference / s.peak >= ratio)) {
                worst = Some(InputSpike {
                    input: solution.info.inputs[k].to_string(),
                    t: w[1].t,
                    second_difference,
                    peak,
                });
            }
        }
    }
    worst
}

/// The largest distance of a run's states from its constraints: the states
/// are a solution only where they satisfy `g(q) = 0`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConstraintResidual {
    /// The constraint farthest from holding.
    pub constraint: String,
    /// Its distance, `|g_k(q)| / |dg_k/dq|` (the first-order distance from
    /// the constraint's surface, in the coordinates' units).
    pub distance: f64,
    /// When, s.
    pub t: f64,
    /// The largest coordinate, for scale (`|q|_inf`, at least 1).
    pub scale: f64,
}

impl ConstraintResidual {
    /// Whether the states leave their constraints beyond what Newton's
    /// tolerance (`1e-10` relative) and round-off explain: by more than
    /// [`CONSTRAINT_TOLERANCE`] of the coordinates' scale.
    pub fn violated(&self) -> bool {
        !(self.distance <= CONSTRAINT_TOLERANCE * self.scale)
    }
}

impl std::fmt::Display for ConstraintResidual {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the reported states leave constraint `{}` by {:.3e} m at t = {} s: they are not a solution of the \
             crane's equations there (a step too large for Newton's scaled test to mean the equations hold); \
             take a smaller dt",
            self.constraint,
            self.distance,
            Seconds(self.t)
        )
    }
}

/// The relative distance from the constraints a state may have and still
/// count as on them: converged steps are measured at 1e-12 and below; a
/// step Newton's scaled test accepts where the equations are not solved (a
/// single step of 1e6 s) leaves metres.
pub const CONSTRAINT_TOLERANCE: f64 = 1e-6;

/// The [`ConstraintResidual`] of `solution`'s states under `model`.
pub fn constraint_residual<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    solution: &Solution<N, M, A>,
) -> ConstraintResidual {
    let mut worst = ConstraintResidual {
        constraint: String::new(),
        distance: 0.0,
        t: solution.states.first().map_or(f64::NAN, |s| s.t),
        scale: 1.0,
    };
    for state in &solution.states {
        worst.scale = worst.scale.max(state.q.amax());
        let (k, distance) = super::audit::constraint_distance(model, &state.q);
        // NaN counts as the worst
        if !(distance <= worst.distance) {
            worst.distance = distance;
            worst.t = state.t;
            worst.constraint = solution.info.constraints.get(k).copied().unwrap_or("").to_string();
        }
    }
    worst
}

/// `path_smoothness` in summary.json.
#[derive(Debug, Clone, Serialize)]
pub struct PathSmoothnessSummary {
    /// The highest path derivative the inputs depend on.
    pub needed: usize,
    /// The highest continuous one.
    pub continuous: usize,
    /// `continuous >= needed`.
    pub sufficient: bool,
}

/// A discretised run's inputs against the exact ones (the reduced
/// formulation's at the same steps), over the middle 60 % of the run (away
/// from the schemes' start-up and the end of the move), and the step-to-step
/// noise in them
/// ([`round_off_floor`](crate::study::convergence::round_off_floor)).
/// Eqs. (22) take the inputs from the scheme's second differences of the
/// absolute coordinates, whose rounding grows like `1/dt^2` in the inputs:
/// below some step the noise is most of the error, and a finer step is
/// less accurate ([`dominates`](Self::dominates)).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RoundOff {
    /// The largest `|u - u_exact|` over the window.
    pub error: f64,
    /// The round-off floor, `max |Delta^6 u| / 32` over the window.
    pub floor: f64,
    /// The largest exact input in magnitude over the run (the scale).
    pub peak: f64,
}

/// Below this fraction of the largest input an error is at round-off
/// whatever its cause: no finding.
pub const ROUND_OFF_NEGLIGIBLE: f64 = 1e-12;

impl RoundOff {
    /// Whether round-off makes up most of the error: the error at most the
    /// floor (where the error is noise it was measured at 0.55 to 0.61 of
    /// the floor; where it is the scheme's, far above it) and above
    /// [`ROUND_OFF_NEGLIGIBLE`] of the peak.
    pub fn dominates(&self) -> bool {
        self.error <= self.floor && self.error > ROUND_OFF_NEGLIGIBLE * self.peak
    }
}

/// The replay's results in summary.json.
#[derive(Debug, Clone, Serialize)]
pub struct ReplaySummary {
    /// Largest |x(t) - gamma(t)| on [t0, tf], m.
    pub max_load_deviation: f64,
    /// |x(tf) - gamma(tf)|, m.
    pub deviation_at_tf: f64,
    /// Largest |x(t) - gamma(tf)| in the settling window, m.
    pub residual_sway: f64,
    /// Length of the settling window, s.
    pub settle_time: f64,
    /// Forward step, s.
    pub dt: f64,
    /// Forward scheme.
    pub scheme: String,
    /// The plant parameters that differ from the planner's.
    pub plant: std::collections::BTreeMap<String, f64>,
    /// The feedback law, if any (`null`: the computed torques alone); the
    /// numbers above are then those with feedback.
    pub feedback: Option<String>,
    /// The largest deviation of the open-loop replay (the same as
    /// `max_load_deviation` without feedback), m.
    pub open_loop_max_load_deviation: f64,
    /// Ropes that would have to push in the replay (below 0 by more than
    /// [`REPLAY_SLACK_TOLERANCE`] of the largest tension): the first time,
    /// per rope.
    pub first_slack: std::collections::BTreeMap<String, f64>,
    /// The load's travel `|gamma(t1) - gamma(t0)|`, m: the scale of
    /// [`misses`](Self::misses).
    pub travel: f64,
}

impl ReplaySummary {
    /// Whether the replayed load does not arrive: it ends, or sways after
    /// the move, farther from the path's end than
    /// [`REPLAY_TOLERANCE`](super::audit::REPLAY_TOLERANCE) of its travel
    /// (at least 1 mm).
    pub fn misses(&self) -> bool {
        let tolerance = (super::audit::REPLAY_TOLERANCE * self.travel).max(1e-3);
        !(self.deviation_at_tf.max(self.residual_sway) <= tolerance)
    }
}

/// The slack rule of a replay
/// ([`crane_runtime::replay::SLACK_TOLERANCE`], which names the rope when
/// the forward dynamics fail after it).
pub const REPLAY_SLACK_TOLERANCE: f64 = crane_runtime::replay::SLACK_TOLERANCE;

/// The one slack rule of every study (`--strict`, planning, replay): a
/// rope tension `n` is below its floor (0: taut) when `n < floor -
/// SLACK_TOLERANCE * max(peak, |floor|)`, `peak` the largest `|N|` of any
/// rope over the run ([`Solution::largest_tension`]: the multipliers come
/// from one solve, so their round-off scales with the largest force the
/// crane carries). Above it, a value under the floor is round-off around a
/// rope that carries no load (as at the paper's start, where N1 = 0 exactly
/// and evaluates to about -2.6e-13 N; on a slow move N1 stays below 1e-6 N
/// for seconds, and its own peak is no scale for that round-off).
pub const SLACK_TOLERANCE: f64 = 1e-9;

/// How far below `floor` a tension may be and still count as at it, in a
/// run whose largest rope tension is `peak` (see [`SLACK_TOLERANCE`]).
pub fn slack_allowance(floor: f64, peak: f64) -> f64 {
    SLACK_TOLERANCE * peak.max(floor.abs())
}

/// The first time rope `r` of `solution` is slack ([`below_floor`] 0, with
/// the largest tension of the run), if ever.
pub fn first_slack<const N: usize, const M: usize, const A: usize>(
    solution: &Solution<N, M, A>,
    r: usize,
) -> Option<f64> {
    let peak = solution.largest_tension();
    (0..solution.states.len())
        .find(|&i| below_floor(solution.tensions_at(i)[r], 0.0, peak))
        .map(|i| solution.states[i].t)
}

/// Whether the tension `n` is below `floor` beyond round-off, in a run
/// whose largest rope tension is `peak` (see [`SLACK_TOLERANCE`]).
pub fn below_floor(n: f64, floor: f64, peak: f64) -> bool {
    n < floor - slack_allowance(floor, peak)
}

fn column_extremes<const K: usize, const N: usize, const M: usize, const A: usize>(
    states: &[State<N, M, A>],
    names: &[&str],
    value: impl Fn(&State<N, M, A>, usize) -> f64,
) -> Vec<Extreme> {
    (0..K)
        .map(|k| {
            let (t, v) = states
                .iter()
                .map(|s| (s.t, value(s, k)))
                .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
                .unwrap_or((f64::NAN, f64::NAN));
            Extreme {
                name: names[k].to_string(),
                value: v,
                t,
            }
        })
        .collect()
}

/// Largest `|value|` per column over a stream of vectors, and when.
struct StreamingExtremes<const K: usize> {
    worst: [(f64, f64); K],
}

impl<const K: usize> StreamingExtremes<K> {
    fn new() -> Self {
        Self {
            worst: [(f64::NAN, f64::NAN); K],
        }
    }

    fn add(&mut self, t: f64, values: &nalgebra::SVector<f64, K>) {
        for (w, &v) in self.worst.iter_mut().zip(values.iter()) {
            if w.1.is_nan() || v.abs() > w.1.abs() {
                *w = (t, v);
            }
        }
    }

    fn into_extremes(self, names: &[&str]) -> Vec<Extreme> {
        self.worst
            .iter()
            .zip(names)
            .map(|(&(t, value), name)| Extreme {
                name: name.to_string(),
                value,
                t,
            })
            .collect()
    }
}

impl Summary {
    /// `" N m"` for the input called `name` if the crane declares its unit,
    /// else empty.
    pub fn unit_suffix(&self, name: &str) -> String {
        self.peak_torque
            .iter()
            .position(|p| p.name == name)
            .and_then(|k| self.input_units.get(k))
            .filter(|unit| !unit.is_empty())
            .map_or_else(String::new, |unit| format!(" {unit}"))
    }
}

/// The summary of a run; `references(t)` is the analytical reference at `t`
/// where the model has one.
pub fn summarize<const N: usize, const M: usize, const A: usize>(
    model: &str,
    formulation: &str,
    solution: &Solution<N, M, A>,
    references: Option<&dyn Fn(f64) -> Option<State<N, M, A>>>,
    limits: &[(usize, f64)],
    wall_time_s: f64,
) -> Summary {
    let info = solution.info;
    let states = &solution.states;
    let peak_torque = column_extremes::<A, N, M, A>(states, info.inputs, |s, k| s.u[k]);
    let ropes = info
        .ropes
        .iter()
        .enumerate()
        .map(|(r, rope)| {
            let series = || {
                states
                    .iter()
                    .enumerate()
                    .map(|(i, s)| (s.t, solution.tensions_at(i)[r]))
            };
            let (t_min, min_tension) = series()
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap_or((f64::NAN, f64::NAN));
            let max_tension = series().map(|(_, n)| n).fold(f64::NEG_INFINITY, f64::max);
            let (min_length, t_min_length) = solution.shortest_ropes.get(r).copied().unwrap_or((f64::NAN, f64::NAN));
            RopeSummary {
                name: rope.tension.to_string(),
                min_tension,
                t_min,
                max_tension,
                first_slack: first_slack(solution, r),
                constraint: info.constraints.get(rope.constraint).copied().unwrap_or("").to_string(),
                min_length,
                t_min_length,
                length_at_rest: None,
            }
        })
        .collect();
    let torque_limits = limits
        .iter()
        .map(|&(k, limit)| LimitSummary {
            name: info.inputs[k].to_string(),
            limit,
            peak: states.iter().fold(0.0f64, |m, s| m.max(s.u[k].abs())),
            first_violation: states.iter().find(|s| s.u[k].abs() > limit).map(|s| s.t),
        })
        .collect();
    let reference = references.map(|reference_at| {
        let lambda_names: Vec<String> = (1..=M).map(|i| format!("lambda{i}")).collect();
        let lambda_refs: Vec<&str> = lambda_names.iter().map(String::as_str).collect();
        // one pass over the states, the reference evaluated at each: no copy
        // of the run (a run of 2e6 steps would otherwise hold 2 x 320 MB)
        let mut u = StreamingExtremes::<A>::new();
        let mut q = StreamingExtremes::<N>::new();
        let mut lambda = StreamingExtremes::<M>::new();
        let mut e_u_at_1_5s = None;
        for s in states {
            let Some(r) = reference_at(s.t) else { continue };
            u.add(s.t, &(s.u - r.u));
            q.add(s.t, &(s.q - r.q));
            lambda.add(s.t, &(s.lambda - r.lambda));
            if e_u_at_1_5s.is_none() && (s.t - 1.5).abs() <= 1e-9 * solution.dt + 4.0 * f64::EPSILON {
                e_u_at_1_5s = Some((s.u - r.u).norm() / r.u.norm());
            }
        }
        ReferenceErrors {
            e_u_at_1_5s,
            max_abs_error_u: u.into_extremes(info.inputs),
            max_abs_error_q: q.into_extremes(info.coordinates),
            max_abs_error_lambda: lambda.into_extremes(&lambda_refs),
        }
    });
    let newton = NewtonSummary {
        total_iterations: solution.newton_iterations.iter().sum(),
        mean_per_step: solution.mean_newton_iterations(),
        max_per_step: solution.newton_iterations.iter().copied().max().unwrap_or(0),
        min_norm_steps: solution.min_norm_steps,
        redundant_start_steps: solution.redundant_start_steps,
        held_steps: solution.held_steps,
        continued_steps: solution.continued_steps,
        crossings: solution.crossings,
        first_crossing: solution.first_crossing,
    };
    Summary {
        model: model.to_string(),
        description: info.description.to_string(),
        formulation: formulation.to_string(),
        scheme: solution.scheme.to_string(),
        dt: solution.dt,
        t0: states.first().map_or(f64::NAN, |s| s.t),
        tf: states.last().map_or(f64::NAN, |s| s.t),
        steps: solution.steps(),
        newton,
        wall_time_s,
        peak_torque,
        input_units: vec![String::new(); A],
        ropes,
        torque_limits,
        reference,
        replay: None,
        internal_dynamics: RunDiagnosis::none(),
        path_smoothness: None,
        constraint_residual: None,
        round_off: None,
        input_spike: input_spike(solution),
        ramp: None,
        shortest_feature: None,
        stable_inversion: None,
        state_selection: None,
    }
}

/// Whether Newton met an iteration matrix singular to working precision
/// (and fell back on the minimum-norm step), or the step held what a nearly
/// slack rope leaves free, in more than 1 % of the steps and more than two:
/// the paper's degenerate start costs one, its move slowed to 1000 s holds
/// 0.18 % of the steps, and a path along which a rope stays without tension
/// (the load straight below the boom tip for a long time) leaves a
/// coordinate free at every step, where the inputs are one choice of many.
pub fn singular_steps(summary: &Summary) -> bool {
    too_many_singular(summary.newton.min_norm_steps + summary.newton.held_steps, summary.steps)
}

/// The rule of [`singular_steps`]: `count` singular steps of `steps`.
pub fn too_many_singular(count: usize, steps: usize) -> bool {
    count > 2 && count * 100 > steps
}
