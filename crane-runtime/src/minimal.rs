//! The servo problem in minimal coordinates, paper eqs. (24a-e) with
//! (24b-d) as corrected in docs/errata.md, on any [`Scheme`].
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
//! The iteration matrix is the exact Jacobian, built column by column from
//! derivatives the macro generates ([`MinimalMap::map_derivatives`]: `phi`,
//! `P`, `dP/dmu_k`, `d(P' mu')/dmu` from one function body) and the model's
//! Jacobians, by the chain rule through the scheme's affine maps (no dual
//! numbers in the step; a unit test checks it against them). It is
//! equilibrated before each solve (docs/numerics.md: `M~` is singular along
//! the whole motion for a massless pulley, the full system is regular but
//! badly scaled). Newton starts from a quadratic extrapolation of the last
//! three steps (docs/numerics.md: from the previous step alone it fails near the
//! degenerate start).
//!
//! At a degenerate start, where a rope carries (almost) no tension and so
//! leaves the pulley weakly fixed (the paper's sect. 5.1 start, rope L1),
//! the first steps are taken by the redundant stepper and followed in
//! minimal coordinates until every rope carries
//! [`DEGENERATE_TENSION_RATIO`] of the largest tension
//! ([`Solution::redundant_start_steps`] counts them).
//!
//! Results are reported in redundant terms, `q = phi(mu)`, `q' = P mu'`, with
//! the multipliers recovered from the redundant equations of motion by least
//! squares, `G G^T lambda = G (f + B^T u - M q'')`, so both formulations can
//! be compared column by column (Fig. 1).

use std::ops::Range;

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::driver::{
    Options, ServoTarget, StepReport, Stepper, check_parameters, check_step_size, check_step_time, check_target,
    record, servo_target, step_count, step_error,
};
use crate::error::Error;
use crate::init;
use crate::linsolve::DenseSolver;
use crate::model::{CraneModel, MapDerivatives, MinimalMap, Scalar};
use crate::newton::{Newton, NewtonFailure, NewtonOptions, NonlinearSystem, normalised_residual};
use crate::redundant::RedundantStepper;
use crate::scheme::{History, Scheme, StepFormula};
use crate::solution::{Solution, State};
use crate::trajectory::Trajectory;

/// Condition estimate of `D2 phi_x` above which the split is refused: beyond
/// it the servo constraints no longer determine `mu2` to more than 4 digits.
pub const OUTPUT_JACOBIAN_CONDITION_LIMIT: f64 = 1e12;

/// The residual of eqs. (24b-e) at one step, in the unknowns
/// `z = [mu; dt mu2_hat; dt^2 mu2_tilde; dt^2 u]`.
#[derive(Clone)]
struct MinimalEquations<'m, Mdl, const N: usize, const M: usize, const A: usize, const F: usize> {
    model: &'m Mdl,
    dt: f64,
    target: ServoTarget<A>,
    /// The scheme's affine maps `mu1 -> nu1, nu1'` for this step.
    formula: StepFormula<F>,
    blocks: [Range<usize>; 4],
}

/// One iterate of eqs. (24b-e) in the model's terms, generic over the scalar.
struct Point<T: Scalar, const N: usize, const F: usize, const A: usize> {
    /// `dt^2 mu''`.
    accel_dt2: SVector<T, F>,
    /// `dt^2 u`.
    u_scaled: SVector<T, A>,
    /// `phi`, `P` and their derivatives at `(mu, mu')`.
    map: MapDerivatives<T, N, F>,
    q: SVector<T, N>,
    p: SMatrix<T, N, F>,
    /// `P'(mu, mu')`.
    p_rate: SMatrix<T, N, F>,
    v: SVector<T, N>,
    /// `dt^2 q'' = P (dt^2 mu'') + dt^2 P' mu'`.
    accel_q_dt2: SVector<T, N>,
    /// `B^T(q)`.
    inputs: SMatrix<T, N, A>,
    /// `r = M (dt^2 q'') - dt^2 f - B^T (dt^2 u)`: the dynamics rows are `P^T r`.
    unbalanced: SVector<T, N>,
}

/// What a residual evaluation produces, generic over the scalar.
struct Residual<T: Scalar, const F: usize, const A: usize> {
    dynamics: SVector<T, F>,
    acceleration: SVector<T, A>,
    velocity: SVector<T, A>,
    position: SVector<T, A>,
}

