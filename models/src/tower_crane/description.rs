//! The rotary tower crane as a built-in crane: a rest-to-rest move of the
//! load from `(10, 0, 5)` to `(6, 12, 10)` in 10 s (the jib slews by about
//! 63 degrees) from the load hanging at rest below the trolley, and the
//! drawing.

use crane_runtime::State;
use nalgebra::{SVector, vector};

use super::model::TowerCrane;
use crate::case::Case;
use crate::crane::{Crane, Maneuver};
use crate::drawing::{Drawing, Pose};
use crate::path::{PathSpec, Profile};

/// The rotary tower crane: slewing jib, trolley, hoist, load on one rope.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Description;

/// The crane on its default move.
pub type DefaultCase = Case<Description, 8, 3, 3>;

/// End time of the default move, s.
pub const TF: f64 = 10.0;

/// The slewing angle `phi = atan2(y1, x1)` of the jib in a state.
pub fn slewing_angle(state: &State<8, 3, 3>) -> f64 {
    state.q[1].atan2(state.q[0])
}

impl Crane<8, 3, 3> for Description {
    type Model = TowerCrane;
    const NAME: &'static str = "tower-crane";
    const DESCRIPTION: &'static str = "rotary tower crane: slewing jib, trolley, hoist winch, one rope";

    fn input_units() -> &'static [&'static str] {
        &["N m", "N", "N m"]
    }

    /// Poly9 (eqs. 41-45) from `(10, 0, 5)` to `(6, 12, 10)` in [`TF`]; the
    /// start `p0 = [x1, y1, xt, yt, L] = [30, 0, 10, 0, 15]`: the jib along
    /// `X`, the trolley at 10 m, the load 15 m below it.
    fn maneuver() -> Maneuver<3> {
        Maneuver {
            path: PathSpec {
                profile: Profile::Poly9,
                t0: 0.0,
                t1: TF,
                start: vector![10.0, 0.0, 5.0],
                end: vector![6.0, 12.0, 10.0],
            },
            p0: vec![30.0, 0.0, 10.0, 0.0, 15.0],
        }
    }

    fn minimal_guess(_: &TowerCrane, start: &State<8, 3, 3>) -> Vec<f64> {
        minimal_guess(start).as_slice().to_vec()
    }

    fn derived_outputs() -> &'static [&'static str] {
        &["phi"]
    }

    /// The slewing angle of the jib, in rad.
    fn derived(_: &TowerCrane, state: &State<8, 3, 3>) -> Vec<f64> {
        vec![slewing_angle(state)]
    }

    /// `q = [x1, y1, xt, yt, L | x, y, z]`: the tower from the origin to
    /// height `H`, the jib to its tip `(x1, y1, H)`, the trolley B and the
    /// rope to the load C.
    fn drawing(model: &TowerCrane) -> Option<Drawing> {
        let h = model.H;
        Some(Drawing {
            spatial: true,
            fixed: vec![("O", [0.0; 3])],
            pose: Box::new(move |q| {
                let trolley = [q[2], q[3], h];
                let load = [q[5], q[6], q[7]];
                Pose {
                    boom: vec![[0.0, 0.0, 0.0], [0.0, 0.0, h], [q[0], q[1], h]],
                    ropes: vec![[trolley, load]],
                    pulley: trolley,
                    load,
                }
            }),
            ropes: "jib O-tip, trolley B, rope B-C (L)",
        })
    }
}

/// The minimal coordinates `mu = [phi, rho, x, y, z]` of a redundant state:
/// the jib's angle, the trolley's signed distance from the axis along the
/// jib, the load.
pub fn minimal_guess(state: &State<8, 3, 3>) -> SVector<f64, 5> {
    let q = &state.q;
    let phi = q[1].atan2(q[0]);
    let rho = q[2] * phi.cos() + q[3] * phi.sin();
    SVector::from([phi, rho, q[5], q[6], q[7]])
}
