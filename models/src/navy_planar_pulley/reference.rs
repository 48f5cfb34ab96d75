//! Analytical flatness-based solution of the planar US Navy crane with
//! pulley mass (paper, Appendix B), by the "direct way" of eqs. (124a-o)
//! with the docs/errata.md for (124h) (`m_l g`, not `m g`).
//!
//! Geometry (eq. 55): winch 2 at `S` (the origin), winch 3 at
//! `P = -s (sin(alpha), cos(alpha))`, winch 1 at
//! `A = -(l + s) (sin(alpha), cos(alpha))`, main pulley `B = (x0, z0)`
//! (mass `m0`), load `C = (x, z)` (mass `m_l`). The flat outputs are the load
//! coordinates and the pulley height, `y = [x, z, z0]` (eq. 50).
//!
//! The solution is purely algebraic (Appendix B, after (124o)):
//! 1. (124g), (124h): `lambda4 = m_l (z'' + g)/(z0 - z)` and
//!    `x0 = x + m_l x''/lambda4`, functions of `y` and `y''`;
//! 2. (124i)-(124l): `L1`, `L0`, `L2` and `L3 = L0 + |BC|`;
//! 3. (124d): `lambda2 = lambda4 (L3 - L0)/L0`, the massless `L0` row;
//! 4. (124e), (124f): `lambda1`, `lambda3` from the pulley's equations of
//!    motion, a 2x2 linear system that needs `x0''` and so `y''''` (the
//!    paper's text after (124o) says "functions of x and x''", which holds
//!    only for `m0 = 0`: with pulley mass they depend on the flat outputs up
//!    to the fourth derivative, which is why backward Euler shows its
//!    first-order error in `lambda1`, `lambda3` too);
//! 5. (124a)-(124c): the winch torques `u` from `L1'', L2'', L3''` (again
//!    `y''''`).
//!
//! [`flat_configuration`] does steps 1-3 for any [`Scalar`];
//! [`pulley_multipliers`] does step 4. [`reference()`] pushes second-order
//! time-Taylor dual numbers through steps 1-3: with `y = (y, y', y'')` and
//! `y'' = (y'', y''', y'''')` as [`Dual2`] numbers, every coordinate carries
//! its value, velocity and acceleration exactly (no finite differences), which
//! steps 4 and 5 need.
//!
//! The same tensions follow from Newton's law for load and pulley,
//! eqs. (113)-(123): `N3 = lambda4 (L3 - L0)` (114), `N0 = lambda2 L0 = N3`
//! (122a), `N1 = lambda1 L1`, `N2 = lambda3 L2` from (122b, c); the unit tests
//! check both routes against each other.

use super::model::NavyPlanarPulley;
use crane_runtime::{Scalar, Trajectory};
use nalgebra::SVector;
use num_dual::Dual2;

/// The algebraic part of the flatness solution (steps 1-3 of the module
/// docs) for one scalar type.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatConfiguration<T: Scalar> {
    /// `q = [L1, L2, L3, L0, x0, x, z, z0]` (eqs. 49-50).
    pub q: SVector<T, 8>,
    /// Length `L = L3 - L0 = |BC|` of the load rope.
    pub load_rope: T,
    /// Angle of the load rope `BC` with the vertical, `tan(theta) = -x''/(z'' + g)`
    /// (eqs. 102, 113).
    pub theta: T,
    /// Multiplier of the `L0` constraint, `lambda2 = lambda4 L / L0` (124d).
    pub lambda2: T,
    /// Multiplier of the hoist constraint, `lambda4 = m_l (z'' + g)/(z0 - z)` (124h).
    pub lambda4: T,
}

