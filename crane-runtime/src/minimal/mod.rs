//! The servo problem in minimal coordinates, paper eqs. (24a-e) with
//! (24b-d) as corrected in docs/errata.md, on any scheme.
//!
//! With `mu = [mu1; mu2]`, `mu' = [nu1; mu2_hat]` and the reduced quantities
//! `M~ = P^T M P`, `f~ = P^T f - P^T M P' mu'`, `B~^T = P^T B^T` (eqs. 18-19),
//! the unknowns of a step are `mu1, mu2, mu2_hat, mu2_tilde, u`; the
//! scheme eliminates `nu1` and `nu1'` as affine functions of `mu1`
//! (`nu1 = (mu1 - mu1_n)/dt`, eq. 24a, for backward Euler; below written
//! for it, with `c (mu1 - mu1bar)` and `vbar` of [`crate::scheme`] in place
//! of `mu1 - mu1_n` and `nu1_n` for BDF-k). Rows and unknowns are
//! scaled so that the iteration matrix does not degrade with `dt`:
//! ```text
//! (24b) dt^2:  M~ [mu1 - mu1_n - dt nu1_n; s] - dt^2 f~ - B~^T ut            = 0   (f rows)
//! (24c) dt^2:  D1 phi_x (mu1 - mu1_n - dt nu1_n) + D2 phi_x s + dt^2 (w - gamma'') = 0   (a rows)
//! (24d) dt:    D1 phi_x (mu1 - mu1_n) + D2 phi_x h - dt gamma'            = 0   (a rows)
//! (24e)        phi_x(mu) - gamma                                           = 0   (a rows)
//! unknowns z = [mu (f); h = dt mu2_hat (a); s = dt^2 mu2_tilde (a); ut = dt^2 u (a)]
//! ```
//! The stages, one module each:
//! - `equations`: the residual and its exact Jacobian, column by column from
//!   derivatives the macro generates ([`MinimalMap::map_derivatives`]: `phi`,
//!   `P`, `dP/dmu_k`, `d(P' mu')/dmu` from one function body) and the model's
//!   Jacobians, by the chain rule through the scheme's affine maps (no dual
//!   numbers in the step; a unit test checks it against them). It is
//!   equilibrated before each solve (docs/numerics.md: `M~` is singular along
//!   the whole motion for a massless pulley, the full system is regular but
//!   badly scaled);
//! - [`coordinates`](minimal_start): minimal coordinates of a redundant state
//!   and the output Jacobian `D2 phi_x` (eq. 12);
//! - [`degenerate`](DEGENERATE_TENSION_RATIO): the degenerate start, where a
//!   rope carries (almost) no tension and leaves the pulley weakly fixed (the
//!   paper's sect. 5.1 start, rope L1): the first steps are taken by the
//!   redundant problem and followed in minimal coordinates until every rope
//!   carries [`DEGENERATE_TENSION_RATIO`] of the largest tension
//!   ([`Solution::redundant_start_steps`] counts them), a [`Handover`].
//!
//! Newton starts from the cubic extrapolation of the last four steps (the
//! quadratic of three in the first steps and after a singular step;
//! [`Predictor::Extrapolation`]; docs/numerics.md: from the previous step
//! alone it fails near the degenerate start). Results are reported in
//! redundant terms, `q = phi(mu)`, `q' = P mu'`, with the multipliers
//! recovered from the redundant equations of motion by least squares,
//! `G G^T lambda = G (f + B^T u - M q'')`, so both formulations can be
//! compared column by column (Fig. 1).

mod coordinates;
mod degenerate;
mod equations;

use std::ops::{Deref, Range};

use nalgebra::{DMatrix, DVector, SVector};

pub use coordinates::{OUTPUT_JACOBIAN_CONDITION_LIMIT, minimal_start};
pub use degenerate::DEGENERATE_TENSION_RATIO;
pub(crate) use degenerate::degenerate;

use crate::driver::record;
use crate::error::Error;
use crate::init;
use crate::linsolve::DenseSolver;
use crate::model::{CraneModel, MinimalMap};
use crate::newton::NonlinearSystem;
use crate::options::Options;
use crate::problem::{Accepted, Predictor, Problem, ServoTarget, Start};
use crate::redundant::{Redundant, check_target, servo_target};
use crate::scheme::{Method, Scheme, StepFormula};
use crate::solution::{Solution, State};
use crate::stepper::{Handover, Stepper};
use crate::trajectory::Trajectory;
use coordinates::OutputJacobian;
use equations::MinimalEquations;

