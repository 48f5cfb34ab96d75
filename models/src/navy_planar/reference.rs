//! Analytical flatness-based solution of the planar US Navy crane with
//! massless main pulley (paper, Appendix A, eqs. 101-110, with the docs/errata.md
//! for (105) and (108)).
//!
//! Geometry: winch 2 at the boom tip `P` (the origin), winch 1 at
//! `A = (-l sin(alpha), -l cos(alpha))`, pulley `B = (x0, z0)`, load
//! `C = (x, z)`. The crane is differentially flat with the load coordinates
//! as flat outputs: the coordinates `q` follow from `x, x''` and the inputs
//! `u` from `x, ..., x''''` (eqs. 111-112).
//!
//! [`flat_configuration`] evaluates the algebraic part (101)-(109) for any
//! [`Scalar`]. [`reference()`] pushes second-order time-Taylor dual numbers
//! through it: with `x = (x, x', x'')` and `x'' = (x'', x''', x'''')` as
//! [`Dual2`] numbers, every output carries its value, first and second time
//! derivative, which gives the velocities `q'`, the accelerations `q''` and
//! with them the winch torques (110) exactly (no finite differences).
//!
//! # The degenerate start
//! At the paper's start (46) the load hangs at rest straight below `P`
//! (`x = 0`, `x'' = 0`): rope `L1` is slack and the static balance alone
//! leaves the pulley height free (docs/errata.md, "Degenerate starts"). The
//! formulas below are nevertheless regular there and need no special case:
//! `theta = 0` (102) and the load-rope line passes through `P`, so `D = P`,
//! `d = 0` (105), `beta = alpha`, `gamma = pi/2` (107): `AB` is perpendicular
//! to the straight line `PBC`, which is the bisector condition of (106) in
//! the limit of a straight angle `PBC`. All functions involved (`atan2`
//! with `z'' + g > 0`, `asin` at `sin(alpha) < 1`, `1/sin(gamma)` at
//! `gamma = pi/2`, `1/sin(alpha + theta)`) are smooth there, so this value is
//! also the limit `t -> t0+` of the flatness solution, and it is the printed
//! `p0 = [5 sqrt 3, 10, 5, 0, -5]` with `N1 = lambda1 = 0` (up to round-off
//! from `cos(pi/2)`).

use super::model::NavyPlanar;
use crane_runtime::{Scalar, Trajectory};
use nalgebra::SVector;
use num_dual::Dual2;
use std::f64::consts::PI;

/// The algebraic part of the flatness solution, eqs. (101)-(109), for one
/// scalar type.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatConfiguration<T: Scalar> {
    /// `q = [L1, L2, L0, x0, z0, x, z]` (eq. 108).
    pub q: SVector<T, 7>,
    /// Angle of the load rope `BC` with the vertical (eq. 102).
    pub theta: T,
    /// `d = |PD|`, `D` where the load-rope line meets the boom line (eq. 105,
    /// docs/errata.md); positive when `D` lies on the ray from `P` towards `A`.
    pub d: T,
    /// Angle `APB` at the boom tip (eq. 105).
    pub beta: T,
    /// Half the angle `PBC` at the pulley (eqs. 106-107).
    pub gamma: T,
    /// Tension in rope 1 (`AB`), `N1 = 2 N2 cos(gamma)` (eq. 106).
    pub n1: T,
    /// Tension in the hoist rope (`BC`, and `PB`: `N0 = N2`), eq. (109).
    pub n2: T,
}

