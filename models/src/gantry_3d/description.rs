//! The 3D gantry crane as a built-in crane: a rest-to-rest move of the load
//! from `(0, 0, -5)` to `(6, 3, -3)` in 8 s from the load hanging at rest
//! straight below the trolley, its flatness-based reference and the drawing.

use crane_runtime::State;
use nalgebra::SVector;
use nalgebra::vector;

use super::model::Gantry3d;
use super::reference::reference_at;
use crate::case::Case;
use crate::crane::{Crane, LowerBound, Maneuver, bang_bang, finite_state};
use crate::drawing::{Drawing, Pose};
use crate::path::{Path, PathSpec, Profile};

/// The 3D gantry crane: bridge, trolley, hoist, load on one rope.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Description;

/// The crane on its default move.
pub type DefaultCase = Case<Description, 6, 1, 3>;

/// End time of the default move, s.
pub const TF: f64 = 8.0;

impl Crane<6, 1, 3> for Description {
    type Model = Gantry3d;
    const NAME: &'static str = "gantry-3d";
    const DESCRIPTION: &'static str = "3D gantry crane: bridge, trolley, hoist winch, one rope";
    const HAS_REFERENCE: bool = true;

    fn input_units() -> &'static [&'static str] {
        &["N", "N", "N m"]
    }

    /// Poly9 (eqs. 41-45) from `(0, 0, -5)` to `(6, 3, -3)` in [`TF`]; the
    /// start `p0 = [X, Y, L] = [0, 0, 5]`: at rest below the trolley.
    fn maneuver() -> Maneuver<3> {
        Maneuver {
            path: PathSpec {
                profile: Profile::Poly9,
                t0: 0.0,
                t1: TF,
                start: vector![0.0, 0.0, -5.0],
                end: vector![6.0, 3.0, -3.0],
            },
            p0: vec![0.0, 0.0, 5.0],
        }
    }

    /// The flatness-based solution of [`reference`](super::reference).
    fn reference(model: &Gantry3d, path: &Path<3>, t: f64) -> Option<State<6, 1, 3>> {
        let r = reference_at(model, path, t);
        finite_state(State {
            t,
            q: r.q,
            v: r.v,
            u: r.u,
            lambda: r.lambda,
        })
    }

    /// The X momentum of the whole crane (bridge, trolley, load: `m_b +
    /// m_t + m_l`) changes only by `u1`, the Y momentum of the trolley and
    /// the load (`m_t + m_l`) only by `u2` (the rope's pull is internal to
    /// each, and gravity is vertical). From rest to rest the load hangs
    /// below the trolley at both ends, so each group's centre of mass moves
    /// as far as the load does: no move under `|u1| <= f1` is faster than
    /// the bang-bang time of that mass over that distance
    /// ([`bang_bang`]), and the same for `u2`.
    fn lower_bound(
        model: &Gantry3d,
        start: &SVector<f64, 3>,
        end: &SVector<f64, 3>,
        limits: &[(usize, f64)],
    ) -> Option<LowerBound> {
        limits
            .iter()
            .filter_map(|&(k, force)| {
                let (mass, what, axis) = match k {
                    0 => (
                        model.m_b + model.m_t + model.m_l,
                        "the whole crane (m_b + m_t + m_l)",
                        0,
                    ),
                    1 => (model.m_t + model.m_l, "the trolley and the load (m_t + m_l)", 1),
                    _ => return None,
                };
                let distance = (end[axis] - start[axis]).abs();
                (distance > 0.0).then(|| LowerBound {
                    duration: bang_bang(distance, mass, force),
                    derivation: format!(
                        "{} alone moves {what}, {mass} kg, {distance} m along {}: bang-bang 2 sqrt(d m / |u|max) \
                         at |{}| <= {force}",
                        ["u1", "u2"][k],
                        ["X", "Y"][axis],
                        ["u1", "u2"][k]
                    ),
                })
            })
            .max_by(|a, b| a.duration.total_cmp(&b.duration))
    }

    fn minimal_guess(_: &Gantry3d, start: &State<6, 1, 3>) -> Vec<f64> {
        minimal_guess(start).as_slice().to_vec()
    }

    /// `q = [X, Y, L | x, y, z]`: the bridge at `X` spanning `y` from -10 to
    /// 10 m at height 0, the trolley `(X, Y, 0)`, the rope to the load.
    fn drawing(_: &Gantry3d) -> Option<Drawing> {
        Some(Drawing {
            spatial: true,
            fixed: vec![("O", [0.0; 3])],
            pose: Box::new(|q| {
                let trolley = [q[0], q[1], 0.0];
                let load = [q[3], q[4], q[5]];
                Pose {
                    boom: vec![[q[0], -10.0, 0.0], [q[0], 10.0, 0.0]],
                    ropes: vec![[trolley, load]],
                    pulley: trolley,
                    load,
                }
            }),
            ropes: "bridge at X, trolley B, rope B-C (L)",
        })
    }
}

/// The minimal coordinates `mu = [X, Y, x, y, z]` of a redundant state
/// (exact: they are coordinates of `q`).
pub fn minimal_guess(state: &State<6, 1, 3>) -> SVector<f64, 5> {
    let q = &state.q;
    SVector::from([q[0], q[1], q[3], q[4], q[5]])
}
