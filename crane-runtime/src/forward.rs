//! The forward problem on any scheme: given the inputs `u(t)`, integrate
//! the crane's index-3 equations of motion
//! ```text
//! M q'' = f(q, q') + B^T(q) u - G^T(q) lambda,   g(q) = 0
//! ```
//! for `q`, `q'` and `lambda` (paper eq. 1a-1b without the servo
//! constraints). The scheme eliminates `v` and `a` of all `n` coordinates as
//! affine functions of `q_{n+1}` exactly as in the servo problems; the
//! dynamic rows are the servo problem's ([`dynamic_rows`]), multiplied by
//! `dt^2` and solved for `dt^2 lambda`:
//! ```text
//! r_dyn = M (dt^2 a) - dt^2 f(q, v) - B^T(q) (dt^2 u) + G^T(q) (dt^2 lambda) = 0
//! r_g   = g(q) = 0,         unknowns z = [q; dt^2 lambda]
//! ```
//! `M` may be singular (a massless pulley): the full iteration matrix
//! `[c^2 M + ...; G]` is regular where the ropes fix the pulley.

use std::ops::{Deref, Range};

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::driver::solve;
use crate::error::Error;
use crate::model::CraneModel;
use crate::newton::{NonlinearSystem, normalised_residual};
use crate::options::Options;
use crate::problem::{Accepted, Predictor, Problem, Start, dynamic_rows};
use crate::scheme::{Method, StepFormula};
use crate::solution::{Solution, State};
use crate::stepper::Stepper;

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

/// One forward step as a [`Problem`] in the unknowns `z = [q; dt^2 lambda]`,
/// for the crane behind the handle `H` driven by the inputs `In`.
#[derive(Clone)]
pub struct Forward<H, In, const N: usize, const M: usize, const A: usize> {
    model: H,
    inputs: In,
    mass: SMatrix<f64, N, N>,
    /// `u` at the new time.
    input: SVector<f64, A>,
    formula: StepFormula<N>,
    /// The dynamic rows' floors of the residual test (their inertia or
    /// applied forces, the larger) at the last evaluation.
    floors: SVector<f64, N>,
    blocks: [Range<usize>; 2],
}

impl<H, In, const N: usize, const M: usize, const A: usize> Forward<H, In, N, M, A>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized>,
    In: Inputs<A>,
{
    /// The crane behind `model` driven by `inputs`.
    pub fn new(model: H, inputs: In) -> Self {
        let mass = model.mass_matrix();
        Self {
            model,
            inputs,
            mass,
            input: SVector::zeros(),
            formula: StepFormula::unprepared(),
            floors: SVector::zeros(),
            blocks: [0..N, N..N + M],
        }
    }

    /// The input law.
    pub fn inputs(&self) -> &In {
        &self.inputs
    }

    /// `q`, `v` and `a` from the unknowns.
    fn kinematics(&self, z: &DVector<f64>) -> [SVector<f64, N>; 3] {
        let q = SVector::<f64, N>::from_fn(|i, _| z[i]);
        let mut v = SVector::<f64, N>::zeros();
        let mut a = SVector::<f64, N>::zeros();
        for i in 0..N {
            let (v_i, a_dt2) = self.formula.kinematics(i, z[i]);
            v[i] = v_i;
            a[i] = a_dt2 / (self.formula.dt * self.formula.dt);
        }
        [q, v, a]
    }
}

impl<H, In, const N: usize, const M: usize, const A: usize> NonlinearSystem for Forward<H, In, N, M, A>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized>,
    In: Inputs<A>,
{
    fn dim(&self) -> usize {
        N + M
    }

    fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) {
        let kinematics = self.kinematics(z);
        let lambda_scaled = SVector::<f64, M>::from_fn(|i, _| z[N + i]);
        let u_scaled = self.input * (self.formula.dt * self.formula.dt);
        let model = &*self.model;
        let rows = dynamic_rows(
            model,
            &self.mass,
            &self.formula,
            &kinematics,
            &u_scaled,
            &lambda_scaled,
            &model.constraints(&kinematics[0]),
            N,
            r,
            jac,
        );
        // the given inputs are applied forces: a row's scale is its inertia
        // or all its applied forces
        self.floors = SVector::from_fn(|i, _| rows.inertia[i].abs().max((rows.applied[i] + rows.inputs[i]).abs()));
    }

    fn normalised_residual(&self, z: &DVector<f64>, r: &DVector<f64>, jac: &DMatrix<f64>) -> f64 {
        normalised_residual(r, jac, z, |i| if i < N { self.floors[i] } else { 0.0 })
    }

    fn blocks(&self) -> &[Range<usize>] {
        &self.blocks
    }
}

