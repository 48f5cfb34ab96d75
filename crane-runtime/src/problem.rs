//! What a problem supplies to the [`Stepper`](crate::stepper::Stepper): its
//! unknowns' layout, its residual and iteration matrix given the step
//! formula of a [`Method`](crate::scheme::Method), and what a state is made
//! of after a step; and the dynamic block every problem on redundant
//! coordinates shares ([`dynamic_rows`]).
//!
//! The problems of this crate: the servo problem in redundant coordinates
//! ([`crate::redundant`], eqs. 22a-d), in minimal coordinates
//! ([`crate::minimal`], eqs. 24a-e) and the forward dynamics
//! ([`crate::forward`], eq. 1). A problem never names a scheme; a scheme
//! never names a problem.

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::error::Error;
use crate::model::CraneModel;
use crate::newton::NonlinearSystem;
use crate::scheme::StepFormula;
use crate::solution::State;

/// The load target of one step: `gamma, gamma', gamma''` at the new time.
pub type ServoTarget<const A: usize> = [SVector<f64, A>; 3];

/// How the stepper predicts a step's unknowns before Newton.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Predictor {
    /// The scheme's extrapolation of the discretised coordinates
    /// ([`History::predict`](crate::scheme::History::predict), one degree
    /// above the scheme's after three regular steps) for the first
    /// `leading` unknowns (which are the first `leading` coordinates); the
    /// other unknowns from the quadratic through the last three steps, or
    /// the last step's values in the first steps and after a step on a
    /// singular iteration matrix.
    Scheme {
        /// How many leading unknowns are discretised coordinates.
        leading: usize,
    },
    /// The polynomial through the last `points` steps' unknowns (at most
    /// [`MAX_EXTRAPOLATION`](crate::scheme::MAX_EXTRAPOLATION); the cubic
    /// through four as soon as four are known, more as they become known;
    /// the quadratic through three, or the last step's, before that and
    /// after a step on a singular iteration matrix); if Newton fails from
    /// it, a second solve from the last step's unknowns.
    Extrapolation {
        /// The most steps the polynomial goes through (4: the cubic).
        points: usize,
    },
    /// As [`Scheme`](Self::Scheme), but every unknown is a correction: the
    /// first `leading` to the scheme's extrapolation of the discretised
    /// coordinates, which the problem gets in double-double with its step
    /// formula ([`History::extended_formula`](crate::scheme::History::extended_formula)),
    /// the others to what the problem holds from the last step (their
    /// change over the step: after a regular step the line through their
    /// last two changes, which is the quadratic through their last three
    /// values, else none). A correction is small, so `f64` holds it with an
    /// error far below the rounding of the values themselves.
    Correction {
        /// How many leading unknowns are corrections to the extrapolated
        /// discretised coordinates.
        leading: usize,
    },
}

/// What a problem makes of the start state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Start<const K: usize> {
    /// The discretised coordinates at the start.
    pub y0: SVector<f64, K>,
    /// Their rates.
    pub v0: SVector<f64, K>,
    /// Whether the crane rests at the start (then the scheme's history is
    /// the exact past of a crane at rest).
    pub at_rest: bool,
}

/// An accepted step: the crane's state and the new discretised coordinates
/// and rates for the scheme's history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Accepted<const N: usize, const M: usize, const A: usize, const K: usize> {
    /// The state at the new time, in redundant terms.
    pub state: State<N, M, A>,
    /// The discretised coordinates `y_{n+1}`.
    pub y: SVector<f64, K>,
    /// Their rates `y'_{n+1}`.
    pub v: SVector<f64, K>,
    /// What rounding `y` and `y'` to `f64` took from them, for a problem
    /// that holds them to double-double precision ([`Predictor::Correction`]).
    pub trailing: Option<[SVector<f64, K>; 2]>,
}

