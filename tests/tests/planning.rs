//! Planning with the inverse dynamics (`crane_models::plan`): the fastest
//! feasible move and parameter sweeps, checked against a duration with a
//! closed-form answer, against brute force and against single runs.

use crane_models::plan::{Limits, Settings, evaluate, fastest, sweep, sweep_point};
use crane_models::{Case, Path, PathSpec, Profile, gantry_3d, navy_planar};
use crane_runtime::nalgebra::vector;

/// The paper's crane under |u2| <= 150 N m (the limit of
/// examples/navy-planar-fig5-8.toml): the answer meets every limit, 2 %
/// faster violates one, and the interval check holds.
#[test]
fn the_fastest_move_is_feasible_and_a_faster_one_is_not() {
    let case = navy_planar::PaperCase::maneuver().unwrap();
    let limits = Limits {
        torque: vec![(1, 150.0)],
        tension: vec![],
    };
    let settings = Settings::default();
    let best = fastest(&case, &limits, &settings).unwrap();
    println!(
        "T* = {:.4} s after {} evaluations; {} = {:.3} at t = {:.3} s; interval {:?}",
        best.duration, best.evaluations, best.binding.name, best.binding.value, best.binding.at, best.interval
    );
    let at = |d: f64| {
        evaluate(&case, d, &settings)
            .0
            .feasible::<navy_planar::NavyPlanar, 7, 3, 2>(&limits)
    };
    assert!(at(best.duration));
    assert!(!at(0.98 * best.duration));
    assert!(best.bracket.1 - best.bracket.0 <= settings.tolerance);
    assert_eq!(best.binding.name, "u2");
    assert!(
        best.binding.value <= 150.0 && best.binding.value > 149.0,
        "{:?}",
        best.binding
    );
    assert!(best.interval.holds);
}

/// A closed-form answer: lowering the gantry's load straight down by
/// |dz| = 5 m on the poly9 profile s(tau), the rope tension is
/// N = m_l (g + z'') with z'' = dz s''(tau) / T^2 (the load hangs on the one
/// rope), so a floor N >= m_l g / 2 holds exactly when
/// T >= T* = sqrt(2 |dz| max s'' / g). max s'' comes from the polynomial
/// 126 tau^5 - 420 tau^6 + 540 tau^7 - 315 tau^8 + 70 tau^9 written out
/// here. The search at dt = 1 ms finds T* to its tolerance (1 ms) plus the
/// error of sampling the tension every step (relative ~(dt/T)^2, 1e-7 s).
#[test]
fn a_tension_floor_gives_the_closed_form_duration() {
    let s2 = |t: f64| {
        2520.0 * t.powi(3) - 12600.0 * t.powi(4) + 22680.0 * t.powi(5) - 17640.0 * t.powi(6) + 5040.0 * t.powi(7)
    };
    let max_s2 = (0..=1_000_000)
        .map(|i| s2(i as f64 * 1e-6))
        .fold(f64::NEG_INFINITY, f64::max);
    let (dz, g) = (5.0f64, 9.81);
    let expected = (2.0 * dz * max_s2 / g).sqrt();
    let model = gantry_3d::Gantry3d::default();
    let path = Path::new(PathSpec {
        profile: Profile::Poly9,
        t0: 0.0,
        t1: 8.0,
        start: vector![0.0, 0.0, -3.0],
        end: vector![0.0, 0.0, -8.0],
    })
    .unwrap();
    let floor = 0.5 * model.m_l * g;
    let case = Case::<gantry_3d::Description, 6, 1, 3>::from_parts(model, path, vec![0.0, 0.0, 3.0], 8.0);
    let limits = Limits {
        torque: vec![],
        tension: vec![(0, floor)],
    };
    let settings = Settings {
        dt: 1e-3,
        ..Settings::default()
    };
    let best = fastest(&case, &limits, &settings).unwrap();
    println!(
        "T* = {:.6} s, closed form {expected:.6} s (max s'' = {max_s2:.6}), {} evaluations",
        best.duration, best.evaluations
    );
    assert!(
        best.duration >= expected - 1e-6 && best.duration <= expected + settings.tolerance + 1e-6,
        "{} vs {expected}",
        best.duration
    );
    assert_eq!(best.binding.name, "N");
}

