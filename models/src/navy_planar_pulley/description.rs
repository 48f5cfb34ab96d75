//! The planar crane with pulley mass as a built-in crane: the paper's
//! manoeuvre (sect. 5.2.3: path eqs. 41, 44, 64, 65; start eqs. 66-67), the
//! Appendix B reference on any path, the minimal coordinates of eq. (59) and
//! the drawing.

use crane_runtime::State;
use nalgebra::{SVector, vector};

use super::model::NavyPlanarPulley;
use super::reference::reference_at;
use crate::case::Case;
use crate::crane::{Crane, Maneuver, finite_state};
use crate::drawing::{Drawing, Pose, scale};
use crate::path::{Path, PathSpec, Profile};

/// The planar US Navy crane with pulley mass (sect. 5.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Description;

/// The crane on the paper's manoeuvre (`PaperCase::new(4.0)`: Figs. 14-17).
pub type PaperCase = Case<Description, 8, 4, 3>;

/// The paper's start `p0 = [L1, L2, L3, L0, x0] = [10, sqrt(175), 15, 10,
/// -5/2 sqrt 3]` (eq. 66 as corrected: the printed `15` and `13.23` are `L3`
/// and `L2`, swapped; docs/errata.md). With the load at rest at `gamma0`
/// (eq. 67) this is a regular static equilibrium: all three ropes are taut.
pub fn paper_p0() -> [f64; 5] {
    [10.0, 175f64.sqrt(), 15.0, 10.0, -2.5 * 3f64.sqrt()]
}

impl Crane<8, 4, 3> for Description {
    type Model = NavyPlanarPulley;
    const NAME: &'static str = "navy-planar-pulley";
    const DESCRIPTION: &'static str = "planar US Navy crane with pulley mass (paper sect. 5.2)";
    const HAS_REFERENCE: bool = true;

    fn input_units() -> &'static [&'static str] {
        &["N m", "N m", "N m"]
    }

    /// The flat outputs `[x, z, z0]` (eqs. 41, 44, 64, 65) from
    /// `(-5/2 sqrt 3, -17.5, -12.5)` at `t0 = 0` to `(-2, -16, -15)` at 4 s
    /// (15 s in Fig. 18).
    fn maneuver() -> Maneuver<3> {
        Maneuver {
            path: PathSpec {
                profile: Profile::Poly9,
                t0: 0.0,
                t1: 4.0,
                start: vector![-2.5 * 3f64.sqrt(), -17.5, -12.5],
                end: vector![-2.0, -16.0, -15.0],
            },
            p0: paper_p0().to_vec(),
        }
    }

    fn reference(model: &NavyPlanarPulley, path: &Path<3>, t: f64) -> Option<State<8, 4, 3>> {
        let r = reference_at(model, path, t);
        finite_state(State {
            t,
            q: r.q,
            v: r.v,
            u: r.u,
            lambda: r.lambda,
        })
    }

    fn minimal_guess(model: &NavyPlanarPulley, start: &State<8, 4, 3>) -> Vec<f64> {
        minimal_guess(model, start).as_slice().to_vec()
    }

    /// `q = [L1, L2, L3, L0, x0 | x, z, z0]`; tip S at the origin, winch 3 at
    /// `P = -s (sin, cos)`, winch 1 at `A = -(l + s) (sin, cos)` (eqs. 49-56).
    fn drawing(model: &NavyPlanarPulley) -> Option<Drawing> {
        let (alpha, l, s) = (model.alpha, model.l, model.s);
        let dir = [-alpha.sin(), 0.0, -alpha.cos()];
        let (a, p, tip) = (scale(dir, l + s), scale(dir, s), [0.0; 3]);
        Some(Drawing {
            spatial: false,
            fixed: vec![("A", a), ("P", p), ("S", tip)],
            pose: Box::new(move |q| {
                let b = [q[4], 0.0, q[7]];
                let c = [q[5], 0.0, q[6]];
                Pose {
                    boom: vec![a, tip],
                    ropes: vec![[a, b], [tip, b], [p, b], [b, c]],
                    pulley: b,
                    load: c,
                }
            }),
            ropes: "ropes A-B (L1), S-B (L2), P-B-C (L3)",
        })
    }
}

/// The minimal coordinates `mu = [beta, gamma, theta, L]` (eq. 59) of a
/// redundant state, by geometry from the positions of the pulley `B = (x0,
/// z0)` and the load `C = (x, z)` (angles as in [`model`](super::model)):
/// `beta` from the direction of `PB` (eq. 62), `theta` and `L` from `BC`
/// (eq. 61), `gamma + theta` from the direction of `BA`. Exact wherever `q`
/// satisfies the constraints (55) with `alpha - beta`, `theta` and
/// `gamma + theta` in `(-pi, pi]` (the range of `atan2`), e.g. at the paper's
/// start, `mu = [pi/3, pi/3, 0, 5]`, and along the whole maneuver;
/// [`crane_runtime::simulate_minimal`] refines it by Gauss-Newton on `phi(mu) = q0` anyway.
pub fn minimal_guess(model: &NavyPlanarPulley, state: &State<8, 4, 3>) -> SVector<f64, 4> {
    let q = &state.q;
    let (x0, x, z, z0) = (q[4], q[5], q[6], q[7]);
    let (sin_a, cos_a) = model.alpha.sin_cos();
    // B - P = -L0 (sin(alpha - beta), cos(alpha - beta))
    let beta = model.alpha - (-(x0 + model.s * sin_a)).atan2(-(z0 + model.s * cos_a));
    // C - B = L (sin(theta), -cos(theta))
    let theta = (x - x0).atan2(z0 - z);
    // A - B = L1 (-sin(gamma + theta), cos(gamma + theta)), A = -(l + s) (sin(alpha), cos(alpha))
    let ls = model.l + model.s;
    let gamma = (x0 + ls * sin_a).atan2(-ls * cos_a - z0) - theta;
    SVector::from([beta, gamma, theta, (x - x0).hypot(z - z0)])
}