/// One problem of crane dynamics on the seam of the schemes: `K`
/// discretised coordinates (`y' = v`, `v' = a` by the scheme), unknowns `z`
/// of [`NonlinearSystem::dim`] entries, and a residual in them that the
/// step's [`StepFormula`] closes.
///
/// The [`Stepper`](crate::stepper::Stepper) does everything around it: the
/// checks before a run, the times of the steps, the history, the
/// predictor, Newton and its errors, the step reports.
pub trait Problem<const N: usize, const M: usize, const A: usize, const K: usize>: NonlinearSystem {
    /// The crane.
    type Model: CraneModel<N, M, A>;

    /// What each step is given besides its time: the load target
    /// ([`ServoTarget`], servo problems) or the inputs (forward dynamics).
    type Drive: Copy;

    /// Whether Newton equilibrates the iteration matrix before each solve.
    const EQUILIBRATED: bool = false;

    /// Whether a step from a state with a nearly slack rope holds the
    /// directions the iteration matrix barely determines
    /// ([`nearly_slack`](crate::stepper::nearly_slack)). The redundant
    /// servo problem (eqs. 22) does; the dummy-derivative system, whose
    /// jets the damping would hold too, and the forward dynamics do not.
    const HOLDS_NEARLY_SLACK: bool = false;

    /// The crane.
    fn model(&self) -> &Self::Model;

    /// The highest derivative of the load path ([`Structure::path_order`](crate::Structure::path_order))
    /// whose cranes the problem's index reduction covers: a crane needing
    /// more is beyond it, and no convergence theorem bounds the problem's
    /// errors for it. `None` for a problem that is not a
    /// servo problem (the forward dynamics).
    fn path_order_covered(&self) -> Option<usize> {
        None
    }

    /// How the unknowns of a step are predicted.
    fn predictor(&self) -> Predictor;

    /// The drive at `t` from the problem's own source (its path or input law).
    fn drive(&self, t: f64) -> Self::Drive;

    /// Refuse a drive that is not finite.
    fn check_drive(&self, drive: &Self::Drive, t: f64) -> Result<(), Error>;

    /// The discretised coordinates at `start` and, written into `z`, the
    /// unknowns there (Newton's first iterate of the first step is predicted
    /// from them). `dt` is the step of the run.
    fn start(&mut self, start: &State<N, M, A>, dt: f64, z: &mut DVector<f64>) -> Result<Start<K>, Error>;

    /// Set the drive of the next step and the scheme's affine maps of that
    /// step.
    fn prepare(&mut self, drive: &Self::Drive, formula: StepFormula<K>);

    /// The state at `t` from the converged unknowns `z` (which the problem
    /// may not change), or why it is not one (an ill-conditioned map, say).
    fn accept(&mut self, t: f64, z: &DVector<f64>) -> Result<Accepted<N, M, A, K>, Error>;

    /// Whether the step from `before` to `after` left the branch of
    /// solutions it started on, where the problem's equations have other
    /// roots near (the mirror configurations of an algebraic system: a
    /// rope of negative length pushing its load). Such a step is refused
    /// ([`Error::BranchLeft`]) and not recorded. Never, by default.
    fn leaves_branch(&self, before: &State<N, M, A>, after: &State<N, M, A>) -> bool {
        let _ = (before, after);
        false
    }
}

/// A problem that can follow a state another problem computed, so that it
/// takes over with its own history in step ([`Handover`](crate::stepper::Handover)).
pub trait Follow<const N: usize, const M: usize, const A: usize, const K: usize>: Problem<N, M, A, K> {
    /// Whether the problem can take the steps from `state` on.
    fn can_take_over(&self, state: &State<N, M, A>) -> bool;

    /// The discretised coordinates and rates of `state` as this problem has
    /// them after a step with `formula` from its history whose newest value
    /// is `last`, and its unknowns there written into `z`.
    fn follow(
        &mut self,
        state: &State<N, M, A>,
        last: &SVector<f64, K>,
        formula: StepFormula<K>,
        z: &mut DVector<f64>,
    ) -> Result<(SVector<f64, K>, SVector<f64, K>), Error>;
}