impl<Mdl, const N: usize, const M: usize, const A: usize, const F: usize> MinimalEquations<'_, Mdl, N, M, A, F>
where
    Mdl: MinimalMap<N, M, A, F>,
{
    const DIM: usize = F + 3 * A;

    /// `mu`, `mu'` and `dt^2 mu''` from the unknowns (`z(i)` reads unknown `i`).
    fn kinematics<T: Scalar>(&self, z: &impl Fn(usize) -> T) -> [SVector<T, F>; 3] {
        let split = F - A;
        let dt = self.dt;
        let mu = SVector::<T, F>::from_fn(|i, _| z(i));
        let mut mu_dot = SVector::<T, F>::zeros();
        let mut accel_dt2 = SVector::<T, F>::zeros();
        for i in 0..F {
            (mu_dot[i], accel_dt2[i]) = if i < split {
                self.formula.kinematics(i, z(i), dt) // eq. (24a)
            } else {
                (z(F + i - split) * (1.0 / dt), z(F + A + i - split))
            };
        }
        [mu, mu_dot, accel_dt2]
    }

    /// The quantities at the iterate `z` that the residual and its Jacobian share.
    fn point<T: Scalar>(&self, z: &impl Fn(usize) -> T) -> Point<T, N, F, A> {
        let (dt, model) = (self.dt, self.model);
        let dt2 = T::from(dt * dt);
        let [mu, mu_dot, accel_dt2] = self.kinematics(z);
        let u_scaled = SVector::<T, A>::from_fn(|k, _| z(F + 2 * A + k));
        let map = model.map_derivatives(&mu, &mu_dot);
        let (q, p) = (map.phi, map.null_space);
        let p_rate = map.null_space_rate(&mu_dot);
        let v = p * mu_dot;
        // dt^2 q'' = P (dt^2 mu'') + dt^2 P' mu'; the load rows of P' mu' are w (eq. 17)
        let accel_q_dt2 = p * accel_dt2 + p_rate * mu_dot * dt2;
        let inputs = model.input_matrix(&q);
        let forces = model.forces(&q, &v);
        let unbalanced = model.mass_matrix::<T>() * accel_q_dt2 - forces * dt2 - inputs * u_scaled;
        Point {
            accel_dt2,
            u_scaled,
            map,
            q,
            p,
            p_rate,
            v,
            accel_q_dt2,
            inputs,
            unbalanced,
        }
    }

    fn residual<T: Scalar>(&self, x: &Point<T, N, F, A>) -> Residual<T, F, A> {
        let dt = self.dt;
        // (24b) * dt^2: P^T (M dt^2 q'' - dt^2 f - B^T dt^2 u), i.e.
        // M~ (dt^2 mu'') - dt^2 f~ - B~^T (dt^2 u) with f~ = P^T f - P^T M P' mu'
        let dynamics = x.p.tr_mul(&x.unbalanced);
        let off = N - A;
        let mut acceleration = SVector::<T, A>::zeros();
        let mut velocity = SVector::<T, A>::zeros();
        let mut position = SVector::<T, A>::zeros();
        for k in 0..A {
            acceleration[k] = x.accel_q_dt2[off + k] - dt * dt * self.target[2][k]; // (24c)
            velocity[k] = x.v[off + k] * dt - dt * self.target[1][k]; // (24d)
            position[k] = x.q[off + k] - self.target[0][k]; // (24e)
        }
        Residual {
            dynamics,
            acceleration,
            velocity,
            position,
        }
    }

    /// The exact Jacobian of eqs. (24b-e) in `z`, from the generated
    /// derivatives of the map ([`MinimalMap::map_derivatives`]) and of the
    /// model (`df/dq`, `df/dq'`, `d(B^T u)/dq`), column by column. An unknown
    /// `z_j` moves `q`, `dt^2 q''` and `q'` by
    /// ```text
    /// mu_j (eq. 24a for mu1):  P_j,  P'(a)_j + dt^2 (dc/dmu)_j + sigma_j 2 dt^2 P'_j + rho_j P_j,  P'_j + sigma_j P_j
    /// h_k = dt mu2^_k:         0,    2 dt P'_k,                                                    P_k / dt
    /// s_k = dt^2 mu2''_k:      0,    P_k,                                                          0
    /// ```
    /// (`a = dt^2 mu''`, `c = P' mu'`, `P'(a)_j = d(P a)/dmu_j`, `dc/dmu'
    /// = 2 P'`, `sigma_j`, `rho_j` the slopes of `nu1_j` and `dt^2 nu1_j'` in
    /// `mu1_j`); the servo rows are the load rows of these, and the dynamics
    /// rows `P^T r`, `r = M dt^2 q'' - dt^2 f - B^T ut`, change by
    /// `P^T (M dq''dt^2 - dt^2 f_v dq' - (dt^2 f_q + d(B^T ut)/dq) dq)`, plus
    /// `(dP/dmu_j)^T r` (column `j` of `H(r)`) for the columns of `mu`; the
    /// columns of `ut` are `[-P^T B^T; 0]`.
    fn iteration_matrix(&self, x: &Point<f64, N, F, A>, jac: &mut DMatrix<f64>) {
        let (dt, model) = (self.dt, self.model);
        let dt2 = dt * dt;
        let Point {
            accel_dt2,
            u_scaled,
            map,
            q,
            p,
            p_rate,
            v,
            inputs,
            unbalanced: r,
            ..
        } = x;
        let p_accel = map.null_space_rate(accel_dt2); // d(P a)/dmu
        let hessian = map.phi_hessian(r);
        let mass = model.mass_matrix::<f64>();
        let (split, off, rate) = (F - A, N - A, self.formula.rate);
        // P^T M, P^T f_v and P^T (dt^2 f_q + d(B^T ut)/dq) once, so that each
        // column costs F x N products; the paper's cranes have forces free
        // of q' and constant in q (known from the declaration): those
        // Jacobians are neither evaluated nor multiplied
        let pt_mass = p.tr_mul(&mass);
        let force_jacobians =
            (Mdl::FORCES_DEPEND_ON_VELOCITY || Mdl::FORCES_DEPEND_ON_POSITION).then(|| model.force_jacobians(q, v));
        let velocity_term = force_jacobians
            .filter(|_| Mdl::FORCES_DEPEND_ON_VELOCITY)
            .map(|(_, df_dv)| p.tr_mul(&df_dv) * dt2);
        let position_term = force_jacobians
            .filter(|_| Mdl::FORCES_DEPEND_ON_POSITION)
            .map(|(df_dq, _)| p.tr_mul(&(df_dq * dt2 + model.input_jacobian(q, u_scaled))));
        let mut column = |j: usize, dq: SVector<f64, N>, dqdd_dt2: SVector<f64, N>, dv: SVector<f64, N>| {
            let mut dynamics = pt_mass * dqdd_dt2;
            if let Some(term) = &velocity_term {
                dynamics -= term * dv;
            }
            if let Some(term) = &position_term {
                dynamics -= term * dq;
            }
            for i in 0..F {
                jac[(i, j)] = dynamics[i] + if j < F { hessian[(i, j)] } else { 0.0 };
            }
            for k in 0..A {
                jac[(F + k, j)] = dqdd_dt2[off + k];
                jac[(F + A + k, j)] = dt * dv[off + k];
                jac[(F + 2 * A + k, j)] = dq[off + k];
            }
        };
        let zero = SVector::<f64, N>::zeros();
        for j in 0..F {
            let (sigma, rho) = if j < split {
                (rate, (rate * dt) * (rate * dt))
            } else {
                (0.0, 0.0)
            };
            let (p_j, p_rate_j) = (p.column(j).into_owned(), p_rate.column(j).into_owned());
            let dqdd_dt2 = p_accel.column(j)
                + map.curvature_jacobian.column(j) * dt2
                + (p_rate_j * (2.0 * dt2 * sigma))
                + p_j * rho;
            column(j, p_j, dqdd_dt2, p_rate_j + p_j * sigma);
        }
        for k in 0..A {
            let (p_k, p_rate_k) = (p.column(split + k).into_owned(), p_rate.column(split + k).into_owned());
            column(F + k, zero, p_rate_k * (2.0 * dt), p_k / dt);
            column(F + A + k, zero, p_k, zero);
        }
        let reduced_inputs = p.tr_mul(inputs);
        for k in 0..A {
            let u = F + 2 * A + k;
            for i in 0..F {
                jac[(i, u)] = -reduced_inputs[(i, k)];
            }
            for i in F..F + 3 * A {
                jac[(i, u)] = 0.0;
            }
        }
    }
}

