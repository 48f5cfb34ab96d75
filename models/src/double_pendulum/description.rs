//! The double-pendulum crane as a built-in crane: a rest-to-rest move of
//! the load from `(0, -6)` to `(4, -5)` in 10 s on the three-phase profile
//! with ramps continuous to the 6th derivative (the inputs need `x^(6)`),
//! from hook and load hanging at rest below the trolley; its
//! flatness-based reference and the drawing.

use crane_runtime::State;
use nalgebra::{SVector, vector};

use super::model::DoublePendulum;
use super::reference::reference_at;
use crate::case::Case;
use crate::crane::{Crane, LowerBound, Maneuver, bang_bang, finite_state};
use crate::drawing::{Drawing, Pose};
use crate::path::{Path, PathSpec, Profile};

/// The double-pendulum overhead crane: trolley, hoist, hook block, sling, load.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Description;

/// The crane on its default move.
pub type DefaultCase = Case<Description, 6, 2, 2>;

/// End time of the default move, s.
pub const TF: f64 = 10.0;

/// Duration of the acceleration and deceleration ramps of the default move, s.
pub const TAU0: f64 = 3.0;

impl Crane<6, 2, 2> for Description {
    type Model = DoublePendulum;
    const NAME: &'static str = "double-pendulum";
    const DESCRIPTION: &'static str = "double-pendulum overhead crane: trolley, hoist, hook block, load on a sling";
    const HAS_REFERENCE: bool = true;

    fn input_units() -> &'static [&'static str] {
        &["N", "N m"]
    }

    /// The smooth three-phase profile (ramps of [`TAU0`], continuous to the
    /// 6th derivative) from `(0, -6)` to `(4, -5)` in [`TF`]; the start
    /// `p0 = [s, L, xh, zh] = [0, 4, 0, -4]`: hook and load at rest below
    /// the trolley.
    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec {
                profile: Profile::SmoothThreePhase { tau0: TAU0 },
                t0: 0.0,
                t1: TF,
                start: vector![0.0, -6.0],
                end: vector![4.0, -5.0],
            },
            p0: vec![0.0, 4.0, 0.0, -4.0],
        }
    }

    /// The flatness-based solution of [`reference`](super::reference).
    fn reference(model: &DoublePendulum, path: &Path<2>, t: f64) -> Option<State<6, 2, 2>> {
        finite_state(reference_at(model, path, t).state(t))
    }

    /// The horizontal momentum of trolley, hook and load (`m_t + m_h +
    /// m_l`) changes only by `u1`: the ropes' pulls are internal (the
    /// constraints depend on `xh - s` and `x - xh` only), the winch acts
    /// along the rope and gravity is vertical. From rest to rest hook and
    /// load hang below the trolley at both ends, so the centre of mass
    /// moves as far along `x` as the load: no move under `|u1| <= f` is
    /// faster than the bang-bang time of that mass over that distance
    /// ([`bang_bang`]). `u2` gives no such bound (the hoist's force is
    /// not the only vertical one).
    fn lower_bound(
        model: &DoublePendulum,
        start: &SVector<f64, 2>,
        end: &SVector<f64, 2>,
        limits: &[(usize, f64)],
    ) -> Option<LowerBound> {
        let distance = (end[0] - start[0]).abs();
        let mass = model.m_t + model.m_h + model.m_l;
        limits
            .iter()
            .find(|&&(k, _)| k == 0)
            .filter(|_| distance > 0.0)
            .map(|&(_, force)| LowerBound {
                duration: bang_bang(distance, mass, force),
                derivation: format!(
                    "u1 alone moves trolley, hook and load (m_t + m_h + m_l), {mass} kg, {distance} m along x: \
                     bang-bang 2 sqrt(d m / |u|max) at |u1| <= {force}"
                ),
            })
    }

    /// `q = [s, L, xh, zh | x, z]`: the rail at height 0, the trolley
    /// `(s, 0)`, the hoist rope to the hook, the sling to the load.
    fn drawing(_: &DoublePendulum) -> Option<Drawing> {
        Some(Drawing {
            spatial: false,
            fixed: vec![("O", [0.0; 3])],
            pose: Box::new(|q| {
                let trolley = [q[0], 0.0, 0.0];
                let hook = [q[2], 0.0, q[3]];
                let load = [q[4], 0.0, q[5]];
                Pose {
                    boom: vec![[q[0] - 1.0, 0.0, 0.0], [q[0] + 1.0, 0.0, 0.0]],
                    ropes: vec![[trolley, hook], [hook, load]],
                    pulley: hook,
                    load,
                }
            }),
            ropes: "trolley B, hoist rope B-H (L), sling H-C (l_s)",
        })
    }
}