/// Eqs. (24b-e) of one step, as a [`Problem`] in the unknowns
/// `z = [mu; dt mu2_hat; dt^2 mu2_tilde; dt^2 u]`, for the crane behind the
/// handle `H` with its minimal map, on the path `Tr`.
#[derive(Clone)]
pub struct Minimal<H, Tr, const N: usize, const M: usize, const A: usize, const F: usize> {
    model: H,
    trajectory: Tr,
    /// A rough guess of `mu` at the start.
    mu_guess: SVector<f64, F>,
    equations: MinimalEquations<N, A, F>,
    /// `G G^T` and its solver, for the multipliers.
    lambda_solver: DenseSolver,
    normal: DMatrix<f64>,
    normal_rhs: DVector<f64>,
    output: OutputJacobian,
}

impl<H, Tr, const N: usize, const M: usize, const A: usize, const F: usize> Minimal<H, Tr, N, M, A, F>
where
    H: Deref<Target: MinimalMap<N, M, A, F> + Sized>,
    Tr: Trajectory<A>,
{
    /// The servo problem of the crane behind `model` on `trajectory` in its
    /// minimal coordinates, with `mu_guess` a rough guess of them at the start.
    pub fn new(model: H, trajectory: Tr, mu_guess: SVector<f64, F>) -> Self {
        Self {
            model,
            trajectory,
            mu_guess,
            equations: MinimalEquations::new(f64::NAN),
            lambda_solver: DenseSolver::new(M),
            normal: DMatrix::zeros(M, M),
            normal_rhs: DVector::zeros(M),
            output: OutputJacobian::new(A),
        }
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize, const F: usize> NonlinearSystem
    for Minimal<H, Tr, N, M, A, F>
where
    H: Deref<Target: MinimalMap<N, M, A, F> + Sized>,
    Tr: Trajectory<A>,
{
    fn dim(&self) -> usize {
        MinimalEquations::<N, A, F>::DIM
    }

    fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) {
        self.equations.evaluate(&*self.model, z, r, jac)
    }

    fn normalised_residual(&self, z: &DVector<f64>, r: &DVector<f64>, jac: &DMatrix<f64>) -> f64 {
        self.equations.normalised_residual(z, r, jac)
    }

    fn blocks(&self) -> &[Range<usize>] {
        &self.equations.blocks
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize, const F: usize> Problem<N, M, A, F>
    for Minimal<H, Tr, N, M, A, F>
where
    H: Deref<Target: MinimalMap<N, M, A, F> + Sized>,
    Tr: Trajectory<A>,
{
    type Model = H::Target;
    type Drive = ServoTarget<A>;
    const EQUILIBRATED: bool = true;

    fn model(&self) -> &H::Target {
        &self.model
    }

    /// 4: the minimal extension of eqs. (22, 24) reduces servo constraints of
    /// index 5, whose inputs need the path's 4th derivative.
    fn path_order_covered(&self) -> Option<usize> {
        Some(4)
    }

    fn predictor(&self) -> Predictor {
        Predictor::Extrapolation { points: 4 }
    }

    fn drive(&self, t: f64) -> ServoTarget<A> {
        servo_target(&self.trajectory, t)
    }

    fn check_drive(&self, target: &ServoTarget<A>, t: f64) -> Result<(), Error> {
        check_target(target, t, &H::Target::INFO.coordinates[N - A..])
    }

    /// `mu0, mu0'` of the redundant start ([`minimal_start`]); the split must
    /// satisfy eq. (12) there. `s = dt^2 mu2''` at the start: from rest it
    /// is 0 (gamma'' = 0 there); otherwise Newton's first iterate corrects it.
    fn start(&mut self, start: &State<N, M, A>, dt: f64, z: &mut DVector<f64>) -> Result<Start<F>, Error> {
        self.equations = MinimalEquations::new(dt);
        let model = &*self.model;
        let (mu, mu_dot) = minimal_start(model, start, &self.mu_guess)?;
        let split = F - A;
        for i in 0..F {
            z[i] = mu[i];
        }
        for k in 0..A {
            z[F + k] = dt * mu_dot[split + k];
            z[F + 2 * A + k] = dt * dt * start.u[k];
        }
        self.output.check::<N, F, A>(&model.null_space(&mu), start.t)?;
        Ok(Start {
            y0: mu,
            v0: mu_dot,
            at_rest: init::at_rest(&self.trajectory, start),
        })
    }

    fn prepare(&mut self, target: &ServoTarget<A>, formula: StepFormula<F>) {
        self.equations.target = *target;
        self.equations.formula = formula;
    }

    /// Minimal and redundant coordinates, inputs and the multipliers
    /// recovered by least squares, `G G^T lambda = G (f + B^T u - M q'')`.
    fn accept(&mut self, t: f64, z: &DVector<f64>) -> Result<Accepted<N, M, A, F>, Error> {
        let model = &*self.model;
        let dt = self.equations.dt;
        let dt2 = dt * dt;
        let [mu, mu_dot, accel_dt2] = self.equations.kinematics(&|i| z[i]);
        let u = SVector::<f64, A>::from_fn(|k, _| z[F + 2 * A + k] / dt2);
        // phi, P and P' from one generated body (a third of the sines and
        // cosines of three separate calls)
        let map = model.map_derivatives(&mu, &mu_dot);
        let (q, p) = (map.phi, map.null_space);
        let v = p * mu_dot;
        let qdd = (p * accel_dt2) / dt2 + map.null_space_rate(&mu_dot) * mu_dot;
        let jac_g = model.constraint_jacobian(&q);
        let rhs = model.forces(&q, &v) + model.input_matrix(&q) * u - model.mass_matrix::<f64>() * qdd;
        self.normal.copy_from(&(jac_g * jac_g.transpose()));
        self.normal_rhs.copy_from(&(jac_g * rhs));
        self.lambda_solver
            .solve(&self.normal, &mut self.normal_rhs)
            .map_err(|s| Error::SingularIterationMatrix {
                t,
                pivot_ratio: s.pivot_ratio,
            })?;
        let lambda = SVector::<f64, M>::from_fn(|i, _| self.normal_rhs[i]);
        self.output.check::<N, F, A>(&p, t)?;
        Ok(Accepted {
            state: State { t, q, v, u, lambda },
            y: mu,
            v: mu_dot,
            trailing: None,
        })
    }
}

/// Eqs. (24a-e) one step at a time: the [`Minimal`] problem on the scheme
/// `S`, with the first steps of a degenerate start by the [`Redundant`] one.
pub type MinimalStepper<H, Tr, const N: usize, const M: usize, const A: usize, const F: usize, S = Scheme> =
    Handover<Redundant<H, Tr, N, M, A>, Minimal<H, Tr, N, M, A, F>, S, N, M, A, N, F>;

impl<H, Tr, S, const N: usize, const M: usize, const A: usize, const F: usize> MinimalStepper<H, Tr, N, M, A, F, S>
where
    H: Deref<Target: MinimalMap<N, M, A, F> + Sized>,
    Tr: Trajectory<A>,
    S: Method,
{
    /// The minimal coordinates `mu` and velocities `mu'` after the last step.
    pub fn minimal_state(&self) -> (SVector<f64, F>, SVector<f64, F>) {
        self.second().coordinates()
    }

    /// How many of the first steps were taken in redundant coordinates
    /// because a rope was (nearly) slack (see [`DEGENERATE_TENSION_RATIO`]).
    pub fn redundant_start_steps(&self) -> usize {
        self.first_steps()
    }
}

/// A stepper of eqs. (24a-e) for the crane behind `model` (`&crane`, or an
/// owning `Arc`) on `trajectory` from the consistent redundant `start`, with
/// `mu_guess` a rough guess of the minimal coordinates there and the step,
/// scheme and tolerances of `options`; a step does not allocate.
pub fn stepper<H, Tr, S, const N: usize, const M: usize, const A: usize, const F: usize>(
    model: H,
    trajectory: Tr,
    start: &State<N, M, A>,
    mu_guess: &SVector<f64, F>,
    options: &Options<S>,
) -> Result<MinimalStepper<H, Tr, N, M, A, F, S>, Error>
where
    H: Deref<Target: MinimalMap<N, M, A, F> + Sized> + Clone,
    Tr: Trajectory<A> + Clone,
    S: Method,
{
    let minimal = Stepper::new(
        Minimal::new(model.clone(), trajectory.clone(), *mu_guess),
        start,
        options,
    )?;
    Handover::new(minimal, || {
        Stepper::new(Redundant::new(model, trajectory), start, options)
    })
}

/// Integrate eqs. (24a-e) from the redundant `start` to `options.tf()` with
/// its scheme; `mu_guess` is a rough guess of the minimal coordinates at the start.
pub fn simulate_minimal<Mdl, Tr, S, const N: usize, const M: usize, const A: usize, const F: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    mu_guess: &SVector<f64, F>,
    options: &Options<S>,
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: MinimalMap<N, M, A, F>,
    Tr: Trajectory<A> + Clone,
    S: Method,
{
    simulate_minimal_with_progress(model, trajectory, start, mu_guess, options, &mut |_, _| {})
}

/// [`simulate_minimal`], calling `progress(step, steps)` after every step.
pub fn simulate_minimal_with_progress<Mdl, Tr, S, const N: usize, const M: usize, const A: usize, const F: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    mu_guess: &SVector<f64, F>,
    options: &Options<S>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: MinimalMap<N, M, A, F>,
    Tr: Trajectory<A> + Clone,
    S: Method,
{
    let mut stepper = stepper(model, trajectory, start, mu_guess, options)?;
    let mut solution = record(&mut stepper, options.tf(), progress)?;
    solution.redundant_start_steps = stepper.redundant_start_steps();
    Ok(solution)
}
