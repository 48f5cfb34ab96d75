//! The analytical reference of Appendix B
//! (`crane_models::navy_planar_pulley::reference`) against the generated
//! model of sect. 5.2 (`crane_models::navy_planar_pulley::NavyPlanarPulley`):
//! the flatness formulas (124a-o) and the `crane_model!` declaration of
//! eqs. (51), (55), (56) are independent transcriptions that must agree.

use crane_models::navy_planar_pulley::NavyPlanarPulley;
use crane_models::navy_planar_pulley::reference::{ReferenceState, reference, reference_at};
use crane_runtime::{CraneModel, Trajectory};
use nalgebra::{SMatrix, SVector};

/// The paper's path of the flat outputs `[x, z, z0]`, eqs. (41), (44),
/// (64), (65): from `(-5/2 sqrt 3, -17.5, -12.5)` at `t0 = 0` to
/// `(-2, -16, -15)` at `tf`, with `c(tau) = 70 tau^9 - 315 tau^8 + 540 tau^7
/// - 420 tau^6 + 126 tau^5`. Exact derivatives of any order. (Local on
/// purpose: independent of the runtime's `Poly9`.)
struct PaperPath {
    tf: f64,
}

impl Trajectory<3> for PaperPath {
    fn derivative(&self, t: f64, k: usize) -> SVector<f64, 3> {
        let g0 = SVector::<f64, 3>::new(-2.5 * 3f64.sqrt(), -17.5, -12.5);
        let gf = SVector::<f64, 3>::new(-2.0, -16.0, -15.0);
        let tau = t / self.tf;
        let mut coeffs = [0.0, 0.0, 0.0, 0.0, 0.0, 126.0, -420.0, 540.0, -315.0, 70.0];
        for _ in 0..k {
            for j in 0..9 {
                coeffs[j] = (j + 1) as f64 * coeffs[j + 1];
            }
            coeffs[9] = 0.0;
        }
        let c = coeffs.iter().rev().fold(0.0, |acc, &cj| acc * tau + cj);
        match k {
            0 => g0 + (gf - g0) * c,
            _ => (gf - g0) * (c / self.tf.powi(k as i32)),
        }
    }
}

fn params_of(model: &NavyPlanarPulley) -> NavyPlanarPulley {
    *model
}

/// `n` equally spaced times strictly inside `(0, tf)`.
fn times(tf: f64, n: usize) -> impl Iterator<Item = f64> {
    (1..=n).map(move |i| tf * i as f64 / (n + 1) as f64)
}

/// `M a - f - B^T u + G^T lambda` with the generated model (eq. 1a).
fn residual(model: &NavyPlanarPulley, s: &ReferenceState, a: &SVector<f64, 8>) -> SVector<f64, 8> {
    let mass: SMatrix<f64, 8, 8> = model.mass_matrix();
    mass * a - model.forces(&s.q, &s.v) - model.input_matrix(&s.q) * s.u
        + model.constraint_jacobian(&s.q).transpose() * s.lambda
}

/// The reference satisfies `g = 0`, `G q' = 0` and the equations of motion
/// of the generated model at 50 times of both maneuvers (tf = 4 s, Figs.
/// 14-17; tf = 15 s, Fig. 18), with `q''` from the Taylor duals: residual at
/// round-off level relative to the weights.
#[test]
fn reference_satisfies_generated_equations_of_motion() {
    let model = NavyPlanarPulley::default();
    let params = params_of(&model);
    let weight = (model.m_l + model.m0) * model.g;
    for tf in [4.0, 15.0] {
        let path = PaperPath { tf };
        let (mut worst_g, mut worst_r) = (0.0f64, 0.0f64);
        for t in times(tf, 50) {
            let s = reference_at(&params, &path, t);
            let g = model.constraints(&s.q);
            let gv = model.constraint_jacobian(&s.q) * s.v;
            let r = residual(&model, &s, &s.a);
            worst_g = worst_g.max(g.amax()).max(gv.amax());
            worst_r = worst_r.max(r.amax() / weight);
            assert!(g.amax() < 1e-10, "tf = {tf}, t = {t}: g = {g:?}");
            assert!(gv.amax() < 1e-10, "tf = {tf}, t = {t}: G q' = {gv:?}");
            assert!(r.amax() < 1e-12 * weight, "tf = {tf}, t = {t}: residual {r:?}");
        }
        println!("tf = {tf}: max |g|, |G q'| = {worst_g:.1e}; max residual / ((m_l + m0) g) = {worst_r:.1e}");
    }
}