fn write_residual<T: Scalar, const F: usize, const A: usize>(r: &Residual<T, F, A>, mut out: impl FnMut(usize, T)) {
    for i in 0..F {
        out(i, r.dynamics[i]);
    }
    for k in 0..A {
        out(F + k, r.acceleration[k]);
        out(F + A + k, r.velocity[k]);
        out(F + 2 * A + k, r.position[k]);
    }
}

impl<Mdl, const N: usize, const M: usize, const A: usize, const F: usize> NonlinearSystem
    for MinimalEquations<'_, Mdl, N, M, A, F>
where
    Mdl: MinimalMap<N, M, A, F>,
{
    fn dim(&self) -> usize {
        Self::DIM
    }

    fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) -> f64 {
        let point = self.point(&|i| z[i]);
        write_residual(&self.residual(&point), |i, v| r[i] = v);
        self.iteration_matrix(&point, jac);
        // the servo rows (24c-e) by their target terms too: where the load's
        // minimal coordinates are the load coordinates themselves (x = mu2,
        // natural for gantry and overhead cranes) and start at 0 with the
        // crane at rest, no term J_ij z_j of those rows is nonzero, and the
        // row would have no scale at all; and the rows on acceleration and
        // velocity level are in length units (dt^2 a, dt v): what is below
        // eps |gamma| there is below the resolution of the positions they
        // add up to (x_n+1 = x_n + dt v + ...), so |gamma| is their floor
        // too. Without it a crane at rest at the end of a move with x = mu2
        // (D1 phi_x = 0) has acceleration rows whose only term is the 1e-43
        // left in s, judged 100 % off (tower-crane, dt = 0.001: no
        // convergence in 30 iterations at t = 10 s)
        let (dt, target) = (self.dt, &self.target);
        let position = target[0].amax();
        normalised_residual(r, jac, z, |i| match i.checked_sub(F) {
            Some(k) if k < A => (dt * dt * target[2][k].abs()).max(position),
            Some(k) if k < 2 * A => (dt * target[1][k - A].abs()).max(position),
            Some(k) if k < 3 * A => target[0][k - 2 * A].abs(),
            _ => 0.0,
        })
    }

    fn blocks(&self) -> &[Range<usize>] {
        &self.blocks
    }
}

