//! State selection: the dummy-derivative system of a crane with stable
//! internal dynamics, its free states integrated by BDF-k and everything
//! else algebraic at each step time (`crane_runtime::state_selection`).

use crane_runtime::nalgebra::vector;
use crane_runtime::scheme::Scheme;
use crane_runtime::state_selection;
use crane_runtime::trajectory::Poly9;
use crane_runtime::{Options, Solution, init};
use crane_tests::damped::{DampedDrive, DampedSwing};

/// The swing's default move: 3 m across and 1 m up in 4 s, then 2 s at rest.
fn swing_path() -> Poly9<2> {
    Poly9::new(0.0, 4.0, vector![0.0, -5.0], vector![3.0, -4.0]).unwrap()
}

fn swing_run(scheme: Scheme, dt: f64) -> Solution<6, 2, 2> {
    let crane = DampedSwing::default();
    let path = swing_path();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0, 0.0, -2.0]).unwrap();
    let options = Options::new(dt, 6.0).unwrap().with_scheme(scheme);
    state_selection::simulate(&crane, &path, &start, &options, &mut |_, _| {}).unwrap()
}

/// The largest difference of the inputs of `run` from `reference` at the
/// reference's times (a multiple of the run's step), relative to the peak.
fn input_error(run: &Solution<6, 2, 2>, reference: &Solution<6, 2, 2>) -> f64 {
    let stride = (run.dt / reference.dt).round() as usize;
    let peak = reference.states.iter().map(|s| s.u.amax()).fold(0.0, f64::max);
    run.states
        .iter()
        .zip(reference.states.iter().step_by(stride))
        .map(|(a, b)| {
            assert!((a.t - b.t).abs() < 1e-9, "{} {}", a.t, b.t);
            (a.u - b.u).amax()
        })
        .fold(0.0, f64::max)
        / peak
}

/// The swing's states are the bob's horizontal position and velocity (its
/// height follows from the rod), and the linearisation at rest has the
/// damped pendulum's eigenvalues `-b/(2 m2) +- i sqrt(g/l2 - (b/(2 m2))^2)`
/// = -1 +- 1.97611i 1/s, to round-off (the Jacobian is exact).
#[test]
fn the_swing_is_selected_and_its_eigenvalues_are_the_damped_pendulums() {
    let run = swing_run(Scheme::bdf(2).unwrap(), 0.01);
    assert_eq!(run.selected_states, ["x2", "x2'"]);
    let crane = DampedSwing::default();
    let start = run.states[0];
    let mut eigenvalues = state_selection::eigenvalues_at(&crane, swing_path(), &start).unwrap();
    eigenvalues.sort_by(|a, b| a.im.total_cmp(&b.im));
    let (re, im) = (-40.0 / (2.0 * 20.0), (9.81 / 2.0 - 1.0f64).sqrt());
    assert_eq!(eigenvalues.len(), 2);
    for (lambda, expected_im) in eigenvalues.iter().zip([-im, im]) {
        assert!(
            (lambda.re - re).abs() < 1e-9 && (lambda.im - expected_im).abs() < 1e-9,
            "{eigenvalues:?}"
        );
    }
}

/// The belt's damper leaves the motor angle a first-order state with the
/// eigenvalue -k/d = -0.5 1/s (the frozen-time diagnosis cannot resolve it).
#[test]
fn the_damped_belt_leaves_the_motor_angle_with_eigenvalue_minus_k_over_d() {
    let crane = DampedDrive::default();
    let path = Poly9::new(0.0, 4.0, vector![0.0, -5.0], vector![3.0, -4.0]).unwrap();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 0.0, 5.0]).unwrap();
    let options = Options::new(0.01, 5.0).unwrap().with_scheme(Scheme::bdf(2).unwrap());
    let run = state_selection::simulate(&crane, &path, &start, &options, &mut |_, _| {}).unwrap();
    assert_eq!(run.selected_states, ["phi"]);
    let eigenvalues = state_selection::eigenvalues_at(&crane, &path, &start).unwrap();
    assert_eq!(eigenvalues.len(), 1);
    assert!(
        (eigenvalues[0].re + 0.5).abs() < 1e-9 && eigenvalues[0].im == 0.0,
        "{eigenvalues:?}"
    );
    // at rest at the end: the trolley under the load, no trolley force
    let end = run.states.last().unwrap();
    assert!((end.q[1] - 3.0).abs() < 1e-6 && end.u[0].abs() < 1e-3, "{end:?}");
}

