//! The paper's maneuver for the planar crane with pulley mass (sect. 5.2.3):
//! path eqs. (41), (44), (64), (65), start eqs. (66)-(67) with ERRATA,
//! reference Appendix B.

use crane_runtime::trajectory::{Poly9, TrajectoryError};
use crane_runtime::{CraneModel, Error, State, init};
use nalgebra::vector;

use super::model::NavyPlanarPulley;
use super::reference::{PulleyParams, reference_at};

/// The paper's start `p0 = [L1, L2, L3, L0, x0] = [10, sqrt(175), 15, 10,
/// -5/2 sqrt 3]` (eq. 66 with ERRATA: the printed `15` and `13.23` are `L3`
/// and `L2`, swapped). With the load at rest at `gamma0` (eq. 67) this is a
/// regular static equilibrium: all three ropes are taut.
pub fn paper_p0() -> [f64; 5] {
    [10.0, 175f64.sqrt(), 15.0, 10.0, -2.5 * 3f64.sqrt()]
}

/// The path of the flat outputs `[x, z, z0]` (eqs. 41, 44, 64, 65): from
/// `(-5/2 sqrt 3, -17.5, -12.5)` at `t0 = 0` to `(-2, -16, -15)` at `tf`
/// (4 s in Figs. 14-17 and 19, 15 s in Fig. 18).
pub fn paper_path(tf: f64) -> Result<Poly9<3>, TrajectoryError> {
    Poly9::new(
        0.0,
        tf,
        vector![-2.5 * 3f64.sqrt(), -17.5, -12.5],
        vector![-2.0, -16.0, -15.0],
    )
}

/// The crane with the paper's parameters on the paper's maneuver.
#[derive(Debug, Clone)]
pub struct PaperCase {
    /// The crane.
    pub model: NavyPlanarPulley,
    /// The path of the flat outputs `[x, z, z0]`.
    pub path: Poly9<3>,
    /// The start `p0`.
    pub p0: [f64; 5],
}

impl PaperCase {
    /// The paper's case with end time `tf`.
    pub fn new(tf: f64) -> Result<Self, TrajectoryError> {
        Ok(Self {
            model: NavyPlanarPulley::default(),
            path: paper_path(tf)?,
            p0: paper_p0(),
        })
    }

    /// The model's parameters as the reference takes them.
    pub fn params(&self) -> PulleyParams {
        PulleyParams::from_values(&self.model.parameter_values()).expect("12 parameters")
    }
}

impl crate::Case<8, 4, 3> for PaperCase {
    type Model = NavyPlanarPulley;
    type Path = Poly9<3>;

    fn model(&self) -> &NavyPlanarPulley {
        &self.model
    }

    fn path(&self) -> &Poly9<3> {
        &self.path
    }

    fn t0(&self) -> f64 {
        self.path.t0()
    }

    fn tf(&self) -> f64 {
        self.path.tf()
    }

    fn start(&self) -> Result<State<8, 4, 3>, Error> {
        init::check_start(&self.model, &self.path, self.t0(), &self.p0, None)
    }

    fn reference(&self, t: f64) -> Option<State<8, 4, 3>> {
        let r = reference_at(&self.params(), &self.path, t);
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        (finite(r.q.as_slice()) && finite(r.u.as_slice()) && finite(r.lambda.as_slice())).then_some(
            State {
                t,
                q: r.q,
                v: r.v,
                u: r.u,
                lambda: r.lambda,
            },
        )
    }
}
