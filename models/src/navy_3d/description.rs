//! The 3D crane with massless pulley as a built-in crane: the paper's
//! manoeuvre (sect. 6.1.1: path eqs. 82-86 with (86) as corrected, start
//! eqs. 87-88), the flatness-based reference of
//! [`reference`](super::reference) (not in the paper), the slewing angle as
//! a derived output and the drawing.

use crane_runtime::State;
use nalgebra::vector;

use super::model::Navy3d;
use super::reference::reference_at;
use crate::case::Case;
use crate::crane::{Crane, Maneuver, finite_state};
use crate::drawing::{Drawing, Pose, scale};
use crate::path::{Path, PathSpec, Profile};

/// End time of the paper's maneuver, s (eq. 84); it starts at `t0 = 0`, so
/// this is also the duration `tau` of eq. (86).
pub const TF: f64 = 20.0;
/// Duration `tau0` of the acceleration and deceleration phases, s (eq. 86).
pub const TAU0: f64 = 5.0;

/// The 3D US Navy crane with massless pulley (sect. 6.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Description;

/// The crane on the paper's manoeuvre (`PaperCase::new(TF)`: Figs. 22-23).
pub type PaperCase = Case<Description, 11, 4, 3>;

/// The paper's start `p0 = [L1, L2, L0, x0, y0, z0, x2, y2] = [5/2 sqrt 3,
/// 15, 5/2, 5 sqrt 3, 0, 5/2, 5 sqrt 3, 0]` (eq. 87) with the load at
/// `x0 = gamma0 = (5 sqrt 3, 0, -10)` (eq. 88).
///
/// The boom points along `X` (`phi = 0`), its tip `P = (5 sqrt 3, 0, 5)` and
/// winch 1 at `A = P/2`; the pulley hangs on the vertical through `P` and the
/// load, 2.5 m below `P`, at the height of `A`. The load hangs straight below
/// `P`, so rope `L1` carries no tension and the static balance is singular:
/// the pulley may sit anywhere on that vertical. The printed `p0` is the limit
/// `t -> 0+` of the flatness solution (docs/errata.md, degenerate starts), as
/// for the planar crane's start (46).
pub fn paper_p0() -> [f64; 8] {
    let s3 = 3f64.sqrt();
    [2.5 * s3, 15.0, 2.5, 5.0 * s3, 0.0, 2.5, 5.0 * s3, 0.0]
}

/// The slewing angle `phi = atan2(y2, x2)` of the boom (Fig. 21) in a state.
pub fn slewing_angle(state: &State<11, 4, 3>) -> f64 {
    state.q[7].atan2(state.q[6])
}

impl Crane<11, 4, 3> for Description {
    type Model = Navy3d;
    const NAME: &'static str = "navy-3d";
    const DESCRIPTION: &'static str = "3D US Navy crane, massless pulley, slewing (paper sect. 6.1)";
    const HAS_REFERENCE: bool = true;

    fn input_units() -> &'static [&'static str] {
        &["N m", "N m", "N m"]
    }

    /// Eqs. (82)-(86): from `gamma0 = (5 sqrt 3, 0, -10)` at `t0 = 0`
    /// (eq. 83) to `gammaf = (2, 5, -5)` at [`TF`] (eq. 84) on the
    /// three-phase profile with ramps of [`TAU0`] (eqs. 85-86 as corrected).
    fn maneuver() -> Maneuver<3> {
        Maneuver {
            path: PathSpec {
                profile: Profile::ThreePhase { tau0: TAU0 },
                t0: 0.0,
                t1: TF,
                start: vector![5.0 * 3f64.sqrt(), 0.0, -10.0],
                end: vector![2.0, 5.0, -5.0],
            },
            p0: paper_p0().to_vec(),
        }
    }

    /// The flatness-based solution of [`reference`](super::reference).
    fn reference(model: &Navy3d, path: &Path<3>, t: f64) -> Option<State<11, 4, 3>> {
        let r = reference_at(model, path, t)?;
        finite_state(State {
            t,
            q: r.q,
            v: r.v,
            u: r.u,
            lambda: r.lambda,
        })
    }

    fn derived_outputs() -> &'static [&'static str] {
        &["phi"]
    }

    /// The slewing angle `phi = atan2(y, x)` of the boom tip, in rad.
    fn derived(_: &Navy3d, state: &State<11, 4, 3>) -> Vec<f64> {
        vec![slewing_angle(state)]
    }

    /// `q = [L1, L2, L0, x0, y0, z0, x2, y2 | x, y, z]`; boom from O to the
    /// tip `P = (x2, y2, (k + l) cos alpha)`, winch 1 at `A = beta1 P`
    /// (eqs. 68-78).
    fn drawing(model: &Navy3d) -> Option<Drawing> {
        let (alpha, k, l, beta1) = (model.alpha, model.k, model.l, model.beta1);
        let height = (k + l) * alpha.cos();
        Some(Drawing {
            spatial: true,
            fixed: vec![("O", [0.0; 3])],
            pose: Box::new(move |q| {
                let p = [q[6], q[7], height];
                let a = scale(p, beta1);
                let b = [q[3], q[4], q[5]];
                let c = [q[8], q[9], q[10]];
                Pose {
                    boom: vec![[0.0; 3], p],
                    ropes: vec![[a, b], [p, b], [b, c]],
                    pulley: b,
                    load: c,
                }
            }),
            ropes: "ropes A-B (L1), P-B-C (L2)",
        })
    }
}