/// Coordinates and the multipliers of rope 3 from the flat outputs
/// `y = [x, z, z0]` and the load's acceleration `ydd = [x'', z'']`,
/// eqs. (124g, h, i, j, k, l, d) with docs/errata.md (124h).
///
/// Generic so that dual numbers can carry time derivatives through it (see
/// [`reference()`]). Requires `z'' + g > 0` and `z0 > z` (the load hangs
/// below the pulley on a rope that pulls).
pub fn flat_configuration<T: Scalar>(params: &NavyPlanarPulley, y: [T; 3], ydd: [T; 2]) -> FlatConfiguration<T> {
    let [x, z, z0] = y;
    let [xdd, zdd] = ydd;
    let NavyPlanarPulley {
        m_l, alpha, l, s, g, ..
    } = *params;
    let zg = zdd + g;
    let (sin_a, cos_a) = alpha.sin_cos();

    // (124h) with docs/errata.md: m_l z'' = -lambda4 (z - z0) - m_l g.
    let lambda4 = zg * m_l / (z0 - z);
    // (124g): m_l x'' = -lambda4 (x - x0), i.e. (116a).
    let x0 = x + xdd * m_l / lambda4;

    // (124i)-(124l): the rope lengths close the constraints.
    let hyp = |dx: T, dz: T| (dx * dx + dz * dz).sqrt();
    let l1 = hyp(x0 + (l + s) * sin_a, z0 + (l + s) * cos_a);
    let l0 = hyp(x0 + s * sin_a, z0 + s * cos_a);
    let l2 = hyp(x0, z0);
    let load_rope = hyp(x - x0, z - z0);
    let l3 = l0 + load_rope;

    // (124d): the massless rope coordinate L0, 0 = lambda2 L0 - lambda4 (L3 - L0).
    let lambda2 = lambda4 * load_rope / l0;

    FlatConfiguration {
        q: SVector::<T, 8>::from_column_slice(&[l1, l2, l3, l0, x0, x, z, z0]),
        load_rope,
        theta: (-xdd).atan2(zg),
        lambda2,
        lambda4,
    }
}

/// `[lambda1, lambda3]` from the pulley's equations of motion (124e, f),
/// given the configuration and the pulley's acceleration `(x0'', z0'')`:
/// ```text
/// lambda1 (x0 + (l+s) sin(alpha)) + lambda3 x0 = -m0 x0''       - lambda2 (x0 + s sin(alpha)) - lambda4 (x0 - x)
/// lambda1 (z0 + (l+s) cos(alpha)) + lambda3 z0 = -m0 (z0'' + g) - lambda2 (z0 + s cos(alpha)) - lambda4 (z0 - z)
/// ```
/// The determinant is `(l + s)(z0 sin(alpha) - x0 cos(alpha))`: regular
/// unless the pulley lies on the boom line (ropes 1 and 2 collinear).
pub fn pulley_multipliers<T: Scalar>(
    params: &NavyPlanarPulley,
    flat: &FlatConfiguration<T>,
    x0dd: T,
    z0dd: T,
) -> [T; 2] {
    let NavyPlanarPulley { m0, alpha, l, s, g, .. } = *params;
    let (sin_a, cos_a) = alpha.sin_cos();
    let q = &flat.q;
    let (x0, x, z, z0) = (q[4], q[5], q[6], q[7]);
    let (a11, a12) = (x0 + (l + s) * sin_a, x0);
    let (a21, a22) = (z0 + (l + s) * cos_a, z0);
    let b1 = -x0dd * m0 - flat.lambda2 * (x0 + s * sin_a) - flat.lambda4 * (x0 - x);
    let b2 = -(z0dd + g) * m0 - flat.lambda2 * (z0 + s * cos_a) - flat.lambda4 * (z0 - z);
    let det = a11 * a22 - a12 * a21;
    [(b1 * a22 - b2 * a12) / det, (a11 * b2 - a21 * b1) / det]
}

