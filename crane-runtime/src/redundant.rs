//! The servo problem in redundant coordinates, paper eqs. (22a-d), on any
//! scheme.
//!
//! With the servo constraints `x = gamma(t)` substituted, the unknowns of a
//! step are `p_{n+1}`, `u_{n+1}` and `lambda_{n+1}`; the scheme eliminates
//! `v_{n+1}` and `a_{n+1}` as affine functions of `p_{n+1}` (eq. 22a for
//! backward Euler; [`crate::scheme`] for BDF-k). The dynamic rows (22b, 22c)
//! are multiplied by `dt^2` and solved for `dt^2 u` and `dt^2 lambda`, which
//! keeps the iteration matrix's condition number independent of `dt` (about
//! 8e3 on `navy-planar` instead of 2.6e8 at dt = 0.01 and 2.6e12 at
//! dt = 0.001, measured at t = 1.5 s). In general form, valid for any
//! constant mass matrix,
//! ```text
//! r_dyn = dt^2 (M a - f(q, v)) - B^T(q) (dt^2 u) + G^T(q) (dt^2 lambda) = 0   (22b, 22c)
//! r_g   = g(q) = 0                                                             (22d)
//! q = [p_{n+1}; gamma],  v = [(c/dt)(p_{n+1} - pbar); gamma'],
//! a = [(c/dt)(v_p - vbar); gamma'']
//! ```
//! (backward Euler: `c = 1`, `pbar = p_n`, `vbar = v_n`), which for
//! `M = diag(M1, M2)`, `B^T = [B1^T; 0]`, `f = [f1(p, p'); f2(x, x')]` is
//! exactly (22b) and (22c). In the iteration matrix the scheme's slopes
//! replace 1: `d(dt^2 a)/dp = c^2`, `d(dt^2 v)/dp = c dt`.

use std::ops::{Deref, Range};

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::driver::solve;
use crate::error::Error;
use crate::init;
use crate::model::CraneModel;
use crate::newton::{NonlinearSystem, normalised_residual};
use crate::options::Options;
use crate::problem::{Accepted, Follow, Predictor, Problem, ServoTarget, Start, dynamic_rows};
use crate::scheme::{Method, Scheme, StepFormula};
use crate::solution::{Solution, State};
use crate::stepper::Stepper;
use crate::trajectory::Trajectory;

/// Eqs. (22a-d) of one step, as a [`Problem`] in the unknowns
/// `z = [p; dt^2 u; dt^2 lambda]`, for the crane behind the handle `H`
/// (`&Mdl`, `Box<Mdl>`, `Arc<Mdl>`) on the path `Tr`.
#[derive(Clone)]
pub struct Redundant<H, Tr, const N: usize, const M: usize, const A: usize> {
    model: H,
    trajectory: Tr,
    mass: SMatrix<f64, N, N>,
    /// `gamma, gamma', gamma''` at `t_{n+1}`.
    target: ServoTarget<A>,
    /// The scheme's affine maps `p -> v, a` for this step.
    formula: StepFormula<N>,
    /// The dynamic rows' floors of the residual test (their inertia or
    /// applied forces, the larger) at the last evaluation.
    floors: SVector<f64, N>,
    blocks: [Range<usize>; 3],
}

impl<H, Tr, const N: usize, const M: usize, const A: usize> Redundant<H, Tr, N, M, A>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized>,
    Tr: Trajectory<A>,
{
    const P: usize = N - A;

    /// The servo problem of the crane behind `model` on `trajectory`.
    pub fn new(model: H, trajectory: Tr) -> Self {
        let mass = model.mass_matrix();
        Self {
            model,
            trajectory,
            mass,
            target: [SVector::zeros(); 3],
            formula: StepFormula::unprepared(),
            floors: SVector::zeros(),
            blocks: [0..Self::P, Self::P..N, N..N + M],
        }
    }

    /// The load path.
    pub fn trajectory(&self) -> &Tr {
        &self.trajectory
    }

    /// `q`, `v`, `a` at the new time from the unknowns.
    fn kinematics(&self, z: &DVector<f64>) -> [SVector<f64, N>; 3] {
        let (p, dt) = (Self::P, self.formula.dt);
        let mut q = SVector::<f64, N>::zeros();
        let mut v = SVector::<f64, N>::zeros();
        let mut a = SVector::<f64, N>::zeros();
        for i in 0..p {
            q[i] = z[i];
            let (v_i, a_dt2) = self.formula.kinematics(i, z[i]); // eq. (22a)
            v[i] = v_i;
            a[i] = a_dt2 / (dt * dt);
        }
        for k in 0..A {
            q[p + k] = self.target[0][k];
            v[p + k] = self.target[1][k];
            a[p + k] = self.target[2][k];
        }
        [q, v, a]
    }
}

