//! The schemes of the runtime (backward Euler = BDF-1, BDF-2 .. BDF-5) on the
//! two planar cranes in both formulations, checked like the paper's Figs. 7
//! and 16: the relative error of u at t = 1.5 s (eq. 48) against the
//! analytical references of Appendices A and B, and the observed order.
//! Also: q stays on the reference to round-off (the servo constraints use the
//! exact gamma''), and a start in the middle of the move (not at rest, so the
//! scheme starts itself) keeps order k at t = 1.5 s.

use crane_models::{Case, Crane};
use crane_models::{navy_3d, navy_3d_pulley, navy_planar, navy_planar_pulley};
use crane_runtime::{Options, Scheme, Solution, State, init, simulate};
use crane_tests::kit::{self, Formulation, T_ERROR, e_u};

/// End of the runs: the order is also measured on the largest relative
/// error of u over [1, 2] s (below).
const T_END: f64 = 2.0;

/// The paper's move of `case` from its consistent start to 2 s.
fn run<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    formulation: Formulation,
    scheme: Scheme,
    dt: f64,
) -> Solution<N, M, A> {
    kit::run_to(case, formulation, scheme, dt, T_END)
}

/// The largest relative error `|u - u_ref| / |u_ref|` over `[1, 2]` s.
fn window_error<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    run: &Solution<N, M, A>,
) -> f64 {
    run.states
        .iter()
        .filter(|s| s.t >= 1.0 - 1e-9)
        .map(|s| {
            let reference = case.reference(s.t).unwrap();
            (s.u - reference.u).norm() / reference.u.norm()
        })
        .fold(0.0, f64::max)
}

/// The order test of one crane, formulation and scheme (k = its order).
///
/// - e_u(1.5 s), eq. (48), for dt = 0.02, 0.01, 0.005 falls with dt; for
///   k <= 4 its observed order between 0.02 and 0.01 lies in
///   [k - 0.3, k + 0.7]. For BDF-5 the leading error term of the pulley
///   crane crosses zero near 1.5 s (redundant: e_u 5.2e-9 / 1.6e-10 at
///   dt = 0.02 / 0.01, order 5.0, but 3.2e-8 / 1.4e-9 at 0.03 / 0.015, order
///   4.6; minimal: 2.7e-8 / 1.6e-10, order 7.4), and at
///   dt = 0.005 it reaches the round-off floor of the index-3 scheme, which
///   grows like 1/dt^2 (measured 2.4e-8 at dt = 0.001, 1.8e-9 at 0.005 for
///   every k >= 3); the single time is no measure of the order there.
/// - So the order is also measured on the largest relative error over
///   [1, 2] s, which does not depend on where the error crosses zero: in
///   [k - 0.3, k + 0.7] between dt = 0.02 and 0.01 (0.04 and 0.02 for
///   BDF-5, whose error at 0.01 is within a factor 10 of the floor).
fn assert_order<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    name: &str,
    case: &Case<C, N, M, A>,
    formulation: Formulation,
    scheme: Scheme,
) -> [f64; 3] {
    let k = scheme.order() as f64;
    let band = k - 0.3..=k + 0.7;
    let runs = [0.04, 0.02, 0.01, 0.005].map(|dt| run(case, formulation, scheme, dt));
    let table = [e_u(case, &runs[1]), e_u(case, &runs[2]), e_u(case, &runs[3])];
    let order_at_1_5 = (table[0] / table[1]).log2();
    let windows = runs.each_ref().map(|r| window_error(case, r));
    let (coarse, order) = if scheme == Scheme::Bdf5 {
        (0.04, (windows[0] / windows[1]).log2())
    } else {
        (0.02, (windows[1] / windows[2]).log2())
    };
    println!(
        "{name:<19} {:<9} {:<14} e_u(1.5 s) at dt = 0.02 / 0.01 / 0.005: {:.2e} / {:.2e} / {:.2e} (order {order_at_1_5:.2}); \
         max over [1, 2] s: order {order:.2} from dt = {coarse}",
        format!("{formulation:?}"),
        scheme.name(),
        table[0],
        table[1],
        table[2]
    );
    assert!(
        table[1] < table[0],
        "{name} {formulation:?} {scheme}: e_u must fall with dt: {table:?}"
    );
    if scheme != Scheme::Bdf5 {
        assert!(
            table[2] < table[1],
            "{name} {formulation:?} {scheme}: e_u must fall with dt: {table:?}"
        );
        assert!(
            band.contains(&order_at_1_5),
            "{name} {formulation:?} {scheme}: e_u(1.5 s) order {order_at_1_5:.3}: {table:?}"
        );
    }
    assert!(
        band.contains(&order),
        "{name} {formulation:?} {scheme}: order {order:.3} over [1, 2] s: {windows:?}"
    );
    table
}

