//! What the models' unit tests share: a load path with every derivative
//! nonzero, and the check of an analytical reference against the declared
//! equations of motion.

use crane_runtime::{CraneModel, State, Trajectory};
use nalgebra::SVector;

/// A planar load path with nonzero derivatives of every order (so every
/// term of a reference counts): `x = 1 + 0.3 sin(1.3 t)`,
/// `z = z0 + 0.2 cos(0.7 t)`.
pub(crate) struct Wave {
    /// The mean height, m.
    pub(crate) z0: f64,
}

impl Trajectory<2> for Wave {
    fn derivative(&self, t: f64, k: usize) -> SVector<f64, 2> {
        let phase = k as f64 * std::f64::consts::FRAC_PI_2;
        let (x0, z0) = if k == 0 { (1.0, self.z0) } else { (0.0, 0.0) };
        SVector::from([
            x0 + 0.3 * 1.3f64.powi(k as i32) * (1.3 * t + phase).sin(),
            z0 + 0.2 * 0.7f64.powi(k as i32) * (0.7 * t + phase).cos(),
        ])
    }
}

/// Asserts that `reference(t)` satisfies `model`'s declared equations at
/// t = 0.3, 1.1, 2.7 s: the constraints to 1e-12, `M q'' = f + B^T u - G^T
/// lambda` on every row to 1e-4 with `q''` from central differences of the
/// reference's `q'` (h = 1e-4), and `q'` against central differences of `q`
/// to `velocity_tolerance`.
pub(crate) fn assert_satisfies_equations_of_motion<Mdl, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    reference: impl Fn(f64) -> State<N, M, A>,
    velocity_tolerance: f64,
) where
    Mdl: CraneModel<N, M, A>,
{
    let h = 1e-4;
    for t in [0.3, 1.1, 2.7] {
        let (r, after, before) = (reference(t), reference(t + h), reference(t - h));
        let a = (after.v - before.v) / (2.0 * h);
        let g = model.constraints(&r.q);
        assert!(g.amax() < 1e-12, "t = {t}: g = {g}");
        let residual = model.mass_matrix::<f64>() * a - model.forces(&r.q, &r.v) - model.input_matrix(&r.q) * r.u
            + model.constraint_jacobian(&r.q).transpose() * r.lambda;
        assert!(residual.amax() < 1e-4, "t = {t}: {residual}");
        let dq = (after.q - before.q) / (2.0 * h);
        assert!((dq - r.v).amax() < velocity_tolerance, "t = {t}: {}", dq - r.v);
    }
}
