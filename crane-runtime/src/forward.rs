//! The forward problem on any [`Scheme`]: given the inputs `u(t)`, integrate
//! the crane's index-3 equations of motion
//! ```text
//! M q'' = f(q, q') + B^T(q) u - G^T(q) lambda,   g(q) = 0
//! ```
//! for `q`, `q'` and `lambda` (paper eq. 1a-1b without the servo
//! constraints). The scheme eliminates `v` and `a` of all `n` coordinates as
//! affine functions of `q_{n+1}` exactly as in the servo problems; the
//! dynamic rows are multiplied by `dt^2` and solved for `dt^2 lambda`:
//! ```text
//! r_dyn = M (dt^2 a) - dt^2 f(q, v) - dt^2 B^T(q) u + G^T(q) (dt^2 lambda) = 0
//! r_g   = g(q) = 0,         unknowns z = [q; dt^2 lambda]
//! ```
//! `M` may be singular (a massless pulley): the full iteration matrix
//! `[c^2 M + ...; G]` is regular where the ropes fix the pulley. This is the
//! third problem on the seam of [`crate::scheme`]; nothing of it is specific
//! to a scheme.

use std::ops::Range;

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::driver::{Options, StepReport, Stepper, check_parameters, record, step_count, step_error};
use crate::error::Error;
use crate::model::CraneModel;
use crate::newton::{Newton, NewtonOptions, NonlinearSystem, normalised_residual};
use crate::scheme::{History, Scheme, StepFormula};
use crate::solution::{Solution, State};

/// Inputs `u(t)` for the forward problem: a closure `|t| -> SVector`.
pub trait Inputs<const A: usize> {
    /// The inputs at `t`.
    fn at(&self, t: f64) -> SVector<f64, A>;
}

impl<const A: usize, F: Fn(f64) -> SVector<f64, A>> Inputs<A> for F {
    fn at(&self, t: f64) -> SVector<f64, A> {
        self(t)
    }
}

/// The residual of one forward step in `z = [q; dt^2 lambda]`.
#[derive(Clone)]
struct ForwardEquations<'m, Mdl, const N: usize, const M: usize, const A: usize> {
    model: &'m Mdl,
    mass: SMatrix<f64, N, N>,
    dt: f64,
    /// `u` at the new time.
    input: SVector<f64, A>,
    formula: StepFormula<N>,
    blocks: [Range<usize>; 2],
}

impl<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> ForwardEquations<'_, Mdl, N, M, A> {
    /// `q`, `v` and `dt^2 a` from the unknowns.
    fn kinematics(&self, z: &DVector<f64>) -> [SVector<f64, N>; 3] {
        let q = SVector::<f64, N>::from_fn(|i, _| z[i]);
        let mut v = SVector::<f64, N>::zeros();
        let mut a_dt2 = SVector::<f64, N>::zeros();
        for i in 0..N {
            (v[i], a_dt2[i]) = self.formula.kinematics(i, z[i], self.dt);
        }
        [q, v, a_dt2]
    }
}

impl<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize> NonlinearSystem
    for ForwardEquations<'_, Mdl, N, M, A>
{
    fn dim(&self) -> usize {
        N + M
    }

    fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) -> f64 {
        let dt = self.dt;
        let dt2 = dt * dt;
        let [q, v, a_dt2] = self.kinematics(z);
        let lambda_scaled = SVector::<f64, M>::from_fn(|i, _| z[N + i]);
        let model = self.model;
        let u_scaled = self.input * dt2;
        let (df_dq, df_dv) = model.force_jacobians(&q, &v);
        let jac_g = model.constraint_jacobian(&q);
        let inertia = self.mass * a_dt2;
        let applied = model.forces(&q, &v) * dt2 + model.input_matrix(&q) * u_scaled;
        let dynamic = inertia - applied + jac_g.tr_mul(&lambda_scaled);
        r.rows_mut(0, N).copy_from(&dynamic);
        r.rows_mut(N, M).copy_from(&model.constraints(&q));
        let c_dt = self.formula.rate * dt;
        let (da, dv) = (c_dt * c_dt, c_dt * dt);
        let dbu_dq = model.input_jacobian(&q, &u_scaled);
        let dgl_dq = model.constraint_hessian(&q, &lambda_scaled);
        for j in 0..N {
            for i in 0..N {
                jac[(i, j)] = da * self.mass[(i, j)] - dt2 * df_dq[(i, j)] - dv * df_dv[(i, j)] - dbu_dq[(i, j)]
                    + dgl_dq[(i, j)];
            }
            for i in 0..M {
                jac[(N + i, j)] = jac_g[(i, j)];
            }
        }
        for l in 0..M {
            for i in 0..N {
                jac[(i, N + l)] = jac_g[(l, i)];
            }
            for i in 0..M {
                jac[(N + i, N + l)] = 0.0;
            }
        }
        normalised_residual(r, jac, z, |i| if i < N { inertia[i].abs().max(applied[i].abs()) } else { 0.0 })
    }

    fn blocks(&self) -> &[Range<usize>] {
        &self.blocks
    }
}

