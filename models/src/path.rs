//! Load paths as data: the profile, the times and the end points of a move,
//! from which the path `gamma(t)` of the servo constraints is built.
//!
//! A built-in crane's default manoeuvre and a scenario file describe their
//! path the same way ([`PathSpec`]); [`Path`] is the trajectory built from it
//! and keeps the description, so a scenario can change one key of the
//! default (the end point, the duration) and rebuild.

use crane_runtime::Trajectory;
use crane_runtime::bspline::BSpline;
use crane_runtime::double_double::DoubleDouble;
use crane_runtime::trajectory::{Poly9, SmoothThreePhase, ThreePhase, TrajectoryError};
use nalgebra::SVector;

/// The kind of a move's profile: the one list of profiles that scenario
/// files (by name: `trajectory = "poly9"`), planning and the FMU (by
/// integer code: the `path` variable) name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ProfileKind {
    /// Rest-to-rest 5-6-7-8-9 polynomial (eqs. 41-45).
    Poly9,
    /// Ramp, constant speed, ramp (eqs. 85-86 as corrected, docs/errata.md):
    /// four times continuously differentiable.
    ThreePhase,
    /// The same with ramps continuous up to the 6th derivative (bounded
    /// slewing torque for the 3D crane with pulley mass, docs/errata.md).
    SmoothThreePhase,
    /// A clamped B-spline through waypoints or control points: any shape.
    Spline,
}

impl ProfileKind {
    /// The straight moves from `start` to `end`, in the order of their codes.
    pub const ALL: [ProfileKind; 3] = [
        ProfileKind::Poly9,
        ProfileKind::ThreePhase,
        ProfileKind::SmoothThreePhase,
    ];

    /// Every kind a scenario file names: the straight moves and the spline.
    pub const NAMED: [ProfileKind; 4] = [
        ProfileKind::Poly9,
        ProfileKind::ThreePhase,
        ProfileKind::SmoothThreePhase,
        ProfileKind::Spline,
    ];

    /// The name in scenario files: `poly9`, `three-phase`,
    /// `smooth-three-phase`, `spline`.
    pub fn name(self) -> &'static str {
        match self {
            ProfileKind::Poly9 => "poly9",
            ProfileKind::ThreePhase => "three-phase",
            ProfileKind::SmoothThreePhase => "smooth-three-phase",
            ProfileKind::Spline => "spline",
        }
    }

    /// The integer code of a straight move (the FMU's `path` variable): the
    /// place in [`ALL`](Self::ALL), 0, 1, 2; a spline has none.
    pub fn code(self) -> Option<i32> {
        Self::ALL.iter().position(|k| *k == self).map(|i| i as i32)
    }

    /// The names of the kinds with ramps, for messages: `"three-phase" and "smooth-three-phase"`.
    pub fn with_ramps() -> String {
        let names: Vec<String> = Self::ALL
            .iter()
            .filter(|k| k.has_ramps())
            .map(|k| format!("\"{}\"", k.name()))
            .collect();
        names.join(" and ")
    }

    /// The kind of an integer code, if it is one.
    pub fn from_code(code: i32) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.code() == Some(code))
    }

    /// Whether the profile has ramps of a duration `tau0`.
    pub fn has_ramps(self) -> bool {
        matches!(self, ProfileKind::ThreePhase | ProfileKind::SmoothThreePhase)
    }

    /// The straight move of this kind; `tau0` is the ramp duration of the
    /// three-phase kinds (ignored for poly9; `None` there is an error
    /// naming what is missing). A spline is built from its points
    /// ([`SplineShape`]), not here.
    pub fn profile(self, tau0: Option<f64>) -> Result<Profile, MissingRamp> {
        match (self, tau0) {
            (ProfileKind::Poly9, _) => Ok(Profile::Poly9),
            (ProfileKind::ThreePhase, Some(tau0)) => Ok(Profile::ThreePhase { tau0 }),
            (ProfileKind::SmoothThreePhase, Some(tau0)) => Ok(Profile::SmoothThreePhase { tau0 }),
            (kind, _) => Err(MissingRamp(kind)),
        }
    }
}

/// A profile name that is none of [`ProfileKind::NAMED`]'s.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown profile `{0}`; expected {names}", names = ProfileKind::NAMED.map(|k| k.name()).join(", "))]
pub struct UnknownProfile(pub String);

