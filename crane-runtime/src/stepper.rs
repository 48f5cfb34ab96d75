//! One stepper for every problem and scheme: [`Stepper`] owns the start
//! time, the step count, the unknowns, the scheme's [`History`], the
//! predictor, Newton and the mapping of its failures; a [`Problem`] supplies
//! only its unknowns, residual and iteration matrix and what a state is made
//! of. [`Handover`] puts two problems in sequence (the minimal formulation's
//! degenerate start, whose first steps are the redundant problem's), and
//! [`Advance`] is what the run loop of [`crate::driver`] drives.
//!
//! ```
//! use crane_runtime::{Options, Stepper};
//! use crane_runtime::redundant::Redundant;
//! # use crane_runtime::{init, trajectory::Poly9, nalgebra::vector};
//! # crane_macros::crane_model! {
//! #     #[crane(runtime = crane_runtime)]
//! #     #[crane(no_self_test)]
//! #     pub struct Gantry {
//! #         params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, g = 9.81 }
//! #         robot [s, L] load [x, z] inputs [u1, u2]
//! #         kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
//! #         forces { s: u1, L: u2/r, z: -m_l*g }
//! #         constraints { #[rope(N = L)] rope: 0.5*((x - s)^2 + z^2 - L^2), }
//! #     }
//! # }
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let crane = Gantry::default();
//! let path = Poly9::new(0.0, 5.0, vector![0.0, -5.0], vector![4.0, -3.0])?;
//! let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0])?;
//! // the servo problem in redundant coordinates on BDF-2, one step at a time
//! let options = Options::stepping(0.01)?.with_scheme(crane_runtime::Scheme::Bdf2);
//! let mut stepper = Stepper::new(Redundant::new(&crane, &path), &start, &options)?;
//! for _ in 0..100 {
//!     stepper.step()?;
//! }
//! assert!((stepper.state().t - 1.0).abs() < 1e-12);
//! # Ok(())
//! # }
//! ```

use nalgebra::{DVector, SVector};

use crate::double_double::DoubleDouble;
use crate::error::Error;
use crate::model::check_parameters;
use crate::model::{CraneModel, any_rope_tension};
use crate::newton::{Newton, NewtonFailure};
use crate::options::Options;
use crate::problem::{Accepted, Follow, Predictor, Problem};
use crate::scheme::{History, MAX_EXTRAPOLATION, Method, StepFormula, extrapolation_weights, newest_first};
use crate::solution::State;

/// What one step reports.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StepReport {
    /// Newton iterations.
    pub iterations: usize,
    /// Of those, minimum-norm steps on a singular iteration matrix.
    pub min_norm_steps: usize,
    /// Whether the step held the direction a nearly slack rope leaves free
    /// (see [`nearly_slack`]).
    pub held: bool,
    /// Of a step by continuation ([`Stepper::continue_to`]): the shorter
    /// steps it took to stay on its branch (0: one step).
    pub substeps: usize,
    /// Whether the step changed branch where the path does: a rope's length
    /// or a taut rope's tension changed sign within
    /// [`CONTINUATION_SHORTEST`] of the step, or across a singular
    /// configuration shorter steps could not follow
    /// ([`Stepper::step_across`]).
    pub crossed: bool,
}

impl StepReport {
    /// Whether the path left something free at this step: Newton met a
    /// singular iteration matrix, or the step held what a nearly slack
    /// rope leaves free.
    pub fn left_free(&self) -> bool {
        self.min_norm_steps > 0 || self.held
    }
}

/// A rope carrying less than this fraction of the largest tension leaves
/// what it is tied to free to round-off (see [`nearly_slack`]). Measured on
/// the paper's move slowed to 1000 s at dt = 0.001 s, the largest error of
/// u1 against Appendix A with the steps held below a ratio of 1e-13, 1e-12,
/// 1e-11, 1e-10 and 1e-9: 5.0, 6.9e-2, 8.3e-4, 1.9e-5 and 1.3e-6 N m (peak
/// 43.3 N m; round-off once the hold ends, falling as the tension it ends
/// at grows). From 1e-10 the held steps' residual made a reduced run's
/// start on eqs. (22) fail at t = 0.002 s; 1e-11 is the largest ratio that
/// costs no regular run anything.
pub const HOLD_TENSION_RATIO: f64 = 1e-11;

