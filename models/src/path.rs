//! Load paths as data: the profile, the times and the end points of a move,
//! from which the path `gamma(t)` of the servo constraints is built.
//!
//! A built-in crane's default manoeuvre and a scenario file describe their
//! path the same way ([`PathSpec`]); [`Path`] is the trajectory built from it
//! and keeps the description, so a scenario can change one key of the
//! default (the end point, the duration) and rebuild.

use crane_runtime::Trajectory;
use crane_runtime::trajectory::{Poly9, SmoothThreePhase, ThreePhase, TrajectoryError};
use nalgebra::SVector;

/// The profile of a move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Profile {
    /// Rest-to-rest 5-6-7-8-9 polynomial (eqs. 41-45).
    Poly9,
    /// Ramp, constant speed, ramp (eqs. 85-86 as corrected, docs/errata.md),
    /// with ramps of `tau0` seconds: four times continuously differentiable.
    ThreePhase {
        /// Ramp duration, s.
        tau0: f64,
    },
    /// The same with ramps continuous up to the 6th derivative.
    SmoothThreePhase {
        /// Ramp duration, s.
        tau0: f64,
    },
}

/// A move of the load from `start` at `t0` to `end` at `t1` on a profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSpec<const A: usize> {
    /// The profile.
    pub profile: Profile,
    /// Start of the motion, s.
    pub t0: f64,
    /// End of the motion, s.
    pub t1: f64,
    /// Load coordinates at `t0`.
    pub start: SVector<f64, A>,
    /// Load coordinates at `t1`.
    pub end: SVector<f64, A>,
}

#[derive(Debug, Clone, PartialEq)]
enum Built<const A: usize> {
    Poly9(Poly9<A>),
    ThreePhase(ThreePhase<A>),
    SmoothThreePhase(SmoothThreePhase<A>),
}

/// The path of a [`PathSpec`].
///
/// ```
/// use crane_models::path::{Path, PathSpec, Profile};
/// use crane_runtime::Trajectory;
/// use crane_runtime::nalgebra::vector;
/// let spec = PathSpec { profile: Profile::Poly9, t0: 0.0, t1: 4.0, start: vector![0.0, -10.0], end: vector![-3.0, -14.0] };
/// let path = Path::new(spec).unwrap();
/// assert_eq!(path.derivative(2.0, 0), vector![-1.5, -12.0]);
/// assert_eq!(path.spec().t1, 4.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Path<const A: usize> {
    spec: PathSpec<A>,
    built: Built<A>,
}

impl<const A: usize> Path<A> {
    /// Build the path; errors for times, ramps or points the profile refuses.
    pub fn new(spec: PathSpec<A>) -> Result<Self, TrajectoryError> {
        let PathSpec {
            profile,
            t0,
            t1,
            start,
            end,
        } = spec;
        let built = match profile {
            Profile::Poly9 => Built::Poly9(Poly9::new(t0, t1, start, end)?),
            Profile::ThreePhase { tau0 } => Built::ThreePhase(ThreePhase::new(t0, t1 - t0, tau0, start, end)?),
            Profile::SmoothThreePhase { tau0 } => {
                Built::SmoothThreePhase(SmoothThreePhase::new(t0, t1 - t0, tau0, start, end)?)
            }
        };
        Ok(Self { spec, built })
    }

    /// What the path was built from.
    pub fn spec(&self) -> &PathSpec<A> {
        &self.spec
    }
}

impl<const A: usize> Trajectory<A> for Path<A> {
    fn derivative(&self, t: f64, k: usize) -> SVector<f64, A> {
        match &self.built {
            Built::Poly9(p) => p.derivative(t, k),
            Built::ThreePhase(p) => p.derivative(t, k),
            Built::SmoothThreePhase(p) => p.derivative(t, k),
        }
    }

    fn continuity(&self) -> Option<usize> {
        match &self.built {
            Built::Poly9(p) => p.continuity(),
            Built::ThreePhase(p) => p.continuity(),
            Built::SmoothThreePhase(p) => p.continuity(),
        }
    }
}
