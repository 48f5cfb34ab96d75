//! The paper's maneuver for the planar crane with pulley mass (sect. 5.2.3):
//! path eqs. (41), (44), (64), (65), start eqs. (66)-(67) with ERRATA,
//! reference Appendix B.

use crane_runtime::trajectory::{Poly9, TrajectoryError};
use crane_runtime::minimal::simulate_minimal_with_progress;
use crane_runtime::{CraneModel, Error, Options, Solution, State, init};
use nalgebra::{SVector, vector};

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

    fn simulate_minimal_with_progress(
        &self,
        start: &State<8, 4, 3>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<8, 4, 3>, Error>> {
        let guess = minimal_guess(&self.model, start);
        Some(simulate_minimal_with_progress(&self.model, &self.path, start, &guess, options, progress))
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