/// Whether a rope of `state` carries, in magnitude, less than
/// [`HOLD_TENSION_RATIO`] of the largest tension (no rope: never).
///
/// Such a rope barely holds what it is tied to: a massless pulley on it is
/// placed by a balance of forces of round-off size, and round-off moves it,
/// by `eps / ratio` of the crane's size, step to step, which the scheme's
/// second differences turn into inputs of any size (the paper's move slowed
/// to 1000 s: 637 N m where the slow limit is 43.3 N m). A step from such a
/// state (not the first step of a run: a start with a rope at zero tension,
/// like the paper's, has a singular matrix whose minimum-norm solve
/// converges to the determined solution, 8.7e-8 m off in navy-3d's pulley
/// when held) holds the directions the iteration matrix barely determines
/// where the predictor puts them ([`Newton::set_hold`]): the limit of a
/// vanishing tension.
pub fn nearly_slack<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    state: &State<N, M, A>,
) -> bool {
    any_rope_tension(model, state, |n, largest| n.abs() < HOLD_TENSION_RATIO * largest)
}

/// A rope carrying at least this fraction of the largest tension is
/// clearly taut: its tension changing sign within one step is a change of
/// branch to be confirmed by shorter steps ([`rope_branch_left`]); a rope
/// below it may go slack by round-off (the slow move's ropes under
/// [`HOLD_TENSION_RATIO`]).
pub const TAUT_TENSION_RATIO: f64 = 1e-6;

/// Whether a step from `before` to `after` changed the sign of a rope's
/// length, or of the tension of a rope that was clearly taut
/// ([`TAUT_TENSION_RATIO`]): the rope constraints `|d|^2 = L^2` and the
/// force balance hold as well for `-L` and a pushing rope, the mirror
/// configurations a long step's prediction may converge to (navy-planar at
/// dt = 0.5 s: its boom tip above the jib at t = 4 s, `N1 = -1332 N` where
/// the move has `+433.5 N`). A real slackening is confirmed as such by a
/// step short enough to follow it.
pub fn rope_branch_left<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    before: &State<N, M, A>,
    after: &State<N, M, A>,
) -> bool {
    let ropes = Mdl::INFO.ropes.len().min(M);
    let (mut was, mut is) = ([0.0; M], [0.0; M]);
    let (was, is) = (&mut was[..ropes], &mut is[..ropes]);
    model.rope_lengths(&before.q, was);
    model.rope_lengths(&after.q, is);
    if was.iter().zip(is.iter()).any(|(&was, &is)| was > 0.0 && !(is > 0.0)) {
        return true;
    }
    model.rope_tensions(&before.q, &before.lambda, was);
    model.rope_tensions(&after.q, &after.lambda, is);
    let largest = was.iter().map(|n| n.abs()).fold(0.0, f64::max);
    was.iter()
        .zip(is.iter())
        .any(|(&was, &is)| was > 0.0 && was >= TAUT_TENSION_RATIO * largest && !(is > 0.0))
}

/// Anything that advances a crane one step at a time: a [`Stepper`], or
/// problems in sequence ([`Handover`]). The run loop of [`crate::driver`]
/// takes one.
pub trait Advance<const N: usize, const M: usize, const A: usize> {
    /// The crane's model type.
    type Model: CraneModel<N, M, A>;
    /// The crane.
    fn model(&self) -> &Self::Model;
    /// Advance one step.
    fn step(&mut self) -> Result<StepReport, Error>;
    /// The state after the last step (the start before the first).
    fn state(&self) -> &State<N, M, A>;
    /// The time step.
    fn dt(&self) -> f64;
    /// The scheme's name.
    fn scheme_name(&self) -> &'static str;
    /// What the problem's index reduction covers ([`Problem::path_order_covered`]).
    fn path_order_covered(&self) -> Option<usize>;
}

/// The generic one-step integrator of a [`Problem`] `P` on a [`Method`] `S`
/// (`K` discretised coordinates). After construction a step does not
/// allocate; a clone continues independently from the same state.
#[derive(Clone)]
pub struct Stepper<P, S: Method, const N: usize, const M: usize, const A: usize, const K: usize> {
    problem: P,
    history: History<K, S>,
    newton: Newton,
    /// The unknowns: the last step's solution between steps.
    z: DVector<f64>,
    /// The last `MAX_EXTRAPOLATION` steps' unknowns (the extrapolation of
    /// the unknowns the scheme does not predict), a ring: the newest at
    /// `newest`, each older one after it, wrapping around.
    past: [DVector<f64>; MAX_EXTRAPOLATION],
    newest: usize,
    /// The last two solutions of a continuation ([`Stepper::continue_to`]).
    scratch: [DVector<f64>; 2],
    /// How many of `past` are known (1 ..= MAX_EXTRAPOLATION).
    known: usize,
    /// Whether the last step took a minimum-norm step (a singular
    /// iteration matrix): the next one predicts with the scheme's degree.
    last_singular: bool,
    state: State<N, M, A>,
    t0: f64,
    dt: f64,
    steps: usize,
}