/// A step longer than the move does not hide it: gantry-3d under |u1| <=
/// 1000 N with dt = 2 s finds what dt = 0.05 s finds (6.5527 s; every
/// evaluation steps at most a twentieth of the move), where it found every
/// duration down to 2 ms feasible (one step of such a move sees the crane
/// only at rest). The two answers differ by sampling alone: the peak between
/// steps of 6.55 s / 20 is placed to O(dt^3) by the parabola through the
/// samples, a few ms here, within the 1 ms tolerance plus 1 %.
#[test]
fn a_long_step_still_resolves_the_move() {
    let case = gantry_3d::DefaultCase::maneuver().unwrap();
    let limits = Limits {
        torque: vec![(0, 1000.0)],
        tension: vec![],
    };
    let fine = fastest(&case, &limits, &Settings::default()).unwrap();
    let coarse = Settings {
        dt: 2.0,
        ..Settings::default()
    };
    let long = fastest(&case, &limits, &coarse).unwrap();
    println!(
        "T* = {:.4} s at dt <= 0.05 s, {:.4} s at dt <= 2 s",
        fine.duration, long.duration
    );
    assert_eq!(long.binding.name, "u1");
    assert!(
        (long.duration - fine.duration).abs() < 0.01 * fine.duration,
        "{} vs {}",
        long.duration,
        fine.duration
    );
    // the rigid-body bound: u1 moves 1000 kg 6 m
    assert!(long.duration > 2.0 * (6.0f64 * 1000.0 / 1000.0).sqrt());
}

/// Brute force: on a grid of durations 2 ms apart around the answer, every
/// duration below T* (by more than the tolerance) is infeasible, every one
/// above feasible, and the first feasible grid point is within a grid step
/// of T*.
#[test]
fn brute_force_agrees_with_the_bisection() {
    let case = navy_planar::PaperCase::maneuver().unwrap();
    let limits = Limits {
        torque: vec![(0, 150.0), (1, 150.0)],
        tension: vec![],
    };
    let settings = Settings::default();
    let best = fastest(&case, &limits, &settings).unwrap();
    let grid: Vec<f64> = (0..=300).map(|i| best.duration - 0.3007 + 0.002 * i as f64).collect();
    let feasible: Vec<bool> = grid
        .iter()
        .map(|&d| {
            evaluate(&case, d, &settings)
                .0
                .feasible::<navy_planar::NavyPlanar, 7, 3, 2>(&limits)
        })
        .collect();
    let first = grid.iter().zip(&feasible).find(|(_, f)| **f).map(|(d, _)| *d).unwrap();
    println!(
        "bisection {:.4} s ({} evaluations), brute force {first:.4} s (301 evaluations)",
        best.duration, best.evaluations
    );
    for (&d, &f) in grid.iter().zip(&feasible) {
        if (d - best.duration).abs() > settings.tolerance {
            assert_eq!(f, d > best.duration, "d = {d}");
        }
    }
    assert!((first - best.duration).abs() <= 0.002 + settings.tolerance);
}

