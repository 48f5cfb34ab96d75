//! The crane with an elastic trolley drive as a built-in crane: a
//! rest-to-rest move of the load from `(0, -5)` to `(3, -4)` in 8 s on the
//! three-phase profile with ramps continuous to the 6th derivative (the
//! inputs need `x^(6)`), from the load at rest below the trolley with the
//! belt unstretched; its flatness-based reference and the drawing.

use crane_runtime::State;
use nalgebra::vector;

use super::model::ElasticDrive;
use super::reference::reference_at;
use crate::case::Case;
use crate::crane::{Crane, Maneuver, finite_state};
use crate::drawing::{Drawing, Pose};
use crate::path::{Path, PathSpec, Profile};

/// The overhead crane with an elastic belt drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Description;

/// The crane on its default move.
pub type DefaultCase = Case<Description, 5, 1, 2>;

/// End time of the default move, s.
pub const TF: f64 = 8.0;

/// Duration of the acceleration and deceleration ramps of the default move, s.
pub const TAU0: f64 = 2.5;

impl Crane<5, 1, 2> for Description {
    type Model = ElasticDrive;
    const NAME: &'static str = "elastic-drive";
    const DESCRIPTION: &'static str = "overhead crane whose trolley is driven through an elastic belt";
    const HAS_REFERENCE: bool = true;

    fn input_units() -> &'static [&'static str] {
        &["N m", "N m"]
    }

    /// The smooth three-phase profile (ramps of [`TAU0`]) from `(0, -5)` to
    /// `(3, -4)` in [`TF`]; the start `p0 = [phi, s, L] = [0, 0, 5]`: the
    /// load at rest below the trolley, the belt unstretched.
    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec {
                profile: Profile::SmoothThreePhase { tau0: TAU0 },
                t0: 0.0,
                t1: TF,
                start: vector![0.0, -5.0],
                end: vector![3.0, -4.0],
            },
            p0: vec![0.0, 0.0, 5.0],
        }
    }

    /// The flatness-based solution of [`reference`](super::reference).
    fn reference(model: &ElasticDrive, path: &Path<2>, t: f64) -> Option<State<5, 1, 2>> {
        finite_state(reference_at(model, path, t).state(t))
    }

    /// `q = [phi, s, L | x, z]`: the rail at height 0 from the motor at the
    /// origin, the trolley `(s, 0)`, the rope to the load.
    fn drawing(_: &ElasticDrive) -> Option<Drawing> {
        Some(Drawing {
            spatial: false,
            fixed: vec![("motor", [0.0; 3])],
            pose: Box::new(|q| {
                let trolley = [q[1], 0.0, 0.0];
                let load = [q[3], 0.0, q[4]];
                Pose {
                    boom: vec![[0.0; 3], trolley],
                    ropes: vec![[trolley, load]],
                    pulley: trolley,
                    load,
                }
            }),
            ropes: "belt from the motor to the trolley B, rope B-C (L)",
        })
    }
}
