//! Analytical flatness-based solution of the 3D US Navy crane with massless
//! main pulley (sect. 6.1). The paper gives none for the 3D cranes; this one
//! reduces the 3D crane to the planar crane of Appendix A in the plane of the
//! ropes.
//!
//! # Derivation
//! Load: `m_l x'' = -m_l g e_z - lambda4 (x - B)` (rows `x, y, z` of eq. 1a
//! with (80), (81)), so the load rope pulls along `a = x'' + g e_z`: with
//! `d = a/|a|` the pulley is `B = x + s d`, `s = L2 - L0`, and the rope
//! tension is `N2 = lambda4 s = m_l |a|`. The massless `L0` row gives
//! `lambda3 L0 = lambda4 (L2 - L0)`: the segment `PB` carries `N2` too. The
//! massless pulley rows read
//! ```text
//! N1 e_BA + N2 (e_BP - d) = 0,          N1 = lambda2 L1,
//! ```
//! so `B`, `A`, `P` and the load rope are coplanar. `A` and `P` lie on the
//! boom line through `O`, hence the load-rope line `x + sigma d` meets the
//! boom line, in a point `D = rho b(phi)` with
//! `b(phi) = (sin(alpha) cos(phi), sin(alpha) sin(phi), cos(alpha))`,
//! `rho > 0`. Eliminating `rho` and `phi` leaves a quadratic in `sigma`
//! (the line meets the upper nappe of the cone of half-angle `alpha` about
//! the `Z`-axis): `|x_h + sigma d_h|^2 = tan(alpha)^2 (z + sigma d_z)^2`,
//! `z + sigma d_z > 0`. Then `phi = atan2(D_y, D_x)` is the slewing angle
//! and `P = (k + l) b(phi)`, `A = beta1 P`.
//!
//! In the plane of `b` and `d` the rest is the planar crane of Appendix A
//! with the boom tip `P` as origin, "vertical" `d` (so that the load rope
//! is "vertical", `theta = 0`), boom angle `alpha'` between `b` and `d`, and
//! `l' = |PA| = (1 - beta1)(k + l)`: with `x'` the load's offset from `P`
//! perpendicular to `d`, eqs. (105)-(108) with docs/errata.md give
//! ```text
//! d' sin(alpha') = -x',    sin(beta) = (1 - d'/l') sin(alpha'),
//! gamma = (beta - alpha' + pi)/2,
//! L1 = l' sin(beta)/sin(gamma),    L0 = l' sin(gamma - beta)/sin(gamma),
//! B = P - L0 (sin(alpha' - beta) e_x' + cos(alpha' - beta) d),
//! N1 = 2 N2 cos(gamma)     (eq. 106).
//! ```
//! The boom rows `(x2, y2)` then give the slewing torque and `lambda1`
//! (tangential and radial parts), the winch rows `u1, u2` (as eq. 110):
//! ```text
//! u3 = r (M P_h'' - F_h) . t,     lambda1 = (F_h - M P_h'') . e_r / r,
//! u1 = J1/r1 L1'' - r1 N1,        u2 = J2/r2 L2'' - r2 N2,
//! ```
//! with `F_h = beta1 lambda2 (B - A)_h + lambda3 (B - P)_h` the horizontal
//! pull of ropes `L1`, `L0` on the boom, `M = J_b/r^2`, `e_r = (cos phi,
//! sin phi)`, `t = (-sin phi, cos phi)`.
//!
//! As for Appendix A, [`reference()`] pushes second-order time-Taylor dual
//! numbers through the algebraic part: `q` depends on `x, x''`, `q'` on
//! `x, ..., x'''`, `q''` and `u` on `x, ..., x''''`.
//!
//! # The degenerate start
//! At `t0` the load rests below `P` (`d = e_z`, `x' = 0`): then `d' = 0`,
//! `beta = alpha'`, `gamma = pi/2`, `N1 = 0`: the pulley at the height of
//! `A`, which is the paper's `p0` (eq. 87), the limit `t -> 0+` of this
//! solution (all functions involved are smooth there, as in Appendix A).

use super::model::Navy3d;
use crane_runtime::{Scalar, Trajectory};
use nalgebra::SVector;
use num_dual::Dual2;
use std::f64::consts::PI;

