//! The paper's checks of the planar crane with massless pulley (sect. 5.1.3):
//! consistent start, convergence of u to the analytical solution of Appendix A
//! (Figs. 5-7, eq. 48), the long maneuver of Fig. 9, and rope tensions (Fig. 8).

use crane_models::navy_planar::{NavyPlanar, PaperCase, paper_p0};
use crane_runtime::{Error, Options, Scheme, Solution, init, simulate};
use crane_tests::kit::{self, Formulation};

const DTS: [f64; 6] = [0.1, 0.05, 0.02, 0.01, 0.005, 0.001];

fn run(case: &PaperCase, dt: f64) -> Solution<7, 3, 2> {
    let start = case.start().expect("the paper's start is consistent");
    simulate(case.model(), case.path(), &start, &Options::new(dt, case.tf()).unwrap()).expect("the run converges")
}

#[test]
fn paper_start_is_consistent_and_matches_appendix_a() {
    let case = PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let reference = case.reference(0.0).unwrap();
    // eq. (46) is the t -> 0 limit of the flatness solution; both are exact
    // formulas, so they agree to round-off
    for i in 0..7 {
        assert!((start.q[i] - reference.q[i]).abs() < 1e-10, "q[{i}]");
    }
    // u and lambda of the static balance against the flatness solution at t0
    // (force scale m_l g ~ 1e3: 1e-10 relative)
    assert!((start.u - reference.u).amax() < 1e-7, "{} vs {}", start.u, reference.u);
    assert!(
        (start.lambda - reference.lambda).amax() < 1e-7,
        "{} vs {}",
        start.lambda,
        reference.lambda
    );
    // the slack rope L1 of the degenerate start (docs/errata.md)
    assert!(start.lambda[0].abs() < 1e-10);
}

#[test]
fn perturbed_start_names_the_violated_constraint() {
    let case = PaperCase::new(4.0).unwrap();
    let mut p0 = paper_p0();
    p0[0] += 0.1; // L1 too long: rope1 no longer closes
    let error = init::check_start(case.model(), case.path(), 0.0, &p0, None).unwrap_err();
    match &error {
        Error::InconsistentStart { equation, residual, .. } => {
            assert!(equation.contains("rope1"), "{error}");
            // g_rope1 = -1/2 ((L1 + 0.1)^2 - L1^2) = -(0.1 L1 + 0.005)
            assert!((residual - (0.1 * 5.0 * 3f64.sqrt() + 0.005)).abs() < 1e-12, "{error}");
        }
        other => panic!("expected an inconsistent start, got {other}"),
    }
    // a geometrically consistent start with the pulley at B = (1, -5), off the
    // vertical through the load: all ropes close, but the load rope pulls the
    // load sideways, so the static balance of x fails
    let (x0, z0) = (1.0f64, -5.0f64);
    let (l, alpha) = (10.0, std::f64::consts::FRAC_PI_3);
    let l0 = x0.hypot(z0);
    let l1 = (x0 + l * alpha.sin()).hypot(z0 + l * alpha.cos());
    let l2 = l0 + (0.0 - x0).hypot(-10.0 - z0);
    let error = init::check_start(case.model(), case.path(), 0.0, &[l1, l2, l0, x0, z0], None).unwrap_err();
    assert!(
        error.to_string().contains("static balance of coordinate `x`"),
        "{error}"
    );
}

#[test]
fn static_solve_reports_the_non_unique_equilibrium() {
    let case = PaperCase::new(4.0).unwrap();
    // a rough guess near the paper's start
    let guess = [8.0, 10.5, 5.5, 0.3, -5.5];
    match init::static_equilibrium(case.model(), case.path(), 0.0, &guess) {
        Err(Error::NonUniqueEquilibrium { free, .. }) => {
            // the pulley slides along the hoist rope: z0 and L0 move, and L1 with them
            for name in ["L1", "L0", "z0"] {
                assert!(free.contains(name), "free direction {free}");
            }
        }
        other => panic!("expected a non-unique equilibrium, got {other:?}"),
    }
}

