//! Analytical flatness-based solution of the crane with an elastic trolley
//! drive, written from the load's, the trolley's and the motor's balances
//! (not from the declaration's kernels).
//!
//! With the load `C = (x, z)` as flat output:
//!
//! 1. The rope pulls the load towards the trolley: `m_l (x'', z'' + g) =
//!    -lambda (x - s, z)`, so the trolley is at `s = x - z x'' / (z'' + g)`,
//!    the rope `L = |(x - s, z)|` long, its tension `N = lambda L` with
//!    `lambda = -m_l (z'' + g) / z`.
//! 2. The trolley's balance `m_t s'' = k (r_m phi - s) - m_l x''` gives the
//!    belt's stretch and with it the motor angle
//!    `phi = (s + (m_t s'' + m_l x'') / k) / r_m`.
//! 3. The motor's and the winch's balances give the inputs,
//!    `u1 = J_m phi'' + r_m (m_t s'' + m_l x'')` and
//!    `u2 = J_w L'' / r_w - r_w N`.
//!
//! Step 1 needs `x''`, step 2 the trolley's `s''` (so `x''''`), step 3 the
//! motor's `phi''` (so `x^(6)`). As for the double pendulum, step 1 is
//! evaluated on nested second-order time-Taylor duals ([`Dual2`]`<Dual2>`,
//! derivatives up to order 4), steps 2 and 3 on second-order ones: the
//! inputs exactly, no finite differences.

use super::model::ElasticDrive;
use crane_runtime::{Scalar, State, Trajectory};
use nalgebra::SVector;
use num_dual::{Dual2, DualNum};

/// Step 1: the trolley `s` and the multiplier `lambda` from the load's
/// position `c` and acceleration `cdd`.
pub fn trolley<T: Scalar>(params: &ElasticDrive, c: [T; 2], cdd: [T; 2]) -> (T, T) {
    let fz = cdd[1] + params.g;
    (c[0] - c[1] * cdd[0] / fz, -fz / c[1] * params.m_l)
}

/// The reference state at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceState {
    /// `q = [phi, s, L, x, z]`.
    pub q: SVector<f64, 5>,
    /// `q'`.
    pub v: SVector<f64, 5>,
    /// `[u1, u2]`.
    pub u: SVector<f64, 2>,
    /// `[lambda] = [N / L]`.
    pub lambda: SVector<f64, 1>,
}

impl ReferenceState {
    /// As the crane's state at `t`.
    pub fn state(&self, t: f64) -> State<5, 1, 2> {
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
pub fn reference(params: &ElasticDrive, derivs: &[SVector<f64, 2>; 7]) -> ReferenceState {
    type D2 = Dual2<f64>;
    type D4 = Dual2<D2>;
    let d2 = |k: usize, i: usize| D2::new(derivs[k][i], derivs[k + 1][i], derivs[k + 2][i]);
    let d4 = |k: usize, i: usize| D4::new(d2(k, i), d2(k + 1, i), d2(k + 2, i));
    // step 1 on fourth-order expansions: the trolley with derivatives up to 4
    let (s4, _) = trolley(params, [d4(0, 0), d4(0, 1)], [d4(2, 0), d4(2, 1)]);
    let (s, sdd) = (s4.re, s4.v2);
    let (c, cdd) = ([d2(0, 0), d2(0, 1)], [d2(2, 0), d2(2, 1)]);
    let (_, lambda) = trolley(params, c, cdd);
    let length = ((c[0] - s) * (c[0] - s) + c[1] * c[1]).sqrt();
    // step 2: the belt's force and the motor angle
    let belt = sdd * params.m_t + cdd[0] * params.m_l;
    let phi = (s + belt / params.k) / params.r_m;
    // step 3
    let u = SVector::from([
        params.J_m * phi.v2 + params.r_m * belt.re,
        params.J_w / params.r_w * length.v2 - params.r_w * lambda.re * length.re,
    ]);
    ReferenceState {
        q: SVector::from([phi.re, s.re, length.re, derivs[0][0], derivs[0][1]]),
        v: SVector::from([phi.v1, s.v1, length.v1, derivs[1][0], derivs[1][1]]),
        u,
        lambda: SVector::from([lambda.re]),
    }
}

/// [`reference()`] at time `t` of a load path.
pub fn reference_at(params: &ElasticDrive, path: &impl Trajectory<2>, t: f64) -> ReferenceState {
    let derivs = std::array::from_fn(|k| path.derivative(t, k));
    reference(params, &derivs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{Wave, assert_satisfies_equations_of_motion};

    /// The reference satisfies the declared crane's equations of motion
    /// (the generated kernels), on a path with every derivative nonzero:
    /// the motor row's terms reach 1e4 N m through the belt, central
    /// differences are ~1e-8 of the accelerations, so 1e-4 absolute (and q'
    /// to 1e-6).
    #[test]
    fn reference_satisfies_the_equations_of_motion() {
        let crane = ElasticDrive::default();
        let path = Wave { z0: -5.0 };
        let state = |t: f64| reference_at(&crane, &path, t).state(t);
        assert_satisfies_equations_of_motion(&crane, state, 1e-6);
    }
}
