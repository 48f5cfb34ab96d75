//! Backward Euler for the minimally extended index-3 DAEs in redundant
//! coordinates, paper eqs. (22a-d).
//!
//! With the servo constraints `x = gamma(t)` substituted, the unknowns of a
//! step are `p_{n+1}`, `u_{n+1}` and `lambda_{n+1}`; `v_{n+1} = (p_{n+1} -
//! p_n)/dt` (eq. 22a) is eliminated. The dynamic rows (22b, 22c) are
//! multiplied by `dt^2` and solved for `dt^2 u` and `dt^2 lambda`, which keeps
//! the iteration matrix's condition number independent of `dt` (DESIGN.md §3:
//! about 8e3 on `navy-planar` instead of 2.6e8 at dt = 0.01). In general form,
//! valid for any constant mass matrix,
//! ```text
//! r_dyn = dt^2 (M a - f(q, v)) - B^T(q) (dt^2 u) + G^T(q) (dt^2 lambda) = 0   (22b, 22c)
//! r_g   = g(q) = 0                                                             (22d)
//! q = [p_{n+1}; gamma],  v = [(p_{n+1} - p_n)/dt; gamma'],
//! a = [(p_{n+1} - p_n - dt v_n)/dt^2; gamma'']
//! ```
//! which for `M = diag(M1, M2)`, `B^T = [B1^T; 0]`, `f = [f1(p, p'); f2(x, x')]`
//! is exactly (22b) and (22c).

use std::ops::Range;

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::error::Error;
use crate::model::CraneModel;
use crate::newton::{Newton, NewtonFailure, NewtonOptions, NonlinearSystem, normalised_residual};
use crate::solution::{Solution, State};
use crate::trajectory::Trajectory;

/// Settings of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Time step `dt`.
    pub dt: f64,
    /// End time `tf`; the run starts at the start state's time.
    pub tf: f64,
    /// Newton tolerances.
    pub newton: NewtonOptions,
}

impl Options {
    /// `dt` and `tf` with default Newton tolerances.
    pub fn new(dt: f64, tf: f64) -> Self {
        Self { dt, tf, newton: NewtonOptions::default() }
    }
}

/// What one step reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StepReport {
    /// Newton iterations.
    pub iterations: usize,
    /// Of those, minimum-norm steps on a singular iteration matrix.
    pub min_norm_steps: usize,
}

/// The load target of one step: `gamma, gamma', gamma''` at the new time.
pub type ServoTarget<const A: usize> = [SVector<f64, A>; 3];

/// The residual of eqs. (22b-d) at one step, as a [`NonlinearSystem`] in the
/// unknowns `z = [p; dt^2 u; dt^2 lambda]`.
struct StepEquations<'m, Mdl, const N: usize, const M: usize, const A: usize> {
    model: &'m Mdl,
    mass: SMatrix<f64, N, N>,
    dt: f64,
    /// `gamma, gamma', gamma''` at `t_{n+1}`.
    target: ServoTarget<A>,
    /// `q_n` and `v_n`.
    q_prev: SVector<f64, N>,
    v_prev: SVector<f64, N>,
    blocks: [Range<usize>; 3],
}