/// Each sweep row is the single run with the same parameters, bit for bit;
/// the rows do not depend on the number of threads; a point that cannot run
/// (a negative mass) records its error and the sweep finishes.
#[test]
fn sweep_rows_are_single_runs_whatever_the_threads() {
    let case = navy_planar::PaperCase::maneuver().unwrap();
    let limits = Limits {
        torque: vec![(1, 150.0)],
        tension: vec![],
    };
    let settings = Settings::default();
    let params = vec![("m_l".to_string(), vec![-1.0, 80.0, 100.0, 120.0])];
    let durations = [3.0, 4.0, 5.0];
    let in_pool = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| sweep(&case, &params, &durations, &limits, &settings, &|| {}))
    };
    let (one, two) = (in_pool(1), in_pool(2));
    assert_eq!(one, two);
    assert_eq!(one.len(), 12);
    for point in &one {
        let names: Vec<String> = params.iter().map(|(name, _)| name.clone()).collect();
        let single = sweep_point(&case, &names, &point.values, point.duration, &limits, &settings);
        assert_eq!(point, &single);
        if point.values[0] < 0.0 {
            let error = point.evaluation.error.as_deref().unwrap();
            assert!(error.contains("m_l") && !point.feasible, "{error}");
        } else {
            assert!(point.evaluation.error.is_none());
            // and the single run by hand: the parameter set on the model
            let mut model = *case.model();
            crane_runtime::CraneModel::<7, 3, 2>::set_parameter(&mut model, "m_l", point.values[0]).unwrap();
            let by_hand = Case::<navy_planar::Description, 7, 3, 2>::from_parts(
                model,
                case.path().clone(),
                case.p0.clone(),
                case.tf(),
            );
            assert_eq!(evaluate(&by_hand, point.duration, &settings).0, point.evaluation);
        }
    }
    // heavier loads need more torque
    let peak = |m: f64, d: f64| {
        one.iter()
            .find(|p| p.values[0] == m && p.duration == d)
            .unwrap()
            .evaluation
            .peak_u[1]
            .0
    };
    assert!(peak(120.0, 4.0) > peak(100.0, 4.0) && peak(100.0, 4.0) > peak(80.0, 4.0));
}

/// A path two derivatives rougher than the crane needs gives inputs with
/// impulses, which no torque limit admits: navy-3d-pulley (inputs need the
/// 6th derivative) on the paper's three-phase profile (continuous to the
/// 4th) is refused with the reason, in `fastest` and in every sweep point;
/// on the smooth profile (continuous to the 6th) it is planned, and its
/// answer meets the limit.
#[test]
fn planning_refuses_a_path_whose_inputs_carry_impulses() {
    use crane_models::navy_3d_pulley::{Navy3dPulley, PaperCase, TF};
    use crane_models::plan::PlanError;
    let limits = Limits {
        torque: vec![(3, 150.0)],
        tension: vec![],
    };
    let settings = Settings::default();
    let rough = PaperCase::maneuver().unwrap();
    match fastest(&rough, &limits, &settings) {
        Err(PlanError::PathTooRough { needed, continuous, .. }) => assert_eq!((needed, continuous), (6, 4)),
        other => panic!("expected PathTooRough, got {:?}", other.map(|f| f.duration)),
    }
    let point = sweep_point(&rough, &[], &[], TF, &limits, &settings);
    assert!(!point.feasible);
    assert!(point.evaluation.error.unwrap().contains("impulses"));
    let smooth = PaperCase::smooth(TF).unwrap();
    let best = fastest(&smooth, &limits, &settings).unwrap();
    println!(
        "navy-3d-pulley, smooth profile, |u4| <= 150: T* = {:.4} s",
        best.duration
    );
    assert!(
        evaluate(&smooth, best.duration, &settings)
            .0
            .feasible::<Navy3dPulley, 12, 5, 4>(&limits)
    );
    assert_eq!(best.binding.name, "u4");
}

