//! Analytical flatness-based solution of the double-pendulum crane, written
//! from the load's and the hook's equations of motion (not from the
//! declaration's kernels).
//!
//! With the load `C = (x, z)` as flat output:
//!
//! 1. The sling pulls the load towards the hook: `m_l (x'', z'' + g) =
//!    lambda2 (xh - x, zh - z)`, so the hook is
//!    `(xh, zh) = C + l_s e`, `e = (x'', z'' + g) / |(x'', z'' + g)|`, and
//!    the sling tension `N2 = m_l |(x'', z'' + g)|`.
//! 2. The hoist rope holds hook and load together: with
//!    `F = (m_h xh'' + m_l x'', m_h (zh'' + g) + m_l (z'' + g))`, the total
//!    force the rope carries, `lambda1 (xh - s, zh) = -F`, so the trolley
//!    sits at `s = xh - zh F_x / F_z`, the rope is
//!    `L = -zh |F| / F_z` long and its tension is `N1 = |F|`.
//! 3. The trolley's and the winch's balances give the inputs,
//!    `u1 = m_t s'' + F_x` and `u2 = J L'' / r - r N1`.
//!
//! Step 1 needs `x''`, step 2 the hook's `xh''` (so `x''''`), step 3 the
//! trolley's and the rope's second derivatives (so `x^(6)`). Each step is
//! evaluated on time-Taylor dual numbers: the load's path enters as nested
//! second-order duals [`Dual2`]`<Dual2>` (value and derivatives up to
//! order 4 of `x` and of `x''`), the hook comes out with its derivatives up
//! to order 4, and step 2 on the hook's and the load's second-order
//! expansions gives `s, L` with two derivatives: the inputs exactly, no
//! finite differences.

use super::model::DoublePendulum;
use crane_runtime::{Scalar, State, Trajectory};
use nalgebra::SVector;
use num_dual::Dual2;

/// Step 1: the hook `(xh, zh)` and the sling tension `N2` from the load's
/// position `c` and acceleration `cdd`.
pub fn hook<T: Scalar>(params: &DoublePendulum, c: [T; 2], cdd: [T; 2]) -> ([T; 2], T) {
    let (fx, fz) = (cdd[0], cdd[1] + params.g);
    let norm = (fx * fx + fz * fz).sqrt();
    let scale = norm.recip() * params.l_s;
    ([c[0] + fx * scale, c[1] + fz * scale], norm * params.m_l)
}

/// Step 2: the trolley `s`, the rope length `L` and its tension `N1` from
/// the hook's position and acceleration and the load's acceleration; also
/// the rope's horizontal force `F_x`.
pub fn trolley<T: Scalar>(params: &DoublePendulum, h: [T; 2], hdd: [T; 2], cdd: [T; 2]) -> (T, T, T, T) {
    let g = params.g;
    let fx = hdd[0] * params.m_h + cdd[0] * params.m_l;
    let fz = (hdd[1] + g) * params.m_h + (cdd[1] + g) * params.m_l;
    let n1 = (fx * fx + fz * fz).sqrt();
    let s = h[0] - h[1] * fx / fz;
    let length = -h[1] * n1 / fz;
    (s, length, n1, fx)
}

/// The reference state at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceState {
    /// `q = [s, L, xh, zh, x, z]`.
    pub q: SVector<f64, 6>,
    /// `q'`.
    pub v: SVector<f64, 6>,
    /// `[u1, u2]`.
    pub u: SVector<f64, 2>,
    /// `[lambda_hoist, lambda_sling] = [N1 / L, N2 / l_s]`.
    pub lambda: SVector<f64, 2>,
    /// `[N1, N2]`.
    pub tensions: [f64; 2],
}

impl ReferenceState {
    /// As the crane's state at `t`.
    pub fn state(&self, t: f64) -> State<6, 2, 2> {
        State {
            t,
            q: self.q,
            v: self.v,
            u: self.u,
            lambda: self.lambda,
        }
    }
}

/// The flatness-based reference from the load path's derivatives
/// `derivs[k] = x^(k)`, `k = 0..=6`.
pub fn reference(params: &DoublePendulum, derivs: &[SVector<f64, 2>; 7]) -> ReferenceState {
    type D2 = Dual2<f64>;
    type D4 = Dual2<D2>;
    let d2 = |k: usize, i: usize| D2::new(derivs[k][i], derivs[k + 1][i], derivs[k + 2][i]);
    let d4 = |k: usize, i: usize| D4::new(d2(k, i), d2(k + 1, i), d2(k + 2, i));
    // step 1 on fourth-order expansions: the hook with derivatives up to 4
    let (h4, n2) = hook(params, [d4(0, 0), d4(0, 1)], [d4(2, 0), d4(2, 1)]);
    // the hook's and the load's second-order expansions of position and acceleration
    let h = [h4[0].re, h4[1].re];
    let hdd = [h4[0].v2, h4[1].v2];
    let cdd = [d2(2, 0), d2(2, 1)];
    let (s, length, n1, fx) = trolley(params, h, hdd, cdd);
    let u = SVector::from([
        params.m_t * s.v2 + fx.re,
        params.J / params.r * length.v2 - params.r * n1.re,
    ]);
    let q = SVector::from([s.re, length.re, h[0].re, h[1].re, derivs[0][0], derivs[0][1]]);
    let v = SVector::from([s.v1, length.v1, h[0].v1, h[1].v1, derivs[1][0], derivs[1][1]]);
    let n2 = n2.re.re;
    ReferenceState {
        q,
        v,
        u,
        lambda: SVector::from([n1.re / length.re, n2 / params.l_s]),
        tensions: [n1.re, n2],
    }
}

/// [`reference()`] at time `t` of a load path.
pub fn reference_at(params: &DoublePendulum, path: &impl Trajectory<2>, t: f64) -> ReferenceState {
    let derivs = std::array::from_fn(|k| path.derivative(t, k));
    reference(params, &derivs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{Wave, assert_satisfies_equations_of_motion};

    /// The reference satisfies the declared crane's equations of motion
    /// (the generated kernels, an independent derivation), on a path with
    /// every derivative nonzero: forces of ~1e4 N, central differences of
    /// ~1e-8 of the accelerations, so 1e-4 N (and q' to 1e-7).
    #[test]
    fn reference_satisfies_the_equations_of_motion() {
        let crane = DoublePendulum::default();
        let path = Wave { z0: -6.0 };
        let state = |t: f64| reference_at(&crane, &path, t).state(t);
        assert_satisfies_equations_of_motion(&crane, state, 1e-7);
    }
}
