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

use crate::driver::{Options, StepReport, Stepper, check_parameters, check_step_size, record, step_count, step_error};
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
                jac[(i, j)] =
                    da * self.mass[(i, j)] - dt2 * df_dq[(i, j)] - dv * df_dv[(i, j)] - dbu_dq[(i, j)] + dgl_dq[(i, j)];
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
        check_step_size(dt)?;
        check_parameters(model)?;
        let history = if start.v.amax() == 0.0 {
            History::at_rest(start.q)
        } else {
            History::start(start.q, start.v)
        };
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
            return Err(Error::NonFinite {
                quantity: "input u(t)",
                t,
            });
        }
        let eq = &mut self.equations;
        eq.input = input;
        eq.formula = self.history.formula(self.scheme, dt);
        let predicted = self.history.predict(self.scheme, dt);
        self.z.rows_mut(0, N).copy_from(&predicted);
        let converged = self
            .newton
            .solve(eq, &mut self.z)
            .map_err(|failure| step_error(failure, t))?;
        let [q, v, _] = eq.kinematics(&self.z);
        self.state = State {
            t,
            q,
            v,
            u: input,
            lambda: SVector::from_fn(|i, _| self.z[N + i] / (dt * dt)),
        };
        self.history.push(q, v);
        self.steps += 1;
        Ok(StepReport {
            iterations: converged.iterations,
            min_norm_steps: converged.min_norm_steps,
        })
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{ModelInfo, Rope, Scalar, UnknownParameter};

    /// A planar gantry written by hand: trolley `s`, rope `L`, load `(x, z)`.
    struct Gantry;

    impl CraneModel<4, 1, 2> for Gantry {
        const INFO: ModelInfo = ModelInfo {
            name: "Gantry",
            description: "",
            coordinates: &["s", "L", "x", "z"],
            inputs: &["u1", "u2"],
            constraints: &["rope"],
            ropes: &[Rope {
                tension: "N",
                constraint: 0,
            }],
            parameters: &[],
            positive: &[],
        };
        fn parameter_values(&self) -> Vec<f64> {
            Vec::new()
        }
        fn set_parameter(&mut self, name: &str, _: f64) -> Result<(), UnknownParameter> {
            Err(UnknownParameter {
                name: name.into(),
                known: String::new(),
            })
        }
        fn constraints<T: Scalar>(&self, q: &SVector<T, 4>) -> SVector<T, 1> {
            let d = q[2] - q[0];
            SVector::from([(d * d + q[3] * q[3] - q[1] * q[1]) * 0.5])
        }
        fn constraint_jacobian<T: Scalar>(&self, q: &SVector<T, 4>) -> SMatrix<T, 1, 4> {
            let d = q[2] - q[0];
            SMatrix::from_row_slice(&[-d, -q[1], d, q[3]])
        }
        fn constraint_hessian<T: Scalar>(&self, _: &SVector<T, 4>, lambda: &SVector<T, 1>) -> SMatrix<T, 4, 4> {
            let (l, z) = (lambda[0], T::from(0.0));
            SMatrix::from_row_slice(&[l, z, -l, z, z, -l, z, z, -l, z, l, z, z, z, z, l])
        }
        fn mass_matrix<T: Scalar>(&self) -> SMatrix<T, 4, 4> {
            SMatrix::from_diagonal(&SVector::from([
                T::from(50.0),
                T::from(5.0),
                T::from(200.0),
                T::from(200.0),
            ]))
        }
        fn forces<T: Scalar>(&self, _: &SVector<T, 4>, v: &SVector<T, 4>) -> SVector<T, 4> {
            // a little velocity-dependent friction on the trolley, so that df/dv counts
            SVector::from([-v[0] * 3.0, T::from(0.0), T::from(0.0), T::from(-200.0 * 9.81)])
        }
        fn force_jacobians<T: Scalar>(
            &self,
            _: &SVector<T, 4>,
            _: &SVector<T, 4>,
        ) -> (SMatrix<T, 4, 4>, SMatrix<T, 4, 4>) {
            let mut df_dv = SMatrix::zeros();
            df_dv[(0, 0)] = T::from(-3.0);
            (SMatrix::zeros(), df_dv)
        }
        fn input_matrix<T: Scalar>(&self, q: &SVector<T, 4>) -> SMatrix<T, 4, 2> {
            // the winch force grows with the rope length, so d(B^T u)/dq counts
            let mut b = SMatrix::zeros();
            b[(0, 0)] = T::from(1.0);
            b[(1, 1)] = q[1] * 0.1;
            b
        }
        fn input_jacobian<T: Scalar>(&self, _: &SVector<T, 4>, u: &SVector<T, 2>) -> SMatrix<T, 4, 4> {
            let mut j = SMatrix::zeros();
            j[(1, 1)] = u[1] * 0.1;
            j
        }
        fn rope_lengths(&self, q: &SVector<f64, 4>, out: &mut [f64]) {
            out[0] = q[1];
        }
    }

    /// The forward iteration matrix is the Jacobian of the forward residual:
    /// against central differences at random points and histories, for
    /// every scheme, entry by entry to 1e-6 of the largest entry (central
    /// differences of a smooth residual: ~1e-9).
    #[test]
    fn iteration_matrix_matches_central_differences() {
        let mut seed = 7u64;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for scheme in Scheme::ALL {
            for _ in 0..20 {
                let past: Vec<SVector<f64, 4>> = (0..5).map(|_| SVector::from_fn(|_, _| 3.0 + rnd())).collect();
                let rates: Vec<SVector<f64, 4>> = (0..5).map(|_| SVector::from_fn(|_, _| rnd())).collect();
                let history = History::from_past(&past, &rates);
                let dt = 0.01;
                let mut equations = ForwardEquations {
                    model: &Gantry,
                    mass: Gantry.mass_matrix(),
                    dt,
                    input: SVector::from([rnd() * 100.0, rnd() * 1000.0]),
                    formula: history.formula(scheme, dt),
                    blocks: [0..4, 4..5],
                };
                let z = DVector::from_fn(5, |i, _| if i < 4 { 3.0 + rnd() } else { rnd() * 0.1 });
                let (mut r, mut jac) = (DVector::zeros(5), DMatrix::zeros(5, 5));
                equations.evaluate(&z, &mut r, &mut jac);
                let mut worst = 0.0f64;
                for j in 0..5 {
                    let h = 1e-6 * (1.0 + z[j].abs());
                    let (mut plus, mut minus) = (z.clone(), z.clone());
                    plus[j] += h;
                    minus[j] -= h;
                    let (mut rp, mut rm, mut scratch) = (DVector::zeros(5), DVector::zeros(5), DMatrix::zeros(5, 5));
                    equations.evaluate(&plus, &mut rp, &mut scratch);
                    equations.evaluate(&minus, &mut rm, &mut scratch);
                    for i in 0..5 {
                        worst = worst.max(((rp[i] - rm[i]) / (2.0 * h) - jac[(i, j)]).abs());
                    }
                }
                assert!(
                    worst <= 1e-6 * jac.amax(),
                    "{scheme}: worst {worst:e} of {}",
                    jac.amax()
                );
            }
        }
    }
}