/// Every scheme in both formulations of one crane; each order more accurate
/// than the one before it at dt = 0.01.
fn assert_orders_of_every_scheme<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    name: &str,
    case: &Case<C, N, M, A>,
) {
    for formulation in [Formulation::Redundant, Formulation::Minimal] {
        let mut previous = f64::INFINITY;
        for scheme in Scheme::ALL {
            let table = assert_order(name, case, formulation, scheme);
            assert!(table[1] < previous, "{formulation:?} {scheme}: {table:?}");
            previous = table[1];
        }
    }
}

#[test]
fn navy_planar_converges_with_order_k_in_both_formulations() {
    assert_orders_of_every_scheme("navy-planar", &navy_planar::PaperCase::new(4.0).unwrap());
}

#[test]
fn navy_planar_pulley_converges_with_order_k_in_both_formulations() {
    assert_orders_of_every_scheme("navy-planar-pulley", &navy_planar_pulley::PaperCase::new(4.0).unwrap());
}

/// Backward Euler is the paper's scheme and the default: its e_u at
/// dt = 0.01 is the one of Fig. 7 (about 1.5e-3), whatever the seam.
#[test]
fn the_default_scheme_is_backward_euler() {
    assert_eq!(*Options::new(0.01, 1.0).unwrap().scheme(), Scheme::BackwardEuler);
    let case = navy_planar::PaperCase::new(4.0).unwrap();
    let e = e_u(&case, &run(&case, Formulation::Redundant, Scheme::default(), 0.01));
    assert!((1.4e-3..1.6e-3).contains(&e), "{e}");
}

/// For both planar cranes the coordinates are fixed algebraically at every
/// step by the servo constraints (with the exact gamma'') and the massless
/// or flat-output rows, so every scheme reproduces q to round-off. Measured
/// over the whole move: pulley crane 3.6e-15 m for every scheme and dt (bound
/// 1e-13 m, about 30 ulps of its 17 m coordinates); massless pulley 2.3e-12 m
/// from t = 0.1 s on (bound 2e-11 m). In the first steps after the massless
/// pulley's degenerate start (slack rope L1, a singular iteration matrix)
/// the weakly determined direction is off by 4e-10 m at dt = 0.01 and 4.5e-8 m
/// at dt = 0.001, the same for every scheme.
#[test]
fn coordinates_stay_on_the_reference_for_every_scheme() {
    let massless = navy_planar::PaperCase::new(4.0).unwrap();
    let pulley = navy_planar_pulley::PaperCase::new(4.0).unwrap();
    for scheme in Scheme::ALL {
        for dt in [0.02, 0.005] {
            let a = run(&massless, Formulation::Redundant, scheme, dt);
            let b = run(&pulley, Formulation::Redundant, scheme, dt);
            let worst = |states: &[State<7, 3, 2>]| {
                states
                    .iter()
                    .filter(|s| s.t >= 0.1)
                    .map(|s| (s.q - massless.reference(s.t).unwrap().q).amax())
                    .fold(0.0, f64::max)
            };
            let worst_pulley = b
                .states
                .iter()
                .map(|s| (s.q - pulley.reference(s.t).unwrap().q).amax())
                .fold(0.0, f64::max);
            println!(
                "{scheme} dt = {dt}: max |q - q_ref| = {:.2e} m (navy-planar, t >= 0.1 s), {worst_pulley:.2e} m (pulley)",
                worst(&a.states)
            );
            assert!(worst(&a.states) < 2e-11, "{scheme} dt = {dt}: {}", worst(&a.states));
            assert!(worst_pulley < 1e-13, "{scheme} dt = {dt}: {worst_pulley}");
        }
    }
}

