//! The planar crane in minimal coordinates (sect. 5.1.2, scheme 24a-e) and the
//! commutative diagram of Fig. 1: redundant and minimal formulations describe
//! the same motion.

use crane_macros::crane_model;
use crane_models::navy_planar::PaperCase;
use crane_runtime::{Error, Options, Scheme, Solution, init, simulate_minimal};
use crane_tests::kit::{self, Formulation};

const DTS: [f64; 6] = [0.1, 0.05, 0.02, 0.01, 0.005, 0.001];

fn run_minimal(case: &PaperCase, dt: f64) -> Solution<7, 3, 2> {
    let start = case.start().unwrap();
    case.simulate_minimal(&start, &Options::new(dt, case.tf()).unwrap())
        .unwrap()
        .expect("the minimal run converges")
}

fn run_redundant(case: &PaperCase, dt: f64) -> Solution<7, 3, 2> {
    let start = case.start().unwrap();
    crane_runtime::simulate(case.model(), case.path(), &start, &Options::new(dt, case.tf()).unwrap()).unwrap()
}

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

/// The slow maneuver of Fig. 9, down to dt = 0.001 (the first steps, while
/// rope L1 is nearly slack, are taken in redundant coordinates: see
/// `degenerate_start_then_minimal_coordinates_follow_appendix_a`).
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

/// At the paper's start rope L1 is slack (N1 = 0, eq. 46), and while N1 is
/// tiny only N1 fixes the pulley along the load rope: the force balance at
/// the pulley holds to round-off of N2 (~1e-13 N), which moves the pulley
/// by ~1e-13 N / N1 x l. The minimal stepper takes those steps in redundant
/// coordinates until every rope carries 1e-5 of the largest tension, and
/// they are the redundant run's steps bit for bit. From there on, q is the
/// minimal formulation's own and follows Appendix A to 1e-8 m for tf = 4 s
/// and Fig. 9 at every dt from 0.01 to 0.001 (the load's q is prescribed,
/// the robot's q depends on the load's acceleration, which backward Euler
/// reproduces exactly up to round-off on a rest-to-rest path: measured
/// below 1e-9 m); before, the redundant run's own error at the degenerate
/// start is printed (up to 2e-6 m at dt = 0.001 on Fig. 9, ~1e-13 / N1).
#[test]
fn degenerate_start_then_minimal_coordinates_follow_appendix_a() {
    for tf in [4.0, 15.0] {
        let case = PaperCase::new(tf).unwrap();
        for dt in [0.01, 0.005, 0.002, 0.001] {
            let (redundant, minimal) = (run_redundant(&case, dt), run_minimal(&case, dt));
            let k = minimal.redundant_start_steps;
            assert!(k >= 1, "rope L1 is slack at the paper's start: tf = {tf}, dt = {dt}");
            assert_eq!(minimal.states[..=k], redundant.states[..=k], "tf = {tf}, dt = {dt}");
            let tension_ratio = |i: usize| minimal.tensions_at(i)[0] / minimal.tensions_at(i)[1];
            assert!(
                tension_ratio(k) >= 1e-5 && tension_ratio(k - 1) < 1e-5,
                "tf = {tf}, dt = {dt}, k = {k}"
            );
            let error = |s: &crane_runtime::State<7, 3, 2>| (s.q - case.reference(s.t).unwrap().q).amax();
            let start_error = minimal.states[..=k].iter().map(error).fold(0.0, f64::max);
            let minimal_error = minimal.states[k..].iter().map(error).fold(0.0, f64::max);
            println!(
                "tf = {tf:>2}, dt = {dt:<5}: {k:>3} redundant steps (to t = {:.3} s), max |q - q_ref| {start_error:.1e} m there, {minimal_error:.1e} m after",
                minimal.states[k].t
            );
            assert!(minimal_error <= 1e-8, "tf = {tf}, dt = {dt}: {minimal_error:e}");
        }
    }
}