/// The runtime error for a failed Newton solve of the step to `t`.
fn step_error(failure: NewtonFailure, t: f64) -> Error {
    match failure {
        NewtonFailure::NotConverged { iterations, residual } => Error::NewtonNotConverged {
            t,
            iterations,
            residual,
        },
        NewtonFailure::Singular { pivot_ratio, .. } => Error::SingularIterationMatrix { t, pivot_ratio },
        NewtonFailure::NonFinite { .. } => Error::NonFinite {
            quantity: "Newton iterate",
            t,
        },
    }
}

impl<P, S, const N: usize, const M: usize, const A: usize, const K: usize> Stepper<P, S, N, M, A, K>
where
    P: Problem<N, M, A, K>,
    S: Method,
{
    /// A stepper of `problem` from the consistent `start` with the step,
    /// scheme and Newton tolerances of `options` (its end time is not
    /// used). The crane's parameters are checked first
    /// ([`check_parameters`]); the scheme's history before the start
    /// follows its start-up rule ([`History::new`]).
    pub fn new(mut problem: P, start: &State<N, M, A>, options: &Options<S>) -> Result<Self, Error> {
        check_parameters(problem.model())?;
        let dt = options.dt();
        let dim = problem.dim();
        let mut z = DVector::zeros(dim);
        let at = problem.start(start, dt, &mut z)?;
        let history = History::new(*options.scheme(), at.y0, at.v0, at.at_rest);
        let mut newton = if P::EQUILIBRATED {
            Newton::equilibrated(dim, *options.newton())
        } else {
            Newton::new(dim, *options.newton())
        };
        if let Some(form) = problem.triangular() {
            newton.set_triangular(form);
        }
        Ok(Self {
            problem,
            history,
            newton,
            past: std::array::from_fn(|_| z.clone()),
            newest: 0,
            scratch: [z.clone(), z.clone()],
            z,
            known: 1,
            last_singular: false,
            state: *start,
            t0: start.t,
            dt,
            steps: 0,
        })
    }

    /// The state after the last step (the start before the first).
    pub fn state(&self) -> &State<N, M, A> {
        &self.state
    }

    /// The discretised coordinates and their rates after the last step
    /// (`q, q'` in redundant coordinates, `mu, mu'` in minimal ones).
    pub fn coordinates(&self) -> (SVector<f64, K>, SVector<f64, K>) {
        (*self.history.value(), *self.history.rate())
    }

    /// Rebuild the scheme's history from the unknowns of the last steps
    /// (as many as are known, up to the scheme's), each mapped by
    /// `coordinates` to its discretised coordinates and rates: for a
    /// problem that changed which of its unknowns are discretised (a new
    /// selection of states). It allocates.
    pub fn rediscretise(&mut self, coordinates: impl Fn(&P, &DVector<f64>) -> (SVector<f64, K>, SVector<f64, K>)) {
        let (values, rates): (Vec<SVector<f64, K>>, Vec<SVector<f64, K>>) = newest_first(&self.past, self.newest)
            .take(self.known)
            .map(|z| coordinates(&self.problem, z))
            .unzip();
        if let Some(history) = History::from_past(*self.history.method(), &values, &rates) {
            self.history = history;
        }
        // the iteration matrix has another form: new scales
        self.newton.forget_scales();
    }

    /// The pivot ratio of the last LU of an iteration matrix
    /// ([`Newton::pivot_ratio`]).
    pub fn pivot_ratio(&self) -> f64 {
        self.newton.pivot_ratio()
    }

    /// The problem.
    pub fn problem(&self) -> &P {
        &self.problem
    }

    /// The unknowns of the last step (those the problem started from before
    /// the first), in the problem's layout.
    pub fn unknowns(&self) -> &DVector<f64> {
        &self.z
    }

    /// The unknowns of the last accepted step (of the start before the
    /// first), whatever a failed step left in [`unknowns`](Self::unknowns).
    pub fn accepted_unknowns(&self) -> &DVector<f64> {
        &self.past[self.newest]
    }

    /// The problem, to change between steps.
    pub fn problem_mut(&mut self) -> &mut P {
        &mut self.problem
    }

    /// The time step.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The scheme.
    pub fn scheme(&self) -> &S {
        self.history.method()
    }

    /// LU factorisations of Newton's matrices over the steps so far (a
    /// deterministic cost: [`DenseSolver::factorisations`](crate::linsolve::DenseSolver::factorisations)).
    pub fn factorisations(&self) -> usize {
        self.newton.factorisations()
    }

    /// Newton iterations over the steps so far whose update the problem
    /// took stage by stage
    /// ([`NonlinearSystem::staged_update`](crate::newton::NonlinearSystem::staged_update)).
    pub fn staged_updates(&self) -> usize {
        self.newton.staged_updates()
    }

    /// Of the [`staged_updates`](Self::staged_updates), those that kept
    /// the factors of the update before
    /// ([`CHORD_UPDATE`](crate::newton::CHORD_UPDATE)).
    pub fn chord_updates(&self) -> usize {
        self.newton.chord_updates()
    }

    /// Steps taken.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// The time of the next step, `t0 + (steps + 1) dt`.
    pub fn next_time(&self) -> f64 {
        self.t0 + (self.steps + 1) as f64 * self.dt
    }

    /// Advance one step, to [`next_time`](Self::next_time), with the drive
    /// from the problem's own source.
    pub fn step(&mut self) -> Result<StepReport, Error> {
        self.step_own_to(self.next_time())
    }

    /// [`step_to`](Self::step_to) with the problem's own drive at `t`,
    /// which the problem may then take beyond double precision
    /// ([`Extended::target_time`](crate::scheme::Extended::target_time)).
    pub(crate) fn step_own_to(&mut self, t: f64) -> Result<StepReport, Error> {
        let expected = self.next_time();
        check_step_time(t, expected, self.dt)?;
        let drive = self.problem.drive(expected);
        self.advance(expected, &drive, true)
    }

    /// Advance one step to time `t`, which must be
    /// [`next_time`](Self::next_time) `= t0 + (n + 1) dt` to within 1e-9 of
    /// the step and a few ulps of `t` ([`Error::WrongStepTime`] otherwise),
    /// with the given drive (the load target `gamma, gamma', gamma''` at `t`
    /// for the servo problems). The step is taken at `next_time`.
    pub fn step_to(&mut self, t: f64, drive: &P::Drive) -> Result<StepReport, Error> {
        let expected = self.next_time();
        check_step_time(t, expected, self.dt)?;
        self.advance(expected, drive, false)
    }

    /// [`step_to`](Self::step_to) taking the solution it finds even where it
    /// leaves its branch ([`Problem::leaves_branch`]): the step across a
    /// singular configuration that shorter steps cannot follow (a rope whose
    /// tension passes zero leaves what it holds free there).
    pub fn step_across(&mut self, t: f64, drive: &P::Drive) -> Result<StepReport, Error> {
        let expected = self.next_time();
        check_step_time(t, expected, self.dt)?;
        self.advance_checked(expected, drive, false, false)
    }

    /// One step, refused where it leaves its branch; `own`: the drive is
    /// the problem's own.
    fn advance(&mut self, t: f64, drive: &P::Drive, own: bool) -> Result<StepReport, Error> {
        self.advance_checked(t, drive, true, own)
    }

    /// One step: the scheme's formula, the prediction, Newton, the state;
    /// with `check_branch`, refused where it leaves its branch
    /// ([`Problem::leaves_branch`]), else taken as a crossing.
    fn advance_checked(
        &mut self,
        t: f64,
        drive: &P::Drive,
        check_branch: bool,
        own: bool,
    ) -> Result<StepReport, Error> {
        self.problem.check_drive(drive, t)?;
        let predictor = self.problem.predictor();
        let smooth = self.smooth_prediction();
        self.problem
            .prepare(drive, self.formula(predictor, usize::from(smooth), own));
        self.predict(predictor);
        let mut held = P::HOLDS_NEARLY_SLACK && self.steps > 0 && nearly_slack(self.problem.model(), &self.state);
        self.newton.set_hold(held);
        let converged = match self.newton.solve(&mut self.problem, &mut self.z) {
            Ok(converged) => converged,
            // a held solve that does not end (its residual still halving
            // at the iteration limit) is taken again as a regular step
            Err(_) if held => {
                held = false;
                self.newton.set_hold(false);
                self.predict(predictor);
                self.newton
                    .solve(&mut self.problem, &mut self.z)
                    .map_err(|failure| step_error(failure, t))?
            }
            // the extrapolation can overshoot where the solution turns along
            // a weakly determined direction: retry from the last step (its
            // discretised coordinates still from the scheme's predictor)
            Err(first) if self.known >= 3 => {
                self.z.copy_from(&self.past[self.newest]);
                match predictor {
                    Predictor::Scheme { leading } => {
                        let predicted = self.history.predict(self.dt, 0);
                        self.z.rows_mut(0, leading).copy_from(&predicted.rows(0, leading));
                    }
                    Predictor::Correction { .. } => {
                        self.problem.prepare(drive, self.formula(predictor, 0, own));
                        self.z.fill(0.0);
                    }
                    Predictor::Extrapolation { .. } => {}
                }
                let mut retried = self
                    .newton
                    .solve(&mut self.problem, &mut self.z)
                    .map_err(|failure| step_error(failure, t))?;
                // the statistics count the failed attempt's iterations too
                retried.iterations += first.iterations();
                retried
            }
            Err(failure) => return Err(step_error(failure, t)),
        };
        let accepted = self.problem.accept(t, &self.z)?;
        if check_branch && self.problem.leaves_branch(&self.state, &accepted.state) {
            return Err(Error::BranchLeft { t });
        }
        self.record(accepted);
        self.last_singular = converged.min_norm_steps > 0;
        Ok(StepReport {
            iterations: converged.iterations,
            // every solve of a held step is a minimum-norm one, by choice
            min_norm_steps: if held { 0 } else { converged.min_norm_steps },
            held,
            substeps: 0,
            crossed: !check_branch,
        })
    }

    /// Whether the step's prediction may take one degree more than the
    /// scheme's: after three regular steps.
    fn smooth_prediction(&self) -> bool {
        !self.last_singular && self.known >= 3
    }

    /// The scheme's formula of the next step; with its double-double part
    /// (prediction with `extra` points, and the step's time where the
    /// drive is the problem's `own`) for a problem that solves for
    /// corrections ([`Predictor::Correction`]).
    fn formula(&self, predictor: Predictor, extra: usize, own: bool) -> StepFormula<K> {
        match predictor {
            Predictor::Correction { .. } => {
                let time = own.then(|| DoubleDouble::step_time(self.t0, self.steps as u64 + 1, self.dt));
                self.history.extended_formula(self.dt, extra, time)
            }
            _ => self.history.formula(self.dt),
        }
    }

    /// Newton's first iterate of the step (see [`Predictor`]).
    fn predict(&mut self, predictor: Predictor) {
        match predictor {
            // after a regular step, the discretised coordinates from the
            // polynomial one degree above the scheme's and the other
            // unknowns (inputs, multipliers) from the quadratic through the
            // last three steps: the scheme's own degree and the last
            // step's inputs and multipliers cost backward Euler a third
            // iteration in almost every step (navy-planar, dt = 0.01: 2.98
            // iterations per step against 2.00). After a step on a singular
            // iteration matrix the free direction is not determined by the
            // equations and follows the predictor, which a higher degree
            // would amplify (a slow move with a slack rope then fails at
            // t = 0.9 s): the scheme's degree and the last step's values.
            Predictor::Scheme { leading } => {
                let smooth = self.smooth_prediction();
                let predicted = self.history.predict(self.dt, usize::from(smooth));
                self.z.rows_mut(0, leading).copy_from(&predicted.rows(0, leading));
                if smooth {
                    self.extrapolate(leading, 3);
                }
            }
            // the same as corrections: the leading unknowns' prediction is
            // in the step's formula, the others' change over the step is
            // the line through their last two changes (the quadratic
            // through their last three values), or none
            Predictor::Correction { leading } => {
                self.z.fill(0.0);
                if self.smooth_prediction() {
                    self.extrapolate(leading, 2);
                }
            }
            // the cubic through the last four steps after a regular step,
            // the quadratic through the last three before that and after a
            // step on a singular iteration matrix, the last step at first
            // (measured on navy-planar in minimal coordinates, tf = 4 s:
            // from the last step alone Newton fails by t = 0.8 s at dt =
            // 0.1; a linear extrapolation from the first step off the
            // degenerate start diverges at dt = 0.1 and 0.05; the quadratic
            // converges at every dt from 0.1 to 0.001; the cubic, once four
            // steps are known, takes 2.04 Newton iterations per step at
            // dt = 0.01 against the quadratic's 2.85, with e_u(1.5 s) the
            // same at every dt of `crane convergence`)
            Predictor::Extrapolation { points } => {
                let points = if !self.last_singular && self.known >= 4 {
                    self.known.min(points.min(MAX_EXTRAPOLATION))
                } else if self.known >= 3 {
                    3
                } else {
                    1
                };
                self.extrapolate(0, points);
            }
        }
    }

    /// The unknowns from `first` on from the polynomial through the last
    /// `points` steps' unknowns (`points <= known`).
    fn extrapolate(&mut self, first: usize, points: usize) {
        let weights = extrapolation_weights(points);
        // newest first, added unknown by unknown in that order (a vector
        // at a time)
        let z = &mut self.z.as_mut_slice()[first..];
        z.fill(-0.0);
        for (past, &weight) in newest_first(&self.past, self.newest).zip(&weights).take(points) {
            for (zi, &h) in z.iter_mut().zip(&past.as_slice()[first..]) {
                *zi += weight * h;
            }
        }
    }

    /// Keep an accepted step: the state, the history, the unknowns for the
    /// predictor.
    fn record(&mut self, accepted: Accepted<N, M, A, K>) {
        self.state = accepted.state;
        match accepted.trailing {
            Some([y_lo, v_lo]) => self.history.push_extended(accepted.y, y_lo, accepted.v, v_lo),
            None => self.history.push(accepted.y, accepted.v),
        }
        self.newest = self.newest.checked_sub(1).unwrap_or(MAX_EXTRAPOLATION - 1);
        self.past[self.newest].copy_from(&self.z);
        self.known = (self.known + 1).min(MAX_EXTRAPOLATION);
        self.steps += 1;
    }

    /// Take `state`, computed by another problem for the step to
    /// [`next_time`](Self::next_time), as this stepper's step: the problem
    /// finds its coordinates and unknowns there ([`Follow`]), so that its
    /// history and predictor are in step when it takes over.
    pub fn follow(&mut self, state: &State<N, M, A>) -> Result<(), Error>
    where
        P: Follow<N, M, A, K>,
    {
        let formula = self.history.formula(self.dt);
        let (y, v) = self.problem.follow(state, self.history.value(), formula, &mut self.z)?;
        self.record(Accepted {
            state: *state,
            y,
            v,
            trailing: None,
        });
        Ok(())
    }
}

