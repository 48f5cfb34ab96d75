//! The paper's maneuver for the planar crane (sect. 5.1.3): path eqs. (41)-(45),
//! start eq. (46), reference Appendix A.

use crane_runtime::trajectory::{Poly9, TrajectoryError};
use crane_runtime::{Error, Options, Solution, State, Trajectory, init};
use crane_runtime::minimal::simulate_minimal_with_progress;
use nalgebra::{SVector, vector};

use super::model::NavyPlanar;
use super::reference::{PlanarParams, reference_at};

/// The paper's start `p0 = [5 sqrt 3, 10, 5, 0, -5]` (eq. 46): the limit of
/// the flatness solution at `t0` (ERRATA, "Degenerate starts").
pub fn paper_p0() -> [f64; 5] {
    [5.0 * 3f64.sqrt(), 10.0, 5.0, 0.0, -5.0]
}

/// The load path of eqs. (41)-(43): from `(0, -10)` at `t0 = 0` to
/// `(-3, -14)` at `tf` (4 s in Figs. 5-8, 15 s in Fig. 9).
pub fn paper_path(tf: f64) -> Result<Poly9<2>, TrajectoryError> {
    Poly9::new(0.0, tf, vector![0.0, -10.0], vector![-3.0, -14.0])
}

/// The crane with the paper's parameters on the paper's maneuver.
#[derive(Debug, Clone)]
pub struct PaperCase {
    /// The crane.
    pub model: NavyPlanar,
    /// The load path.
    pub path: Poly9<2>,
    /// The start `p0`.
    pub p0: [f64; 5],
}

impl PaperCase {
    /// The paper's case with end time `tf`.
    pub fn new(tf: f64) -> Result<Self, TrajectoryError> {
        Ok(Self { model: NavyPlanar::default(), path: paper_path(tf)?, p0: paper_p0() })
    }

    fn params(&self) -> PlanarParams {
        let m = &self.model;
        PlanarParams { m_l: m.m_l, J1: m.J1, J2: m.J2, r1: m.r1, r2: m.r2, alpha: m.alpha, l: m.l, g: m.g }
    }
}

impl crate::Case<7, 3, 2> for PaperCase {
    type Model = NavyPlanar;
    type Path = Poly9<2>;

    fn model(&self) -> &NavyPlanar {
        &self.model
    }

    fn path(&self) -> &Poly9<2> {
        &self.path
    }

    fn t0(&self) -> f64 {
        self.path.t0()
    }

    fn tf(&self) -> f64 {
        self.path.tf()
    }

    fn start(&self) -> Result<State<7, 3, 2>, Error> {
        init::check_start(&self.model, &self.path, self.t0(), &self.p0, None)
    }

    fn simulate_minimal_with_progress(
        &self,
        start: &State<7, 3, 2>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<7, 3, 2>, Error>> {
        let guess = minimal_guess(&self.model, start);
        Some(simulate_minimal_with_progress(&self.model, &self.path, start, &guess, options, progress))
    }

    fn reference(&self, t: f64) -> Option<State<7, 3, 2>> {
        let r = reference_at(&self.params(), &self.path, t);
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        (finite(r.q.as_slice()) && finite(r.u.as_slice()) && finite(r.lambda.as_slice())).then_some(State {
            t,
            q: r.q,
            v: r.v,
            u: r.u,
            lambda: r.lambda,
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

/// The load path's derivatives `gamma^(0..=4)` at `t`.
pub fn path_derivatives(path: &impl Trajectory<2>, t: f64) -> [SVector<f64, 2>; 5] {
    std::array::from_fn(|k| path.derivative(t, k))
}
