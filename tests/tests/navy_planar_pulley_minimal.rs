//! The planar crane with pulley mass in minimal coordinates (sect. 5.2.2,
//! eqs. 59-63 with docs/errata.md (60); scheme 24a-e) and the commutative diagram of
//! Fig. 1: redundant and minimal formulations describe the same motion.

use crane_models::navy_planar_pulley::{NavyPlanarPulley, PaperCase, minimal_guess};
use crane_runtime::check::check_minimal_map;
use crane_runtime::{MinimalMap, Options, Scheme, Solution, simulate};
use crane_tests::kit::{self, Formulation};
use nalgebra::{SMatrix, SVector};

const DTS: [f64; 6] = [0.1, 0.05, 0.02, 0.01, 0.005, 0.001];

fn run_minimal(case: &PaperCase, dt: f64) -> Solution<8, 4, 3> {
    let start = case.start().unwrap();
    case.simulate_minimal(&start, &Options::new(dt, case.tf()).unwrap())
        .expect("the crane declares a minimal map")
        .expect("the minimal run converges")
}

fn run_redundant(case: &PaperCase, dt: f64) -> Solution<8, 4, 3> {
    let start = case.start().unwrap();
    simulate(case.model(), case.path(), &start, &Options::new(dt, case.tf()).unwrap()).unwrap()
}

// ---------------------------------------------------------------------------
// The map (eqs. 59-63)

/// `mu = [beta, gamma, theta, L]` along the paper's maneuvers, from the
/// Appendix B reference by [`minimal_guess`]: `(min, max)` per coordinate.
fn mu_range_along_maneuver() -> [(f64, f64); 4] {
    let mut range = [(f64::INFINITY, f64::NEG_INFINITY); 4];
    for tf in [4.0, 15.0] {
        let case = PaperCase::new(tf).unwrap();
        for i in 0..=400 {
            let t = tf * i as f64 / 400.0;
            let mu = minimal_guess(case.model(), &case.reference(t).unwrap());
            for (r, m) in range.iter_mut().zip(mu.iter()) {
                *r = (r.0.min(*m), r.1.max(*m));
            }
        }
    }
    range
}

/// The map satisfies the constraints (55) identically and its generated
/// derivatives match central differences: g(phi) and G P are round-off
/// (~1e-16 relative), P and P' err by ~1e-9 when right and O(1) when wrong.
/// The box holds the whole maneuver (tf = 4 s and 15 s) with a margin and
/// keeps every length positive: `beta` in (0, pi), `gamma + theta + alpha -
/// beta` in [0.24, 1.95] and `gamma + theta + alpha` in [1.54, 2.65].
#[test]
fn minimal_map_satisfies_the_constraints_and_its_derivatives_check() {
    let range = mu_range_along_maneuver();
    println!("mu along the maneuvers: {range:.4?}");
    let mu_box = [(0.7, 1.3), (0.8, 1.3), (-0.3, 0.3), (0.5, 8.0)];
    for (r, b) in range.iter().zip(&mu_box) {
        assert!(b.0 < r.0 && r.1 < b.1, "maneuver {r:?} outside the box {b:?}");
    }
    let report = check_minimal_map(&NavyPlanarPulley::default(), &mu_box, 1.0, 200, 5);
    println!("{report}");
    assert!(
        report.get("g(phi(mu)) = 0").unwrap().worst_relative_error < 1e-13,
        "{report}"
    );
    assert!(report.get("G P = 0").unwrap().worst_relative_error < 1e-13, "{report}");
    assert!(report.worst() < 1e-6, "{report}");
}

/// The paper's start (eqs. 66-67, docs/errata.md) is `mu = [pi/3, pi/3, 0, 5]`, and
/// [`minimal_guess`] inverts the map exactly along the reference solution.
#[test]
fn minimal_guess_inverts_the_map_along_the_reference() {
    let case = PaperCase::new(4.0).unwrap();
    let model = case.model();
    let start = case.start().unwrap();
    let mu0 = minimal_guess(model, &start);
    let third = std::f64::consts::FRAC_PI_3;
    let expected = SVector::<f64, 4>::from([third, third, 0.0, 5.0]);
    println!(
        "mu0 = {:?}, |mu0 - [pi/3, pi/3, 0, 5]| = {:.1e}",
        mu0.as_slice(),
        (mu0 - expected).amax()
    );
    assert!((mu0 - expected).amax() < 1e-14, "{mu0}");
    assert!((model.phi(&mu0) - start.q).amax() < 1e-13);
    let mut worst = 0.0f64;
    for i in 0..=100 {
        let reference = case.reference(4.0 * i as f64 / 100.0).unwrap();
        worst = worst.max((model.phi(&minimal_guess(model, &reference)) - reference.q).amax());
    }
    println!("max |phi(minimal_guess(q_ref)) - q_ref| = {worst:.1e} m");
    assert!(worst < 1e-12, "{worst}");
}