/// Coordinates and tensions from the load position `x = [x, z]` and its
/// acceleration `xdd = [x'', z'']`, eqs. (101)-(109) with the docs/errata.md.
///
/// Generic so that dual numbers can carry time derivatives through it (see
/// [`reference()`]). Requires `z'' + g > 0` (the hoist rope can only pull the
/// load upwards).
pub fn flat_configuration<T: Scalar>(params: &NavyPlanar, x: [T; 2], xdd: [T; 2]) -> FlatConfiguration<T> {
    let [x, z] = x;
    let [xdd, zdd] = xdd;
    let NavyPlanar { m_l, alpha, l, g, .. } = *params;
    let zg = zdd + g;

    // (102): tan(theta) = -x'' / (z'' + g), from Newton's law (101) for the load.
    let theta = (-xdd).atan2(zg);
    let (sin_t, cos_t) = theta.sin_cos();

    // (105) with docs/errata.md: D = C + s (sin theta, -cos theta) = -d (sin alpha, cos alpha);
    // eliminating s gives d sin(alpha + theta) = -(x cos theta + z sin theta).
    let sin_at = (theta + alpha).sin();
    let d = -(x * cos_t + z * sin_t) / sin_at;
    // (105): sin(beta) = (1 - d/l) sin(alpha + theta), from (103)-(104).
    let beta = ((-d / l + 1.0) * sin_at).asin();
    // (107): AB bisects the angle PBC (force balance (106) at the massless pulley).
    let gamma = (beta - alpha - theta + PI) * 0.5;

    // (108), law of sines in the triangle PAB, with docs/errata.md x0 = -L0 sin(alpha - beta).
    let sin_g = gamma.sin();
    let l1 = beta.sin() * l / sin_g;
    let l0 = (gamma - beta).sin() * l / sin_g;
    let (sin_ab, cos_ab) = (-beta + alpha).sin_cos();
    let x0 = -l0 * sin_ab;
    let z0 = -l0 * cos_ab;
    let (dx, dz) = (x - x0, z - z0);
    let len = (dx * dx + dz * dz).sqrt();
    let l2 = l0 + len;

    // (109) and (106).
    let n2 = (xdd * xdd + zg * zg).sqrt() * m_l;
    let n1 = n2 * gamma.cos() * 2.0;

    FlatConfiguration {
        q: SVector::<T, 7>::from_column_slice(&[l1, l2, l0, x0, z0, x, z]),
        theta,
        d,
        beta,
        gamma,
        n1,
        n2,
    }
}

/// The analytical reference at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceState {
    /// Coordinates `q = [L1, L2, L0, x0, z0, x, z]` (eq. 108).
    pub q: SVector<f64, 7>,
    /// Velocities `q'`.
    pub v: SVector<f64, 7>,
    /// Accelerations `q''` (the winch rows `L1'', L2''` enter (110)).
    pub a: SVector<f64, 7>,
    /// Winch torques `[u1, u2]` (eq. 110).
    pub u: SVector<f64, 2>,
    /// Multipliers of the constraints `[rope1, rope0, hoist]` of eq. (33):
    /// `[N1/L1, N0/L0, N2/(L2 - L0)]` (tension `N = lambda L` for the 1/2-scaled
    /// rope constraints; signs from `M q'' = f + B^T u - G^T lambda`).
    pub lambda: SVector<f64, 3>,
    /// Rope tensions `[N1, N2]` (eqs. 106, 109), in the order of the model's
    /// ropes; the rope `PB` carries `N0 = N2`.
    pub tensions: [f64; 2],
}

/// The flatness-based reference (Appendix A) from the load path's
/// derivatives `derivs[k] = x^(k)`, `k = 0..=4`.
///
/// `q` depends on `x, x''`; `q'` additionally on `x', x'''`; `q''` and `u`
/// on all of them up to `x''''` (eqs. 111-112).
pub fn reference(params: &NavyPlanar, derivs: &[SVector<f64, 2>; 5]) -> ReferenceState {
    // Second-order Taylor expansions in time of the position and of the acceleration.
    let taylor = |k: usize, i: usize| Dual2::new(derivs[k][i], derivs[k + 1][i], derivs[k + 2][i]);
    let flat = flat_configuration(params, [taylor(0, 0), taylor(0, 1)], [taylor(2, 0), taylor(2, 1)]);

    let q = flat.q.map(|c| c.re);
    let v = flat.q.map(|c| c.v1);
    let a = flat.q.map(|c| c.v2);
    let (n1, n2) = (flat.n1.re, flat.n2.re);
    let n0 = n2; // (106): one rope runs over the massless pulley.

    // (110), torque balance at the winches; L2'' = L0'' + L''.
    let u = SVector::<f64, 2>::new(
        params.J1 / params.r1 * a[0] - n1 * params.r1,
        params.J2 / params.r2 * a[1] - n0 * params.r2,
    );
    let lambda = SVector::<f64, 3>::new(n1 / q[0], n0 / q[2], n2 / (q[1] - q[2]));

    ReferenceState {
        q,
        v,
        a,
        u,
        lambda,
        tensions: [n1, n2],
    }
}