/// The shortest step of a continuation ([`Stepper::continue_to`]), as a
/// fraction of the time step: a change of branch that persists down to it
/// is the path's own (a rope going slack), taken as found.
pub const CONTINUATION_SHORTEST: f64 = 1.0 / (1u64 << 20) as f64;

/// The most Newton solves one step by continuation may take
/// ([`Stepper::continue_to`]).
pub const CONTINUATION_SOLVES: usize = 2000;

impl<P, S, const N: usize, const M: usize, const A: usize> Stepper<P, S, N, M, A, 0>
where
    P: Problem<N, M, A, 0>,
    S: Method,
{
    /// The step to `t` ([`next_time`](Self::next_time)) by continuation in
    /// time, for a problem that is algebraic at each time (nothing
    /// discretised, `K = 0`, so that a shorter step costs no accuracy):
    /// from the last step's solution along the problem's own drive, in
    /// steps halved where Newton fails or the solution leaves its branch
    /// ([`Problem::leaves_branch`]) and doubled after each that succeeds,
    /// each predicted by the secant through the two before; only the step
    /// to `t`, with `drive`, is recorded. A change of branch that persists
    /// down to [`CONTINUATION_SHORTEST`] of the step is taken. Fails with
    /// the Newton failure of the shortest step, or [`Error::BranchLeft`]
    /// after [`CONTINUATION_SOLVES`] solves.
    pub fn continue_to(&mut self, t: f64, drive: &P::Drive) -> Result<StepReport, Error> {
        let t = {
            let expected = self.next_time();
            check_step_time(t, expected, self.dt)?;
            expected
        };
        let formula = self.history.formula(self.dt);
        let shortest = CONTINUATION_SHORTEST * self.dt;
        // the known solution (at `from`, whose state is `at`) and the one
        // before it, `back` earlier (0: none known on this continuation)
        let (mut from, mut at, mut back) = (self.state.t, self.state, 0.0);
        let mut known = 1;
        self.scratch[0].copy_from(&self.past[self.newest]);
        let mut h = 0.5 * (t - from);
        let (mut iterations, mut substeps, mut crossed) = (0, 0, false);
        for _ in 0..CONTINUATION_SOLVES {
            let last = from + h >= t - 0.5 * shortest;
            let to = if last { t } else { from + h };
            let owned;
            let target = if last {
                drive
            } else {
                owned = self.problem.drive(to);
                &owned
            };
            self.problem.check_drive(target, to)?;
            self.problem.prepare(target, formula);
            // the secant through the two known solutions, or the last one
            self.z.copy_from(&self.scratch[0]);
            if known == 2 {
                let ratio = (to - from) / back;
                self.z.axpy(ratio, &self.scratch[0], 1.0);
                self.z.axpy(-ratio, &self.scratch[1], 1.0);
            }
            self.newton.set_hold(false);
            let solved = self.newton.solve(&mut self.problem, &mut self.z);
            iterations += solved.as_ref().map_or_else(|f| f.iterations(), |c| c.iterations);
            let shorter = (to - from) > shortest;
            let converged = match solved {
                Ok(converged) => converged,
                Err(failure) if !shorter => return Err(step_error(failure, to)),
                Err(_) => {
                    h = 0.5 * (to - from);
                    continue;
                }
            };
            let accepted = self.problem.accept(to, &self.z)?;
            if self.problem.leaves_branch(&at, &accepted.state) {
                if shorter {
                    h = 0.5 * (to - from);
                    continue;
                }
                crossed = true;
            }
            substeps += 1;
            if last {
                self.record(accepted);
                self.last_singular = converged.min_norm_steps > 0;
                return Ok(StepReport {
                    iterations,
                    min_norm_steps: converged.min_norm_steps,
                    held: false,
                    substeps,
                    crossed,
                });
            }
            // the newest known solution first, the one before it second
            self.scratch.swap(0, 1);
            self.scratch[0].copy_from(&self.z);
            known = 2;
            back = to - from;
            (from, at) = (to, accepted.state);
            h = 2.0 * back;
        }
        Err(Error::BranchLeft { t })
    }
}

