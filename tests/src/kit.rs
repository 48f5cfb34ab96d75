//! The shared test kit: the paper's checks written once for every built-in
//! crane, so that the per-crane test files read like the paper's checks.
//!
//! - [`run`]: a crane's case from its consistent start, either formulation
//!   ([`Formulation`], the study's dispatch), any scheme;
//! - [`e_u`]: the relative error of `u` at t = 1.5 s (eq. 48);
//! - [`assert_order`]: e_u falls with dt and the observed order between the
//!   two smallest steps lies in a band;
//! - [`input_differences`], [`largest`]: self-convergence `D(dt) = max |u(dt)
//!   - u(dt/2)|` where there is no reference;
//! - [`assert_ratio_of_order`]: a ratio `D(dt)/D(dt/2)` near `2^k`;
//! - [`redundant_minimal_difference`]: the commutative diagram of Fig. 1;
//! - [`stand_in_path`]: one rest-to-rest path for cranes or tests that need
//!   some path.

use std::ops::RangeInclusive;

use crane_models::{Case, Crane, Path, PathSpec, Profile};
use crane_runtime::{Options, Scheme, Solution};
use nalgebra::SVector;

pub use crane_models::study::Formulation;
pub use crane_models::study::convergence::{T_ERROR, observed_order};

/// `case` from its consistent start to `tf` with `scheme` and step `dt`;
/// panics with the crane, formulation, scheme and step if the start or the
/// run fails (these are tests).
pub fn run_to<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    formulation: Formulation,
    scheme: Scheme,
    dt: f64,
    tf: f64,
) -> Solution<N, M, A> {
    let start = case
        .start()
        .unwrap_or_else(|e| panic!("{}: the start is consistent: {e}", C::NAME));
    let options = Options::new(dt, tf)
        .unwrap_or_else(|e| panic!("{}: {e}", C::NAME))
        .with_scheme(scheme);
    formulation
        .simulate(case, &start, &options, &mut |_, _| {})
        .unwrap_or_else(|e| panic!("{} {formulation:?} {scheme} at dt = {dt}: {e}", C::NAME))
}

/// [`run_to`] the case's end time.
pub fn run<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    formulation: Formulation,
    scheme: Scheme,
    dt: f64,
) -> Solution<N, M, A> {
    run_to(case, formulation, scheme, dt, case.tf())
}

/// The relative error of `u` at t = 1.5 s, eq. (48); the run must have a
/// step there and the crane a reference.
pub fn e_u<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    solution: &Solution<N, M, A>,
) -> f64 {
    let state = solution.state_near(T_ERROR).expect("a step near 1.5 s");
    assert!((state.t - T_ERROR).abs() < 1e-9, "no step at 1.5 s: {}", state.t);
    case.relative_input_error(state)
        .unwrap_or_else(|| panic!("{} has no reference at 1.5 s", C::NAME))
}

/// e_u for every step in `dts` (coarse to fine) falls monotonically, and
/// the observed order between the two smallest steps lies in `band`;
/// returns the errors.
pub fn assert_order<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    formulation: Formulation,
    scheme: Scheme,
    dts: &[f64],
    band: RangeInclusive<f64>,
) -> Vec<f64> {
    let errors: Vec<f64> = dts
        .iter()
        .map(|&dt| e_u(case, &run(case, formulation, scheme, dt)))
        .collect();
    let label = format!("{} {formulation:?} {scheme}, tf = {}", C::NAME, case.tf());
    for (dt, e) in dts.iter().zip(&errors) {
        println!("{label}: dt = {dt:<7} e_u = {e:.4e}");
    }
    for w in errors.windows(2) {
        assert!(w[1] < w[0], "{label}: e_u must fall with dt: {errors:?}");
    }
    let n = dts.len();
    let order = observed_order(dts[n - 2], errors[n - 2], dts[n - 1], errors[n - 1]);
    println!(
        "{label}: observed order between dt = {} and {}: {order:.4}",
        dts[n - 2],
        dts[n - 1]
    );
    assert!(
        band.contains(&order),
        "{label}: observed order {order} outside {band:?}"
    );
    errors
}