/// The load target `gamma, gamma', gamma''` of the step to `t`.
pub(crate) fn servo_target<const A: usize>(trajectory: &impl Trajectory<A>, t: f64) -> ServoTarget<A> {
    let mut target = [SVector::zeros(); 3];
    trajectory.derivatives_into(t, &mut target);
    target
}

/// The unknowns `[p; dt^2 u; dt^2 lambda]` of `state` at step `dt`, into `z`.
fn write_unknowns<const N: usize, const M: usize, const A: usize>(
    state: &State<N, M, A>,
    dt: f64,
    z: &mut DVector<f64>,
) {
    let (p, dt2) = (N - A, dt * dt);
    z.rows_mut(0, p).copy_from(&state.q.rows(0, p));
    z.rows_mut(p, A).copy_from(&(state.u * dt2));
    z.rows_mut(N, M).copy_from(&(state.lambda * dt2));
}

/// Refuse a NaN or infinite load target.
pub(crate) fn check_target<const A: usize>(
    target: &ServoTarget<A>,
    t: f64,
    load: &[&'static str],
) -> Result<(), Error> {
    if !target.iter().all(|x| x.iter().all(|v| v.is_finite())) {
        return Err(Error::NonFinite {
            quantity: "load target gamma(t)",
            t,
        });
    }
    check_path_position(&target[0], t, load)
}

/// Refuse a load position beyond 1e100 (`load`: the load coordinates'
/// names): the constraints' squares of lengths would overflow, and the
/// step would end as a non-finite Newton iterate.
pub(crate) fn check_path_position<const A: usize>(
    position: &SVector<f64, A>,
    t: f64,
    load: &[&'static str],
) -> Result<(), Error> {
    match position.iter().position(|x| x.abs() > 1e100) {
        Some(k) => Err(Error::PathOutOfRange {
            coordinate: load.get(k).copied().unwrap_or("load coordinate"),
            value: position[k],
            t,
        }),
        None => Ok(()),
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize> NonlinearSystem for Redundant<H, Tr, N, M, A>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized>,
    Tr: Trajectory<A>,
{
    fn dim(&self) -> usize {
        N + M
    }

    fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) {
        let p = Self::P;
        let kinematics = self.kinematics(z);
        let u_scaled = SVector::<f64, A>::from_fn(|k, _| z[p + k]);
        let lambda_scaled = SVector::<f64, M>::from_fn(|i, _| z[N + i]);
        let model = &*self.model;
        // residual: dynamic rows (22b, 22c) scaled by dt^2, then (22d); the
        // iteration matrix column by column of z: p, then dt^2 u (-B^T over
        // 0), dt^2 lambda
        let rows = dynamic_rows(
            model,
            &self.mass,
            &self.formula,
            &kinematics,
            &u_scaled,
            &lambda_scaled,
            p,
            r,
            jac,
        );
        for k in 0..A {
            for i in 0..N {
                jac[(i, p + k)] = -rows.input_matrix[(i, k)];
            }
        }
        // dynamic rows also by their largest term (the load row of x nearly
        // vanishes when the load hangs straight below the pulley)
        self.floors = SVector::from_fn(|i, _| rows.inertia[i].abs().max(rows.applied[i].abs()));
    }

    fn normalised_residual(&self, z: &DVector<f64>, r: &DVector<f64>, jac: &DMatrix<f64>) -> f64 {
        normalised_residual(r, jac, z, |i| if i < N { self.floors[i] } else { 0.0 })
    }

    fn blocks(&self) -> &[Range<usize>] {
        &self.blocks
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize> Problem<N, M, A, N> for Redundant<H, Tr, N, M, A>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized>,
    Tr: Trajectory<A>,
{
    type Model = H::Target;
    type Drive = ServoTarget<A>;

    /// A massless pulley on a nearly slack rope is placed by forces of
    /// round-off size, and the scheme differentiates its position twice.
    const HOLDS_NEARLY_SLACK: bool = true;

    fn model(&self) -> &H::Target {
        &self.model
    }

    /// The scheme's extrapolation for `p`, the last step's scaled `u` and `lambda`.
    /// 4: the minimal extension of eqs. (22, 24) reduces servo constraints of
    /// index 5, whose inputs need the path's 4th derivative.
    fn path_order_covered(&self) -> Option<usize> {
        Some(4)
    }

    fn predictor(&self) -> Predictor {
        Predictor::Scheme { leading: Self::P }
    }

    fn drive(&self, t: f64) -> ServoTarget<A> {
        servo_target(&self.trajectory, t)
    }

    fn check_drive(&self, target: &ServoTarget<A>, t: f64) -> Result<(), Error> {
        check_target(target, t, &H::Target::INFO.coordinates[N - A..])
    }

    fn start(&mut self, start: &State<N, M, A>, dt: f64, z: &mut DVector<f64>) -> Result<Start<N>, Error> {
        write_unknowns(start, dt, z);
        Ok(Start {
            y0: start.q,
            v0: start.v,
            at_rest: init::at_rest(&self.trajectory, start),
        })
    }

    fn prepare(&mut self, target: &ServoTarget<A>, formula: StepFormula<N>) {
        self.target = *target;
        self.formula = formula;
    }

    fn accept(&mut self, t: f64, z: &DVector<f64>) -> Result<Accepted<N, M, A, N>, Error> {
        let (p, dt2) = (Self::P, self.formula.dt * self.formula.dt);
        let [q, v, _] = self.kinematics(z);
        let u = SVector::from_fn(|k, _| z[p + k] / dt2);
        let lambda = SVector::from_fn(|i, _| z[N + i] / dt2);
        Ok(Accepted {
            state: State { t, q, v, u, lambda },
            y: q,
            v,
        })
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize> Follow<N, M, A, N> for Redundant<H, Tr, N, M, A>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized>,
    Tr: Trajectory<A>,
{
    /// Always: a consistent state is all its history needs.
    fn can_take_over(&self, _state: &State<N, M, A>) -> bool {
        true
    }

    /// `q` and `q'` of the state, and its unknowns `[p; dt^2 u; dt^2 lambda]`.
    fn follow(
        &mut self,
        state: &State<N, M, A>,
        _last: &SVector<f64, N>,
        formula: StepFormula<N>,
        z: &mut DVector<f64>,
    ) -> Result<(SVector<f64, N>, SVector<f64, N>), Error> {
        write_unknowns(state, formula.dt, z);
        Ok((state.q, state.v))
    }
}

/// Eqs. (22a-d) one step at a time: the [`Stepper`] of the [`Redundant`]
/// problem on the scheme `S`, made by
/// `Stepper::new(Redundant::new(&crane, &path), &start, &options)`; after
/// construction a step does not allocate.
pub type RedundantStepper<H, Tr, const N: usize, const M: usize, const A: usize, S = Scheme> =
    Stepper<Redundant<H, Tr, N, M, A>, S, N, M, A, N>;

/// Integrate eqs. (22a-d) from `start` to `options.tf()` with its scheme.
///
/// Storage for all steps is reserved up front; the step loop does not allocate.
/// The result is what the causal inverse computes: for a crane that is not
/// flat it can grow without bound, which
/// [`internal::diagnose`](crate::internal::diagnose) tells.
pub fn simulate<Mdl, Tr, S, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    options: &Options<S>,
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
    S: Method,
{
    simulate_with_progress(model, trajectory, start, options, &mut |_, _| {})
}

/// [`simulate`], calling `progress(step, steps)` after every step.
pub fn simulate_with_progress<Mdl, Tr, S, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    options: &Options<S>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
    S: Method,
{
    solve(Redundant::new(model, trajectory), start, options, progress)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{Gantry, central_difference_error, random_history, uniform};
    use crate::trajectory::FromFn;

    /// The redundant iteration matrix (eqs. 22b-d in `[p; dt^2 u; dt^2
    /// lambda]`) is the Jacobian of the residual: against central
    /// differences at random points, histories and load targets, for every
    /// scheme and three steps, entry by entry to 1e-6 of the largest entry
    /// (central differences of a smooth residual: ~1e-9). The gantry's
    /// friction and rope-length-dependent winch make every term count.
    #[test]
    fn iteration_matrix_matches_central_differences() {
        let mut rnd = uniform(3);
        let path = FromFn(|_t: f64, _k: usize| SVector::<f64, 2>::zeros());
        for scheme in Scheme::ALL {
            for dt in [0.1, 0.01, 0.001] {
                for _ in 0..10 {
                    let (history, start) = random_history(scheme, &mut rnd);
                    let mut problem = Redundant::new(&Gantry, &path);
                    problem.start(&start, dt, &mut DVector::zeros(5)).unwrap();
                    let target = [0.0, 1.0, 2.0].map(|scale| SVector::from_fn(|_, _| scale + rnd()));
                    problem.prepare(&target, history.formula(dt));
                    // p = [s, L] of the crane's size, dt^2 u, dt^2 lambda
                    let z = DVector::from_fn(5, |i, _| match i {
                        0 | 1 => 3.0 + rnd(),
                        2 | 3 => dt * dt * 1000.0 * rnd(),
                        _ => dt * dt * 100.0 * rnd(),
                    });
                    let (worst, largest) = central_difference_error(&mut problem, &z);
                    assert!(
                        worst <= 1e-6 * largest,
                        "{scheme}, dt = {dt}: worst {worst:e} of {largest:e}"
                    );
                }
            }
        }
    }
}