impl<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>
    StepEquations<'_, Mdl, N, M, A>
{
    const P: usize = N - A;

    /// `q`, `v`, `a` at the new time from the unknowns.
    fn kinematics(&self, z: &DVector<f64>) -> [SVector<f64, N>; 3] {
        let (p, dt) = (Self::P, self.dt);
        let mut q = SVector::<f64, N>::zeros();
        let mut v = SVector::<f64, N>::zeros();
        let mut a = SVector::<f64, N>::zeros();
        for i in 0..p {
            q[i] = z[i];
            v[i] = (z[i] - self.q_prev[i]) / dt; // eq. (22a)
            a[i] = (z[i] - self.q_prev[i] - dt * self.v_prev[i]) / (dt * dt);
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
        for j in 0..p {
            // d a_j/d p_j = 1/dt^2, d v_j/d p_j = 1/dt (scaled by dt^2)
            for i in 0..N {
                jac[(i, j)] = self.mass[(i, j)] - dt2 * df_dq[(i, j)] - dt * df_dv[(i, j)]
                    - dbu_dq[(i, j)]
                    + dgl_dq[(i, j)];
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
            if i < N { inertia[i].abs().max(applied[i].abs()) } else { 0.0 }
        })
    }

    fn blocks(&self) -> &[Range<usize>] {
        &self.blocks
    }
}

/// Backward Euler on eqs. (22a-d), one step at a time.
///
/// Built from a consistent start (see [`crate::init`]); after construction
/// [`step`](Self::step) does not allocate.
pub struct RedundantStepper<'m, Mdl, Tr, const N: usize, const M: usize, const A: usize> {
    equations: StepEquations<'m, Mdl, N, M, A>,
    trajectory: Tr,
    newton: Newton,
    z: DVector<f64>,
    state: State<N, M, A>,
    t0: f64,
    steps: usize,
}

impl<'m, Mdl, Tr, const N: usize, const M: usize, const A: usize> RedundantStepper<'m, Mdl, Tr, N, M, A>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
{
    /// A stepper from `start` with time step `dt`.
    pub fn new(
        model: &'m Mdl,
        trajectory: Tr,
        start: &State<N, M, A>,
        dt: f64,
        newton: NewtonOptions,
    ) -> Result<Self, Error> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Error::InvalidTimeStep { dt });
        }
        check_parameters(model)?;
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
            q_prev: start.q,
            v_prev: start.v,
            blocks: [0..p, p..N, N..N + M],
        };
        Ok(Self {
            equations,
            trajectory,
            newton: Newton::new(N + M, newton),
            z,
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

    /// Advance one step along the stepper's trajectory.
    pub fn step(&mut self) -> Result<StepReport, Error> {
        let t = self.t0 + (self.steps + 1) as f64 * self.equations.dt;
        self.step_to(t, &servo_target(&self.trajectory, t))
    }

    /// Advance one step to time `t` (which must be `t_n + dt`) with the load
    /// target `gamma, gamma', gamma''` at `t`.
    pub fn step_to(&mut self, t: f64, target: &ServoTarget<A>) -> Result<StepReport, Error> {
        check_target(target, t)?;
        let (p, dt) = (N - A, self.equations.dt);
        let dt2 = dt * dt;
        let eq = &mut self.equations;
        eq.target = *target;
        eq.q_prev = self.state.q;
        eq.v_prev = self.state.v;
        // predictor: explicit Euler for p, previous scaled u and lambda
        for i in 0..p {
            self.z[i] = self.state.q[i] + dt * self.state.v[i];
        }
        let converged = self.newton.solve(eq, &mut self.z).map_err(|failure| step_error(failure, t))?;
        let [q, v, _] = eq.kinematics(&self.z);
        self.state = State {
            t,
            q,
            v,
            u: SVector::from_fn(|k, _| self.z[p + k] / dt2),
            lambda: SVector::from_fn(|i, _| self.z[N + i] / dt2),
        };
        self.steps += 1;
        Ok(StepReport { iterations: converged.iterations, min_norm_steps: converged.min_norm_steps })
    }
}

/// The load target `gamma, gamma', gamma''` of the step to `t`.
pub(crate) fn servo_target<const A: usize>(trajectory: &impl Trajectory<A>, t: f64) -> ServoTarget<A> {
    [0, 1, 2].map(|k| trajectory.derivative(t, k))
}

/// Refuse a NaN or infinite load target.
pub(crate) fn check_target<const A: usize>(target: &ServoTarget<A>, t: f64) -> Result<(), Error> {
    if target.iter().all(|x| x.iter().all(|v| v.is_finite())) {
        Ok(())
    } else {
        Err(Error::NonFinite { quantity: "load target gamma(t)", t })
    }
}

/// The runtime error for a failed Newton solve of the step to `t`.
pub(crate) fn step_error(failure: NewtonFailure, t: f64) -> Error {
    match failure {
        NewtonFailure::NotConverged { iterations, residual } => Error::NewtonNotConverged { t, iterations, residual },
        NewtonFailure::Singular { pivot_ratio } => Error::SingularIterationMatrix { t, pivot_ratio },
        NewtonFailure::NonFinite => Error::NonFinite { quantity: "Newton iterate", t },
    }
}

/// Refuse NaN or infinite parameters before they turn into NaN results.
pub(crate) fn check_parameters<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
) -> Result<(), Error> {
    for (name, value) in Mdl::INFO.parameters.iter().zip(model.parameter_values()) {
        if !value.is_finite() {
            return Err(Error::NonFiniteParameter { name, value });
        }
    }
    Ok(())
}

