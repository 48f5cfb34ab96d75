//! The 3D crane with pulley mass as a built-in crane: the paper's manoeuvre
//! (sect. 6.2.1: the three-phase path of eqs. 85-86, (86) as corrected,
//! between eqs. 97 and 98; start eqs. 99-100, (99) as corrected), the same
//! manoeuvre on the C6 profile, the slewing angle and the drawing.
//!
//! The slewing torque `u4` depends on the load path's derivatives up to
//! order 6 (docs/errata.md, smoothness for the 3D crane with pulley mass):
//! on the paper's C4 profile it has impulses at the phase switches t = 0, 5,
//! 15, 20 s, which backward Euler shows as spikes of size impulse/dt;
//! [`PaperCase::smooth`] avoids them.

use crane_runtime::State;
use crane_runtime::trajectory::TrajectoryError;
use nalgebra::{SVector, vector};

use super::model::Navy3dPulley;
use crate::case::Case;
use crate::crane::{Crane, Maneuver};
use crate::drawing::{Drawing, Pose, scale};
use crate::path::{Path, PathSpec, Profile};

/// End time of the paper's maneuver, s (eq. 98); it starts at `t0 = 0`, so
/// this is also the duration `tau` of eq. (86).
pub const TF: f64 = 20.0;
/// Duration `tau0` of the acceleration and deceleration phases, s (eq. 86).
pub const TAU0: f64 = 5.0;

/// The 3D US Navy crane with pulley mass (sect. 6.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Description;

/// The crane on the paper's manoeuvre (`PaperCase::new(TF)`: Fig. 25) or
/// on its C6 variant (`PaperCase::smooth(TF)`).
pub type PaperCase = Case<Description, 12, 5, 4>;

/// The paper's start `p0 = [L1, L2, L3, L0, x0, y0, x3, y3] = [5/2 sqrt 3,
/// sqrt(43.75), 15, 5/2, 5 sqrt 3, 0, 5 sqrt 3, 0]` (eq. 99 as corrected:
/// the printed `6.6144` is `sqrt(43.75) = 6.614378...` rounded) with the
/// outputs at `[x, y, z, z0] = (5 sqrt 3, 0, -10, 5/2)` (eq. 100).
///
/// The boom points along `X`, `P = (5 sqrt 3, 0, 5)`, `A = P/2`,
/// `S = 3/2 P`; the pulley hangs 2.5 m below `P` at the height of `A` and the
/// load 12.5 m below the pulley. Rope `L1` is horizontal, rope `L2` runs up
/// to `S`: all three ropes are taut and the static balance is regular,
/// unlike the degenerate start (87) of sect. 6.1.
pub fn paper_p0() -> [f64; 8] {
    let s3 = 3f64.sqrt();
    [2.5 * s3, 43.75f64.sqrt(), 15.0, 2.5, 5.0 * s3, 0.0, 5.0 * s3, 0.0]
}

/// The outputs `[x, y, z, z0]` at the start (eqs. 97, 100).
fn gamma0() -> SVector<f64, 4> {
    vector![5.0 * 3f64.sqrt(), 0.0, -10.0, 2.5]
}

/// The outputs `[x, y, z, z0]` at the end (eq. 98).
fn gammaf() -> SVector<f64, 4> {
    vector![2.0, 5.0, -5.0, 2.0]
}

/// The slewing angle `phi = atan2(y3, x3)` of the boom in a state.
pub fn slewing_angle(state: &State<12, 5, 4>) -> f64 {
    state.q[7].atan2(state.q[6])
}

impl PaperCase {
    /// The paper's manoeuvre on the C6 profile
    /// [`SmoothThreePhase`](crane_runtime::trajectory::SmoothThreePhase):
    /// the slewing torque `u4` stays bounded at the phase switches.
    pub fn smooth(tf: f64) -> Result<Self, TrajectoryError> {
        let mut case = Self::new(tf)?;
        case.path = Path::new(PathSpec {
            profile: Profile::SmoothThreePhase { tau0: TAU0 },
            ..*case.path.spec()
        })?;
        Ok(case)
    }
}

impl Crane<12, 5, 4> for Description {
    type Model = Navy3dPulley;
    const NAME: &'static str = "navy-3d-pulley";
    const DESCRIPTION: &'static str = "3D US Navy crane with pulley mass, slewing (paper sect. 6.2)";

    fn input_units() -> &'static [&'static str] {
        &["N m", "N m", "N m", "N m"]
    }

    /// From `gamma0` (eq. 97) at `t0 = 0` to `gammaf` (eq. 98) at [`TF`] on
    /// the three-phase profile of eqs. (85)-(86) as corrected (ramps of
    /// [`TAU0`]; `tf >= 10 s`).
    fn maneuver() -> Maneuver<4> {
        Maneuver {
            path: PathSpec {
                profile: Profile::ThreePhase { tau0: TAU0 },
                t0: 0.0,
                t1: TF,
                start: gamma0(),
                end: gammaf(),
            },
            p0: paper_p0().to_vec(),
        }
    }

    fn derived_outputs() -> &'static [&'static str] {
        &["phi"]
    }

    /// The slewing angle `phi = atan2(y, x)` of the boom tip, in rad.
    fn derived(_: &Navy3dPulley, state: &State<12, 5, 4>) -> Vec<f64> {
        vec![slewing_angle(state)]
    }

    /// `q = [L1, L2, L3, L0, x0, y0, x3, y3 | x, y, z, z0]`; `P = (x3, y3,
    /// (k + l) cos alpha)`, `A = beta1 P`, `S = beta2 P` the boom tip
    /// (eqs. 89-93).
    fn drawing(model: &Navy3dPulley) -> Option<Drawing> {
        let (alpha, k, l, beta1, beta2) = (model.alpha, model.k, model.l, model.beta1, model.beta2);
        let height = (k + l) * alpha.cos();
        Some(Drawing {
            spatial: true,
            fixed: vec![("O", [0.0; 3])],
            pose: Box::new(move |q| {
                let p = [q[6], q[7], height];
                let (a, s) = (scale(p, beta1), scale(p, beta2));
                let b = [q[4], q[5], q[11]];
                let c = [q[8], q[9], q[10]];
                Pose {
                    boom: vec![[0.0; 3], scale(p, beta1.max(beta2).max(1.0))],
                    ropes: vec![[a, b], [s, b], [p, b], [b, c]],
                    pulley: b,
                    load: c,
                }
            }),
            ropes: "ropes A-B (L1), S-B (L2), P-B-C (L3)",
        })
    }
}
