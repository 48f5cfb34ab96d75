//! The degenerate start: where a rope carries (almost) no tension it leaves
//! the pulley weakly fixed (the paper's sect. 5.1 start, rope L1), and the
//! first steps are the redundant problem's (eqs. 22), followed in minimal
//! coordinates ([`Follow`]) until every rope carries
//! [`DEGENERATE_TENSION_RATIO`] of the largest tension.

use std::ops::Deref;

use nalgebra::{DVector, SVector};

use super::Minimal;
use super::coordinates::minimal_coordinates;
use crate::error::Error;
use crate::model::{CraneModel, MinimalMap, any_rope_tension};
use crate::problem::Follow;
use crate::scheme::StepFormula;
use crate::solution::State;
use crate::trajectory::Trajectory;

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
pub(crate) fn degenerate<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    state: &State<N, M, A>,
) -> bool {
    any_rope_tension(model, state, |n, largest| !(n >= DEGENERATE_TENSION_RATIO * largest))
}

impl<H, Tr, const N: usize, const M: usize, const A: usize, const F: usize> Follow<N, M, A, F>
    for Minimal<H, Tr, N, M, A, F>
where
    H: Deref<Target: MinimalMap<N, M, A, F> + Sized>,
    Tr: Trajectory<A>,
{
    /// Once every rope carries [`DEGENERATE_TENSION_RATIO`] of the largest tension.
    fn can_take_over(&self, state: &State<N, M, A>) -> bool {
        !degenerate(&*self.model, state)
    }

    /// `mu` by Gauss-Newton from the last step, and `mu'` as the minimal
    /// formulation has it (taking over the projection of the redundant `q'`
    /// made the next minimal step fail at dt = 0.05): `nu1` from the
    /// scheme's formula on the `mu1` history (eq. 24a), `mu2^` from the servo
    /// constraint on velocity level (24d), `D1 phi_x nu1 + D2 phi_x mu2^ =
    /// gamma'(t)`; and `s = dt^2 mu2''` from the one on acceleration level
    /// (24c).
    fn follow(
        &mut self,
        state: &State<N, M, A>,
        last: &SVector<f64, F>,
        formula: StepFormula<F>,
        z: &mut DVector<f64>,
    ) -> Result<(SVector<f64, F>, SVector<f64, F>), Error> {
        let model = &*self.model;
        let (dt, split, off) = (self.equations.dt, F - A, N - A);
        let (mu, mut mu_dot, p) = minimal_coordinates(model, state, last)?;
        for i in 0..split {
            mu_dot[i] = formula.kinematics(i, mu[i]).0;
        }
        self.output.set::<N, F, A>(&p);
        let [gamma_rate, gamma_accel] = [1, 2].map(|k| self.trajectory.derivative(state.t, k));
        let mu2_hat = self.output.solve::<A>(
            |i| gamma_rate[i] - (0..split).map(|j| p[(off + i, j)] * mu_dot[j]).sum::<f64>(),
            state.t,
        )?;
        for k in 0..A {
            mu_dot[split + k] = mu2_hat[k];
        }
        let accel_dt2 = SVector::<f64, F>::from_fn(|i, _| if i < split { formula.kinematics(i, mu[i]).1 } else { 0.0 });
        let curvature = model.null_space_rate(&mu, &mu_dot) * mu_dot; // its load rows are w (eq. 17)
        let s = self.output.solve::<A>(
            |i| {
                dt * dt * (gamma_accel[i] - curvature[off + i])
                    - (0..split).map(|j| p[(off + i, j)] * accel_dt2[j]).sum::<f64>()
            },
            state.t,
        )?;
        for i in 0..F {
            z[i] = mu[i];
        }
        for k in 0..A {
            z[F + k] = dt * mu_dot[split + k];
            z[F + A + k] = s[k];
            z[F + 2 * A + k] = dt * dt * state.u[k];
        }
        Ok((mu, mu_dot))
    }
}