/// At the end of the maneuver the load rests at (-3, -14), off the vertical
/// through P: rope L1 is taut and the equilibrium is unique. The static solve
/// finds it from a rough guess, and it agrees with Appendix A at rest.
#[test]
fn static_solve_finds_a_regular_equilibrium() {
    let case = PaperCase::new(4.0).unwrap();
    let reference = case.reference(4.0).unwrap();
    let guess = [
        reference.q[0] + 0.5,
        reference.q[1] - 0.5,
        reference.q[2] + 0.4,
        reference.q[3] - 0.3,
        reference.q[4] + 0.3,
    ];
    let state = init::static_equilibrium(case.model(), case.path(), 4.0, &guess).unwrap();
    // Newton converges to round-off (1e-11 relative update test); the
    // reference is exact: agreement to 1e-9 in metres and 1e-7 in N m, N/m
    assert!((state.q - reference.q).amax() < 1e-9, "{} vs {}", state.q, reference.q);
    assert!((state.u - reference.u).amax() < 1e-7, "{} vs {}", state.u, reference.u);
    assert!((state.lambda - reference.lambda).amax() < 1e-7);
    // and the solution passes the consistency check as a user-given start
    let p: Vec<f64> = state.q.iter().take(5).copied().collect();
    init::check_start(case.model(), case.path(), 4.0, &p, None).unwrap();
}

#[test]
fn u_converges_with_order_one_tf4() {
    let errors = kit::assert_order(
        &PaperCase::new(4.0).unwrap(),
        Formulation::Redundant,
        Scheme::BackwardEuler,
        &DTS,
        0.9..=1.1,
    );
    // Fig. 7 (left): errors of a few percent at dt = 0.1 down to ~1e-4
    assert!(errors[0] < 0.05 && errors[5] < 1e-3, "{errors:?}");
}

#[test]
fn u_converges_with_order_one_tf15() {
    kit::assert_order(
        &PaperCase::new(15.0).unwrap(),
        Formulation::Redundant,
        Scheme::BackwardEuler,
        &DTS,
        0.9..=1.1,
    );
}

/// docs/errata.md, "Where the discretisation error sits": for the massless pulley the
/// coordinates are fixed algebraically at each step by the servo constraints
/// (which use the exact gamma'') and the massless rows, so backward Euler
/// reproduces q (and lambda) to round-off while u carries the O(dt) error.
#[test]
fn coordinates_and_multipliers_follow_the_reference() {
    let case = PaperCase::new(4.0).unwrap();
    let solution = run(&case, 0.1); // Fig. 5
    let (mut q_err, mut lambda_err) = (0.0f64, 0.0f64);
    for state in &solution.states {
        let reference = case.reference(state.t).unwrap();
        q_err = q_err.max((state.q - reference.q).amax());
        lambda_err = lambda_err.max((state.lambda - reference.lambda).amax() / reference.lambda.amax());
    }
    println!("dt = 0.1: max |q - q_ref| = {q_err:.2e} m, max relative lambda error {lambda_err:.2e}");
    // measured 1.1e-12 m and 2.9e-13: round-off of the 10-15 m coordinates
    // and of the multipliers; bounds 10x above
    assert!(q_err < 1e-11, "{q_err}");
    assert!(lambda_err < 3e-12, "{lambda_err}");
}

#[test]
fn ropes_stay_taut_along_the_maneuver() {
    for tf in [4.0, 15.0] {
        let case = PaperCase::new(tf).unwrap();
        let solution = run(&case, 0.01);
        let peak = solution.tensions.iter().fold(0.0f64, |m, n| m.max(n.abs()));
        for (i, state) in solution.states.iter().enumerate() {
            for (rope, n) in solution.info.ropes.iter().zip(solution.tensions_at(i)) {
                // N1 is exactly 0 at the degenerate start and evaluates to
                // ~1e-13 N of either sign; anything below -1e-9 peak is slack
                assert!(
                    *n >= -1e-9 * peak,
                    "rope {} slack at t = {}: {n}",
                    rope.tension,
                    state.t
                );
            }
        }
    }
}

#[test]
fn invalid_settings_are_typed_errors() {
    let case = PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let model = case.model();
    // the settings are checked once, when they are made
    assert!(matches!(Options::new(-0.1, 4.0), Err(Error::InvalidTimeStep { .. })));
    assert!(matches!(
        Options::new(f64::NAN, 4.0),
        Err(Error::InvalidTimeStep { .. })
    ));
    assert!(matches!(
        Options::new(0.1, f64::INFINITY),
        Err(Error::InvalidEndTime { .. })
    ));
    assert!(matches!(Options::stepping(0.0), Err(Error::InvalidTimeStep { .. })));
    let no_iterations = crane_runtime::newton::NewtonOptions {
        max_iterations: 0,
        ..Default::default()
    };
    assert!(matches!(
        Options::new(0.1, 4.0).unwrap().with_newton(no_iterations),
        Err(Error::InvalidNewtonOptions(_))
    ));
    // a run to the start or before it, and steps that do not fit the span
    assert!(matches!(
        simulate(model, case.path(), &start, &Options::stepping(0.1).unwrap()),
        Err(Error::InvalidTimeSpan { .. })
    ));
    assert!(matches!(
        simulate(model, case.path(), &start, &Options::new(0.1, 0.0).unwrap()),
        Err(Error::InvalidTimeSpan { .. })
    ));
    assert!(matches!(
        simulate(model, case.path(), &start, &Options::new(0.3, 4.0).unwrap()),
        Err(Error::StepsDoNotFit { .. })
    ));
    let broken = NavyPlanar {
        m_l: f64::NAN,
        ..NavyPlanar::default()
    };
    assert!(matches!(
        simulate(&broken, case.path(), &start, &Options::new(0.1, 4.0).unwrap()),
        Err(Error::NonFiniteParameter { name: "m_l", .. })
    ));
}

