//! Analytical flatness-based solution of the 3D gantry crane (not in the
//! paper; written from the load's equations of motion, independently of the
//! generated model code).
//!
//! The load hangs from the trolley's rope exit `(X, Y, 0)` on the rope `L`.
//! Its equations of motion, `m_l x'' = -lambda (x - X)`, `m_l y'' = -lambda
//! (y - Y)`, `m_l z'' = -lambda z - m_l g` (with the rope constraint
//! `1/2 ((x - X)^2 + (y - Y)^2 + z^2 - L^2)`, `M q'' = f + B^T u - G^T
//! lambda`), give the multiplier and the trolley from the load's path alone:
//! ```text
//! lambda = -m_l (z'' + g) / z,   X = x - z x'' / (z'' + g),   Y = y - z y'' / (z'' + g),
//! L = |(x - X, y - Y, z)|
//! ```
//! (the rope points along the load's acceleration minus gravity): the crane
//! is differentially flat with the load coordinates as flat outputs. The
//! robot rows then give the inputs,
//! ```text
//! u1 = (m_b + m_t) X'' - lambda (x - X),   u2 = m_t Y'' - lambda (y - Y),
//! u3 = r (J / r^2 L'' - lambda L)
//! ```
//! with `X'', Y'', L''` from the load's derivatives up to order 4. As for
//! Appendix A, second-order time-Taylor dual numbers carry `X, Y, L` with
//! their first and second time derivatives exactly.

use crane_runtime::Trajectory;
use nalgebra::SVector;
use num_dual::{Dual2, DualNum};

use super::model::Gantry3d;

/// The reference at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceState {
    /// `q = [X, Y, L, x, y, z]`.
    pub q: SVector<f64, 6>,
    /// `q'`.
    pub v: SVector<f64, 6>,
    /// `q''`.
    pub a: SVector<f64, 6>,
    /// `[u1, u2, u3]`: bridge force, trolley force, winch torque.
    pub u: SVector<f64, 3>,
    /// The rope's multiplier; its tension is `lambda L`.
    pub lambda: SVector<f64, 1>,
}

/// The reference from the load's derivatives `derivs[k] = x^(k)`, `k = 0..=4`.
pub fn reference(p: &Gantry3d, derivs: &[SVector<f64, 3>; 5]) -> ReferenceState {
    let taylor = |k: usize, i: usize| Dual2::<f64>::new(derivs[k][i], derivs[k + 1][i], derivs[k + 2][i]);
    let [x, y, z] = [0, 1, 2].map(|i| taylor(0, i));
    let [xdd, ydd, zdd] = [0, 1, 2].map(|i| taylor(2, i));
    let lift = zdd + p.g;
    let big_x = x - z * xdd / lift;
    let big_y = y - z * ydd / lift;
    let rope = ((x - big_x).powi(2) + (y - big_y).powi(2) + z * z).sqrt();
    let lambda = -(lift * p.m_l / z).re;
    let coordinates = [big_x, big_y, rope, x, y, z];
    let q = SVector::from_fn(|i, _| coordinates[i].re);
    let v = SVector::from_fn(|i, _| coordinates[i].v1);
    let a = SVector::from_fn(|i, _| coordinates[i].v2);
    let u = SVector::from([
        (p.m_b + p.m_t) * a[0] - lambda * (q[3] - q[0]),
        p.m_t * a[1] - lambda * (q[4] - q[1]),
        p.r * (p.J / (p.r * p.r) * a[2] - lambda * q[2]),
    ]);
    ReferenceState {
        q,
        v,
        a,
        u,
        lambda: SVector::from([lambda]),
    }
}

/// [`reference()`] at time `t` of a load path.
pub fn reference_at(p: &Gantry3d, path: &impl Trajectory<3>, t: f64) -> ReferenceState {
    reference(p, &std::array::from_fn(|k| path.derivative(t, k)))
}