/// Eq. (12) with the split (63): `D2 phi_x` (rows x, z, z0 and columns
/// gamma, theta, L of P) has determinant
/// `-L l sin(beta) cos(alpha - beta) / sin^2(gamma + theta + alpha - beta)`
/// (checked here on a grid of the box above), nonzero on the whole box:
/// `L > 0`, `beta` in (0, pi) and `|alpha - beta| < pi/2`.
#[test]
fn output_jacobian_is_regular() {
    let model = NavyPlanarPulley::default();
    let (a, l) = (model.alpha, model.l);
    let mut smallest = f64::INFINITY;
    for beta in [0.75, 1.0, 1.25] {
        for gamma in [0.85, 1.05, 1.25] {
            for theta in [-0.25, 0.0, 0.25] {
                for big_l in [1.0, 4.0, 7.0] {
                    let mu = SVector::<f64, 4>::from([beta, gamma, theta, big_l]);
                    let d2: SMatrix<f64, 3, 3> = model.null_space(&mu).fixed_view::<3, 3>(5, 1).into_owned();
                    let expected =
                        -big_l * l * beta.sin() * (a - beta).cos() / (gamma + theta + a - beta).sin().powi(2);
                    let det = d2.determinant();
                    assert!(
                        (det - expected).abs() < 1e-12 * expected.abs(),
                        "{det} vs {expected} at {mu}"
                    );
                    smallest = smallest.min(det.abs());
                }
            }
        }
    }
    println!("smallest |det D2 phi_x| on the grid: {smallest:.3}");
    // eq. (12) holds on the whole grid, far from singular (measured 6.52)
    assert!(smallest > 1.0, "D2 phi_x nearly singular: {smallest}");
}

// ---------------------------------------------------------------------------
// Convergence (eq. 48)

#[test]
fn minimal_formulation_converges_with_order_one_tf4() {
    kit::assert_order(
        &PaperCase::new(4.0).unwrap(),
        Formulation::Minimal,
        Scheme::BackwardEuler,
        &DTS,
        0.9..=1.1,
    );
}

/// The slow maneuver of Fig. 18; unlike the massless-pulley crane's
/// degenerate start, the regular start (66) lets it run down to dt = 0.001.
#[test]
fn minimal_formulation_converges_with_order_one_tf15() {
    kit::assert_order(
        &PaperCase::new(15.0).unwrap(),
        Formulation::Minimal,
        Scheme::BackwardEuler,
        &DTS,
        0.9..=1.1,
    );
}

// ---------------------------------------------------------------------------
// The commutative diagram (Fig. 1)

/// Largest differences over a run: `[u_red - u_min, lambda_red - lambda_min,
/// q_red - q_min, q_red - q_ref, q_min - q_ref]` (max norms).
fn differences(case: &PaperCase, redundant: &Solution<8, 4, 3>, minimal: &Solution<8, 4, 3>) -> [f64; 5] {
    assert_eq!(redundant.states.len(), minimal.states.len());
    let mut worst = [0.0f64; 5];
    for (r, m) in redundant.states.iter().zip(&minimal.states) {
        assert!((r.t - m.t).abs() < 1e-12);
        let reference = case.reference(r.t).unwrap();
        let d = [
            (r.u - m.u).amax(),
            (r.lambda - m.lambda).amax(),
            (r.q - m.q).amax(),
            (r.q - reference.q).amax(),
            (m.q - reference.q).amax(),
        ];
        for (w, d) in worst.iter_mut().zip(d) {
            *w = w.max(d);
        }
    }
    worst
}