impl<H, In, const N: usize, const M: usize, const A: usize> Problem<N, M, A, N> for Forward<H, In, N, M, A>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized>,
    In: Inputs<A>,
{
    type Model = H::Target;
    type Drive = SVector<f64, A>;

    fn model(&self) -> &H::Target {
        &self.model
    }

    /// The scheme's extrapolation for `q`, the last step's scaled `lambda`.
    fn predictor(&self) -> Predictor {
        Predictor::Scheme { leading: N }
    }

    fn drive(&self, t: f64) -> SVector<f64, A> {
        self.inputs.at(t)
    }

    fn check_drive(&self, input: &SVector<f64, A>, t: f64) -> Result<(), Error> {
        if input.iter().all(|x| x.is_finite()) {
            Ok(())
        } else {
            Err(Error::NonFinite {
                quantity: "input u(t)",
                t,
            })
        }
    }

    /// From the consistent `start` (its `q`, `v`, `lambda`); at rest
    /// (`v = 0`) the crane rested before `t0`.
    fn start(&mut self, start: &State<N, M, A>, dt: f64, z: &mut DVector<f64>) -> Result<Start<N>, Error> {
        self.input = start.u;
        z.rows_mut(0, N).copy_from(&start.q);
        z.rows_mut(N, M).copy_from(&(start.lambda * (dt * dt)));
        Ok(Start {
            y0: start.q,
            v0: start.v,
            at_rest: start.v.amax() == 0.0,
        })
    }

    fn prepare(&mut self, input: &SVector<f64, A>, formula: StepFormula<N>) {
        self.input = *input;
        self.formula = formula;
    }

    fn accept(&mut self, t: f64, z: &DVector<f64>) -> Result<Accepted<N, M, A, N>, Error> {
        let [q, v, _] = self.kinematics(z);
        let lambda = SVector::from_fn(|i, _| z[N + i] / (self.formula.dt * self.formula.dt));
        Ok(Accepted {
            state: State {
                t,
                q,
                v,
                u: self.input,
                lambda,
            },
            y: q,
            v,
            trailing: None,
        })
    }
}

/// The forward problem one step at a time: the [`Stepper`] of [`Forward`],
/// made by `Stepper::new(Forward::new(&crane, inputs), &start, &options)`
/// from a consistent start (its `q`, `v`, `lambda`); after construction a
/// step does not allocate.
pub type ForwardStepper<H, In, const N: usize, const M: usize, const A: usize, S = crate::scheme::Scheme> =
    Stepper<Forward<H, In, N, M, A>, S, N, M, A, N>;

/// Integrate the forward problem from `start` to `options.tf()` with the
/// inputs `inputs(t)` on its scheme.
pub fn simulate_forward<Mdl, In, S, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    inputs: In,
    start: &State<N, M, A>,
    options: &Options<S>,
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    In: Inputs<A>,
    S: Method,
{
    solve(Forward::new(model, inputs), start, options, &mut |_, _| {})
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scheme::Scheme;
    use crate::test_support::{Gantry, central_difference_error, random_history, uniform};

    /// The forward iteration matrix is the Jacobian of the forward residual:
    /// against central differences at random points and histories, for
    /// every scheme, entry by entry to 1e-6 of the largest entry (central
    /// differences of a smooth residual: ~1e-9).
    #[test]
    fn iteration_matrix_matches_central_differences() {
        let mut rnd = uniform(7);
        for scheme in Scheme::ALL {
            for _ in 0..20 {
                let (history, start) = random_history(scheme, &mut rnd);
                let dt = 0.01;
                let mut equations = Forward::new(&Gantry, |_t: f64| SVector::<f64, 2>::zeros());
                equations.start(&start, dt, &mut DVector::zeros(5)).unwrap();
                let input = SVector::from([rnd() * 100.0, rnd() * 1000.0]);
                equations.prepare(&input, history.formula(dt));
                let z = DVector::from_fn(5, |i, _| if i < 4 { 3.0 + rnd() } else { rnd() * 0.1 });
                let (worst, largest) = central_difference_error(&mut equations, &z);
                assert!(worst <= 1e-6 * largest, "{scheme}: worst {worst:e} of {largest}");
            }
        }
    }
}