/// Self-convergence without a reference: for consecutive runs (each with
/// half the step of the one before), per input the largest `|u_k(dt) -
/// u_k(dt/2)|` over the coarse run's times `t` with `include(t)`.
pub fn input_differences<const N: usize, const M: usize, const A: usize>(
    runs: &[Solution<N, M, A>],
    include: impl Fn(f64) -> bool + Copy,
) -> Vec<[f64; A]> {
    runs.windows(2)
        .map(|pair| {
            pair[0]
                .input_difference(&pair[1], include)
                .expect("each run has half the step of the one before")
                .map(|(d, _)| d)
        })
        .collect()
}

/// The largest `|u_k(dt) - u_k(dt/2)|` over all inputs and the coarse run's
/// times `t` with `include(t)`, and the time where it occurs.
pub fn largest_input_difference<const N: usize, const M: usize, const A: usize>(
    coarse: &Solution<N, M, A>,
    fine: &Solution<N, M, A>,
    include: impl Fn(f64) -> bool,
) -> (f64, f64) {
    let per_input = coarse
        .input_difference(fine, include)
        .expect("the fine run has half the step");
    per_input
        .into_iter()
        .fold((0.0, 0.0), |w, d| if d.0 > w.0 { d } else { w })
}

/// Asserts that a ratio `D(dt)/D(dt/2)` of errors or differences that
/// shrink like `C dt^k` lies within 25 % of `2^k`, `k` the order of
/// `scheme` (the band leaves room for the next term at the coarser step).
pub fn assert_ratio_of_order(what: &str, scheme: Scheme, ratio: f64) {
    let expected = 2f64.powi(scheme.order() as i32);
    assert!(
        (ratio / expected - 1.0).abs() <= 0.25,
        "{what} {scheme}: ratio {ratio}, expected 2^k = {expected} within 25 %"
    );
}

/// The largest entry.
pub fn largest<const A: usize>(differences: &[f64; A]) -> f64 {
    differences.iter().fold(0.0, |m, &d| m.max(d))
}

/// The largest `|u_redundant - u_minimal|` over the common times of two runs
/// of one case at one step, and where (Fig. 1: the formulations approach
/// each other as dt shrinks).
pub fn redundant_minimal_difference<const N: usize, const M: usize, const A: usize>(
    redundant: &Solution<N, M, A>,
    minimal: &Solution<N, M, A>,
) -> (f64, f64) {
    assert_eq!(redundant.states.len(), minimal.states.len(), "runs on the same grid");
    redundant
        .states
        .iter()
        .zip(&minimal.states)
        .map(|(r, m)| ((r.u - m.u).amax(), r.t))
        .fold((0.0, 0.0), |w, d| if d.0 > w.0 { d } else { w })
}

/// One stand-in path: rest to rest (Poly9, eqs. 41-45) from `start` at
/// t = 0 to `end` at `duration`.
pub fn stand_in_path<const A: usize>(start: SVector<f64, A>, end: SVector<f64, A>, duration: f64) -> Path<A> {
    Path::new(PathSpec {
        profile: Profile::Poly9,
        t0: 0.0,
        t1: duration,
        start,
        end,
    })
    .expect("a valid stand-in path")
}

/// How far a crane's exact inputs (the reduced formulation's) may be from
/// their reference, relative to the input's size, at every step, every
/// scheme and every dt: about ten times the largest measured (`cargo test
/// --release -p crane-tests --test dummy_derivatives -- --nocapture`;
/// `stages` for the cranes without a reference, there the difference of
/// the staged and the whole solve). Newton stops after a correction below
/// 1e-10 relative whose error is of the order of its square, so what is
/// left is round-off: a few ulps of the equilibrated condition (below 10
/// on the double pendulum's move) times the jets' range.
///
/// | crane | measured | bound |
/// |---|---|---|
/// | navy-planar, navy-planar-pulley, gantry-3d, tower-crane, double-pendulum | 8.4e-16 .. 3.0e-15 | 2e-14 |
/// | elastic-drive (jets to N/s^6 on a stiff belt) | 2.75e-14 | 3e-13 |
/// | navy-3d, navy-3d-pulley (slewing: the jets of a rotating boom) | 3.99e-14, 3.2e-14 | 4e-13 |
pub fn exactness_bound(crane: &str) -> f64 {
    match crane {
        "elastic-drive" => 3e-13,
        "navy-3d" | "navy-3d-pulley" => 4e-13,
        _ => 2e-14,
    }
}