/// Radius `r = (k + l) sin(alpha)` of the circle of the boom tip `P`.
pub fn boom_radius(model: &Navy3d) -> f64 {
    (model.k + model.l) * model.alpha.sin()
}

type V3<T> = [T; 3];

fn dot<T: Scalar>(a: V3<T>, b: V3<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub<T: Scalar>(a: V3<T>, b: V3<T>) -> V3<T> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn axpy<T: Scalar>(s: T, a: V3<T>, b: V3<T>) -> V3<T> {
    [a[0] * s + b[0], a[1] * s + b[1], a[2] * s + b[2]]
}

fn scale<T: Scalar>(s: T, a: V3<T>) -> V3<T> {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// The algebraic part of the flatness solution for one scalar type.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatConfiguration<T: Scalar> {
    /// `q = [L1, L2, L0, x0, y0, z0, x2, y2, x, y, z]` (eqs. 68-69).
    pub q: SVector<T, 11>,
    /// Slewing angle `phi = atan2(y2, x2)`.
    pub phi: T,
    /// Half the angle `PBC` at the pulley (`C` the load), as in eq. (106).
    pub gamma: T,
    /// Tension of rope `L1`, `N1 = 2 N2 cos(gamma)`.
    pub n1: T,
    /// Tension of the hoist rope (load rope and segment `PB`), `N2 = m_l |x'' + g e_z|`.
    pub n2: T,
}

/// Coordinates and tensions from the load position `x` and acceleration
/// `xdd` (see the module docs). `None` where the load rope does not meet
/// the boom's cone (`z'' + g <= 0` or a rope tilted so far that the cone
/// intersection does not exist).
pub fn flat_configuration<T: Scalar>(params: &Navy3d, x: V3<T>, xdd: V3<T>) -> Option<FlatConfiguration<T>> {
    let Navy3d {
        m_l,
        alpha,
        k,
        l,
        beta1,
        g,
        ..
    } = *params;
    let boom = k + l;
    let (sin_a, cos_a) = alpha.sin_cos();
    let tan2 = (sin_a / cos_a).powi(2);

    // the load rope's direction, from the load's equation of motion
    let acc = [xdd[0], xdd[1], xdd[2] + g];
    let norm_a = dot(acc, acc).sqrt();
    let n2 = norm_a * m_l;
    let d = scale(norm_a.recip(), acc);
    if d[2].re() <= 0.0 {
        return None;
    }

    // where the rope line x + sigma d meets the boom's cone (upper nappe)
    let qa = d[0] * d[0] + d[1] * d[1] - d[2] * d[2] * tan2;
    let qb = x[0] * d[0] + x[1] * d[1] - x[2] * d[2] * tan2;
    let qc = x[0] * x[0] + x[1] * x[1] - x[2] * x[2] * tan2;
    let disc = qb * qb - qa * qc;
    if disc.re() < 0.0 || qa.re() == 0.0 {
        return None;
    }
    let roots = [(-qb - disc.sqrt()) / qa, (-qb + disc.sqrt()) / qa];
    // the root on the upper nappe (z > 0); of two, the nearer to the load
    let sigma = roots
        .into_iter()
        .filter(|s| (x[2] + d[2] * *s).re() > 0.0)
        .min_by(|a, b| a.re().abs().total_cmp(&b.re().abs()))?;
    let meet = axpy(sigma, d, x);
    let phi = meet[1].atan2(meet[0]);
    let (sin_p, cos_p) = phi.sin_cos();
    let b = [cos_p * sin_a, sin_p * sin_a, T::from(cos_a)];
    let tip = scale(T::from(boom), b);

    // the planar crane of Appendix A in the plane of b and d
    let b_d = dot(b, d);
    let perp = axpy(-b_d, d, b);
    let perp_norm = dot(perp, perp).sqrt();
    let e_x = scale(perp_norm.recip(), perp);
    let alpha_p = perp_norm.atan2(b_d);
    let arm = (1.0 - beta1) * boom; // l' = |PA|
    let x_p = dot(sub(x, tip), e_x);
    let d_p = -x_p / alpha_p.sin(); // (105), theta = 0
    let beta = ((-d_p / arm + 1.0) * alpha_p.sin()).asin();
    let gamma = (beta - alpha_p + PI) * 0.5; // (107)
    let sin_g = gamma.sin();
    let l1 = beta.sin() * arm / sin_g; // (108)
    let l0 = (gamma - beta).sin() * arm / sin_g;
    let (sin_ab, cos_ab) = (alpha_p - beta).sin_cos();
    let pulley = sub(tip, axpy(l0 * cos_ab, d, scale(l0 * sin_ab, e_x)));
    let hoist = sub(x, pulley);
    let l2 = l0 + dot(hoist, hoist).sqrt();
    let n1 = n2 * gamma.cos() * 2.0; // (106)

    Some(FlatConfiguration {
        q: SVector::<T, 11>::from_column_slice(&[
            l1, l2, l0, pulley[0], pulley[1], pulley[2], tip[0], tip[1], x[0], x[1], x[2],
        ]),
        phi,
        gamma,
        n1,
        n2,
    })
}

/// The analytical reference at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceState {
    /// Coordinates `q = [L1, L2, L0, x0, y0, z0, x2, y2, x, y, z]`.
    pub q: SVector<f64, 11>,
    /// Velocities `q'`.
    pub v: SVector<f64, 11>,
    /// Accelerations `q''`.
    pub a: SVector<f64, 11>,
    /// Inputs `[u1, u2, u3]`.
    pub u: SVector<f64, 3>,
    /// Multipliers of `[slew, rope1, rope0, hoist]` (eq. 78).
    pub lambda: SVector<f64, 4>,
    /// Rope tensions `[N1, N2]` in the order of the model's ropes.
    pub tensions: [f64; 2],
    /// Slewing angle `phi`.
    pub phi: f64,
}

