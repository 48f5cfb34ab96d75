//! The servo problem in redundant coordinates, paper eqs. (22a-d), on any
//! [`Scheme`].
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
//! exactly (22b) and (22c). In the iteration matrix the scheme's `c`
//! replaces 1: `d(dt^2 a)/dp = c^2`, `d(dt^2 v)/dp = c dt`.

use std::ops::Range;

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::driver::{
    Options, ServoTarget, StepReport, Stepper, check_parameters, check_step_size, check_step_time, check_target,
    record, servo_target, step_count, step_error,
};
use crate::error::Error;
use crate::init;
use crate::model::CraneModel;
use crate::newton::{Newton, NewtonOptions, NonlinearSystem, normalised_residual};
use crate::scheme::{History, Scheme, StepFormula};
use crate::solution::{Solution, State};
use crate::trajectory::Trajectory;

/// The residual of eqs. (22b-d) at one step, as a [`NonlinearSystem`] in the
/// unknowns `z = [p; dt^2 u; dt^2 lambda]`.
#[derive(Clone)]
struct StepEquations<'m, Mdl, const N: usize, const M: usize, const A: usize> {
    model: &'m Mdl,
    mass: SMatrix<f64, N, N>,
    dt: f64,
    /// `gamma, gamma', gamma''` at `t_{n+1}`.
    target: ServoTarget<A>,
    /// The scheme's affine maps `p -> v, a` for this step.
    formula: StepFormula<N>,
    blocks: [Range<usize>; 3],
}

impl<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> StepEquations<'_, Mdl, N, M, A> {
    const P: usize = N - A;

    /// `q`, `v`, `a` at the new time from the unknowns.
    fn kinematics(&self, z: &DVector<f64>) -> [SVector<f64, N>; 3] {
        let (p, dt) = (Self::P, self.dt);
        let mut q = SVector::<f64, N>::zeros();
        let mut v = SVector::<f64, N>::zeros();
        let mut a = SVector::<f64, N>::zeros();
        for i in 0..p {
            q[i] = z[i];
            let (v_i, a_dt2) = self.formula.kinematics(i, z[i], dt); // eq. (22a)
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

impl<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> NonlinearSystem
    for StepEquations<'_, Mdl, N, M, A>
{
    fn dim(&self) -> usize {
        N + M
    }

    fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) -> f64 {
        let (p, dt) = (Self::P, self.dt);
        let dt2 = dt * dt;
        let [q, v, a] = self.kinematics(z);
        let u_scaled = SVector::<f64, A>::from_fn(|k, _| z[p + k]);
        let lambda_scaled = SVector::<f64, M>::from_fn(|i, _| z[N + i]);

        let model = self.model;
        let f = model.forces(&q, &v);
        let (df_dq, df_dv) = model.force_jacobians(&q, &v);
        let bt = model.input_matrix(&q);
        let dbu_dq = model.input_jacobian(&q, &u_scaled);
        let jac_g = model.constraint_jacobian(&q);
        let dgl_dq = model.constraint_hessian(&q, &lambda_scaled);
        let g = model.constraints(&q);

        // residual: dynamic rows (22b, 22c) scaled by dt^2, then (22d)
        let inertia = self.mass * a * dt2;
        let applied = f * dt2;
        let inputs = bt * u_scaled;
        let constraint_forces = jac_g.tr_mul(&lambda_scaled);
        let dynamic = inertia - applied - inputs + constraint_forces;
        r.rows_mut(0, N).copy_from(&dynamic);
        r.rows_mut(N, M).copy_from(&g);
        // iteration matrix, column by column of z
        jac.fill(0.0);
        let c_dt = self.formula.rate * dt; // the scheme's c
        let (da, dv) = (c_dt * c_dt, c_dt * dt);
        for j in 0..p {
            // d a_j/d p_j = c^2/dt^2, d v_j/d p_j = c/dt (scaled by dt^2)
            for i in 0..N {
                jac[(i, j)] =
                    da * self.mass[(i, j)] - dt2 * df_dq[(i, j)] - dv * df_dv[(i, j)] - dbu_dq[(i, j)] + dgl_dq[(i, j)];
            }
            for i in 0..M {
                jac[(N + i, j)] = jac_g[(i, j)];
            }
        }
        for k in 0..A {
            for i in 0..N {
                jac[(i, p + k)] = -bt[(i, k)];
            }
        }
        for l in 0..M {
            for i in 0..N {
                jac[(i, N + l)] = jac_g[(l, i)];
            }
        }
        // dynamic rows also by their largest term (the load row of x nearly
        // vanishes when the load hangs straight below the pulley)
        normalised_residual(r, jac, z, |i| {
            if i < N {
                inertia[i].abs().max(applied[i].abs())
            } else {
                0.0
            }
        })
    }

    fn blocks(&self) -> &[Range<usize>] {
        &self.blocks
    }
}

/// Eqs. (22a-d) on a [`Scheme`], one step at a time.
///
/// Built from a consistent start (see [`crate::init`]); after construction
/// [`step`](Self::step) does not allocate. A clone continues independently
/// from the same state and history.
#[derive(Clone)]
pub struct RedundantStepper<'m, Mdl, Tr, const N: usize, const M: usize, const A: usize> {
    equations: StepEquations<'m, Mdl, N, M, A>,
    trajectory: Tr,
    newton: Newton,
    z: DVector<f64>,
    scheme: Scheme,
    /// Past `q` and `v` (only the `p` rows are used).
    history: History<N>,
    state: State<N, M, A>,
    t0: f64,
    steps: usize,
}