/// Another boom (`l`, `alpha` in a scenario's parameters) with the default
/// `p0`: the start at rest is again degenerate (rope L1 slack, the pulley
/// free along the hoist rope), so the static solve finds a family; the run
/// starts from the member the flatness solution reaches at t0, in closed
/// form: the pulley B on the vertical through P and the load, level with
/// winch A at (-l sin alpha, -l cos alpha), so `L1 = l sin alpha`,
/// `L0 = l cos alpha`, `L2 = 10 m` (the load 10 m below P). It once needed
/// a hand-computed `p0`.
#[test]
fn another_boom_starts_from_the_flatness_limit_without_a_p0() {
    use crane_models::Case;
    use crane_models::navy_planar::Description;
    use crane_runtime::CraneModel;
    let default = PaperCase::new(4.0).unwrap();
    for (l, alpha) in [(12.0f64, 0.8f64), (9.0, 1.2), (10.0, 1.0)] {
        let mut model = *default.model();
        model.set_parameter("l", l).unwrap();
        model.set_parameter("alpha", alpha).unwrap();
        let case =
            Case::<Description, 7, 3, 2>::from_parts(model, default.path().clone(), paper_p0().to_vec(), default.tf());
        assert!(
            case.start().is_err(),
            "the paper's p0 does not fit l = {l}, alpha = {alpha}"
        );
        let start = case
            .run_start()
            .unwrap_or_else(|e| panic!("l = {l}, alpha = {alpha}: {e}"));
        let (s, c) = alpha.sin_cos();
        let expected = [l * s, 10.0, l * c, 0.0, -l * c, 0.0, -10.0];
        // the reference's formulas at theta = 0 are exact: round-off of 10 m
        for (q, e) in start.q.iter().zip(expected) {
            assert!((q - e).abs() < 1e-12, "l = {l}, alpha = {alpha}: {:?}", start.q);
        }
        assert!(start.lambda[0].abs() < 1e-10, "rope L1 slack: {}", start.lambda);
        // the run from there is the flatness solution's, to the reduced
        // formulation's round-off (2e-14 measured bound on the paper's crane)
        let options = Options::new(0.01, case.tf()).unwrap();
        let solution = Formulation::DummyDerivative
            .simulate(&case, &start, &options, &mut |_, _| {})
            .unwrap();
        let e_u = kit::e_u(&case, &solution);
        assert!(
            e_u < kit::exactness_bound("navy-planar"),
            "l = {l}, alpha = {alpha}: e_u = {e_u}"
        );
    }
}

/// Winches of J1 = J2 = 1e6 kg m^2 in eqs. (22) with backward Euler: the
/// iteration matrix's winch rows are 1e13 times its rope rows, its pivot
/// ratio below 1e-14 as it stands, and it was taken for singular: Newton's
/// minimum-norm steps crept (30 of 0.9 each) and the run failed at the
/// first step at every dt. Equilibrated it is regular: the run converges at
/// order one to the flatness solution (measured e_u 3.29e-3 and 3.30e-4).
#[test]
fn heavy_winches_converge_in_redundant_coordinates() {
    use crane_models::Case;
    use crane_models::navy_planar::Description;
    use crane_runtime::CraneModel;
    let default = PaperCase::new(4.0).unwrap();
    let mut model = *default.model();
    model.set_parameter("J1", 1e6).unwrap();
    model.set_parameter("J2", 1e6).unwrap();
    let case = Case::<Description, 7, 3, 2>::from_parts(model, default.path().clone(), paper_p0().to_vec(), 4.0);
    let errors: Vec<f64> = [1e-3, 1e-4]
        .iter()
        .map(|&dt| {
            let solution = kit::run_to(&case, Formulation::Redundant, Scheme::BackwardEuler, dt, 1.6);
            kit::e_u(&case, &solution)
        })
        .collect();
    let order = (errors[0] / errors[1]).log10();
    assert!((0.95..1.05).contains(&order), "order {order}: {errors:?}");
    assert!(errors[1] < 1e-3, "{errors:?}");
}
