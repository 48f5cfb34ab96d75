//! The residual of eqs. (24b-e) and its exact Jacobian, from the
//! derivatives the macro generates for a minimal map.

use std::ops::Range;

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::model::{MapDerivatives, MinimalMap, Scalar};
use crate::newton::normalised_residual;
use crate::problem::ServoTarget;
use crate::scheme::StepFormula;

/// The residual of eqs. (24b-e) at one step, in the unknowns
/// `z = [mu; dt mu2_hat; dt^2 mu2_tilde; dt^2 u]`.
#[derive(Clone)]
pub(super) struct MinimalEquations<const N: usize, const A: usize, const F: usize> {
    pub(super) dt: f64,
    pub(super) target: ServoTarget<A>,
    /// The scheme's affine maps `mu1 -> nu1, nu1'` for this step.
    pub(super) formula: StepFormula<F>,
    pub(super) blocks: [Range<usize>; 4],
}

/// One iterate of eqs. (24b-e) in the model's terms, generic over the scalar.
pub(super) struct Point<T: Scalar, const N: usize, const F: usize, const A: usize> {
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
pub(super) struct Residual<T: Scalar, const F: usize, const A: usize> {
    dynamics: SVector<T, F>,
    acceleration: SVector<T, A>,
    velocity: SVector<T, A>,
    position: SVector<T, A>,
}

impl<const N: usize, const A: usize, const F: usize> MinimalEquations<N, A, F> {
    /// Number of unknowns.
    pub(super) const DIM: usize = F + 3 * A;

    /// The equations of a run with step `dt` (the target and formula are
    /// set before each step).
    pub(super) fn new(dt: f64) -> Self {
        Self {
            dt,
            target: [SVector::zeros(); 3],
            formula: StepFormula {
                rate: f64::NAN,
                dt,
                value_offset: SVector::zeros(),
                rate_offset: SVector::zeros(),
                extended: None,
            },
            blocks: [0..F, F..F + A, F + A..F + 2 * A, F + 2 * A..F + 3 * A],
        }
    }

    /// `mu`, `mu'` and `dt^2 mu''` from the unknowns (`z(i)` reads unknown `i`).
    pub(super) fn kinematics<T: Scalar>(&self, z: &impl Fn(usize) -> T) -> [SVector<T, F>; 3] {
        let split = F - A;
        let dt = self.dt;
        let mu = SVector::<T, F>::from_fn(|i, _| z(i));
        let mut mu_dot = SVector::<T, F>::zeros();
        let mut accel_dt2 = SVector::<T, F>::zeros();
        for i in 0..F {
            (mu_dot[i], accel_dt2[i]) = if i < split {
                self.formula.kinematics(i, z(i)) // eq. (24a)
            } else {
                (z(F + i - split) * (1.0 / dt), z(F + A + i - split))
            };
        }
        [mu, mu_dot, accel_dt2]
    }

    /// The quantities at the iterate `z` that the residual and its Jacobian share.
    pub(super) fn point<Mdl, T, const M: usize>(&self, model: &Mdl, z: &impl Fn(usize) -> T) -> Point<T, N, F, A>
    where
        Mdl: MinimalMap<N, M, A, F>,
        T: Scalar,
    {
        let dt = self.dt;
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

    pub(super) fn residual<T: Scalar>(&self, x: &Point<T, N, F, A>) -> Residual<T, F, A> {
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
    pub(super) fn iteration_matrix<Mdl, const M: usize>(
        &self,
        model: &Mdl,
        x: &Point<f64, N, F, A>,
        jac: &mut DMatrix<f64>,
    ) where
        Mdl: MinimalMap<N, M, A, F>,
    {
        let dt = self.dt;
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
        let (split, off) = (F - A, N - A);
        let slopes = self.formula.slopes();
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
                (slopes.velocity, slopes.acceleration_dt2)
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

pub(super) fn write_residual<T: Scalar, const F: usize, const A: usize>(
    r: &Residual<T, F, A>,
    mut out: impl FnMut(usize, T),
) {
    for i in 0..F {
        out(i, r.dynamics[i]);
    }
    for k in 0..A {
        out(F + k, r.acceleration[k]);
        out(F + A + k, r.velocity[k]);
        out(F + 2 * A + k, r.position[k]);
    }
}

impl<const N: usize, const A: usize, const F: usize> MinimalEquations<N, A, F> {
    /// The residual and iteration matrix at `z` for `model`.
    pub(super) fn evaluate<Mdl, const M: usize>(
        &self,
        model: &Mdl,
        z: &DVector<f64>,
        r: &mut DVector<f64>,
        jac: &mut DMatrix<f64>,
    ) where
        Mdl: MinimalMap<N, M, A, F>,
    {
        let point = self.point(model, &|i| z[i]);
        write_residual(&self.residual(&point), |i, v| r[i] = v);
        self.iteration_matrix(model, &point, jac);
    }

    /// The normalised residual of [`evaluate`](Self::evaluate)'s `r` and
    /// `jac` at `z`
    /// ([`NonlinearSystem::normalised_residual`](crate::newton::NonlinearSystem::normalised_residual)).
    pub(super) fn normalised_residual(&self, z: &DVector<f64>, r: &DVector<f64>, jac: &DMatrix<f64>) -> f64 {
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::CraneModel;
    use crate::scheme::{History, Scheme};
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
        const { assert!(<Overhead as CraneModel<4, 1, 2>>::FORCES_DEPEND_ON_VELOCITY) };
        const { assert!(<Overhead as CraneModel<4, 1, 2>>::FORCES_DEPEND_ON_POSITION) };
        const DIM: usize = 3 + 3 * 2;
        for scheme in Scheme::ALL {
            for dt in [0.1, 0.01, 0.001] {
                for _ in 0..10 {
                    let past: Vec<SVector<f64, 3>> = (0..5).map(|_| SVector::from_fn(|_, _| rnd())).collect();
                    let rates: Vec<SVector<f64, 3>> = (0..5).map(|_| SVector::from_fn(|_, _| rnd())).collect();
                    let history = History::from_past(scheme, &past, &rates).expect("a past");
                    let target = [
                        SVector::from_fn(|_, _| rnd()),
                        SVector::from_fn(|_, _| rnd()),
                        SVector::from_fn(|_, _| rnd()),
                    ];
                    let mut equations = MinimalEquations::<4, 2, 3>::new(dt);
                    equations.target = target;
                    equations.formula = history.formula(dt);
                    // the load 2 .. 6 m below the cart, moving, inputs of the crane's size
                    let z = DVector::from_fn(DIM, |i, _| match i {
                        0 | 1 => rnd(),
                        2 => 4.0 + 2.0 * rnd(),
                        3 | 4 => dt * rnd(),
                        5 | 6 => dt * dt * rnd(),
                        _ => dt * dt * 1000.0 * rnd(),
                    });
                    let mut jac = DMatrix::zeros(DIM, DIM);
                    equations.iteration_matrix(&model, &equations.point(&model, &|i| z[i]), &mut jac);
                    let mut dual = DMatrix::zeros(DIM, DIM);
                    for j in 0..DIM {
                        let point = equations.point(&model, &|i| Dual64::new(z[i], if i == j { 1.0 } else { 0.0 }));
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
