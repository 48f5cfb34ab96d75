//! The analytical reference of Appendix A (`crane_models::navy_planar::reference`)
//! against the hand-written model of sect. 5.1 ([`crate::handwritten`]): two
//! independent transcriptions of the paper that must agree.

use crate::handwritten::HandNavyPlanar;
use crane_models::navy_planar::NavyPlanar;
use crane_models::navy_planar::reference::{ReferenceState, reference, reference_at};
use crane_runtime::{CraneModel, Trajectory};
use nalgebra::{SMatrix, SVector};

/// The paper's rest-to-rest path (41)-(45) from `(0, -10)` at `t0 = 0` to
/// `(-3, -14)` at `tf`, with `c(tau) = 70 tau^9 - 315 tau^8 + 540 tau^7 -
/// 420 tau^6 + 126 tau^5`. Exact derivatives of any order. (Local on purpose:
/// independent of the runtime's `Poly9`.)
struct PaperPath {
    tf: f64,
}

impl Trajectory<2> for PaperPath {
    fn derivative(&self, t: f64, k: usize) -> SVector<f64, 2> {
        let (g0, gf) = (SVector::<f64, 2>::new(0.0, -10.0), SVector::<f64, 2>::new(-3.0, -14.0));
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

fn params_of(model: &HandNavyPlanar) -> NavyPlanar {
    let mut params = NavyPlanar::default();
    for (name, value) in <NavyPlanar as CraneModel<7, 3, 2>>::INFO
        .parameters
        .iter()
        .zip(model.parameter_values())
    {
        params.set_parameter(name, value).expect("the same parameters");
    }
    params
}

/// `n` equally spaced times strictly inside `(0, tf)`.
fn times(tf: f64, n: usize) -> impl Iterator<Item = f64> {
    (1..=n).map(move |i| tf * i as f64 / (n + 1) as f64)
}

/// `M a - f - B^T u + G^T lambda` with the hand-written model (eq. 1a).
fn residual(model: &HandNavyPlanar, s: &ReferenceState, a: &SVector<f64, 7>) -> SVector<f64, 7> {
    let mass: SMatrix<f64, 7, 7> = model.mass_matrix();
    mass * a - model.forces(&s.q, &s.v) - model.input_matrix(&s.q) * s.u
        + model.constraint_jacobian(&s.q).transpose() * s.lambda
}

/// The reference satisfies `g = 0`, `G q' = 0` and the equations of motion
/// of the hand-written model at 50 times, with `q''` from the Taylor duals:
/// residual at round-off level relative to the load weight.
#[test]
fn reference_satisfies_handwritten_equations_of_motion() {
    let model = HandNavyPlanar::default();
    let params = params_of(&model);
    let weight = model.m_l * model.g;
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
            assert!(r.amax() < 1e-9 * weight, "tf = {tf}, t = {t}: residual {r:?}");
        }
        println!("tf = {tf}: max |g|, |G q'| = {worst_g:.1e}; max residual / (m_l g) = {worst_r:.1e}");
    }
}

/// The same residual with `q''` from central second differences of the
/// reference's `q(t)` (`h = 1e-3`) instead of the duals. The difference
/// quotient errs by `h^2/12 q''''` plus `~4 e_q / h^2` round-off; the unit
/// tests of the reference bound this by 5e-5 over the path. Only rows with
/// mass see it, so the residual is at most `max(M) * 5e-5 = 100 * 5e-5 =
/// 5e-3` N (5e-6 relative to the load weight); it must also shrink by about
/// 4 when `h` is halved to `5e-4`.
#[test]
fn reference_with_finite_difference_accelerations() {
    let model = HandNavyPlanar::default();
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
    assert!(r2 < 5e-3, "residual {r2:e} N");
    assert!((3.5..4.5).contains(&(r1 / r2)), "order: ratio {} for h -> h/2", r1 / r2);
}

/// At t0 the reference is the paper's start (46)-(47), rope 1 is slack
/// (`lambda1 = 0`), and it is a static equilibrium of the hand-written model.
#[test]
fn reference_start_is_paper_p0() {
    let model = HandNavyPlanar::default();
    let s = reference_at(&params_of(&model), &PaperPath { tf: 4.0 }, 0.0);
    let p0 = [5.0 * 3f64.sqrt(), 10.0, 5.0, 0.0, -5.0];
    for (i, e) in p0.iter().enumerate() {
        assert!((s.q[i] - e).abs() < 1e-10, "p0[{i}] = {} != {e}", s.q[i]);
    }
    assert_eq!((s.q[5], s.q[6]), (0.0, -10.0));
    assert!(s.lambda[0].abs() < 1e-12, "lambda1 = {}", s.lambda[0]);
    assert!(model.constraints(&s.q).amax() < 1e-12);
    let r = residual(&model, &s, &SVector::zeros());
    assert!(r.amax() < 1e-10, "static balance residual {r:?}");
}

/// `N = lambda L` with the model's ropes (INFO and `rope_lengths`)
/// reproduces the reference's tensions, and the ropes never push: `N1, N2 >=
/// 0` along the path (both tf of the paper).
#[test]
fn rope_tensions_are_consistent_and_nonnegative() {
    let model = HandNavyPlanar::default();
    let params = params_of(&model);
    let ropes = HandNavyPlanar::INFO.ropes;
    for tf in [4.0, 15.0] {
        let path = PaperPath { tf };
        let mut min = [f64::INFINITY; 2];
        for t in std::iter::once(0.0).chain(times(tf, 50)).chain(std::iter::once(tf)) {
            let s = reference_at(&params, &path, t);
            let mut lengths = [0.0; 2];
            model.rope_lengths(&s.q, &mut lengths);
            for (i, rope) in ropes.iter().enumerate() {
                let n = s.lambda[rope.constraint] * lengths[i];
                assert!(
                    (n - s.tensions[i]).abs() < 1e-9 * (1.0 + n.abs()),
                    "{} at t = {t}",
                    rope.tension
                );
                // N1 is 2 N2 cos(pi/2) ~ 1e-13 at the slack start.
                assert!(n >= -1e-10, "{} = {n} < 0 at t = {t} (tf = {tf})", rope.tension);
                min[i] = min[i].min(n);
            }
        }
        println!("tf = {tf}: min N1 = {:.3e}, min N2 = {:.3}", min[0], min[1]);
    }
}

/// `reference` and `reference_at` agree, and the derivatives beyond the
/// fourth are not used (eqs. 111-112).
#[test]
fn reference_uses_derivatives_up_to_four() {
    let params = NavyPlanar::default();
    let path = PaperPath { tf: 4.0 };
    let derivs: [SVector<f64, 2>; 5] = std::array::from_fn(|k| path.derivative(1.5, k));
    let s = reference(&params, &derivs);
    assert_eq!(s, reference_at(&params, &path, 1.5));
    println!(
        "t = 1.5 s: u = [{:.6}, {:.6}] N m, lambda = [{:.6}, {:.6}, {:.6}], N = [{:.4}, {:.4}] N",
        s.u[0], s.u[1], s.lambda[0], s.lambda[1], s.lambda[2], s.tensions[0], s.tensions[1]
    );
}
