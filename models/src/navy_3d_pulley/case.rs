//! The paper's maneuver for the 3D crane with pulley mass (sect. 6.2.1):
//! the three-phase path of eqs. (85)-(86) (ERRATA (86)) between eqs. (97) and
//! (98), start eqs. (99)-(100) with ERRATA (99); and the same maneuver on the
//! C6 profile [`SmoothThreePhase`].
//!
//! The slewing torque `u4` depends on the load path's derivatives up to
//! order 6 (ERRATA, "Smoothness needed by the 3D crane with pulley mass"): on
//! the paper's C4 profile it has impulses at the phase switches t = 0, 5, 15,
//! 20 s, which backward Euler shows as spikes of size impulse/dt;
//! [`PaperCase::smooth`] avoids them.

use crane_runtime::trajectory::{SmoothThreePhase, ThreePhase, TrajectoryError};
use crane_runtime::{Error, State, Trajectory, init};
use nalgebra::{SVector, vector};

use super::model::Navy3dPulley;

/// End time of the paper's maneuver, s (eq. 98); it starts at `t0 = 0`, so
/// this is also the duration `tau` of eq. (86).
pub const TF: f64 = 20.0;
/// Duration `tau0` of the acceleration and deceleration phases, s (eq. 86).
pub const TAU0: f64 = 5.0;

/// The paper's start `p0 = [L1, L2, L3, L0, x0, y0, x3, y3] = [5/2 sqrt 3,
/// sqrt(43.75), 15, 5/2, 5 sqrt 3, 0, 5 sqrt 3, 0]` (eq. 99; ERRATA: the
/// printed `6.6144` is `sqrt(43.75) = 6.614378...` rounded) with the outputs
/// at `[x, y, z, z0] = (5 sqrt 3, 0, -10, 5/2)` (eq. 100).
///
/// The boom points along `X`, `P = (5 sqrt 3, 0, 5)`, `A = P/2`,
/// `S = 3/2 P`; the pulley hangs 2.5 m below `P` at the height of `A` and the
/// load 12.5 m below the pulley. Rope `L1` is horizontal, rope `L2` runs up
/// to `S`: all three ropes are taut and the static balance is regular
/// (ERRATA), unlike the degenerate start (87) of sect. 6.1.
pub fn paper_p0() -> [f64; 8] {
    let s3 = 3f64.sqrt();
    [
        2.5 * s3,
        43.75f64.sqrt(),
        15.0,
        2.5,
        5.0 * s3,
        0.0,
        5.0 * s3,
        0.0,
    ]
}

/// The outputs `[x, y, z, z0]` at the start (eqs. 97, 100).
fn gamma0() -> SVector<f64, 4> {
    vector![5.0 * 3f64.sqrt(), 0.0, -10.0, 2.5]
}

/// The outputs `[x, y, z, z0]` at the end (eq. 98).
fn gammaf() -> SVector<f64, 4> {
    vector![2.0, 5.0, -5.0, 2.0]
}

/// The paper's load path: from `gamma0` (eq. 97) at `t0 = 0` to `gammaf`
/// (eq. 98) at `tf` (20 s in the paper, [`TF`]) on the three-phase profile
/// of eqs. (85)-(86) with ERRATA (ramps of `tau0 = 5 s`; `tf >= 10 s`).
pub fn paper_path(tf: f64) -> Result<ThreePhase<4>, TrajectoryError> {
    ThreePhase::new(0.0, tf, TAU0, gamma0(), gammaf())
}

/// Which ramp profile the maneuver uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Profile {
    /// The paper's C4 profile, eqs. (85)-(86) ([`ThreePhase`]).
    Paper,
    /// The C6 profile [`SmoothThreePhase`]: bounded slewing torque.
    Smooth,
}

/// The load path of a [`PaperCase`]: the paper's profile or the smooth one.
#[derive(Debug, Clone, PartialEq)]
pub enum Path {
    /// Eqs. (85)-(86), C4 at the phase switches.
    Paper(ThreePhase<4>),
    /// Same phases with C6 ramps.
    Smooth(SmoothThreePhase<4>),
}

impl Path {
    /// The path from `gamma0` (eq. 97) to `gammaf` (eq. 98) over `[0, tf]`
    /// with ramps of [`TAU0`] on the given profile.
    pub fn new(profile: Profile, tf: f64) -> Result<Self, TrajectoryError> {
        Ok(match profile {
            Profile::Paper => Path::Paper(paper_path(tf)?),
            Profile::Smooth => {
                Path::Smooth(SmoothThreePhase::new(0.0, tf, TAU0, gamma0(), gammaf())?)
            }
        })
    }
}

impl Trajectory<4> for Path {
    fn derivative(&self, t: f64, k: usize) -> SVector<f64, 4> {
        match self {
            Path::Paper(path) => path.derivative(t, k),
            Path::Smooth(path) => path.derivative(t, k),
        }
    }
}

/// The crane with the paper's parameters on the paper's maneuver (or on its
/// smooth variant).
#[derive(Debug, Clone)]
pub struct PaperCase {
    /// The crane.
    pub model: Navy3dPulley,
    /// The path of the outputs `[x, y, z, z0]`.
    pub path: Path,
    /// The start `p0`.
    pub p0: [f64; 8],
    /// End time `tf` of the path (it starts at `t0 = 0`).
    pub tf: f64,
}

impl PaperCase {
    /// The paper's case with end time `tf` ([`TF`] = 20 s in the paper;
    /// ramps of `tau0 = 5 s`, so `tf >= 10 s`).
    pub fn new(tf: f64) -> Result<Self, TrajectoryError> {
        Self::with_profile(Profile::Paper, tf)
    }

    /// The same maneuver on the C6 profile [`SmoothThreePhase`]: the slewing
    /// torque `u4` stays bounded at the phase switches.
    pub fn smooth(tf: f64) -> Result<Self, TrajectoryError> {
        Self::with_profile(Profile::Smooth, tf)
    }

    /// The maneuver on the given profile.
    pub fn with_profile(profile: Profile, tf: f64) -> Result<Self, TrajectoryError> {
        Ok(Self {
            model: Navy3dPulley::default(),
            path: Path::new(profile, tf)?,
            p0: paper_p0(),
            tf,
        })
    }
}

impl crate::Case<12, 5, 4> for PaperCase {
    type Model = Navy3dPulley;
    type Path = Path;

    fn model(&self) -> &Navy3dPulley {
        &self.model
    }

    fn path(&self) -> &Path {
        &self.path
    }

    fn t0(&self) -> f64 {
        0.0
    }

    fn tf(&self) -> f64 {
        self.tf
    }

    fn start(&self) -> Result<State<12, 5, 4>, Error> {
        init::check_start(&self.model, &self.path, self.t0(), &self.p0, None)
    }

    /// None: the paper gives no analytical solution for the 3D cranes.
    fn derived_outputs(&self) -> &'static [&'static str] {
        &["phi"]
    }

    /// The slewing angle `phi = atan2(y, x)` of the boom tip, in rad.
    fn derived(&self, state: &State<12, 5, 4>) -> Vec<f64> {
        vec![slewing_angle(state)]
    }

    fn reference(&self, _t: f64) -> Option<State<12, 5, 4>> {
        None
    }
}

/// The slewing angle `phi = atan2(y3, x3)` of the boom in a state.
pub fn slewing_angle(state: &State<12, 5, 4>) -> f64 {
    state.q[7].atan2(state.q[6])
}
