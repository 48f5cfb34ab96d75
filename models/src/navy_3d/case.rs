//! The paper's maneuver for the 3D crane with massless pulley (sect. 6.1.1):
//! path eqs. (82)-(86) with ERRATA (86), start eqs. (87)-(88), and the
//! flatness-based reference of [`reference`](super::reference) (not in the
//! paper).

use crane_runtime::trajectory::{ThreePhase, TrajectoryError};
use crane_runtime::{CraneModel, Error, State, init};
use nalgebra::vector;

use super::model::Navy3d;
use super::reference::{Params3d, reference_at};

/// End time of the paper's maneuver, s (eq. 84); it starts at `t0 = 0`, so
/// this is also the duration `tau` of eq. (86).
pub const TF: f64 = 20.0;
/// Duration `tau0` of the acceleration and deceleration phases, s (eq. 86).
pub const TAU0: f64 = 5.0;

/// The paper's start `p0 = [L1, L2, L0, x0, y0, z0, x2, y2] = [5/2 sqrt 3,
/// 15, 5/2, 5 sqrt 3, 0, 5/2, 5 sqrt 3, 0]` (eq. 87) with the load at
/// `x0 = gamma0 = (5 sqrt 3, 0, -10)` (eq. 88).
///
/// The boom points along `X` (`phi = 0`), its tip `P = (5 sqrt 3, 0, 5)` and
/// winch 1 at `A = P/2`; the pulley hangs on the vertical through `P` and the
/// load, 2.5 m below `P`, at the height of `A`. The load hangs straight below
/// `P`, so rope `L1` carries no tension and the static balance is singular:
/// the pulley may sit anywhere on that vertical. The printed `p0` is the limit
/// `t -> 0+` of the flatness solution (ERRATA, "Degenerate starts"), as for
/// the planar crane's start (46).
pub fn paper_p0() -> [f64; 8] {
    let s3 = 3f64.sqrt();
    [2.5 * s3, 15.0, 2.5, 5.0 * s3, 0.0, 2.5, 5.0 * s3, 0.0]
}

/// The load path of eqs. (82)-(86): from `gamma0 = (5 sqrt 3, 0, -10)` at
/// `t0 = 0` (eq. 83) to `gammaf = (2, 5, -5)` at `tf = tau` (eq. 84; 20 s in
/// the paper, [`TF`]), with the three-phase profile `c(t)` (eqs. 85-86 as
/// corrected in ERRATA: ramps of `tau0 = 5 s`, constant speed in between;
/// `tf >= 2 tau0 = 10 s`).
pub fn paper_path(tf: f64) -> Result<ThreePhase<3>, TrajectoryError> {
    ThreePhase::new(
        0.0,
        tf,
        TAU0,
        vector![5.0 * 3f64.sqrt(), 0.0, -10.0],
        vector![2.0, 5.0, -5.0],
    )
}

/// The crane with the paper's parameters on the paper's maneuver.
#[derive(Debug, Clone)]
pub struct PaperCase {
    /// The crane.
    pub model: Navy3d,
    /// The load path.
    pub path: ThreePhase<3>,
    /// The start `p0`.
    pub p0: [f64; 8],
    /// End time `tf` of the path (it starts at `t0 = 0`).
    pub tf: f64,
}

impl PaperCase {
    /// The paper's case with end time `tf` ([`TF`] = 20 s in the paper;
    /// ramps of `tau0 = 5 s`, so `tf >= 10 s`).
    pub fn new(tf: f64) -> Result<Self, TrajectoryError> {
        Ok(Self {
            model: Navy3d::default(),
            path: paper_path(tf)?,
            p0: paper_p0(),
            tf,
        })
    }

    /// The model's parameters as the reference takes them.
    pub fn params(&self) -> Params3d {
        Params3d::from_values(&self.model.parameter_values()).expect("11 parameters")
    }
}

impl crate::Case<11, 4, 3> for PaperCase {
    type Model = Navy3d;
    type Path = ThreePhase<3>;

    fn model(&self) -> &Navy3d {
        &self.model
    }

    fn path(&self) -> &ThreePhase<3> {
        &self.path
    }

    fn t0(&self) -> f64 {
        0.0
    }

    fn tf(&self) -> f64 {
        self.tf
    }

    fn start(&self) -> Result<State<11, 4, 3>, Error> {
        init::check_start(&self.model, &self.path, self.t0(), &self.p0, None)
    }

    /// The flatness-based solution of [`reference`](super::reference) (the
    /// paper gives none for the 3D cranes).
    fn derived_outputs(&self) -> &'static [&'static str] {
        &["phi"]
    }

    /// The slewing angle `phi = atan2(y, x)` of the boom tip, in rad.
    fn derived(&self, state: &State<11, 4, 3>) -> Vec<f64> {
        vec![slewing_angle(state)]
    }

    fn reference(&self, t: f64) -> Option<State<11, 4, 3>> {
        let r = reference_at(&self.params(), &self.path, t)?;
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        (finite(r.q.as_slice())
            && finite(r.v.as_slice())
            && finite(r.u.as_slice())
            && finite(r.lambda.as_slice()))
        .then_some(State {
            t,
            q: r.q,
            v: r.v,
            u: r.u,
            lambda: r.lambda,
        })
    }
}

/// The slewing angle `phi = atan2(y2, x2)` of the boom (Fig. 21) in a state.
pub fn slewing_angle(state: &State<11, 4, 3>) -> f64 {
    state.q[7].atan2(state.q[6])
}