/// Number of steps of size `dt` from `t0` to `tf`, refusing spans that are
/// not a whole number of steps (to 1e-9 relative).
pub(crate) fn step_count(t0: f64, tf: f64, dt: f64) -> Result<usize, Error> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(Error::InvalidTimeStep { dt });
    }
    if !(tf.is_finite() && t0.is_finite() && tf > t0) {
        return Err(Error::InvalidTimeSpan { t0, tf });
    }
    let span = tf - t0;
    let steps = (span / dt).round();
    if (steps * dt - span).abs() > 1e-9 * span || steps < 1.0 {
        return Err(Error::StepsDoNotFit { span, dt });
    }
    Ok(steps as usize)
}

/// Rope tensions `N = lambda * L` of a state, appended to `out`.
fn push_tensions<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    state: &State<N, M, A>,
    lengths: &mut [f64],
    out: &mut Vec<f64>,
) {
    model.rope_lengths(&state.q, lengths);
    for (rope, length) in Mdl::INFO.ropes.iter().zip(lengths.iter()) {
        out.push(state.lambda[rope.constraint] * length);
    }
}

/// Integrate eqs. (22a-d) from `start` to `options.tf`.
///
/// Storage for all steps is reserved up front; the step loop does not allocate.
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
    let mut stepper = RedundantStepper::new(model, trajectory, start, options.dt, options.newton)?;
    run_steps(model, start, &mut stepper, steps, options.dt, &mut progress)
}

/// A one-step integrator of the inverse dynamics (backward Euler in
/// redundant or minimal coordinates).
pub trait Stepper<const N: usize, const M: usize, const A: usize> {
    /// Advance one step along the trajectory.
    fn step(&mut self) -> Result<StepReport, Error>;
    /// The state after the last step (the start before the first).
    fn state(&self) -> &State<N, M, A>;
}

impl<Mdl, Tr, const N: usize, const M: usize, const A: usize> Stepper<N, M, A> for RedundantStepper<'_, Mdl, Tr, N, M, A>
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

/// Take `steps` steps and collect the solution. Storage for all steps is
/// reserved up front; the loop does not allocate.
pub(crate) fn run_steps<Mdl, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    start: &State<N, M, A>,
    stepper: &mut impl Stepper<N, M, A>,
    steps: usize,
    dt: f64,
    progress: &mut impl FnMut(usize, usize),
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
{
    let ropes = Mdl::INFO.ropes.len();
    let mut states = Vec::with_capacity(steps + 1);
    let mut newton_iterations = Vec::with_capacity(steps + 1);
    let mut tensions = Vec::with_capacity((steps + 1) * ropes);
    let mut lengths = vec![0.0; ropes];
    let mut min_norm_steps = 0;
    states.push(*start);
    newton_iterations.push(0);
    push_tensions(model, start, &mut lengths, &mut tensions);
    for step in 1..=steps {
        let report = stepper.step()?;
        let state = stepper.state();
        states.push(*state);
        newton_iterations.push(report.iterations);
        min_norm_steps += report.min_norm_steps;
        push_tensions(model, state, &mut lengths, &mut tensions);
        progress(step, steps);
    }
    Ok(Solution { info: Mdl::INFO, dt, states, newton_iterations, tensions, min_norm_steps })
}