/// The same residual with `q''` from central second differences of the
/// reference's `q(t)` instead of the duals. The difference quotient errs by
/// `h^2/12 q''''` plus `~4 e_q / h^2` round-off (bounded by 5e-5 over the
/// path at `h = 1e-3` in the reference's unit tests); only rows with mass see
/// it, so the residual is at most `max(M) * 5e-5 = 150 * 5e-5 = 7.5e-3` N,
/// and it must shrink by about 4 when `h` is halved.
#[test]
fn reference_with_finite_difference_accelerations() {
    let model = NavyPlanarPulley::default();
    let params = params_of(&model);
    let path = PaperPath { tf: 4.0 };
    let q_at = |t: f64| reference_at(&params, &path, t).q;
    let worst = |h: f64| {
        times(4.0, 50).fold(0.0f64, |worst, t| {
            let s = reference_at(&params, &path, t);
            let a = (q_at(t + h) - q_at(t) * 2.0 + q_at(t - h)) / (h * h);
            worst.max(residual(&model, &s, &a).amax())
        })
    };
    let (r1, r2) = (worst(2e-3), worst(1e-3));
    println!("finite-difference q'': max residual {r1:.2e} N (h = 2e-3), {r2:.2e} N (h = 1e-3)");
    assert!(r2 < 7.5e-3, "residual {r2:e} N");
    assert!((3.5..4.5).contains(&(r1 / r2)), "order: ratio {} for h -> h/2", r1 / r2);
}

/// At t0 the reference is the corrected start (66)-(67) and a static
/// equilibrium of the generated model with all ropes taut.
#[test]
fn reference_start_is_paper_p0() {
    let model = NavyPlanarPulley::default();
    let s = reference_at(&params_of(&model), &PaperPath { tf: 4.0 }, 0.0);
    let p0 = [10.0, 175f64.sqrt(), 15.0, 10.0, -2.5 * 3f64.sqrt()];
    for (i, e) in p0.iter().enumerate() {
        assert!((s.q[i] - e).abs() < 1e-12, "p0[{i}] = {} != {e}", s.q[i]);
    }
    assert_eq!((s.q[5], s.q[6], s.q[7]), (-2.5 * 3f64.sqrt(), -17.5, -12.5));
    assert!(model.constraints(&s.q).amax() < 1e-12);
    let r = residual(&model, &s, &SVector::zeros());
    assert!(r.amax() < 1e-10, "static balance residual {r:?}");
    assert!(s.tensions.iter().all(|&n| n > 400.0), "{:?}", s.tensions);
}

/// `N = lambda L` with the model's ropes (INFO and `rope_lengths`)
/// reproduces the reference's tensions, the ropes never push along either
/// maneuver, and the segment `PB` of rope 3 carries the same tension as
/// `BC` (`lambda2 L0 = lambda4 (L3 - L0)`, eqs. 122a, 124d).
#[test]
fn rope_tensions_are_consistent_and_positive() {
    let model = NavyPlanarPulley::default();
    let params = params_of(&model);
    let ropes = NavyPlanarPulley::INFO.ropes;
    assert_eq!(ropes.len(), 3);
    for tf in [4.0, 15.0] {
        let path = PaperPath { tf };
        let mut min = [f64::INFINITY; 3];
        for t in std::iter::once(0.0).chain(times(tf, 50)).chain(std::iter::once(tf)) {
            let s = reference_at(&params, &path, t);
            let mut lengths = [0.0; 3];
            model.rope_lengths(&s.q, &mut lengths);
            for (i, rope) in ropes.iter().enumerate() {
                let n = s.lambda[rope.constraint] * lengths[i];
                assert!(
                    (n - s.tensions[i]).abs() < 1e-9 * (1.0 + n.abs()),
                    "{} at t = {t}",
                    rope.tension
                );
                assert!(n > 0.0, "{} = {n} <= 0 at t = {t} (tf = {tf})", rope.tension);
                min[i] = min[i].min(n);
            }
            let n0 = s.lambda[1] * s.q[3];
            assert!((n0 - s.tensions[2]).abs() < 1e-9 * s.tensions[2], "N0 = N3 at t = {t}");
        }
        println!(
            "tf = {tf}: min N1 = {:.2}, min N2 = {:.2}, min N3 = {:.2}",
            min[0], min[1], min[2]
        );
    }
}

/// `reference` and `reference_at` agree, and derivatives beyond the fourth
/// are not used (Appendix B: `u` depends on `y, ..., y''''`).
#[test]
fn reference_uses_derivatives_up_to_four() {
    let params = NavyPlanarPulley::default();
    let path = PaperPath { tf: 4.0 };
    let derivs: [SVector<f64, 3>; 5] = std::array::from_fn(|k| path.derivative(1.5, k));
    let s = reference(&params, &derivs);
    assert_eq!(s, reference_at(&params, &path, 1.5));
    println!(
        "t = 1.5 s: u = {:.6?} N m, lambda = {:.6?}, N = {:.4?} N",
        s.u.as_slice(),
        s.lambda.as_slice(),
        s.tensions
    );
}
