//! The planar crane with massless pulley as a built-in crane: the paper's
//! manoeuvre (sect. 5.1.3: path eqs. 41-45, start eq. 46), the Appendix A
//! reference on any path, the minimal coordinates of eq. (36) and the
//! drawing.

use crane_runtime::State;
use nalgebra::{SVector, vector};

use super::model::NavyPlanar;
use super::reference::reference_at;
use crate::case::Case;
use crate::crane::{Crane, Maneuver, finite_state};
use crate::drawing::{Drawing, Pose};
use crate::path::{Path, PathSpec, Profile};

/// The planar US Navy crane with massless pulley (sect. 5.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Description;

/// The crane on the paper's manoeuvre: `PaperCase::new(4.0)` for Figs. 5-8,
/// `PaperCase::new(15.0)` for Fig. 9.
pub type PaperCase = Case<Description, 7, 3, 2>;

/// The paper's start `p0 = [5 sqrt 3, 10, 5, 0, -5]` (eq. 46): the limit of
/// the flatness solution at `t0` (docs/errata.md, degenerate starts).
pub fn paper_p0() -> [f64; 5] {
    [5.0 * 3f64.sqrt(), 10.0, 5.0, 0.0, -5.0]
}

impl Crane<7, 3, 2> for Description {
    type Model = NavyPlanar;
    const NAME: &'static str = "navy-planar";
    const DESCRIPTION: &'static str = "planar US Navy crane, massless pulley (paper sect. 5.1)";
    const HAS_REFERENCE: bool = true;

    fn input_units() -> &'static [&'static str] {
        &["N m", "N m"]
    }

    /// Eqs. (41)-(43): from `(0, -10)` at `t0 = 0` to `(-3, -14)` at 4 s
    /// (Figs. 5-8; 15 s in Fig. 9), from `p0` of eq. (46).
    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec {
                profile: Profile::Poly9,
                t0: 0.0,
                t1: 4.0,
                start: vector![0.0, -10.0],
                end: vector![-3.0, -14.0],
            },
            p0: paper_p0().to_vec(),
        }
    }

    fn reference(model: &NavyPlanar, path: &Path<2>, t: f64) -> Option<State<7, 3, 2>> {
        let r = reference_at(model, path, t);
        finite_state(State {
            t,
            q: r.q,
            v: r.v,
            u: r.u,
            lambda: r.lambda,
        })
    }

    fn minimal_guess(model: &NavyPlanar, start: &State<7, 3, 2>) -> Vec<f64> {
        minimal_guess(model, start).as_slice().to_vec()
    }

    /// `q = [L1, L2, L0, x0, z0 | x, z]`; tip P at the origin, winch 1 at
    /// `A = -l (sin alpha, cos alpha)` on the boom (eqs. 25-33).
    fn drawing(model: &NavyPlanar) -> Option<Drawing> {
        let (alpha, l) = (model.alpha, model.l);
        let a = [-l * alpha.sin(), 0.0, -l * alpha.cos()];
        let p = [0.0; 3];
        Some(Drawing {
            spatial: false,
            fixed: vec![("A", a), ("P", p)],
            pose: Box::new(move |q| {
                let b = [q[3], 0.0, q[4]];
                let c = [q[5], 0.0, q[6]];
                Pose {
                    boom: vec![a, p],
                    ropes: vec![[a, b], [p, b], [b, c]],
                    pulley: b,
                    load: c,
                }
            }),
            ropes: "ropes A-B (L1), P-B-C (L2)",
        })
    }
}

/// A rough guess of the minimal coordinates `mu = [beta, gamma, theta, L]`
/// (eq. 36) at a redundant state, from the triangle PAB and the load rope:
/// exact at the paper's start (beta = alpha, gamma = pi/2, theta = 0).
pub fn minimal_guess(model: &NavyPlanar, state: &State<7, 3, 2>) -> SVector<f64, 4> {
    let q = &state.q;
    let (x0, z0, x, z) = (q[3], q[4], q[5], q[6]);
    // beta: angle at P between the boom (towards A) and PB
    // (eq. 37: x0 = -L0 sin(alpha - beta), z0 = -L0 cos(alpha - beta))
    let beta = model.alpha + x0.atan2(-z0);
    // gamma: angle at B in the triangle PAB, from the law of cosines
    let (l, l1, l0) = (model.l, q[0], q[2]);
    let gamma = ((l1 * l1 + l0 * l0 - l * l) / (2.0 * l1 * l0)).clamp(-1.0, 1.0).acos();
    SVector::from([beta, gamma, (x - x0).atan2(z0 - z), (x - x0).hypot(z - z0)])
}