/// Refuse a step to `t` that is not `expected = t0 + (n + 1) dt`: to 1e-9
/// of the step, plus four ulps of the time (past t = 8192 s an ulp is 1.8e-12
/// s, more than 1e-9 of dt = 0.001 s, and a host's `t_n + dt` may differ from
/// `t0 + (n + 1) dt` in its last bits).
fn check_step_time(t: f64, expected: f64, dt: f64) -> Result<(), Error> {
    if (t - expected).abs() <= 1e-9 * dt + 4.0 * f64::EPSILON * expected.abs() {
        Ok(())
    } else {
        Err(Error::WrongStepTime { t, expected })
    }
}

impl<P, S, const N: usize, const M: usize, const A: usize, const K: usize> Advance<N, M, A>
    for Stepper<P, S, N, M, A, K>
where
    P: Problem<N, M, A, K>,
    S: Method,
{
    type Model = P::Model;
    fn model(&self) -> &P::Model {
        self.problem.model()
    }
    fn step(&mut self) -> Result<StepReport, Error> {
        Stepper::step(self)
    }
    fn state(&self) -> &State<N, M, A> {
        &self.state
    }
    fn dt(&self) -> f64 {
        self.dt
    }
    fn scheme_name(&self) -> &'static str {
        self.history.method().name()
    }
    fn path_order_covered(&self) -> Option<usize> {
        self.problem.path_order_covered()
    }
}