/// The flatness-based reference from the load path's derivatives
/// `derivs[k] = x^(k)`, `k = 0..=4`; `None` where
/// [`flat_configuration`] has no solution.
pub fn reference(params: &Navy3d, derivs: &[SVector<f64, 3>; 5]) -> Option<ReferenceState> {
    let taylor = |k: usize, i: usize| Dual2::new(derivs[k][i], derivs[k + 1][i], derivs[k + 2][i]);
    let flat = flat_configuration(
        params,
        [taylor(0, 0), taylor(0, 1), taylor(0, 2)],
        [taylor(2, 0), taylor(2, 1), taylor(2, 2)],
    )?;
    let q = flat.q.map(|c| c.re);
    let v = flat.q.map(|c| c.v1);
    let a = flat.q.map(|c| c.v2);
    let (n1, n2) = (flat.n1.re, flat.n2.re);
    let (l1, l2, l0) = (q[0], q[1], q[2]);
    let lambda2 = n1 / l1;
    let lambda3 = n2 / l0; // N0 = N2 over the massless pulley
    let lambda4 = n2 / (l2 - l0);

    // boom rows (x2, y2): M P'' = u3/r^2 (-y2, x2) - lambda1 (x2, y2) + F
    let Navy3d {
        J_b, J1, J2, r1, r2, ..
    } = *params;
    let r = boom_radius(params);
    let mass = J_b / (r * r);
    let b1 = params.beta1;
    let (x0, y0, x2, y2) = (q[3], q[4], q[6], q[7]);
    let force = [
        b1 * lambda2 * (x0 - b1 * x2) + lambda3 * (x0 - x2),
        b1 * lambda2 * (y0 - b1 * y2) + lambda3 * (y0 - y2),
    ];
    let (cos_p, sin_p) = (x2 / r, y2 / r);
    let tangential = (mass * a[6] - force[0]) * -sin_p + (mass * a[7] - force[1]) * cos_p;
    let radial = (force[0] - mass * a[6]) * cos_p + (force[1] - mass * a[7]) * sin_p;
    let u = SVector::<f64, 3>::new(J1 / r1 * a[0] - r1 * n1, J2 / r2 * a[1] - r2 * n2, r * tangential);
    let lambda = SVector::<f64, 4>::new(radial / r, lambda2, lambda3, lambda4);
    Some(ReferenceState {
        q,
        v,
        a,
        u,
        lambda,
        tensions: [n1, n2],
        phi: flat.phi.re,
    })
}

/// [`reference()`] at time `t` of a load path.
pub fn reference_at(params: &Navy3d, path: &impl Trajectory<3>, t: f64) -> Option<ReferenceState> {
    let derivs = std::array::from_fn(|k| path.derivative(t, k));
    reference(params, &derivs)
}