/// BDF-k on the states: the inputs converge at order k as dt halves, down
/// to dt = 1e-4 with no growth, against BDF-5 at dt = 1e-4 (whose error,
/// ~C dt^5, is far below the finest BDF-2 run's ~1e-8). The measured order
/// of each halving is within 0.25 of k.
#[test]
fn inputs_converge_at_the_bdf_order_down_to_a_tenth_of_a_millisecond() {
    let reference = swing_run(Scheme::bdf(5).unwrap(), 1e-4);
    for (k, steps) in [
        (1usize, [0.0016, 0.0008, 0.0004, 0.0002, 0.0001]),
        (2, [0.0016, 0.0008, 0.0004, 0.0002, 0.0001]),
    ] {
        let errors: Vec<f64> = steps
            .iter()
            .map(|&dt| input_error(&swing_run(Scheme::bdf(k).unwrap(), dt), &reference))
            .collect();
        println!("BDF-{k}: {errors:?}");
        for pair in errors.windows(2) {
            let order = (pair[0] / pair[1]).log2();
            assert!((order - k as f64).abs() < 0.25, "BDF-{k}: {errors:?}");
        }
    }
}

/// A flat crane through the same entry point is the dummy-derivative run
/// itself (no states; the same inputs bit for bit).
#[test]
fn a_flat_crane_has_no_states_and_todays_inputs() {
    use crane_models::{Case, navy_planar::Description};
    let case = Case::<Description, 7, 3, 2>::maneuver().unwrap();
    let start = case.start().unwrap();
    let options = Options::new(0.01, case.tf()).unwrap();
    let (crane, path) = (case.model(), case.path());
    let run = state_selection::simulate(crane, path, &start, &options, &mut |_, _| {}).unwrap();
    // the flat crane's own stepper, recorded step by step
    let mut stepper =
        crane_runtime::dummy_derivative::DummyDerivativeStepper::new(crane, path, &start, &options).unwrap();
    let flat = crane_runtime::driver::record(&mut stepper, options.tf(), &mut |_, _| {}).unwrap();
    assert!(run.selected_states.is_empty());
    assert_eq!(run.states, flat.states);
}

/// On the coupled trolley (unstable internal dynamics) the states'
/// linearisation at rest has the eigenvalues the frozen-time diagnosis
/// finds there, +-9.9045 1/s: two computations from different equations
/// (the dummy-derivative system's Jacobian against the projection of eqs.
/// 1a-b onto the free directions) agreeing to 1e-9 relative, where both are
/// exact at rest.
#[test]
fn the_coupled_trolleys_states_have_the_diagnosis_eigenvalues_at_rest() {
    use crane_models::coupled_trolley::CoupledTrolley;
    let crane = CoupledTrolley::default();
    let path = Poly9::new(0.0, 5.0, vector![0.0, -5.0], vector![4.0, -3.0]).unwrap();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0]).unwrap();
    let mut selected: Vec<f64> = state_selection::eigenvalues_at(&crane, &path, &start)
        .unwrap()
        .iter()
        .map(|lambda| {
            assert_eq!(lambda.im, 0.0, "a real pair: {lambda}");
            lambda.re
        })
        .collect();
    let diagnosis = crane_runtime::internal::internal_dynamics(&crane, &start).unwrap();
    let mut frozen: Vec<f64> = diagnosis.eigenvalues.iter().map(|&(re, _)| re).collect();
    selected.sort_by(f64::total_cmp);
    frozen.sort_by(f64::total_cmp);
    assert_eq!(selected.len(), 2);
    assert_eq!(frozen.len(), 2);
    for (a, b) in selected.iter().zip(&frozen) {
        assert!((a - b).abs() < 1e-9 * b.abs(), "{selected:?} {frozen:?}");
    }
    assert!((selected[1] - 9.9045).abs() < 1e-4, "{selected:?}");
}