/// Two problems in sequence: `first` takes the steps until `second` can
/// take over from its state ([`Follow::can_take_over`]); meanwhile
/// `second` follows each of those states ([`Stepper::follow`]), so its
/// history is its own when it takes over. Both follow one path: the drive
/// of [`step`](Self::step), the second problem's own, is taken as the
/// first's own too (which a problem may take beyond double precision from
/// its own path).
#[derive(Clone)]
pub struct Handover<P1, P2, S: Method, const N: usize, const M: usize, const A: usize, const K1: usize, const K2: usize>
{
    first: Option<Stepper<P1, S, N, M, A, K1>>,
    second: Stepper<P2, S, N, M, A, K2>,
    first_steps: usize,
}

impl<P1, P2, S, const N: usize, const M: usize, const A: usize, const K1: usize, const K2: usize>
    Handover<P1, P2, S, N, M, A, K1, K2>
where
    P1: Problem<N, M, A, K1, Drive = P2::Drive>,
    P2: Follow<N, M, A, K2>,
    S: Method,
{
    /// `second` from its start, with the first steps by the stepper
    /// `first()` builds if `second` cannot take the start. Both must start
    /// from the same state with the same step and scheme (the minimal
    /// stepper builds them from one start and one [`Options`]).
    pub fn new(
        second: Stepper<P2, S, N, M, A, K2>,
        first: impl FnOnce() -> Result<Stepper<P1, S, N, M, A, K1>, Error>,
    ) -> Result<Self, Error> {
        let first = if second.problem.can_take_over(&second.state) {
            None
        } else {
            let first = first()?;
            if first.dt != second.dt {
                return Err(Error::HandoverMismatch {
                    what: format!("time step ({} s and {} s)", first.dt, second.dt),
                });
            }
            if first.state != second.state {
                return Err(Error::HandoverMismatch {
                    what: format!("start (at t = {} s and {} s)", first.state.t, second.state.t),
                });
            }
            Some(first)
        };
        Ok(Self {
            first,
            second,
            first_steps: 0,
        })
    }

    /// The state after the last step (the start before the first).
    pub fn state(&self) -> &State<N, M, A> {
        &self.second.state
    }

    /// The time step.
    pub fn dt(&self) -> f64 {
        self.second.dt
    }

    /// How many steps the first problem took.
    pub fn first_steps(&self) -> usize {
        self.first_steps
    }

    /// The stepper of the second problem.
    pub fn second(&self) -> &Stepper<P2, S, N, M, A, K2> {
        &self.second
    }

    /// Advance one step with the second problem's drive.
    pub fn step(&mut self) -> Result<StepReport, Error> {
        let t = self.second.next_time();
        let drive = self.second.problem.drive(t);
        self.step_with(t, &drive, true)
    }

    /// Advance one step to `t` (`t_n + dt`) with the given drive.
    pub fn step_to(&mut self, t: f64, drive: &P2::Drive) -> Result<StepReport, Error> {
        self.step_with(t, drive, false)
    }

    /// One step to `t` with `drive`, the problems' `own` or not.
    fn step_with(&mut self, t: f64, drive: &P2::Drive, own: bool) -> Result<StepReport, Error> {
        let Some(first) = self.first.as_mut() else {
            return if own {
                self.second.step_own_to(t)
            } else {
                self.second.step_to(t, drive)
            };
        };
        // the two start alike and step in lockstep: one check of the time
        let t_next = self.second.next_time();
        check_step_time(t, t_next, self.second.dt)?;
        let report = first.advance(t_next, drive, own)?;
        let state = first.state;
        self.second.follow(&state)?;
        self.first_steps += 1;
        if self.second.problem.can_take_over(&state) {
            self.first = None;
        }
        Ok(report)
    }
}