/// A start that is not at rest: navy-planar picked up at t0 = 1 s in the
/// middle of the Fig. 5 move, from the Appendix A state there. The history
/// before t0 is unknown, so the scheme starts itself with an order ramp
/// (BDF-j on step j, `History::new`). For this flat crane the start-up error
/// leaves u after 2k steps, so e_u(1.5 s) keeps order k. Expected from the
/// rest start's table: the same e_u at 1.5 s to within the start-up's
/// leftovers.
#[test]
fn a_start_in_mid_move_keeps_order_k() {
    let case = navy_planar::PaperCase::new(4.0).unwrap();
    let t0 = 1.0;
    let reference = case.reference(t0).unwrap();
    let p0: Vec<f64> = reference.q.iter().take(5).copied().collect();
    let v0: Vec<f64> = reference.v.iter().take(5).copied().collect();
    let start =
        init::check_start(case.model(), case.path(), t0, &p0, Some(&v0)).expect("the reference state is consistent");
    assert!(!init::at_rest(case.path(), &start));
    for scheme in Scheme::ALL {
        let k = scheme.order() as f64;
        let errors = [0.02, 0.01].map(|dt| {
            let solution = simulate(
                case.model(),
                case.path(),
                &start,
                &Options::new(dt, T_ERROR).unwrap().with_scheme(scheme),
            )
            .unwrap();
            let from_rest = e_u(&case, &run(&case, Formulation::Redundant, scheme, dt));
            (e_u(&case, &solution), from_rest)
        });
        let order = (errors[0].0 / errors[1].0).log2();
        println!(
            "{scheme}: start at t0 = 1 s: e_u(1.5 s) = {:.2e} / {:.2e} at dt = 0.02 / 0.01 (order {order:.2}); from rest {:.2e} / {:.2e}",
            errors[0].0, errors[1].0, errors[0].1, errors[1].1
        );
        assert!((k - 0.3..=k + 0.7).contains(&order), "{scheme}: order {order}");
        // the start-up has left: within 10 % of the run from rest
        for (mid, rest) in errors {
            assert!(
                (mid - rest).abs() <= 0.1 * rest,
                "{scheme}: {mid:e} vs {rest:e} from rest"
            );
        }
    }
}

/// Self-convergence of BDF-k without a reference: `u(dt) = u + C(t) dt^k +
/// ...`, so `D(dt)/D(dt/2) -> 2^k`; the check is that the ratio lies within
/// 25 % of `2^k` (k = 2: [3, 5]; 3: [6, 10]; 4: [12, 20]) for the given
/// inputs and the first pair of step ratios given.
fn assert_self_convergence<const N: usize, const M: usize, const A: usize>(
    name: &str,
    scheme: Scheme,
    differences: &[[f64; A]],
    inputs: &[usize],
    pairs: usize,
) {
    let expected = 2f64.powi(scheme.order() as i32);
    for &k in inputs {
        let ratios: Vec<f64> = differences.windows(2).map(|w| w[0][k] / w[1][k]).collect();
        let d: Vec<String> = differences.iter().map(|d| format!("{:.2e}", d[k])).collect();
        let label = if A == 1 {
            "largest over the inputs".to_string()
        } else {
            format!("u{}", k + 1)
        };
        println!(
            "{name} {scheme}: {label}: D = [{}], ratios {ratios:.2?} (2^k = {expected})",
            d.join(", ")
        );
        for &r in &ratios[..pairs] {
            kit::assert_ratio_of_order(&format!("{name} u{}", k + 1), scheme, r);
        }
    }
}

/// navy-3d (sect. 6.1) on the paper's C4 three-phase move: away from the
/// phase switches (0, 5, 15, 20 s; a window of 0.5 s, where the 5th
/// derivative of the path jumps and BDF-k for k >= 4 loses order locally)
/// D(dt)/D(dt/2) approaches 2^k. Measured for dt = 0.04, 0.02, 0.01, 0.005:
/// k = 2: 4.15, 3.99; k = 3: 8.26, 8.01; k = 4: 16.2, 11.9 (at dt = 0.01
/// BDF-4's error, 5e-11 relative at t = 10 s, meets the round-off floor, so
/// only the first ratio is asserted for k = 4).
#[test]
fn navy_3d_self_converges_with_order_k() {
    let case = navy_3d::PaperCase::new(navy_3d::TF).unwrap();
    let start = case.start().unwrap();
    let switches = [0.0, 5.0, 15.0, 20.0];
    let away = |t: f64| switches.iter().all(|s| (t - s).abs() > 0.5);
    for (scheme, pairs) in [(Scheme::Bdf2, 2), (Scheme::Bdf3, 2), (Scheme::Bdf4, 1)] {
        let runs: Vec<Solution<11, 4, 3>> = [0.04, 0.02, 0.01, 0.005]
            .map(|dt| {
                simulate(
                    case.model(),
                    case.path(),
                    &start,
                    &Options::new(dt, case.tf()).unwrap().with_scheme(scheme),
                )
                .unwrap()
            })
            .into();
        let all_inputs: Vec<[f64; 1]> = kit::input_differences(&runs, away)
            .iter()
            .map(|d| [kit::largest(d)])
            .collect();
        assert_self_convergence::<11, 4, 1>("navy-3d", scheme, &all_inputs, &[0], pairs);
    }
}