/// Find minimal coordinates for a redundant start: `phi(mu0) = q0` by
/// Gauss-Newton from `mu_guess`, and `mu0'` from `P mu0' = q0'` (least squares).
pub fn minimal_start<Mdl, const N: usize, const M: usize, const A: usize, const F: usize>(
    model: &Mdl,
    start: &State<N, M, A>,
    mu_guess: &SVector<f64, F>,
) -> Result<(SVector<f64, F>, SVector<f64, F>), Error>
where
    Mdl: MinimalMap<N, M, A, F>,
{
    let (mu, mu_dot, p) = minimal_coordinates(model, start, mu_guess)?;
    let tolerance = 1e-9 * start.v.amax().max(1.0);
    let residual = (p * mu_dot - start.v).amax();
    if residual > tolerance {
        return Err(Error::InconsistentStart {
            equation: "q0' = P mu0' (eq. 8)".into(),
            residual,
            tolerance,
        });
    }
    Ok((mu, mu_dot))
}

/// `mu` with `phi(mu) = q` by Gauss-Newton from `mu_guess`, the least-squares
/// `mu'` of `P mu' = q'` (the projection of `q'` onto the motions the map
/// allows) and `P`; allocation-free.
fn minimal_coordinates<Mdl, const N: usize, const M: usize, const A: usize, const F: usize>(
    model: &Mdl,
    state: &State<N, M, A>,
    mu_guess: &SVector<f64, F>,
) -> Result<(SVector<f64, F>, SVector<f64, F>, SMatrix<f64, N, F>), Error>
where
    Mdl: MinimalMap<N, M, A, F>,
{
    const MAX_ITERATIONS: usize = 50;
    let mut mu = *mu_guess;
    let scale = state.q.amax().max(1.0);
    // normal equations P^T P x = P^T rhs (P has full column rank for a
    // map that satisfies eq. 12; its condition is ~10 on the built-in maps)
    let least_squares = |p: &SMatrix<f64, N, F>, rhs: &SVector<f64, N>| {
        nalgebra::linalg::Cholesky::new(p.tr_mul(p)).map(|c| c.solve(&p.tr_mul(rhs)))
    };
    for iteration in 0..=MAX_ITERATIONS {
        let residual = state.q - model.phi(&mu);
        let p = model.null_space(&mu);
        if residual.amax() <= 1e-12 * scale {
            let mu_dot = least_squares(&p, &state.v).ok_or(Error::NonFinite {
                quantity: "minimal start velocity",
                t: state.t,
            })?;
            return Ok((mu, mu_dot, p));
        }
        if iteration == MAX_ITERATIONS || !residual.amax().is_finite() {
            return Err(Error::MinimalStartNotFound {
                iterations: iteration,
                residual: residual.amax(),
            });
        }
        let step = least_squares(&p, &residual).ok_or(Error::MinimalStartNotFound {
            iterations: iteration,
            residual: residual.amax(),
        })?;
        mu += step;
    }
    Err(Error::MinimalStartNotFound {
        iterations: MAX_ITERATIONS,
        residual: f64::NAN,
    })
}

/// A rope whose tension is below this fraction of the largest tension marks
/// a degenerate start (docs/numerics.md): the minimal stepper takes its first
/// steps in redundant coordinates until every rope carries at least this
/// much. Measured on navy-planar at dt = 0.001 (L1 slack at t0): the minimal
/// formulation started at rest has `q` 8.8e-5 m (tf = 4 s) and 4.2e-4 m
/// (Fig. 9) off Appendix A near the start; started from the redundant state
/// once `N1/N2` reaches 1e-5 (t = 0.02 s and 0.2 s), 4.0e-10 and below 1.2e-9.
pub const DEGENERATE_TENSION_RATIO: f64 = 1e-5;

/// Whether some rope of `state` carries less than [`DEGENERATE_TENSION_RATIO`]
/// of the largest rope tension (no rope: never).
fn degenerate<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    state: &State<N, M, A>,
) -> bool {
    let ropes = Mdl::INFO.ropes;
    let mut lengths = [0.0; M];
    let lengths = &mut lengths[..ropes.len().min(M)];
    model.rope_lengths(&state.q, lengths);
    let tension = |i: usize| state.lambda[ropes[i].constraint] * lengths[i];
    let largest = (0..lengths.len()).map(|i| tension(i).abs()).fold(0.0, f64::max);
    (0..lengths.len()).any(|i| !(tension(i) >= DEGENERATE_TENSION_RATIO * largest))
}