/// The analytical reference at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceState {
    /// Coordinates `q = [L1, L2, L3, L0, x0, x, z, z0]`.
    pub q: SVector<f64, 8>,
    /// Velocities `q'`.
    pub v: SVector<f64, 8>,
    /// Accelerations `q''` (the winch rows enter (124a-c), the `x0` row (124e)).
    pub a: SVector<f64, 8>,
    /// Winch torques `[u1, u2, u3]` (124a-c).
    pub u: SVector<f64, 3>,
    /// Multipliers of the constraints `[rope1, rope0, rope2, hoist]` of
    /// eq. (55): `[N1/L1, N0/L0, N2/L2, N3/(L3 - L0)]` (tension `N = lambda L`
    /// for the 1/2-scaled rope constraints; signs from
    /// `M q'' = f + B^T u - G^T lambda`).
    pub lambda: SVector<f64, 4>,
    /// Rope tensions `[N1, N2, N3]`, in the order of the model's ropes; the
    /// segment `PB` of rope 3 carries `N0 = N3` (122a, 124d).
    pub tensions: [f64; 3],
}

/// The flatness-based reference (Appendix B, eqs. 124a-o) from the flat
/// outputs' derivatives `derivs[k] = y^(k)`, `y = [x, z, z0]`, `k = 0..=4`.
///
/// `q` depends on `y, y''`; `q'` additionally on `y', y'''`; `q''`, `lambda1`,
/// `lambda3` and `u` on all of them up to `y''''`.
pub fn reference(params: &NavyPlanarPulley, derivs: &[SVector<f64, 3>; 5]) -> ReferenceState {
    // Second-order Taylor expansions in time of the outputs and of their accelerations.
    let taylor = |k: usize, i: usize| Dual2::new(derivs[k][i], derivs[k + 1][i], derivs[k + 2][i]);
    let flat = flat_configuration(
        params,
        [taylor(0, 0), taylor(0, 1), taylor(0, 2)],
        [taylor(2, 0), taylor(2, 1)],
    );

    let q = flat.q.map(|c| c.re);
    let v = flat.q.map(|c| c.v1);
    let a = flat.q.map(|c| c.v2);
    let re = FlatConfiguration {
        q,
        load_rope: flat.load_rope.re,
        theta: flat.theta.re,
        lambda2: flat.lambda2.re,
        lambda4: flat.lambda4.re,
    };
    let [lambda1, lambda3] = pulley_multipliers(params, &re, a[4], a[7]);
    let lambda = SVector::<f64, 4>::new(lambda1, re.lambda2, lambda3, re.lambda4);

    // (124a)-(124c): J_i/r_i^2 L_i'' = (tension term) + u_i/r_i.
    let NavyPlanarPulley {
        J1, J2, J3, r1, r2, r3, ..
    } = *params;
    let (n1, n2, n3) = (lambda1 * q[0], lambda3 * q[1], re.lambda4 * re.load_rope);
    let u = SVector::<f64, 3>::new(
        J1 / r1 * a[0] - n1 * r1,
        J2 / r2 * a[1] - n2 * r2,
        J3 / r3 * a[2] - n3 * r3,
    );

    ReferenceState {
        q,
        v,
        a,
        u,
        lambda,
        tensions: [n1, n2, n3],
    }
}