/// Fig. 1: both formulations solve the same index-3 DAE, so their solutions
/// approach each other as dt shrinks.
///
/// - `u` (and `lambda1`, `lambda3`) carry backward Euler's first-order error
///   through second differences (docs/errata.md, "Where the discretisation error
///   sits"), discretised differently in `q` (redundant) and `mu` (minimal):
///   their difference shrinks like dt (measured 7.7 dt .. 8.3 dt N m), with
///   observed order 1 between the two smallest steps.
/// - `q` has no discretisation error in either scheme: the servo constraints
///   (24c, e) fix the load's position and acceleration exactly, and the load
///   rows `m_l x'' = -lambda4 (x - x0)`, `m_l (z'' + g) = -lambda4 (z - z0)`
///   (124g, h), which the reduced equations (24b) contain (the null space
///   of `P^T` is the range of `G^T`, eq. 11), then fix `x0`, and with it all
///   of `q`. So the `q` difference does not shrink with dt; it
///   is what the Newton iterations leave. The redundant scheme's `q` matches
///   Appendix B to round-off (< 1e-11 m, measured <= 7e-13 m). The minimal
///   scheme's is within 1e-8 m (measured 4.8e-9 m at dt = 0.01, 6.0e-9 m at
///   dt = 0.005, <= 3e-11 m at the other dt): Newton's residual exit
///   (`NewtonOptions::residual_tol = 1e-13`, normalised residual) accepts the
///   iterate after a single update from the predictor before `q` is at
///   round-off; with that exit disabled `q` is exact to round-off as well,
///   see [`minimal_coordinates_are_exact_when_newton_iterates_to_round_off`].
#[test]
fn redundant_and_minimal_formulations_agree_as_dt_shrinks() {
    let case = PaperCase::new(4.0).unwrap();
    let table: Vec<[f64; 5]> = DTS
        .iter()
        .map(|&dt| differences(&case, &run_redundant(&case, dt), &run_minimal(&case, dt)))
        .collect();
    for (dt, [du, dl, dq, dq_red, dq_min]) in DTS.iter().zip(&table) {
        println!(
            "dt = {dt:<6} max |u_red - u_min| = {du:.3e} N m ({:.2} dt), |lambda_red - lambda_min| = {dl:.3e} N/m, \
             |q_red - q_min| = {dq:.2e} m, |q_red - q_ref| = {dq_red:.2e} m, |q_min - q_ref| = {dq_min:.2e} m",
            du / dt
        );
    }
    for w in table.windows(2) {
        assert!(w[1][0] < w[0][0], "u difference must shrink with dt: {table:?}");
        assert!(w[1][1] < w[0][1], "lambda difference must shrink with dt: {table:?}");
    }
    let n = DTS.len();
    let order = (table[n - 2][0] / table[n - 1][0]).ln() / (DTS[n - 2] / DTS[n - 1]).ln();
    println!(
        "u difference: observed order between dt = {} and {}: {order:.4}",
        DTS[n - 2],
        DTS[n - 1]
    );
    assert!((0.9..=1.1).contains(&order), "observed order {order}");
    for (dt, [_, _, dq, dq_red, _]) in DTS.iter().zip(&table) {
        assert!(*dq_red < 1e-11, "redundant q at dt = {dt}: {dq_red:e}");
        assert!(*dq < 1e-8, "q difference at dt = {dt}: {dq:e}");
    }
}

/// The cause of the `q` difference above: with Newton's residual exit
/// disabled (`residual_tol = 0`, so every step iterates until the update test
/// `|dz| <= 1e-10 |z| + 1e-14` holds, after which the quadratically
/// convergent iteration leaves only round-off), the minimal scheme reproduces
/// `q` of Appendix B to round-off like the redundant one (measured
/// 2.5e-14 m), 1e-11 m being three orders of magnitude below the 6e-9 m the
/// residual exit leaves. (At dt = 0.001 the update test alone is not met: the
/// round-off in the update exceeds it at t = 1.255 s, which is what the
/// residual exit is for, docs/numerics.md.)
#[test]
fn minimal_coordinates_are_exact_when_newton_iterates_to_round_off() {
    use crane_runtime::newton::NewtonOptions;
    let case = PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let newton = NewtonOptions {
        residual_tol: 0.0,
        ..NewtonOptions::default()
    };
    for dt in &DTS[..5] {
        let minimal = case
            .simulate_minimal(
                &start,
                &Options::new(*dt, case.tf()).unwrap().with_newton(newton).unwrap(),
            )
            .unwrap()
            .expect("the minimal run converges on the update test");
        let dq = minimal
            .states
            .iter()
            .map(|s| (s.q - case.reference(s.t).unwrap().q).amax())
            .fold(0.0, f64::max);
        println!(
            "residual exit off, dt = {dt:<6} max |q_min - q_ref| = {dq:.2e} m, {:.2} Newton iterations per step",
            minimal.mean_newton_iterations()
        );
        assert!(dq < 1e-11, "minimal q at dt = {dt}: {dq:e}");
    }
}