impl<P1, P2, S, const N: usize, const M: usize, const A: usize, const K1: usize, const K2: usize> Advance<N, M, A>
    for Handover<P1, P2, S, N, M, A, K1, K2>
where
    P1: Problem<N, M, A, K1, Drive = P2::Drive>,
    P2: Follow<N, M, A, K2>,
    S: Method,
{
    type Model = P2::Model;
    fn model(&self) -> &P2::Model {
        self.second.problem.model()
    }
    fn step(&mut self) -> Result<StepReport, Error> {
        Handover::step(self)
    }
    fn state(&self) -> &State<N, M, A> {
        &self.second.state
    }
    fn dt(&self) -> f64 {
        self.second.dt
    }
    fn scheme_name(&self) -> &'static str {
        self.second.history.method().name()
    }
    fn path_order_covered(&self) -> Option<usize> {
        self.second.problem.path_order_covered()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::redundant::Redundant;
    use crate::test_support::Gantry;
    use crate::trajectory::FromFn;
    use nalgebra::SVector;

    /// A controller that adds `dt` to its own clock reaches `t_n + dt` only
    /// to a few ulps of `t0 + (n + 1) dt`, more than 1e-9 of dt once t
    /// passes 8192 s at dt = 0.001: `step_to` takes those times (and steps at
    /// `t0 + (n + 1) dt`), and refuses one a tenth of a step off.
    #[test]
    fn step_to_takes_a_host_clock_across_a_power_of_two() {
        let hold = FromFn(|_t: f64, k: usize| {
            if k == 0 {
                SVector::<f64, 2>::new(0.0, -5.0)
            } else {
                SVector::zeros()
            }
        });
        let t0 = 8191.99;
        let start = State {
            t: t0,
            q: SVector::from([0.0, 5.0, 0.0, -5.0]),
            v: SVector::zeros(),
            u: SVector::from([0.0, -0.1 * 200.0 * 9.81 / 0.5]),
            lambda: SVector::from([200.0 * 9.81 / 5.0]),
        };
        let options = Options::stepping(0.001).unwrap();
        let mut stepper = Stepper::new(Redundant::new(&Gantry, &hold), &start, &options).unwrap();
        let mut clock = t0;
        let mut off_by = 0.0f64;
        for _ in 0..20 {
            clock += 0.001;
            off_by = off_by.max((clock - stepper.next_time()).abs());
            let target = [0, 1, 2].map(|k| hold.0(clock, k));
            stepper.step_to(clock, &target).unwrap();
        }
        assert!(
            off_by > 1e-12,
            "the clock drifted by {off_by:e}: the test needs more than 1e-9 dt"
        );
        assert!((stepper.state().t - (t0 + 0.02)).abs() < 1e-9);
        let target = [0, 1, 2].map(|k| hold.0(clock, k));
        let wrong = stepper.step_to(clock + 0.0011, &target);
        assert!(matches!(wrong, Err(Error::WrongStepTime { .. })), "{wrong:?}");
    }
}