/// Eqs. (24a-e) on a [`Scheme`], one step at a time; [`step`](Self::step)
/// does not allocate.
#[derive(Clone)]
pub struct MinimalStepper<'m, Mdl, Tr, const N: usize, const M: usize, const A: usize, const F: usize> {
    equations: MinimalEquations<'m, Mdl, N, M, A, F>,
    trajectory: Tr,
    newton: Newton,
    z: DVector<f64>,
    /// Converged unknowns of the last three steps, newest first, for the predictor.
    history: [DVector<f64>; 3],
    known: usize,
    scheme: Scheme,
    /// Past `mu` and `mu'` (only the `mu1` rows are used by the scheme).
    past: History<F>,
    state: State<N, M, A>,
    t0: f64,
    steps: usize,
    lambda_solver: DenseSolver,
    normal: DMatrix<f64>,
    normal_rhs: DVector<f64>,
    output_solver: DenseSolver,
    output_jacobian: DMatrix<f64>,
    output_rhs: DVector<f64>,
    /// While a rope is (nearly) slack at a degenerate start: the redundant
    /// stepper that takes those first steps (see [`DEGENERATE_TENSION_RATIO`]).
    redundant_start: Option<RedundantStepper<'m, Mdl, Tr, N, M, A>>,
    redundant_steps: usize,
}

impl<'m, Mdl, Tr, const N: usize, const M: usize, const A: usize, const F: usize>
    MinimalStepper<'m, Mdl, Tr, N, M, A, F>