/// The forward problem on a [`Scheme`], one step at a time; after
/// construction [`step`](Self::step) does not allocate.
pub struct ForwardStepper<'m, Mdl, In, const N: usize, const M: usize, const A: usize> {
    equations: ForwardEquations<'m, Mdl, N, M, A>,
    inputs: In,
    newton: Newton,
    z: DVector<f64>,
    scheme: Scheme,
    history: History<N>,
    state: State<N, M, A>,
    t0: f64,
    steps: usize,
}

impl<'m, Mdl, In, const N: usize, const M: usize, const A: usize> ForwardStepper<'m, Mdl, In, N, M, A>
where
    Mdl: CraneModel<N, M, A>,
    In: Inputs<A>,
{
    /// A stepper from the consistent `start` (its `q`, `v`, `lambda`). The
    /// history before the start: at rest (`v = 0`) the crane rested before
    /// `t0` (exact); otherwise the order ramps up (BDF-j on step j).
    pub fn new(
        model: &'m Mdl,
        inputs: In,
        start: &State<N, M, A>,
        dt: f64,
        scheme: Scheme,
        newton: NewtonOptions,
    ) -> Result<Self, Error> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Error::InvalidTimeStep { dt });
        }
        check_parameters(model)?;
        let history = if start.v.amax() == 0.0 { History::at_rest(start.q) } else { History::start(start.q, start.v) };
        let mut z = DVector::zeros(N + M);
        z.rows_mut(0, N).copy_from(&start.q);
        z.rows_mut(N, M).copy_from(&(start.lambda * (dt * dt)));
        let equations = ForwardEquations {
            model,
            mass: model.mass_matrix(),
            dt,
            input: start.u,
            formula: history.formula(scheme, dt),
            blocks: [0..N, N..N + M],
        };
        Ok(Self {
            equations,
            inputs,
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

    /// Advance one step with the inputs at the new time.
    pub fn step(&mut self) -> Result<StepReport, Error> {
        let dt = self.equations.dt;
        let t = self.t0 + (self.steps + 1) as f64 * dt;
        let input = self.inputs.at(t);
        if !input.iter().all(|x| x.is_finite()) {
            return Err(Error::NonFinite { quantity: "input u(t)", t });
        }
        let eq = &mut self.equations;
        eq.input = input;
        eq.formula = self.history.formula(self.scheme, dt);
        let predicted = self.history.predict(self.scheme, dt);
        self.z.rows_mut(0, N).copy_from(&predicted);
        let converged = self.newton.solve(eq, &mut self.z).map_err(|failure| step_error(failure, t))?;
        let [q, v, _] = eq.kinematics(&self.z);
        self.state = State { t, q, v, u: input, lambda: SVector::from_fn(|i, _| self.z[N + i] / (dt * dt)) };
        self.history.push(q, v);
        self.steps += 1;
        Ok(StepReport { iterations: converged.iterations, min_norm_steps: converged.min_norm_steps })
    }
}

impl<Mdl, In, const N: usize, const M: usize, const A: usize> Stepper<N, M, A> for ForwardStepper<'_, Mdl, In, N, M, A>
where
    Mdl: CraneModel<N, M, A>,
    In: Inputs<A>,
{
    fn step(&mut self) -> Result<StepReport, Error> {
        ForwardStepper::step(self)
    }
    fn state(&self) -> &State<N, M, A> {
        ForwardStepper::state(self)
    }
}

/// Integrate the forward problem from `start` to `options.tf` with the
/// inputs `inputs(t)` on `options.scheme`.
pub fn simulate_forward<Mdl, In, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    inputs: In,
    start: &State<N, M, A>,
    options: &Options,
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    In: Inputs<A>,
{
    let steps = step_count(start.t, options.tf, options.dt)?;
    let mut stepper = ForwardStepper::new(model, inputs, start, options.dt, options.scheme, options.newton)?;
    record(model, start, &mut stepper, steps, options, &mut |_, _| {})
}