/// navy-3d-pulley (sect. 6.2) on the C6 profile: away from the switches
/// (window 1 s) every input self-converges with order k for k = 2, 3, and the
/// winch torques u1..u3 for k = 4, measured for dt = 0.1, 0.05, 0.025:
/// k = 2: 4.02, 4.03, 4.02, 4.02 (u1..u4); k = 3: 7.94, 8.00, 7.94, 7.97;
/// k = 4: 15.9, 15.0, 15.7 and 91.9 for the slewing torque u4. u4 depends on
/// the path's 6th derivative and is computed from the second difference of
/// the slewing angle, which the pulley's force balance fixes; its BDF-4
/// differences do not settle into order 4 at these steps (D = 0.36, 3.9e-3,
/// 1.7e-2 N m for dt = 0.1, 0.05, 0.025, largest near t = 1.1 and 4 s). A
/// 1e-13 relative change of m_l moves u4 by up to 9e-5 N m at dt = 0.0125,
/// so round-off (1e-16) does not explain it; it is an open question (the
/// crane's inputs need the path's 6th derivative, beyond what the index-3
/// formulation tolerates for BDF-4), kept visible rather than hidden behind
/// a wider band.
#[test]
fn navy_3d_pulley_smooth_self_converges_with_order_k() {
    let case = navy_3d_pulley::PaperCase::smooth(navy_3d_pulley::TF).unwrap();
    let start = case.start().unwrap();
    let switches = [0.0, 5.0, 15.0, 20.0];
    let away = |t: f64| switches.iter().all(|s| (t - s).abs() > 1.0);
    for (scheme, inputs) in [
        (Scheme::Bdf2, &[0, 1, 2, 3][..]),
        (Scheme::Bdf3, &[0, 1, 2, 3][..]),
        (Scheme::Bdf4, &[0, 1, 2][..]),
    ] {
        let runs: Vec<Solution<12, 5, 4>> = [0.1, 0.05, 0.025]
            .map(|dt| {
                simulate(
                    case.model(),
                    case.path(),
                    &start,
                    &Options::new(dt, case.tf()).unwrap().with_scheme(scheme),
                )
                .unwrap()
            })
            .into();
        assert_self_convergence::<12, 5, 4>(
            "navy-3d-pulley (smooth)",
            scheme,
            &kit::input_differences(&runs, away),
            inputs,
            1,
        );
    }
}

/// The online stepper refuses a step to a time that is not `t_n + dt`
/// instead of stamping the wrong time on the result.
#[test]
fn a_step_to_the_wrong_time_is_refused() {
    use crane_runtime::redundant::Redundant;
    use crane_runtime::{Error, Stepper, Trajectory};
    let case = navy_planar::PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let options = Options::stepping(0.01).unwrap().with_scheme(Scheme::Bdf3);
    let mut stepper = Stepper::new(Redundant::new(case.model(), case.path()), &start, &options).unwrap();
    let target = |t: f64| [0, 1, 2].map(|k| case.path().derivative(t, k));
    let error = stepper.step_to(0.02, &target(0.02)).unwrap_err();
    assert_eq!(
        error,
        Error::WrongStepTime {
            t: 0.02,
            expected: 0.01
        }
    );
    assert_eq!(error.to_string(), "a step must go to t_n + dt = 0.01 s, not 0.02 s");
    assert_eq!(stepper.state().t, 0.0, "a refused step leaves the state alone");
    stepper.step_to(0.01, &target(0.01)).unwrap();
    assert!((stepper.state().t - 0.01).abs() < 1e-15);
}

/// A run whose results cannot be held is an error before the first step,
/// not a `capacity overflow` panic or an allocation failure.
#[test]
fn a_run_too_long_to_hold_is_a_typed_error() {
    use crane_runtime::Error;
    let case = navy_planar::PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    // 1e18 and 1e12 steps: their times are not told apart at double
    // precision (1.2e-4 s at 1e12 s, 1.2e-7 s at 1e9 s)
    for (dt, tf) in [(1e-6, 1e12), (1e-3, 1e9)] {
        let error = simulate(case.model(), case.path(), &start, &Options::new(dt, tf).unwrap()).unwrap_err();
        assert!(matches!(error, Error::TimesUnresolved { .. }), "{error:?}");
    }
    // 2e9 steps: told apart (2.3e-10 s at 2e6 s), but 368 GB of states
    let error = simulate(case.model(), case.path(), &start, &Options::new(1e-3, 2e6).unwrap()).unwrap_err();
    let Error::TooManySteps { steps, bytes } = error else {
        panic!("{error:?}")
    };
    assert_eq!(steps, 2e9);
    assert!(bytes > 3e11, "{bytes}");
    println!("{error}");
}