/// The terms of the dynamic rows of eq. (1a) on redundant coordinates at
/// one iterate, multiplied by `dt^2` (what a problem needs after
/// [`dynamic_rows`] wrote the rows: the sizes of the terms for the
/// residual's normalisation, `B^T` for the columns of the inputs).
pub struct DynamicTerms<const N: usize, const A: usize> {
    /// `M a dt^2`.
    pub inertia: SVector<f64, N>,
    /// `f dt^2`.
    pub applied: SVector<f64, N>,
    /// `B^T (dt^2 u)`.
    pub inputs: SVector<f64, N>,
    /// `B^T(q)`.
    pub input_matrix: SMatrix<f64, N, A>,
}

/// The dynamic rows (22b, 22c; eq. 1a for the forward problem) of `model`
/// at `q, v, a` with the scaled inputs `dt^2 u` and multipliers
/// `dt^2 lambda`, written once for every problem on redundant coordinates:
/// ```text
/// r_dyn = M (dt^2 a) - dt^2 f(q, v) - B^T(q) (dt^2 u) + G^T(q) (dt^2 lambda),   r_g = g(q)
/// ```
/// into `r` (rows `0..n`, then the constraints `g(q)` as the caller
/// evaluated them: in `f64`, or beyond where it holds `q` so), and into `jac` their
/// columns for unknowns `z = [q_0 .. q_cols; ...; dt^2 lambda]` (the
/// multipliers last): for the first `cols` coordinates, moved with the
/// slopes of the step's `formula`, `c^2 M - dt^2 df/dq - c dt df/dv -
/// d(B^T dt^2 u)/dq + d(G^T dt^2 lambda)/dq` over `G`, for the multipliers
/// `G^T` over 0, and 0 in the constraint rows of every other column (`g`
/// depends on `q` alone). The dynamic rows of columns between the
/// coordinates and the multipliers (the inputs of the servo problem) are
/// the problem's to write.
#[allow(clippy::too_many_arguments)]
pub fn dynamic_rows<Mdl, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    mass: &SMatrix<f64, N, N>,
    formula: &StepFormula<N>,
    [q, v, a]: &[SVector<f64, N>; 3],
    u_scaled: &SVector<f64, A>,
    lambda_scaled: &SVector<f64, M>,
    constraints: &SVector<f64, M>,
    cols: usize,
    r: &mut DVector<f64>,
    jac: &mut DMatrix<f64>,
) -> DynamicTerms<N, A>
where
    Mdl: CraneModel<N, M, A>,
{
    let (dt, slopes) = (formula.dt, formula.slopes());
    let dt2 = dt * dt;
    let f = model.forces(q, v);
    let (df_dq, df_dv) = model.force_jacobians(q, v);
    let bt = model.input_matrix(q);
    let dbu_dq = model.input_jacobian(q, u_scaled);
    let jac_g = model.constraint_jacobian(q);
    let dgl_dq = model.constraint_hessian(q, lambda_scaled);
    let inertia = mass * a * dt2;
    let applied = f * dt2;
    let inputs = bt * u_scaled;
    let residual = inertia - applied - inputs + jac_g.tr_mul(lambda_scaled);
    r.rows_mut(0, N).copy_from(&residual);
    r.rows_mut(N, M).copy_from(constraints);
    let (da, dv) = (slopes.acceleration_dt2, slopes.velocity_dt2);
    for j in 0..cols {
        for i in 0..N {
            jac[(i, j)] =
                da * mass[(i, j)] - dt2 * df_dq[(i, j)] - dv * df_dv[(i, j)] - dbu_dq[(i, j)] + dgl_dq[(i, j)];
        }
        for i in 0..M {
            jac[(N + i, j)] = jac_g[(i, j)];
        }
    }
    jac.view_mut((N, cols), (M, jac.ncols() - cols)).fill(0.0);
    let lambda = jac.ncols() - M;
    for l in 0..M {
        for i in 0..N {
            jac[(i, lambda + l)] = jac_g[(l, i)];
        }
    }
    DynamicTerms {
        inertia,
        applied,
        inputs,
        input_matrix: bt,
    }
}