impl std::str::FromStr for ProfileKind {
    type Err = UnknownProfile;
    fn from_str(s: &str) -> Result<Self, UnknownProfile> {
        Self::NAMED
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| UnknownProfile(s.to_string()))
    }
}

impl<'de> serde::Deserialize<'de> for ProfileKind {
    /// By [`name`](Self::name).
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

impl std::fmt::Display for ProfileKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A three-phase profile asked for without its ramp duration (or a spline
/// without its points).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("{}", match .0 {
    ProfileKind::Spline => "a spline profile needs its waypoints or its control points".to_string(),
    kind => format!("the {kind} profile needs its ramp duration tau0"),
})]
pub struct MissingRamp(pub ProfileKind);

/// The shape of a spline move: a clamped B-spline of the move's
/// normalised time `s = (t - t0) / (t1 - t0)`, its knots on `[0, 1]` and its
/// control points in load coordinates. The same shape stretched to another
/// duration is the same path slower or faster (a move scaled in time).
#[derive(Debug, Clone, PartialEq)]
pub struct SplineShape {
    degree: usize,
    knots: Vec<f64>,
    control: Vec<Vec<f64>>,
}

impl SplineShape {
    /// The shape of degree `degree` on `knots` (on `[0, 1]`, clamped)
    /// through `control` points of `A` coordinates each, checked as a
    /// [`BSpline`] is.
    pub fn new<const A: usize>(
        degree: usize,
        knots: Vec<f64>,
        control: &[SVector<f64, A>],
    ) -> Result<Self, TrajectoryError> {
        if knots.first() != Some(&0.0) || knots.last() != Some(&1.0) {
            return Err(TrajectoryError::Spline {
                reason: "the knots of a shape in normalised time run from 0 to 1".into(),
            });
        }
        let spline = BSpline::new(degree, knots, control.to_vec())?;
        Ok(Self::of(&spline))
    }

    /// The shape through `waypoints` at normalised `times` (from 0 to 1),
    /// at rest to order `rest` at both ends ([`BSpline::through`]).
    pub fn through<const A: usize>(
        times: &[f64],
        waypoints: &[SVector<f64, A>],
        rest: usize,
    ) -> Result<Self, TrajectoryError> {
        if times.first() != Some(&0.0) || times.last() != Some(&1.0) {
            return Err(TrajectoryError::Spline {
                reason: "the waypoints' times in normalised time run from 0 to 1".into(),
            });
        }
        Ok(Self::of(&BSpline::through(times, waypoints, rest)?))
    }