where
    Mdl: MinimalMap<N, M, A, F>,
    Tr: Trajectory<A>,
{
    /// A backward-Euler stepper from a consistent redundant `start`, with
    /// `mu_guess` a rough guess of the minimal coordinates there.
    pub fn new(
        model: &'m Mdl,
        trajectory: Tr,
        start: &State<N, M, A>,
        mu_guess: &SVector<f64, F>,
        dt: f64,
        newton: NewtonOptions,
    ) -> Result<Self, Error>
    where
        Tr: Clone,
    {
        Self::with_scheme(model, trajectory, start, mu_guess, dt, Scheme::BackwardEuler, newton)
    }

    /// A stepper on `scheme`; the scheme's history before the start comes
    /// from [`init::history`].
    pub fn with_scheme(
        model: &'m Mdl,
        trajectory: Tr,
        start: &State<N, M, A>,
        mu_guess: &SVector<f64, F>,
        dt: f64,
        scheme: Scheme,
        newton: NewtonOptions,
    ) -> Result<Self, Error>
    where
        Tr: Clone,
    {
        check_step_size(dt)?;
        check_parameters(model)?;
        let (mu, mu_dot) = minimal_start(model, start, mu_guess)?;
        let split = F - A;
        let dim = F + 3 * A;
        let mut z = DVector::zeros(dim);
        for i in 0..F {
            z[i] = mu[i];
        }
        for k in 0..A {
            z[F + k] = dt * mu_dot[split + k];
            z[F + 2 * A + k] = dt * dt * start.u[k];
        }
        // s = dt^2 mu2'' at the start: from rest it is 0 (gamma'' = 0 there);
        // otherwise Newton's first iterate corrects it
        let past = init::history(&trajectory, start, mu, mu_dot);
        let equations = MinimalEquations {
            model,
            dt,
            target: [SVector::zeros(); 3],
            formula: past.formula(scheme, dt),
            blocks: [0..F, F..F + A, F + A..F + 2 * A, F + 2 * A..dim],
        };
        let mut stepper = Self {
            equations,
            trajectory,
            newton: Newton::equilibrated(dim, newton),
            history: [z.clone(), z.clone(), z.clone()],
            z,
            known: 1,
            scheme,
            past,
            state: *start,
            t0: start.t,
            steps: 0,
            lambda_solver: DenseSolver::new(M),
            normal: DMatrix::zeros(M, M),
            normal_rhs: DVector::zeros(M),
            output_solver: DenseSolver::new(A),
            output_jacobian: DMatrix::zeros(A, A),
            output_rhs: DVector::zeros(A),
            redundant_start: None,
            redundant_steps: 0,
        };
        if degenerate(model, start) {
            let redundant =
                RedundantStepper::with_scheme(model, stepper.trajectory.clone(), start, dt, scheme, newton)?;
            stepper.redundant_start = Some(redundant);
        }
        let p = model.null_space(&mu);
        stepper.check_output_jacobian(&p, start.t)?;
        Ok(stepper)
    }

    /// The state after the last step, in redundant coordinates.
    pub fn state(&self) -> &State<N, M, A> {
        &self.state
    }

    /// The minimal coordinates `mu` and velocities `mu'` after the last step.
    pub fn minimal_state(&self) -> (SVector<f64, F>, SVector<f64, F>) {
        (*self.past.value(), *self.past.rate())
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
        if let Some(redundant) = self.redundant_start.as_mut() {
            let report = redundant.step_to(t, target)?;
            let state = *redundant.state();
            self.follow_redundant(state)?;
            return Ok(report);
        }
        self.equations.target = *target;
        self.equations.formula = self.past.formula(self.scheme, self.equations.dt);
        // predictor: quadratic extrapolation of the last three steps; before
        // that, the previous step. (Measured on navy-planar, tf = 4 s: from
        // the previous step alone Newton fails by t = 0.8 s at dt = 0.1; a
        // linear extrapolation from the first step off the degenerate start
        // diverges at dt = 0.1 and 0.05; this choice converges at every dt
        // from 0.1 to 0.001.)
        let [h0, h1, h2] = &self.history;
        for i in 0..self.z.len() {
            self.z[i] = if self.known >= 3 {
                3.0 * h0[i] - 3.0 * h1[i] + h2[i]
            } else {
                h0[i]
            };
        }
        let converged = match self.newton.solve(&mut self.equations, &mut self.z) {
            Ok(converged) => converged,
            // the extrapolation can overshoot where the solution turns along
            // the weakly determined pulley direction: retry from the last step
            Err(first) if self.known >= 3 => {
                self.z.copy_from(&self.history[0]);
                let mut retried = self
                    .newton
                    .solve(&mut self.equations, &mut self.z)
                    .map_err(|failure| step_error(failure, t))?;
                if let NewtonFailure::NotConverged { iterations, .. } = first {
                    retried.iterations += iterations;
                }
                retried
            }
            Err(failure) => return Err(step_error(failure, t)),
        };
        self.accept(t)?;
        Ok(StepReport {
            iterations: converged.iterations,
            min_norm_steps: converged.min_norm_steps,
        })
    }

    /// Take the converged unknowns as the new state: minimal and redundant
    /// coordinates, inputs and the recovered multipliers.
    fn accept(&mut self, t: f64) -> Result<(), Error> {
        let eq = &self.equations;
        let (dt, model) = (eq.dt, eq.model);
        let dt2 = dt * dt;
        let z = &self.z;
        let [mu, mu_dot, accel_dt2] = eq.kinematics(&|i| z[i]);
        let u = SVector::<f64, A>::from_fn(|k, _| z[F + 2 * A + k] / dt2);
        // phi, P and P' from one generated body (a third of the sines and
        // cosines of three separate calls)
        let map = model.map_derivatives(&mu, &mu_dot);
        let (q, p) = (map.phi, map.null_space);
        let v = p * mu_dot;
        let qdd = (p * accel_dt2) / dt2 + map.null_space_rate(&mu_dot) * mu_dot;
        // G G^T lambda = G (f + B^T u - M q'')
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
        self.check_output_jacobian(&p, t)?;
        self.record_step(State { t, q, v, u, lambda }, mu, mu_dot);
        Ok(())
    }

    /// Keep an accepted step: the state, `mu` and `mu'` for the scheme, the
    /// unknowns `self.z` for the predictor.
    fn record_step(&mut self, state: State<N, M, A>, mu: SVector<f64, F>, mu_dot: SVector<f64, F>) {
        self.state = state;
        self.past.push(mu, mu_dot);
        let [h0, h1, h2] = &mut self.history;
        std::mem::swap(h1, h2);
        std::mem::swap(h0, h1);
        h0.copy_from(&self.z);
        self.known = (self.known + 1).min(3);
        self.steps += 1;
    }

    /// After a step of the degenerate start in redundant coordinates (eqs.
    /// 22): follow it in minimal coordinates (`mu` by Gauss-Newton from the last
    /// step, `mu'` the projection of `q'`) so that the scheme's history and
    /// the predictor are those of the minimal formulation when it takes over,
    /// after the first step at which every rope carries at least
    /// [`DEGENERATE_TENSION_RATIO`] of the largest tension.
    fn follow_redundant(&mut self, state: State<N, M, A>) -> Result<(), Error> {
        let (model, dt, split) = (self.equations.model, self.equations.dt, F - A);
        let (mu, mut mu_dot, p) = minimal_coordinates(model, &state, self.past.value())?;
        // mu' as the minimal formulation has it (taking over the projection
        // of the redundant q' made the next minimal step fail at dt = 0.05):
        // nu1 from the scheme's formula on the mu1 history (eq. 24a), mu2^
        // from the servo constraint on velocity level (24d),
        // D1 phi_x nu1 + D2 phi_x mu2^ = gamma'(t)
        let formula = self.past.formula(self.scheme, dt);
        for i in 0..split {
            mu_dot[i] = formula.kinematics(i, mu[i], dt).0;
        }
        let off = N - A;
        self.set_output_jacobian(&p);
        let mut solve_servo = |rhs: &dyn Fn(usize) -> f64| -> Result<SVector<f64, A>, Error> {
            for i in 0..A {
                self.output_rhs[i] = rhs(i);
            }
            self.output_solver
                .solve(&self.output_jacobian, &mut self.output_rhs)
                .map_err(|_| Error::SingularOutputJacobian {
                    t: state.t,
                    condition: f64::INFINITY,
                })?;
            Ok(SVector::from_fn(|k, _| self.output_rhs[k]))
        };
        let [gamma_rate, gamma_accel] = [1, 2].map(|k| self.trajectory.derivative(state.t, k));
        let mu2_hat = solve_servo(&|i| gamma_rate[i] - (0..split).map(|j| p[(off + i, j)] * mu_dot[j]).sum::<f64>())?;
        for k in 0..A {
            mu_dot[split + k] = mu2_hat[k];
        }
        // and s = dt^2 mu2'' from the servo constraint on acceleration level (24c)
        let accel_dt2 = SVector::<f64, F>::from_fn(|i, _| {
            if i < split {
                formula.kinematics(i, mu[i], dt).1
            } else {
                0.0
            }
        });
        let curvature = model.null_space_rate(&mu, &mu_dot) * mu_dot; // its load rows are w (eq. 17)
        let s = solve_servo(&|i| {
            dt * dt * (gamma_accel[i] - curvature[off + i])
                - (0..split).map(|j| p[(off + i, j)] * accel_dt2[j]).sum::<f64>()
        })?;
        for i in 0..F {
            self.z[i] = mu[i];
        }
        for k in 0..A {
            self.z[F + k] = dt * mu_dot[split + k];
            self.z[F + A + k] = s[k];
            self.z[F + 2 * A + k] = dt * dt * state.u[k];
        }
        self.record_step(state, mu, mu_dot);
        self.redundant_steps += 1;
        if !degenerate(model, &state) {
            self.redundant_start = None;
        }
        Ok(())
    }

    /// How many of the first steps were taken in redundant coordinates
    /// because a rope was (nearly) slack (see [`DEGENERATE_TENSION_RATIO`]).
    pub fn redundant_start_steps(&self) -> usize {
        self.redundant_steps
    }

    /// `D2 phi_x`, the load rows of `P` in the columns of `mu2` (eq. 12),
    /// into the workspace `self.output_jacobian`.
    fn set_output_jacobian(&mut self, p: &SMatrix<f64, N, F>) {
        let (off, split) = (N - A, F - A);
        for i in 0..A {
            for k in 0..A {
                self.output_jacobian[(i, k)] = p[(off + i, split + k)];
            }
        }
    }

    /// Refuse an ill-conditioned `D2 phi_x` (eq. 12): 1-norm condition
    /// estimate `|D| |D^-1|` with the inverse from one LU.
    fn check_output_jacobian(&mut self, p: &SMatrix<f64, N, F>, t: f64) -> Result<(), Error> {
        self.set_output_jacobian(p);
        let norm1 = |m: &DMatrix<f64>| {
            m.column_iter()
                .map(|c| c.iter().map(|x| x.abs()).sum::<f64>())
                .fold(0.0, f64::max)
        };
        let d_norm = norm1(&self.output_jacobian);
        let inverse_norm = self.output_solver.inverse_norm1(&self.output_jacobian);
        let condition = d_norm * inverse_norm;
        if !(condition <= OUTPUT_JACOBIAN_CONDITION_LIMIT) {
            return Err(Error::SingularOutputJacobian { t, condition });
        }
        Ok(())
    }
}