/// Fig. 1: the two formulations approach each other as dt shrinks. The
/// largest difference in u over the whole run decreases with dt (about
/// 7 dt N m, docs/numerics.md). Both schemes reproduce q exactly in exact
/// arithmetic (docs/errata.md), so the q difference is round-off amplified by
/// the conditioning of the step equations (the residual test at 1e-13,
/// condition numbers up to ~1e6 after the degenerate start; measured up to
/// 1e-11 m): below 1e-9 m. At the degenerate start both are the redundant
/// run's steps (see `degenerate_start_then_minimal_coordinates_follow_appendix_a`).
#[test]
fn redundant_and_minimal_formulations_agree_as_dt_shrinks() {
    let case = PaperCase::new(4.0).unwrap();
    let mut previous = f64::INFINITY;
    for dt in [0.1, 0.05, 0.02, 0.01, 0.005, 0.001] {
        let (redundant, minimal) = (run_redundant(&case, dt), run_minimal(&case, dt));
        let (mut du, mut dq, mut dq_start) = (0.0f64, 0.0f64, 0.0f64);
        for (r, m) in redundant.states.iter().zip(&minimal.states) {
            assert!((r.t - m.t).abs() < 1e-12);
            du = du.max((r.u - m.u).amax());
            if r.t >= 0.05 {
                dq = dq.max((r.q - m.q).amax());
            } else {
                dq_start = dq_start.max((r.q - m.q).amax());
            }
        }
        println!(
            "dt = {dt:<6} max |u_red - u_min| = {du:.3e} N m ({:.2} dt), max |q_red - q_min| = {dq:.3e} m (t >= 0.05 s), {dq_start:.3e} m (t < 0.05 s)",
            du / dt
        );
        assert!(du < previous, "u difference must shrink: {du} after {previous}");
        assert!(dq.max(dq_start) < 1e-9, "{dq} {dq_start}");
        previous = du;
    }
}

crane_model! {
    /// A planar gantry crane whose minimal map uses a split that violates
    /// eq. (12) at rest: mu2 = [pos, theta] gives D2 phi_x = [[1, len cos theta],
    /// [0, len sin theta]], singular for a hanging load (theta = 0).
    pub struct BadSplitGantry {
        params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: -m_l*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
        minimal [len | pos, theta] {
            s = pos;
            L = len;
            x = pos + len*sin(theta);
            z = -len*cos(theta);
        }
    }
}

#[test]
fn a_singular_split_is_a_typed_error_not_a_nan() {
    use crane_runtime::nalgebra::vector;
    use crane_runtime::trajectory::Poly9;
    let crane = BadSplitGantry::default();
    let path = Poly9::new(0.0, 5.0, vector![0.0, -5.0], vector![4.0, -3.0]).unwrap();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.3, 4.5]).unwrap();
    let result = simulate_minimal(
        &crane,
        &path,
        &start,
        &vector![5.0, 0.0, 0.0],
        &Options::new(0.01, 5.0).unwrap(),
    );
    match result {
        Err(Error::SingularOutputJacobian { t, condition }) => {
            assert_eq!(t, 0.0);
            assert!(condition > 1e12, "{condition}");
        }
        other => panic!("expected SingularOutputJacobian, got {:?}", other.map(|s| s.steps())),
    }
}

/// The generated map of eqs. (36)-(40) satisfies the constraints and its
/// derivatives match central differences (errors ~1e-9 for correct
/// derivatives, O(1) for wrong ones; g(phi) and G P are round-off, ~1e-15).
#[test]
fn minimal_map_satisfies_the_constraints_and_its_derivatives_check() {
    use crane_models::navy_planar::NavyPlanar;
    use crane_runtime::check::check_minimal_map;
    // beta, gamma, theta, L around the paper's maneuver (all lengths positive)
    let mu_box = [(0.2, 0.9), (1.2, 2.2), (-0.5, 0.5), (2.0, 10.0)];
    let report = check_minimal_map(&NavyPlanar::default(), &mu_box, 1.0, 200, 3);
    println!("{report}");
    assert!(
        report.get("g(phi(mu)) = 0").unwrap().worst_relative_error < 1e-13,
        "{report}"
    );
    assert!(report.get("G P = 0").unwrap().worst_relative_error < 1e-13, "{report}");
    assert!(report.worst() < 1e-6, "{report}");
}