/// [`reference()`] at time `t` of a path of the flat outputs `[x, z, z0]`.
pub fn reference_at(params: &NavyPlanarPulley, path: &impl Trajectory<3>, t: f64) -> ReferenceState {
    let derivs = std::array::from_fn(|k| path.derivative(t, k));
    reference(params, &derivs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::SMatrix;

    /// The paper's rest-to-rest path (41), (44), (64), (65): from
    /// `(-5/2 sqrt 3, -17.5, -12.5)` at `t0 = 0` to `(-2, -16, -15)` at `tf`,
    /// 5-6-7-8-9 polynomial `c`. (A local stand-in for the runtime's `Poly9`,
    /// so that these tests check the reference on its own.)
    struct PaperPath {
        tf: f64,
    }

    impl Trajectory<3> for PaperPath {
        fn derivative(&self, t: f64, k: usize) -> SVector<f64, 3> {
            let g0 = SVector::<f64, 3>::new(-2.5 * 3f64.sqrt(), -17.5, -12.5);
            let gf = SVector::<f64, 3>::new(-2.0, -16.0, -15.0);
            let tau = t / self.tf;
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
                (gf - g0) * (c / self.tf.powi(k as i32))
            }
        }
    }

    /// `n` equally spaced times strictly inside `(0, tf)`.
    fn times(tf: f64, n: usize) -> impl Iterator<Item = f64> {
        (1..=n).map(move |i| tf * i as f64 / (n + 1) as f64)
    }

    /// `g(q)` and `G(q)` of eqs. (55), (57), (58), written out here so that
    /// these unit tests need no model (`crane-tests` repeats the checks with
    /// the generated model).
    fn constraints_and_jacobian(p: &NavyPlanarPulley, q: &SVector<f64, 8>) -> (SVector<f64, 4>, SMatrix<f64, 4, 8>) {
        let [l1, l2, l3, l0, x0, x, z, z0] = [q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7]];
        let (sa, ca) = p.alpha.sin_cos();
        let (ax, az) = (x0 + (p.l + p.s) * sa, z0 + (p.l + p.s) * ca);
        let (px, pz) = (x0 + p.s * sa, z0 + p.s * ca);
        let g = SVector::<f64, 4>::new(
            0.5 * (ax * ax + az * az - l1 * l1),
            0.5 * (px * px + pz * pz - l0 * l0),
            0.5 * (x0 * x0 + z0 * z0 - l2 * l2),
            0.5 * ((x - x0).powi(2) + (z - z0).powi(2) - (l3 - l0).powi(2)),
        );
        // rows = columns of G1^T (57) and G2^T (58)
        #[rustfmt::skip]
        let jac = SMatrix::<f64, 4, 8>::from_row_slice(&[
            -l1, 0.0, 0.0,     0.0,     ax,     0.0,    0.0,    az,
            0.0, 0.0, 0.0,     -l0,     px,     0.0,    0.0,    pz,
            0.0, -l2, 0.0,     0.0,     x0,     0.0,    0.0,    z0,
            0.0, 0.0, l0 - l3, l3 - l0, x0 - x, x - x0, z - z0, z0 - z,
        ]);
        (g, jac)
    }

    /// `M q'' - f - B^T u + G^T lambda` (eq. 1a with (53), (56)-(58)).
    fn residual(p: &NavyPlanarPulley, s: &ReferenceState) -> SVector<f64, 8> {
        let (_, jac) = constraints_and_jacobian(p, &s.q);
        let mass = SVector::<f64, 8>::from_column_slice(&[
            p.J1 / (p.r1 * p.r1),
            p.J2 / (p.r2 * p.r2),
            p.J3 / (p.r3 * p.r3),
            0.0,
            p.m0,
            p.m_l,
            p.m_l,
            p.m0,
        ]);
        let mut rhs = -(jac.transpose() * s.lambda);
        rhs[0] += s.u[0] / p.r1;
        rhs[1] += s.u[1] / p.r2;
        rhs[2] += s.u[2] / p.r3;
        rhs[6] -= p.m_l * p.g;
        rhs[7] -= p.m0 * p.g;
        mass.component_mul(&s.a) - rhs
    }

    /// Eqs. (64), (66) with docs/errata.md, (67) at t0: a regular static equilibrium,
    /// values worked out by hand: `lambda4 = m_l g / 5 = 196.2`, `lambda2 =
    /// lambda4 5/10 = 98.1`; the pulley balance in x gives `lambda3 = 2
    /// lambda1`, in z `30 lambda1 = m0 g = 1471.5`.
    #[test]
    fn paper_start() {
        let p = NavyPlanarPulley::default();
        let s = reference_at(&p, &PaperPath { tf: 4.0 }, 0.0);
        let s3 = 3f64.sqrt();
        let expected = [10.0, 175f64.sqrt(), 15.0, 10.0, -2.5 * s3, -2.5 * s3, -17.5, -12.5];
        for (i, e) in expected.iter().enumerate() {
            assert!((s.q[i] - e).abs() < 1e-12, "q[{i}] = {} != {e}", s.q[i]);
        }
        assert!(s.v.amax() == 0.0 && s.a.amax() == 0.0, "at rest: {:?} {:?}", s.v, s.a);
        let lambda = [49.05, 98.1, 98.1, 196.2];
        for (i, e) in lambda.iter().enumerate() {
            assert!((s.lambda[i] - e).abs() < 1e-10, "lambda[{i}] = {} != {e}", s.lambda[i]);
        }
        let tensions = [490.5, 98.1 * 175f64.sqrt(), 981.0];
        for (i, e) in tensions.iter().enumerate() {
            assert!((s.tensions[i] - e).abs() < 1e-9, "N[{i}] = {} != {e}", s.tensions[i]);
        }
        // static torques u_i = -N_i r_i
        for (i, n) in tensions.iter().enumerate() {
            assert!((s.u[i] + 0.1 * n).abs() < 1e-10, "u[{i}] = {}", s.u[i]);
        }
        assert!(residual(&p, &s).amax() < 1e-10);
    }

    /// The end state is an equilibrium with everything at rest at gammaf.
    #[test]
    fn paper_end_is_equilibrium() {
        let p = NavyPlanarPulley::default();
        for tf in [4.0, 15.0] {
            let s = reference_at(&p, &PaperPath { tf }, tf);
            assert_eq!((s.q[5], s.q[6], s.q[7]), (-2.0, -16.0, -15.0));
            assert!((s.q[4] + 2.0).abs() < 1e-14, "x0 = x at rest");
            assert!(s.v.amax() < 1e-12 && s.a.amax() < 1e-12);
            assert!(residual(&p, &s).amax() < 1e-10);
            assert!(s.tensions.iter().all(|&n| n > 1.0), "{:?}", s.tensions);
        }
    }

    /// `g(q) = 0`, `G q' = 0` and all eight equations of motion along the
    /// path, with `q''` from the Taylor duals: all hold to round-off. Rows
    /// `L1, L2, L3` hold by construction of (124a-c), row `L0` is (124d),
    /// rows `x0, z0` (124e, f) fix `lambda1, lambda3`, rows `x, z` (124g, h)
    /// fix `x0, lambda4`.
    #[test]
    fn satisfies_constraints_and_equations_of_motion() {
        let p = NavyPlanarPulley::default();
        let scale = (p.m_l + p.m0) * p.g;
        for tf in [4.0, 15.0] {
            for t in times(tf, 50) {
                let s = reference_at(&p, &PaperPath { tf }, t);
                let (g, jac) = constraints_and_jacobian(&p, &s.q);
                assert!(g.amax() < 1e-12, "g = {g:?} at t = {t}");
                assert!((jac * s.v).amax() < 1e-11, "G q' at t = {t}");
                let r = residual(&p, &s);
                assert!(r.amax() < 1e-12 * scale, "residual {r:?} at t = {t}");
                assert!(
                    s.tensions.iter().all(|&n| n > 0.0),
                    "tensions {:?} at t = {t}",
                    s.tensions
                );
            }
        }
    }

    /// Newton's law for load and pulley, eqs. (113)-(123), with the angles of
    /// (119)-(121), gives the same tensions and torques as the direct way.
    /// The directions of the ropes at `B`, read off (122b, c): towards `S`
    /// `(-sin(alpha - mu), -cos(alpha - mu))`, towards `P`
    /// `(-sin(alpha - beta), -cos(alpha - beta))` (so (122b, c) need `mu`,
    /// `beta` measured from `SA` and `PA` towards the vertical), towards `A`
    /// `(-sin(theta + gamma), cos(theta + gamma))`, towards `C`
    /// `(sin(theta), -cos(theta))`.
    #[test]
    fn newton_way_agrees_with_direct_way() {
        let p = NavyPlanarPulley::default();
        let path = PaperPath { tf: 4.0 };
        for t in std::iter::once(0.0).chain(times(4.0, 20)) {
            let s = reference_at(&p, &path, t);
            let d: [SVector<f64, 3>; 5] = std::array::from_fn(|k| path.derivative(t, k));
            let [l1, l2, l3, l0, x0, x, z, z0] = [s.q[0], s.q[1], s.q[2], s.q[3], s.q[4], s.q[5], s.q[6], s.q[7]];
            let (xdd, zdd) = (d[2][0], d[2][1]);
            // (114), (102)
            let theta = (-xdd).atan2(zdd + p.g);
            let n3 = p.m_l * ((zdd + p.g) * theta.cos() - xdd * theta.sin());
            // (117), (116a)
            let big_l = n3 * (z0 - z) / (p.m_l * (zdd + p.g));
            assert!((big_l - (l3 - l0)).abs() < 1e-12, "(117) at t = {t}");
            assert!((x + p.m_l * big_l / n3 * xdd - x0).abs() < 1e-12, "(116a) at t = {t}");
            // (119)-(121)
            let beta = ((p.l * p.l + l0 * l0 - l1 * l1) / (2.0 * l0 * p.l)).acos();
            let ls = p.l + p.s;
            let mu = ((ls * ls + l2 * l2 - l1 * l1) / (2.0 * l2 * ls)).acos();
            let tg = (x0 + ls * p.alpha.sin()).atan2(-(z0 + ls * p.alpha.cos()));
            // (122a-c): solve for N1, N2
            let n0 = n3;
            let (x0dd, z0dd) = (s.a[4], s.a[7]);
            let am = p.alpha - mu;
            let ab = p.alpha - beta;
            let b1 = p.m0 * x0dd - n3 * theta.sin() - n0 * ab.sin();
            let b2 = p.m0 * (z0dd + p.g) + n3 * theta.cos() - n0 * ab.cos();
            // [sin(am) -sin(tg); cos(am) cos(tg)] [N2; N1] = [b1; b2]
            let det = am.sin() * tg.cos() + tg.sin() * am.cos();
            let n2 = (b1 * tg.cos() + tg.sin() * b2) / det;
            let n1 = (am.sin() * b2 - am.cos() * b1) / det;
            let newton = [n1, n2, n3];
            for (i, (n, expected)) in newton.iter().zip(&s.tensions).enumerate() {
                let e = (n - expected).abs();
                assert!(
                    e < 1e-9 * expected.abs().max(1.0),
                    "N{} at t = {t}: {n} vs {expected}",
                    i + 1
                );
            }
            // (123a-c)
            let u = [
                p.J1 / p.r1 * s.a[0] - n1 * p.r1,
                p.J2 / p.r2 * s.a[1] - n2 * p.r2,
                p.J3 / p.r3 * s.a[2] - n0 * p.r3,
            ];
            for (i, (ui, expected)) in u.iter().zip(&s.u).enumerate() {
                assert!((ui - expected).abs() < 1e-9 * s.u.amax(), "u{} at t = {t}", i + 1);
            }
        }
    }

    /// `q'` and `q''` from the duals against central differences of `q(t)`:
    /// the difference quotients err by `h^2/6 q'''` and `h^2/12 q''''` (order
    /// 2) plus round-off `~ e_q/h`, `~ 4 e_q/h^2`; with `h = 1e-3, 2e-3` the
    /// truncation error dominates, so the worst error over the path must be
    /// small and drop by about 4 when `h` is halved.
    #[test]
    fn dual_derivatives_match_finite_differences() {
        let p = NavyPlanarPulley::default();
        let path = PaperPath { tf: 4.0 };
        let q_at = |t: f64| reference_at(&p, &path, t).q;
        let worst_errors = |h: f64| {
            times(4.0, 50).fold((0.0f64, 0.0f64), |(ev, ea), t| {
                let s = reference_at(&p, &path, t);
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