/// Integrate eqs. (24a-e) from the redundant `start` to `options.tf` with `options.scheme`;
/// `mu_guess` is a rough guess of the minimal coordinates at the start.
pub fn simulate_minimal<Mdl, Tr, const N: usize, const M: usize, const A: usize, const F: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    mu_guess: &SVector<f64, F>,
    options: &Options,
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: MinimalMap<N, M, A, F>,
    Tr: Trajectory<A> + Clone,
{
    simulate_minimal_with_progress(model, trajectory, start, mu_guess, options, |_, _| {})
}

/// [`simulate_minimal`], calling `progress(step, steps)` after every step.
pub fn simulate_minimal_with_progress<Mdl, Tr, const N: usize, const M: usize, const A: usize, const F: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    mu_guess: &SVector<f64, F>,
    options: &Options,
    mut progress: impl FnMut(usize, usize),
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: MinimalMap<N, M, A, F>,
    Tr: Trajectory<A> + Clone,
{
    let steps = step_count(start.t, options.tf, options.dt)?;
    let mut stepper = MinimalStepper::with_scheme(
        model,
        trajectory,
        start,
        mu_guess,
        options.dt,
        options.scheme,
        options.newton,
    )?;
    let mut solution = record(model, start, &mut stepper, steps, options, &mut progress)?;
    solution.redundant_start_steps = stepper.redundant_start_steps();
    Ok(solution)
}