/// [`reference()`] at time `t` of a load path.
pub fn reference_at(params: &NavyPlanar, path: &impl Trajectory<2>, t: f64) -> ReferenceState {
    let derivs = std::array::from_fn(|k| path.derivative(t, k));
    reference(params, &derivs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::SMatrix;

    /// The paper's rest-to-rest path (41)-(45): `gamma0 = (0, -10)`,
    /// `gammaf = (-3, -14)`, `t0 = 0`, `tf = 4 s`, 5-6-7-8-9 polynomial `c`.
    /// (A local stand-in for the runtime's `Poly9`, so that these tests check
    /// the reference on its own.)
    struct PaperPath;

    impl Trajectory<2> for PaperPath {
        fn derivative(&self, t: f64, k: usize) -> SVector<f64, 2> {
            let (t0, tf) = (0.0, 4.0);
            let g0 = SVector::<f64, 2>::new(0.0, -10.0);
            let gf = SVector::<f64, 2>::new(-3.0, -14.0);
            let tau = (t - t0) / (tf - t0);
            // c(tau) = 126 tau^5 - 420 tau^6 + 540 tau^7 - 315 tau^8 + 70 tau^9 (44),
            // differentiated k times coefficient-wise.
            let mut coeffs = [0.0, 0.0, 0.0, 0.0, 0.0, 126.0, -420.0, 540.0, -315.0, 70.0];
            for _ in 0..k {
                for j in 0..9 {
                    coeffs[j] = (j + 1) as f64 * coeffs[j + 1];
                }
                coeffs[9] = 0.0;
            }
            let c = coeffs.iter().rev().fold(0.0, |acc, &cj| acc * tau + cj);
            if k == 0 {
                g0 + (gf - g0) * c
            } else {
                (gf - g0) * (c * (tf - t0).powi(-(k as i32)))
            }
        }
    }

    /// `n` equally spaced times strictly inside `(t0, tf)`.
    fn times(n: usize) -> impl Iterator<Item = f64> {
        (1..=n).map(move |i| 4.0 * i as f64 / (n + 1) as f64)
    }

    /// `g(q)` and `G(q)` of eqs. (33), (35), written out here so that these
    /// unit tests need no model (`crane-tests` repeats the check with the
    /// hand-written model).
    fn constraints_and_jacobian(p: &NavyPlanar, q: &SVector<f64, 7>) -> (SVector<f64, 3>, SMatrix<f64, 3, 7>) {
        let [l1, l2, l0, x0, z0, x, z] = [q[0], q[1], q[2], q[3], q[4], q[5], q[6]];
        let (ax, az) = (x0 + p.l * p.alpha.sin(), z0 + p.l * p.alpha.cos());
        let g = SVector::<f64, 3>::new(
            0.5 * (ax * ax + az * az - l1 * l1),
            0.5 * (x0 * x0 + z0 * z0 - l0 * l0),
            0.5 * ((x - x0).powi(2) + (z - z0).powi(2) - (l2 - l0).powi(2)),
        );
        #[rustfmt::skip]
        let jac = SMatrix::<f64, 3, 7>::from_row_slice(&[
            -l1, 0.0,     0.0,     ax,     az,     0.0,    0.0,
            0.0, 0.0,     -l0,     x0,     z0,     0.0,    0.0,
            0.0, l0 - l2, l2 - l0, x0 - x, z0 - z, x - x0, z - z0,
        ]);
        (g, jac)
    }

    /// `M q'' - f - B^T u + G^T lambda` (eq. 1a with (29), (34), (35)).
    fn residual(p: &NavyPlanar, s: &ReferenceState) -> SVector<f64, 7> {
        let (_, jac) = constraints_and_jacobian(p, &s.q);
        let mass = SVector::<f64, 7>::from_column_slice(&[
            p.J1 / (p.r1 * p.r1),
            p.J2 / (p.r2 * p.r2),
            0.0,
            0.0,
            0.0,
            p.m_l,
            p.m_l,
        ]);
        let mut rhs = -(jac.transpose() * s.lambda);
        rhs[0] += s.u[0] / p.r1;
        rhs[1] += s.u[1] / p.r2;
        rhs[6] -= p.m_l * p.g;
        mass.component_mul(&s.a) - rhs
    }

    /// Eqs. (46)-(47) at t0, with the slack rope 1.
    #[test]
    fn paper_start() {
        let p = NavyPlanar::default();
        let s = reference_at(&p, &PaperPath, 0.0);
        let expected = [5.0 * 3f64.sqrt(), 10.0, 5.0, 0.0, -5.0, 0.0, -10.0];
        for (i, e) in expected.iter().enumerate() {
            assert!((s.q[i] - e).abs() < 1e-10, "q[{i}] = {} != {e}", s.q[i]);
        }
        let all = s.q.iter().chain(&s.v).chain(&s.a).chain(&s.u).chain(&s.lambda);
        assert!(all.copied().all(f64::is_finite));
        assert!(s.v.amax() == 0.0 && s.a.amax() == 0.0, "at rest: {:?} {:?}", s.v, s.a);
        // N1 = 2 N2 cos(pi/2): zero up to round-off (2 * 981 * 6e-17).
        assert!(s.lambda[0].abs() < 1e-12, "lambda1 = {}", s.lambda[0]);
        assert!(s.tensions[0].abs() < 1e-12);
        assert!((s.tensions[1] - 981.0).abs() < 1e-10);
        assert!((s.lambda[1] - 981.0 / 5.0).abs() < 1e-10 && (s.lambda[2] - 981.0 / 5.0).abs() < 1e-10);
        // Static torques: u1 = 0 (slack rope), u2 = -N0 r2 = -98.1.
        assert!(s.u[0].abs() < 1e-12);
        assert!((s.u[1] + 98.1).abs() < 1e-12);
        assert!(residual(&p, &s).amax() < 1e-10);
        // The printed p0 is the limit t -> t0+ of the flatness solution: near t0,
        // x'' ~ t^3 (c ~ tau^5), and theta, beta - alpha, pi/2 - gamma and
        // q - q(t0) are O(t^3) (measured |q - q(t0)| = 3.8e-9 at t = 1e-3,
        // 3.8e-12 at t = 1e-4).
        for (t, bound) in [(1e-3, 1e-8), (1e-4, 1e-11)] {
            let near = reference_at(&p, &PaperPath, t);
            let dq = (near.q - s.q).amax();
            assert!(dq < bound, "t = {t}: |q - q(t0)| = {dq:e}");
        }
    }

    /// The end state is a regular equilibrium with the load at rest at gammaf.
    #[test]
    fn paper_end_is_equilibrium() {
        let p = NavyPlanar::default();
        let s = reference_at(&p, &PaperPath, 4.0);
        assert_eq!((s.q[5], s.q[6]), (-3.0, -14.0));
        assert!(s.v.amax() < 1e-12 && s.a.amax() < 1e-12);
        assert!(residual(&p, &s).amax() < 1e-10);
        assert!(s.tensions[0] > 1.0, "rope 1 is taut at the end: {:?}", s.tensions);
    }

    /// `g(q) = 0`, `G q' = 0` and the equations of motion along the path, with
    /// `q''` from the Taylor duals: all hold to round-off. Rows `L1`, `L2` hold
    /// by construction of (110); rows `L0, x0, z0` are the force balance at
    /// the massless pulley, rows `x, z` Newton's law (101) for the load.
    #[test]
    fn satisfies_constraints_and_equations_of_motion() {
        let p = NavyPlanar::default();
        let scale = p.m_l * p.g;
        for t in times(50) {
            let s = reference_at(&p, &PaperPath, t);
            let (g, jac) = constraints_and_jacobian(&p, &s.q);
            assert!(g.amax() < 1e-12, "g = {g:?} at t = {t}");
            assert!((jac * s.v).amax() < 1e-11, "G q' at t = {t}");
            let r = residual(&p, &s);
            assert!(r.amax() < 1e-12 * scale, "residual {r:?} at t = {t}");
            assert!(
                s.tensions[0] > 0.0 && s.tensions[1] > 0.0,
                "tensions {:?} at t = {t}",
                s.tensions
            );
        }
    }

    /// `q'` and `q''` from the duals against central differences of `q(t)`.
    /// These err by `h^2/6 q'''` and `h^2/12 q''''` (order 2) plus round-off
    /// `~ e_q / h` and `~ 4 e_q / h^2`, where `e_q` is the round-off in `q`
    /// itself (measured: up to a few 1e-13 near the end of the path, where
    /// the pulley moves fast and `|q''''| ~ 100`). With `h = 2e-3` and `1e-3`
    /// the round-off stays below 1e-6, a tenth of the worst truncation error,
    /// so the worst error over the path must be small (< 5e-5 at `h = 1e-3`,
    /// measured 1.2e-5) and drop by a factor of 4 when `h` is halved.
    #[test]
    fn dual_derivatives_match_finite_differences() {
        let p = NavyPlanar::default();
        let q_at = |t: f64| reference_at(&p, &PaperPath, t).q;
        let worst_errors = |h: f64| {
            times(50).fold((0.0f64, 0.0f64), |(ev, ea), t| {
                let s = reference_at(&p, &PaperPath, t);
                let (qm, q0, qp) = (q_at(t - h), q_at(t), q_at(t + h));
                let v_fd = (qp - qm) / (2.0 * h);
                let a_fd = (qp - q0 * 2.0 + qm) / (h * h);
                (ev.max((v_fd - s.v).amax()), ea.max((a_fd - s.a).amax()))
            })
        };
        let (ev, ea) = worst_errors(1e-3);
        let (ev2, ea2) = worst_errors(2e-3);
        assert!(ev < 5e-5 && ea < 5e-5, "|q' - fd| = {ev:e}, |q'' - fd| = {ea:e}");
        for ratio in [ev2 / ev, ea2 / ea] {
            assert!(
                (3.5..4.5).contains(&ratio),
                "error ratio {ratio} for h -> h/2, expected 4"
            );
        }
    }
}