/// Limits that never bind (|u2| <= 1e9 N m, ropes allowed to push with
/// 1e12 N) leave the bisection only the durations where the inverse
/// dynamics fails: that is an error naming the failure, not a fastest move
/// "bound by the run itself".
#[test]
fn limits_that_do_not_bind_before_the_runs_fail_are_an_error() {
    use crane_models::plan::PlanError;
    let case = navy_planar::PaperCase::maneuver().unwrap();
    let limits = Limits {
        torque: vec![(1, 1e9)],
        tension: vec![(0, -1e12), (1, -1e12)],
    };
    match fastest(&case, &limits, &Settings::default()) {
        Err(PlanError::RunFailsFirst { duration, error }) => {
            println!("runs fail below {duration:.4} s: {error}");
            assert!(duration > 0.0 && duration < 4.0, "{error}");
        }
        other => panic!("expected RunFailsFirst, got {:?}", other.map(|f| f.duration)),
    }
}

/// A parameter far from the crane's default moves the start far from
/// `p0`: the double pendulum's sling from 0.05 to 5.9 m instead of 2 m
/// moves its hook by up to 3.9 m. Newton finds the static equilibrium from
/// `p0` (its line search weighs each equation in its row's units: on the
/// raw residual it took steps of 1/32 and gave up 0.1 m off), and it is
/// the one at rest by hand: everything straight below the trolley, the hook
/// `l_s` above the load at (0, -6), the hoist rope as long as the hook is
/// deep. A sweep over the sling's length runs every point (it failed all).
#[test]
fn a_start_far_from_p0_is_found_from_it() {
    use crane_models::double_pendulum::Description;
    use crane_runtime::CraneModel;
    let default = Case::<Description, 6, 2, 2>::maneuver().unwrap();
    // p0 = [s, L, xh, zh] = [0, 4, 0, -4] is given for the sling of 2 m; at
    // rest the hook hangs l_s above the load at (0, -6), the hoist rope
    // vertical: q = [0, 6 - l_s, 0, l_s - 6, 0, -6]
    for l_s in [0.05, 0.5, 1.9, 2.1, 2.5, 4.0, 5.9] {
        let mut model = *default.model();
        model.set_parameter("l_s", l_s).unwrap();
        let case =
            Case::<Description, 6, 2, 2>::from_parts(model, default.path().clone(), default.p0.clone(), default.tf());
        let start = case.consistent_start(0.0).unwrap();
        let expected = [0.0, 6.0 - l_s, 0.0, l_s - 6.0, 0.0, -6.0];
        for (q, e) in start.q.iter().zip(expected) {
            // Newton's tolerance, 1e-11 of each block's size
            assert!((q - e).abs() < 1e-9, "l_s = {l_s}: {:?}", start.q);
        }
        assert_eq!(case.run_start().unwrap().q, start.q, "a run starts there too");
    }
    let params = vec![("l_s".to_string(), vec![0.5, 1.5, 2.5, 3.0])];
    let points = sweep(&default, &params, &[], &Limits::default(), &Settings::default(), &|| {});
    for p in &points {
        assert!(
            p.evaluation.error.is_none(),
            "l_s = {:?}: {:?}",
            p.values,
            p.evaluation.error
        );
    }
}

/// A step that makes each evaluation longer than a plan holds is refused
/// before the first run, with the step that would do: `--dt 1e-6` on
/// navy-planar's 4 s move (4e6 steps per run) grew to 12 GB in the bracket.
#[test]
fn a_step_too_small_for_planning_is_refused_before_any_run() {
    let case = navy_planar::PaperCase::maneuver().unwrap();
    let limits = Limits {
        torque: vec![(1, 150.0)],
        tension: vec![],
    };
    let settings = Settings {
        dt: 1e-6,
        ..Settings::default()
    };
    let error = fastest(&case, &limits, &settings).expect_err("refused").to_string();
    assert!(
        error.contains("a run of 4 s at dt = 1e-6 s is 4e6 steps") && error.contains("give dt >= 4e-6 s"),
        "{error}"
    );
    // an evaluation (a sweep point) says the same for its own run
    let (evaluation, solution) = evaluate(&case, 4.0, &settings);
    assert!(solution.is_none());
    assert!(evaluation.error.unwrap().contains("4e6 steps"));
}
