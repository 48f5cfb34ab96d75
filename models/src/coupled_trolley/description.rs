//! The coupled trolley crane as a built-in crane: the move on which its
//! unstable internal dynamics were found, poly9 from `(0, -5)` to `(4, -3)`
//! in 5 s from rest straight below the trolley; its causal inverse explodes (u(2.5 s) ~ 3e12 N), which
//! `crane run` diagnoses and reports.

use nalgebra::vector;

use super::model::CoupledTrolley;
use crate::case::Case;
use crate::crane::{Crane, Maneuver};
use crate::drawing::{Drawing, Pose};
use crate::path::{PathSpec, Profile};

/// The coupled trolley crane (not flat).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Description;

/// The crane on its default move.
pub type DefaultCase = Case<Description, 4, 1, 2>;

/// End time of the default move, s.
pub const TF: f64 = 5.0;

impl Crane<4, 1, 2> for Description {
    type Model = CoupledTrolley;
    const NAME: &'static str = "coupled-trolley";
    const DESCRIPTION: &'static str =
        "planar trolley crane, trolley-load coupling: NOT flat (unstable internal dynamics)";

    fn input_units() -> &'static [&'static str] {
        &["N", "N"]
    }

    /// Poly9 (eqs. 41-45) from `(0, -5)` to `(4, -3)` in [`TF`]; the start
    /// `p0 = [s, L] = [0, 5]`: at rest below the trolley.
    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec {
                profile: Profile::Poly9,
                t0: 0.0,
                t1: TF,
                start: vector![0.0, -5.0],
                end: vector![4.0, -3.0],
            },
            p0: vec![0.0, 5.0],
        }
    }

    /// `q = [s, L | x, z]`: the rail at height 0 from -5 to 10 m, the
    /// trolley at `(s, 0)`, the rope to the load.
    fn drawing(_: &CoupledTrolley) -> Option<Drawing> {
        Some(Drawing {
            spatial: false,
            fixed: vec![("O", [0.0; 3])],
            pose: Box::new(|q| {
                let trolley = [q[0], 0.0, 0.0];
                let load = [q[2], 0.0, q[3]];
                Pose {
                    boom: vec![[-5.0, 0.0, 0.0], [10.0, 0.0, 0.0]],
                    ropes: vec![[trolley, load]],
                    pulley: trolley,
                    load,
                }
            }),
            ropes: "rail, trolley B at s, rope B-C (L)",
        })
    }
}