    fn of<const A: usize>(spline: &BSpline<A>) -> Self {
        Self {
            degree: spline.degree(),
            knots: spline.knots().to_vec(),
            control: spline
                .control_points()
                .iter()
                .map(|p| p.iter().copied().collect())
                .collect(),
        }
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knots, from 0 to 1.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The control points, each the load coordinates.
    pub fn control(&self) -> &[Vec<f64>] {
        &self.control
    }

    /// The first control point (where the move starts) and the last (where it ends).
    pub fn ends(&self) -> (&[f64], &[f64]) {
        (&self.control[0], &self.control[self.control.len() - 1])
    }

    /// The path from `t0` to `t1`: the knots mapped to `t0 (1 - s) + t1 s`
    /// (exactly `t0` and `t1` at the ends).
    pub fn path<const A: usize>(&self, t0: f64, t1: f64) -> Result<BSpline<A>, TrajectoryError> {
        let control = self
            .control
            .iter()
            .map(|p| {
                (p.len() == A)
                    .then(|| SVector::from_column_slice(p))
                    .ok_or_else(|| TrajectoryError::Spline {
                        reason: format!("a control point has {} coordinates, the load {A}", p.len()),
                    })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let knots = self.knots.iter().map(|&s| t0 * (1.0 - s) + t1 * s).collect();
        BSpline::new(self.degree, knots, control)
    }

    /// The shortest span between distinct knots, as a fraction of the move.
    fn shortest_span(&self) -> f64 {
        self.knots
            .windows(2)
            .map(|w| w[1] - w[0])
            .filter(|&d| d > 0.0)
            .fold(1.0, f64::min)
    }
}

/// The profile of a move.
#[derive(Debug, Clone, PartialEq)]
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
    /// A clamped B-spline in the move's normalised time, from its first
    /// control point (`start`) to its last (`end`).
    Spline(std::sync::Arc<SplineShape>),
}

impl Profile {
    /// Its kind.
    pub fn kind(&self) -> ProfileKind {
        match self {
            Profile::Poly9 => ProfileKind::Poly9,
            Profile::ThreePhase { .. } => ProfileKind::ThreePhase,
            Profile::SmoothThreePhase { .. } => ProfileKind::SmoothThreePhase,
            Profile::Spline(_) => ProfileKind::Spline,
        }
    }

    /// The ramp duration, if the profile has ramps.
    pub fn tau0(&self) -> Option<f64> {
        match self {
            Profile::Poly9 | Profile::Spline(_) => None,
            Profile::ThreePhase { tau0 } | Profile::SmoothThreePhase { tau0 } => Some(*tau0),
        }
    }

    /// The same profile with its ramps scaled by `factor` (a move scaled in
    /// time; a spline's shape is in normalised time already).
    pub fn scaled(&self, factor: f64) -> Self {
        match self {
            Profile::Poly9 => Profile::Poly9,
            Profile::ThreePhase { tau0 } => Profile::ThreePhase { tau0: tau0 * factor },
            Profile::SmoothThreePhase { tau0 } => Profile::SmoothThreePhase { tau0: tau0 * factor },
            Profile::Spline(shape) => Profile::Spline(shape.clone()),
        }
    }
}

/// A move of the load from `start` at `t0` to `end` at `t1` on a profile.
#[derive(Debug, Clone, PartialEq)]
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

impl<const A: usize> PathSpec<A> {
    /// The shortest feature of the path, s, that steps must resolve: the
    /// ramps of a three-phase profile, the whole move of a polynomial one,
    /// the shortest span between a spline's knots.
    pub fn shortest_feature(&self) -> f64 {
        match &self.profile {
            Profile::Spline(shape) => shape.shortest_span() * (self.t1 - self.t0),
            profile => profile.tau0().unwrap_or(self.t1 - self.t0),
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Built<const A: usize> {
    Poly9(Poly9<A>),
    ThreePhase(ThreePhase<A>),
    SmoothThreePhase(SmoothThreePhase<A>),
    Spline(BSpline<A>),
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
    /// Build the path; errors for times, ramps or points the profile
    /// refuses (and a spline whose ends are not `start` and `end`).
    pub fn new(spec: PathSpec<A>) -> Result<Self, TrajectoryError> {
        let PathSpec {
            ref profile,
            t0,
            t1,
            start,
            end,
        } = spec;
        let built = match profile {
            Profile::Spline(shape) => {
                let spline = shape.path(t0, t1)?;
                let points = spline.control_points();
                if points[0] != start || points[points.len() - 1] != end {
                    return Err(TrajectoryError::Spline {
                        reason: "the move's start and end are not the spline's first and last control points".into(),
                    });
                }
                Built::Spline(spline)
            }
            Profile::Poly9 => Built::Poly9(Poly9::new(t0, t1, start, end)?),
            Profile::ThreePhase { tau0 } => Built::ThreePhase(ThreePhase::new(t0, t1 - t0, *tau0, start, end)?),
            Profile::SmoothThreePhase { tau0 } => {
                Built::SmoothThreePhase(SmoothThreePhase::new(t0, t1 - t0, *tau0, start, end)?)
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
            Built::Spline(p) => p.derivative(t, k),
        }
    }

    fn derivatives_into(&self, t: f64, out: &mut [SVector<f64, A>]) {
        match &self.built {
            Built::Poly9(p) => p.derivatives_into(t, out),
            Built::ThreePhase(p) => p.derivatives_into(t, out),
            Built::SmoothThreePhase(p) => p.derivatives_into(t, out),
            Built::Spline(p) => p.derivatives_into(t, out),
        }
    }

    fn continuity(&self) -> Option<usize> {
        match &self.built {
            Built::Poly9(p) => p.continuity(),
            Built::ThreePhase(p) => p.continuity(),
            Built::SmoothThreePhase(p) => p.continuity(),
            Built::Spline(p) => p.continuity(),
        }
    }

    fn target_extended(&self, t: DoubleDouble) -> Option<[SVector<DoubleDouble, A>; 3]> {
        match &self.built {
            Built::Poly9(p) => p.target_extended(t),
            Built::ThreePhase(p) => p.target_extended(t),
            Built::SmoothThreePhase(p) => p.target_extended(t),
            Built::Spline(p) => p.target_extended(t),
        }
    }
}