impl<'m, Mdl, Tr, const N: usize, const M: usize, const A: usize> RedundantStepper<'m, Mdl, Tr, N, M, A>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
{
    /// A backward-Euler stepper from `start` with time step `dt`.
    pub fn new(
        model: &'m Mdl,
        trajectory: Tr,
        start: &State<N, M, A>,
        dt: f64,
        newton: NewtonOptions,
    ) -> Result<Self, Error> {
        Self::with_scheme(model, trajectory, start, dt, Scheme::BackwardEuler, newton)
    }

    /// A stepper on `scheme` from `start` with time step `dt`; the scheme's
    /// history before the start comes from [`init::history`].
    pub fn with_scheme(
        model: &'m Mdl,
        trajectory: Tr,
        start: &State<N, M, A>,
        dt: f64,
        scheme: Scheme,
        newton: NewtonOptions,
    ) -> Result<Self, Error> {
        check_step_size(dt)?;
        check_parameters(model)?;
        let history = init::history(&trajectory, start, start.q, start.v);
        let p = N - A;
        let dt2 = dt * dt;
        let mut z = DVector::zeros(N + M);
        z.rows_mut(0, p).copy_from(&start.q.rows(0, p));
        z.rows_mut(p, A).copy_from(&(start.u * dt2));
        z.rows_mut(N, M).copy_from(&(start.lambda * dt2));
        let equations = StepEquations {
            model,
            mass: model.mass_matrix(),
            dt,
            target: [SVector::zeros(); 3],
            formula: history.formula(scheme, dt),
            blocks: [0..p, p..N, N..N + M],
        };
        Ok(Self {
            equations,
            trajectory,
            newton: Newton::new(N + M, newton),
            z,
            scheme,
            history,
            state: *start,
            t0: start.t,
            steps: 0,
        })
    }

    /// The state after the last step (the start before the first).
    pub fn state(&self) -> &State<N, M, A> {
        &self.state
    }

    /// The time step.
    pub fn dt(&self) -> f64 {
        self.equations.dt
    }

    /// The scheme.
    pub fn scheme(&self) -> Scheme {
        self.scheme
    }

    /// Advance one step along the stepper's trajectory.
    pub fn step(&mut self) -> Result<StepReport, Error> {
        let t = self.t0 + (self.steps + 1) as f64 * self.equations.dt;
        self.step_to(t, &servo_target(&self.trajectory, t))
    }

    /// Advance one step to time `t`, which must be `t_n + dt`
    /// ([`Error::WrongStepTime`] otherwise), with the load target
    /// `gamma, gamma', gamma''` at `t`.
    pub fn step_to(&mut self, t: f64, target: &ServoTarget<A>) -> Result<StepReport, Error> {
        check_step_time(t, self.state.t, self.equations.dt)?;
        check_target(target, t)?;
        let (p, dt) = (N - A, self.equations.dt);
        let dt2 = dt * dt;
        let eq = &mut self.equations;
        eq.target = *target;
        eq.formula = self.history.formula(self.scheme, dt);
        // predictor: the scheme's extrapolation for p, previous scaled u and lambda
        let predicted = self.history.predict(self.scheme, dt);
        self.z.rows_mut(0, p).copy_from(&predicted.rows(0, p));
        let converged = self
            .newton
            .solve(eq, &mut self.z)
            .map_err(|failure| step_error(failure, t))?;
        let [q, v, _] = eq.kinematics(&self.z);
        self.state = State {
            t,
            q,
            v,
            u: SVector::from_fn(|k, _| self.z[p + k] / dt2),
            lambda: SVector::from_fn(|i, _| self.z[N + i] / dt2),
        };
        self.history.push(q, v);
        self.steps += 1;
        Ok(StepReport {
            iterations: converged.iterations,
            min_norm_steps: converged.min_norm_steps,
        })
    }
}

/// Integrate eqs. (22a-d) from `start` to `options.tf` with `options.scheme`.
///
/// Storage for all steps is reserved up front; the step loop does not allocate.
/// The result is what the causal inverse computes: for a crane that is not
/// flat it can grow without bound, which
/// [`internal::diagnose`](crate::internal::diagnose) tells.
pub fn simulate<Mdl, Tr, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    options: &Options,
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
{
    simulate_with_progress(model, trajectory, start, options, |_, _| {})
}

/// [`simulate`], calling `progress(step, steps)` after every step.
pub fn simulate_with_progress<Mdl, Tr, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    options: &Options,
    mut progress: impl FnMut(usize, usize),
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
{
    let steps = step_count(start.t, options.tf, options.dt)?;
    let mut stepper =
        RedundantStepper::with_scheme(model, trajectory, start, options.dt, options.scheme, options.newton)?;
    record(model, start, &mut stepper, steps, options, &mut progress)
}

impl<Mdl, Tr, const N: usize, const M: usize, const A: usize> Stepper<N, M, A>
    for RedundantStepper<'_, Mdl, Tr, N, M, A>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
{
    fn step(&mut self) -> Result<StepReport, Error> {
        RedundantStepper::step(self)
    }
    fn state(&self) -> &State<N, M, A> {
        RedundantStepper::state(self)
    }
}