impl<Mdl, Tr, const N: usize, const M: usize, const A: usize, const F: usize> Stepper<N, M, A>
    for MinimalStepper<'_, Mdl, Tr, N, M, A, F>
where
    Mdl: MinimalMap<N, M, A, F>,
    Tr: Trajectory<A>,
{
    fn step(&mut self) -> Result<StepReport, Error> {
        MinimalStepper::step(self)
    }
    fn state(&self) -> &State<N, M, A> {
        MinimalStepper::state(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_dual::Dual64;

    crane_macros::crane_model! {
        /// An overhead crane with cart friction and a winch whose torque
        /// constant grows with the rope wound on (so that `df/dq'` and
        /// `d(B^T u)/dq` count), mapped to `mu = [c | a, b]`.
        #[crane(runtime = crate)]
        #[crane(no_self_test)]
        pub struct Overhead {
            params { mt = 10.0, J = 0.1, r = 0.1, m = 100.0, g = 9.81, d = 3.0 }
            robot  [s, beta]
            load   [xd, zd]
            inputs [uF, uM]
            kinetic = 0.5*mt*dot(s)^2 + 0.5*J*dot(beta)^2 + 0.5*m*(dot(xd)^2 + dot(zd)^2);
            forces { s: uF - d*dot(s), beta: uM*(1.0 + 0.01*beta), zd: m*g }
            constraints {
                rope: 0.5*((xd - s)^2 + zd^2 - (r*beta)^2),
            }
            minimal [c | a, b] {
                s = c;
                beta = sqrt((a - c)^2 + b^2)/r;
                xd = a;
                zd = b;
            }
        }
    }

    /// The iteration matrix built from the generated derivatives is the
    /// Jacobian of the residual: against forward-mode dual numbers pushed
    /// through the same residual (exact to round-off), at random points,
    /// histories and targets, for every scheme, entry by entry to 1e-12 of
    /// the largest entry (round-off of sums of ~10 terms: ~1e-15).
    #[test]
    fn iteration_matrix_is_the_jacobian_of_the_residual() {
        let mut seed = 11u64;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let model = Overhead::default();
        // read off the declaration: friction on dot(s), beta in the winch's force
        assert!(<Overhead as CraneModel<4, 1, 2>>::FORCES_DEPEND_ON_VELOCITY);
        assert!(<Overhead as CraneModel<4, 1, 2>>::FORCES_DEPEND_ON_POSITION);
        const DIM: usize = 3 + 3 * 2;
        for scheme in Scheme::ALL {
            for dt in [0.1, 0.01, 0.001] {
                for _ in 0..10 {
                    let past: Vec<SVector<f64, 3>> = (0..5).map(|_| SVector::from_fn(|_, _| rnd())).collect();
                    let rates: Vec<SVector<f64, 3>> = (0..5).map(|_| SVector::from_fn(|_, _| rnd())).collect();
                    let history = History::from_past(&past, &rates);
                    let target = [
                        SVector::from_fn(|_, _| rnd()),
                        SVector::from_fn(|_, _| rnd()),
                        SVector::from_fn(|_, _| rnd()),
                    ];
                    let equations: MinimalEquations<'_, Overhead, 4, 1, 2, 3> = MinimalEquations {
                        model: &model,
                        dt,
                        target,
                        formula: history.formula(scheme, dt),
                        blocks: [0..3, 3..5, 5..7, 7..9],
                    };
                    // the load 2 .. 6 m below the cart, moving, inputs of the crane's size
                    let z = DVector::from_fn(DIM, |i, _| match i {
                        0 | 1 => rnd(),
                        2 => 4.0 + 2.0 * rnd(),
                        3 | 4 => dt * rnd(),
                        5 | 6 => dt * dt * rnd(),
                        _ => dt * dt * 1000.0 * rnd(),
                    });
                    let mut jac = DMatrix::zeros(DIM, DIM);
                    equations.iteration_matrix(&equations.point(&|i| z[i]), &mut jac);
                    let mut dual = DMatrix::zeros(DIM, DIM);
                    for j in 0..DIM {
                        let point = equations.point(&|i| Dual64::new(z[i], if i == j { 1.0 } else { 0.0 }));
                        let column = equations.residual(&point);
                        write_residual(&column, |i, v| dual[(i, j)] = v.eps);
                    }
                    let worst = (&jac - &dual).amax();
                    assert!(
                        worst <= 1e-12 * dual.amax(),
                        "{scheme}, dt = {dt}: worst {worst:e} of {:e}\n{jac}\n{dual}",
                        dual.amax()
                    );
                }
            }
        }
    }
}