/// The default formulation follows from the states' eigenvalues at the
/// start: the coupled trolley's are unstable (stable inversion), the
/// damped swing's stable (state selection), a flat crane has none (its
/// exact dummy-derivative system).
#[test]
fn the_default_follows_from_the_eigenvalues() {
    use crane_models::study::Formulation;
    assert_eq!(
        Formulation::default_for::<crane_models::coupled_trolley::Description, 4, 1, 2>(),
        Formulation::StableInversion
    );
    assert_eq!(
        Formulation::default_for::<crane_models::navy_planar::Description, 7, 3, 2>(),
        Formulation::DummyDerivative
    );
    assert_eq!(
        Formulation::default_for::<Swing, 6, 2, 2>(),
        Formulation::StateSelection
    );
}

/// The damped swing as a crane with a default move.
struct Swing;

impl crane_models::Crane<6, 2, 2> for Swing {
    type Model = DampedSwing;
    const NAME: &'static str = "damped-swing";

    fn maneuver() -> crane_models::Maneuver<2> {
        crane_models::Maneuver {
            path: crane_models::PathSpec {
                profile: crane_models::Profile::Poly9,
                t0: 0.0,
                t1: 4.0,
                start: vector![0.0, -5.0],
                end: vector![3.0, -4.0],
            },
            p0: vec![0.0, 5.0, 0.0, -2.0],
        }
    }
}

/// A bob whirled round its pivot (the swing's damper at 2 N s/m, the load
/// moved 4 m in 1.2 s): its horizontal position, the state selected at
/// rest, stops fixing its height where the rod passes the horizontal. The
/// states are selected anew there (the bob's height and its rate, then
/// back: four times in the first 0.4 s, at the same times at every step),
/// and BDF-2 keeps its order against eqs. (22) with BDF-4 at dt = 6.25e-5
/// from t = 0.01 s (measured orders 2.54, 2.31, 2.10; with the states
/// kept, the error fell only at order 1: 1.0e-2, 5.7e-3, 2.8e-3, 1.5e-3 of
/// the peak). The reference's own error (BDF-4, about C dt^4) is far below
/// the finest run's 8e-6.
#[test]
fn the_states_are_selected_anew_where_the_rod_passes_the_horizontal() {
    use crane_runtime::driver;
    use crane_runtime::redundant::Redundant;
    let crane = DampedSwing {
        b: 2.0,
        ..DampedSwing::default()
    };
    let path = Poly9::new(0.0, 1.2, vector![0.0, -5.0], vector![4.0, -5.0]).unwrap();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0, 0.0, -2.0]).unwrap();
    let fine = Options::new(0.0000625, 0.4)
        .unwrap()
        .with_scheme(Scheme::bdf(4).unwrap());
    let reference = driver::solve(Redundant::new(&crane, &path), &start, &fine, &mut |_, _| {}).unwrap();
    let peak = reference.states.iter().map(|s| s.u.amax()).fold(0.0, f64::max);
    let mut errors = Vec::new();
    for dt in [0.001, 0.0005, 0.00025, 0.000125] {
        let options = Options::new(dt, 0.4).unwrap().with_scheme(Scheme::bdf(2).unwrap());
        let run = state_selection::simulate(&crane, &path, &start, &options, &mut |_, _| {}).unwrap();
        let times: Vec<f64> = run.reselected_states.iter().map(|(t, _)| *t).collect();
        let states: Vec<&[String]> = run.reselected_states.iter().map(|(_, s)| s.as_slice()).collect();
        assert_eq!(
            states,
            [["z2", "z2'"], ["x2", "x2'"], ["z2", "z2'"], ["x2", "x2'"]],
            "dt = {dt}"
        );
        for (t, expected) in times.iter().zip([0.147, 0.19, 0.303, 0.338]) {
            assert!((t - expected).abs() < 2e-3, "dt = {dt}: {times:?}");
        }
        let stride = (dt / 0.0000625f64).round() as usize;
        // (from t = 0.01 s: the reference's inputs in eqs. (22) carry the
        // index-3 transient of their first steps)
        let error = (run.states.iter().zip(reference.states.iter().step_by(stride)))
            .filter(|(a, _)| a.t >= 0.01)
            .map(|(a, b)| (a.u - b.u).amax())
            .fold(0.0, f64::max)
            / peak;
        errors.push(error);
    }
    println!("errors {errors:?}");
    for pair in errors.windows(2) {
        assert!((pair[0] / pair[1]).log2() > 1.8, "{errors:?}");
    }
}
