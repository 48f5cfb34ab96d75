//! The FMU instance against the runtime, the way the Reference-FMUs test
//! every FMU: the same move through the FMI state machine and through the
//! API must give the same numbers, and every misuse must be an error, not a
//! crash.

use crane_fmi::description::default_experiment;
use crane_fmi::instance::{Component, Instance};
use crane_fmi::start::Start;
use crane_fmi::variables::{Role, variables};
use crane_models::registry::{self, Visit};
use crane_models::study::Formulation;
use crane_models::{CATALOG, Case, Crane, navy_planar};
use crane_runtime::{Options, Trajectory};

/// The value reference of the Real playing `role`.
fn vr<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(role: Role) -> u32 {
    variables::<C, N, M, A>(&Start::default_for::<C, N, M>())
        .unwrap()
        .into_iter()
        .find(|v| v.role == role && !v.integer)
        .unwrap()
        .value_reference
}

/// An initialised instance of `C` with the defaults.
fn started<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>() -> Instance<C, N, M, A> {
    let mut fmu = Instance::<C, N, M, A>::new().unwrap();
    fmu.setup_experiment(default_experiment::<C, N, M, A>(&Start::default_for::<C, N, M>()).0)
        .unwrap();
    fmu.enter_initialization_mode().unwrap();
    fmu.exit_initialization_mode().unwrap();
    fmu
}

/// Inputs and coordinates at the current state.
fn outputs<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(fmu: &Instance<C, N, M, A>) -> Vec<f64> {
    let refs: Vec<u32> = (0..A)
        .map(|k| vr::<C, N, M, A>(Role::Input(k)))
        .chain((0..N).map(|k| vr::<C, N, M, A>(Role::Coordinate(k))))
        .collect();
    let mut values = vec![0.0; refs.len()];
    fmu.get_real(&refs, &mut values).unwrap();
    values
}

/// navy-planar's instance with the Integer `path` (1: the built-in move, 3:
/// the external target) and the internal step `dt`, initialised.
fn navy_planar_started(path: i32, dt: f64) -> Instance<navy_planar::Description, 7, 3, 2> {
    let mut fmu = Instance::<navy_planar::Description, 7, 3, 2>::new().unwrap();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    fmu.set_integer(&[1], &[path]).unwrap();
    fmu.set_real(&[vr::<navy_planar::Description, 7, 3, 2>(Role::Dt)], &[dt])
        .unwrap();
    fmu.exit_initialization_mode().unwrap();
    fmu
}

/// navy-planar's external target's value references, `gamma_k^(o)` for
/// each load coordinate `k` and order `o = 0, 1, 2`.
fn target_refs() -> Vec<u32> {
    (0..2)
        .flat_map(|k| (0..3).map(move |o| (k, o)))
        .map(|(k, o)| vr::<navy_planar::Description, 7, 3, 2>(Role::Target(k, o)))
        .collect()
}

/// Every built-in crane's default move (dt = 0.01, one internal step per
/// communication step) gives the API's run in the crane's default
/// formulation (dummy derivatives for every flat crane; the coupled
/// trolley's bounded solution by stable inversion, played back from its
/// default experiment's start, 2.33 s before the move) bit for bit: inputs
/// and coordinates at every step, the same consistent start.
#[test]
fn every_built_in_fmu_reproduces_the_api_run() {
    struct Compare;
    impl Visit for Compare {
        type Output = usize;
        fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> usize {
            let case = Case::<C, N, M, A>::maneuver().unwrap();
            let options = Options::new(0.01, case.tf()).unwrap();
            let run = Formulation::default_for::<C, N, M, A>()
                .simulate(&case, &case.start().unwrap(), &options, &mut |_, _| {})
                .unwrap();
            let mut fmu = started::<C, N, M, A>();
            for (i, state) in run.states.iter().enumerate() {
                if i > 0 {
                    fmu.do_step(run.states[i - 1].t, 0.01).unwrap();
                }
                let expected: Vec<f64> = state.u.iter().chain(state.q.iter()).copied().collect();
                assert_eq!(outputs(&fmu), expected, "{} at t = {}", C::NAME, state.t);
            }
            run.steps()
        }
    }
    for e in CATALOG {
        let steps = registry::visit(e.name, Compare).unwrap();
        println!("{}: {steps} steps equal", e.name);
    }
}

/// Communication steps of 5 dt give the same states at the communication
/// points as steps of dt (the internal steps are the same steps).
#[test]
fn a_long_communication_step_is_several_internal_steps() {
    type D = navy_planar::Description;
    let (mut fine, mut coarse) = (started::<D, 7, 3, 2>(), started::<D, 7, 3, 2>());
    for k in 0..80 {
        for j in 0..5 {
            fine.do_step((5 * k + j) as f64 * 0.01, 0.01).unwrap();
        }
        coarse.do_step(k as f64 * 0.05, 0.05).unwrap();
        assert_eq!(outputs(&fine), outputs(&coarse), "t = {}", (k + 1) as f64 * 0.05);
    }
}

/// The external target (path = 3) gives the path up to gamma'' only: the
/// crane runs in eqs. (22a-d) (its default, the reduced system, needs the
/// path's derivatives up to order 4). Fed with the default move's values at
/// the end of every step, the run is the API's run of that move in eqs.
/// (22a-d) to round-off: the external target arrives rounded to `f64`,
/// where the API's run takes the path's own target in double-double (the
/// outputs agree to 1e-9 of the largest; measured 8.5e-11, the size of the
/// round-off floor that eqs. 22 had in `f64`, and 4.1e-10 m in the
/// pulley's coordinates after the first step, which the slack rope N1
/// leaves free at the start). With steps of 4 dt the internal targets come
/// from the quintic through both ends, whose error is at most h^6/720
/// max|gamma^(6)| (computed below on the path), and the coordinates at the
/// communication points stay within that bound of the API's run (measured
/// 1.9e-11 m against 1.7e-9 m).
#[test]
fn an_external_target_drives_the_same_crane() {
    type D = navy_planar::Description;
    let case = navy_planar::PaperCase::maneuver().unwrap();
    let path = case.path().clone();
    let path_ref = |t: f64| [path.derivative(t, 0), path.derivative(t, 1), path.derivative(t, 2)];
    let api = crane_runtime::simulate(
        case.model(),
        case.path(),
        &case.start().unwrap(),
        &crane_runtime::Options::new(0.01, 4.0).unwrap(),
    )
    .unwrap();
    for h in [0.01f64, 0.04] {
        let mut external = Instance::<D, 7, 3, 2>::new().unwrap();
        external.setup_experiment(0.0).unwrap();
        external.enter_initialization_mode().unwrap();
        external.set_integer(&[1], &[3]).unwrap();
        external.exit_initialization_mode().unwrap();
        let target_vr = target_refs();
        let steps = (4.0 / h).round() as usize;
        let per_step = (h / 0.01).round() as usize;
        let mut worst = 0.0f64;
        for i in 0..steps {
            let t = i as f64 * h;
            let target = path_ref((i + 1) as f64 * h);
            let values: Vec<f64> = (0..2).flat_map(|k| (0..3).map(move |o| target[o][k])).collect();
            external.set_real(&target_vr, &values).unwrap();
            external.do_step(t, h).unwrap();
            let a = outputs(&external);
            let state = &api.states[(i + 1) * per_step];
            let b: Vec<f64> = state.u.iter().chain(state.q.iter()).copied().collect();
            if h == 0.01 {
                let largest = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                let off = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
                assert!(off <= 1e-9 * largest, "t = {}: {a:?} against {b:?}", t + h);
            }
            worst = worst.max(
                a[2..]
                    .iter()
                    .zip(&b[2..])
                    .map(|(x, y)| (x - y).abs())
                    .fold(0.0, f64::max),
            );
        }
        let sixth = (0..=4000)
            .map(|i| path.derivative(i as f64 * 1e-3, 6).amax())
            .fold(0.0, f64::max);
        let bound = h.powi(6) / 720.0 * sixth;
        println!("h = {h}: largest coordinate difference {worst:.2e} m, interpolation bound {bound:.2e} m");
        // (at h = dt the bound is 0: the run differs from the API's by
        // round-off, checked above)
        if h > 0.01 {
            assert!(worst <= bound, "h = {h}: {worst} > {bound}");
        }
    }
}

/// Misuse is an error with a message, never a panic: a negative mass, a
/// step that is not a multiple of dt, a step at the wrong time, an unknown
/// value reference, setting an output or a parameter after initialisation,
/// an unknown scheme. After an error only reset helps, and reset gives the
/// defaults back: the same run again.
#[test]
fn misuse_is_an_error_and_reset_starts_over() {
    type D = navy_planar::Description;
    let m_l = vr::<D, 7, 3, 2>(Role::Parameter(0));
    let mut fmu = Instance::<D, 7, 3, 2>::new().unwrap();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    fmu.set_real(&[m_l], &[-100.0]).unwrap();
    let error = fmu.exit_initialization_mode().unwrap_err();
    assert!(error.contains("m_l"), "{error}");
    assert!(fmu.do_step(0.0, 0.01).is_err());
    fmu.reset();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    assert!(fmu.set_integer(&[0], &[7]).is_ok());
    assert!(fmu.exit_initialization_mode().unwrap_err().contains("scheme = 7"));
    fmu.reset();
    let reference = {
        let mut f = started::<D, 7, 3, 2>();
        f.do_step(0.0, 0.5).unwrap();
        outputs(&f)
    };
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    fmu.exit_initialization_mode().unwrap();
    assert!(
        fmu.do_step(0.0, 0.015)
            .unwrap_err()
            .contains("not a whole multiple of dt")
    );
    fmu.reset();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    fmu.exit_initialization_mode().unwrap();
    assert!(fmu.do_step(0.1, 0.01).unwrap_err().contains("the instance is at t = 0"));
    fmu.reset();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    fmu.exit_initialization_mode().unwrap();
    assert!(
        fmu.set_real(&[m_l], &[50.0])
            .unwrap_err()
            .contains("only be set before")
    );
    assert!(
        fmu.set_real(&[vr::<D, 7, 3, 2>(Role::Input(0))], &[1.0])
            .unwrap_err()
            .contains("output")
    );
    assert!(fmu.get_real(&[9999], &mut [0.0]).is_err());
    fmu.do_step(0.0, 0.5).unwrap();
    assert_eq!(outputs(&fmu), reference, "after reset the run is the default run");
}

/// Two instances at once step independently: interleaved steps of two
/// different loads equal the runs of each alone.
#[test]
fn instances_are_independent() {
    type D = navy_planar::Description;
    let m_l = vr::<D, 7, 3, 2>(Role::Parameter(0));
    let heavy = || {
        let mut f = Instance::<D, 7, 3, 2>::new().unwrap();
        f.setup_experiment(0.0).unwrap();
        f.enter_initialization_mode().unwrap();
        f.set_real(&[m_l], &[150.0]).unwrap();
        f.exit_initialization_mode().unwrap();
        f
    };
    let (mut a, mut b) = (started::<D, 7, 3, 2>(), heavy());
    for k in 0..100 {
        a.do_step(k as f64 * 0.01, 0.01).unwrap();
        b.do_step(k as f64 * 0.01, 0.01).unwrap();
    }
    let (mut a_alone, mut b_alone) = (started::<D, 7, 3, 2>(), heavy());
    a_alone.do_step(0.0, 1.0).unwrap();
    b_alone.do_step(0.0, 1.0).unwrap();
    assert_eq!(outputs(&a), outputs(&a_alone));
    assert_eq!(outputs(&b), outputs(&b_alone));
    assert_ne!(outputs(&a), outputs(&b));
}

/// A Newton failure in mid-run (an unreachable end point, the one that
/// stops `crane run` at t = 0.23 s) is an error of that step with the
/// runtime's message; the instance then refuses to step until reset.
#[test]
fn a_newton_failure_is_an_error_of_its_step() {
    type D = navy_planar::Description;
    let mut fmu = Instance::<D, 7, 3, 2>::new().unwrap();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    fmu.set_real(
        &[vr::<D, 7, 3, 2>(Role::End(0)), vr::<D, 7, 3, 2>(Role::Duration)],
        &[8.0, 2.0],
    )
    .unwrap();
    fmu.exit_initialization_mode().unwrap();
    let mut failed = None;
    for k in 0..200 {
        if let Err(e) = fmu.do_step(k as f64 * 0.01, 0.01) {
            failed = Some((k, e));
            break;
        }
    }
    let (k, message) = failed.expect("the unreachable move fails");
    assert_eq!(k, 22, "{message}");
    assert!(message.contains("did not converge at t = 0.23 s"), "{message}");
    assert!(fmu.do_step(0.23, 0.01).is_err());
    fmu.reset();
    assert!(fmu.setup_experiment(0.0).is_ok());
}

/// Long runs cross powers of two: past t = 8192 s an ulp of the time
/// (1.8e-12 s) exceeds 1e-9 of dt = 0.001 s, and a host's `t + h` differs
/// from the instance's `t0 + n dt` in its last bits. Started at 8191.9 s
/// with dt = 0.001 and communication steps of 0.01 s (the host adding
/// `h` to its own time), both the built-in move and the external target
/// (whose internal steps go through `Stepper::step_to`) cross 8192 s; a NaN
/// communication point and a non-positive step are errors.
#[test]
fn a_run_crosses_t_8192_and_odd_communication_points_are_errors() {
    type D = navy_planar::Description;
    let t0 = 8191.9;
    for path in [0, 3] {
        let mut fmu = Instance::<D, 7, 3, 2>::new().unwrap();
        fmu.setup_experiment(t0).unwrap();
        fmu.enter_initialization_mode().unwrap();
        fmu.set_real(&[vr::<D, 7, 3, 2>(Role::Dt)], &[0.001]).unwrap();
        fmu.set_real(&[vr::<D, 7, 3, 2>(Role::T0)], &[t0]).unwrap();
        fmu.set_integer(&[1], &[path]).unwrap();
        fmu.exit_initialization_mode().unwrap();
        if path == 3 {
            // hold the load where it is: the target at rest
            let refs: Vec<u32> = (0..2).map(|k| vr::<D, 7, 3, 2>(Role::Target(k, 0))).collect();
            let mut at = vec![0.0; 2];
            let coords: Vec<u32> = (5..7).map(|k| vr::<D, 7, 3, 2>(Role::Coordinate(k))).collect();
            fmu.get_real(&coords, &mut at).unwrap();
            fmu.set_real(&refs, &at).unwrap();
        }
        let mut t = t0;
        for _ in 0..20 {
            fmu.do_step(t, 0.01)
                .unwrap_or_else(|e| panic!("path {path} at t = {t}: {e}"));
            t += 0.01;
        }
        assert!(fmu.time() > 8192.09, "path {path}: {}", fmu.time());
    }
    let mut fmu = started::<D, 7, 3, 2>();
    assert!(fmu.do_step(f64::NAN, 0.01).unwrap_err().contains("finite"));
    let mut fmu2 = started::<D, 7, 3, 2>();
    assert!(fmu2.do_step(0.0, 0.0).unwrap_err().contains("must be positive"));
    let mut fmu3 = started::<D, 7, 3, 2>();
    assert!(fmu3.do_step(0.0, -0.01).unwrap_err().contains("must be positive"));
    fmu.reset();
}

/// `g = -9.81` is refused at initialisation (every built-in declares `g`
/// positive), with the parameter named.
#[test]
fn gravity_with_the_wrong_sign_is_an_fmi_error() {
    type D = navy_planar::Description;
    let g = crane_runtime::CraneModel::<7, 3, 2>::parameter_values(&navy_planar::NavyPlanar::default()).len() - 1;
    let mut fmu = Instance::<D, 7, 3, 2>::new().unwrap();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    fmu.set_real(&[vr::<D, 7, 3, 2>(Role::Parameter(g))], &[-9.81]).unwrap();
    let error = fmu.exit_initialization_mode().unwrap_err();
    assert!(error.contains("`g`") && error.contains("positive"), "{error}");
}

/// `dt = 1e-300` is refused at initialisation naming `dt` (it used to reach
/// Newton as a singular iteration matrix).
#[test]
fn a_tiny_dt_is_an_fmi_error_naming_dt() {
    type D = navy_planar::Description;
    let mut fmu = Instance::<D, 7, 3, 2>::new().unwrap();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    fmu.set_real(&[vr::<D, 7, 3, 2>(Role::Dt)], &[1e-300]).unwrap();
    let error = fmu.exit_initialization_mode().unwrap_err();
    assert!(
        error.starts_with("`dt`") && error.contains("at least 1e-6 s"),
        "{error}"
    );
}

/// A built-in move through the pulley (navy-planar to (-3, 5), above the
/// boom tip) drives its ropes to negative lengths (the hoist rope N2 first,
/// at t = 1.68 s): `fmi2DoStep` fails there naming the rope, instead of
/// returning a motion no crane can make.
#[test]
fn a_rope_of_non_positive_length_is_an_fmi_error() {
    type D = navy_planar::Description;
    let mut fmu = Instance::<D, 7, 3, 2>::new().unwrap();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    let end: Vec<u32> = (0..2).map(|k| vr::<D, 7, 3, 2>(Role::End(k))).collect();
    fmu.set_real(&end, &[-3.0, 5.0]).unwrap();
    fmu.exit_initialization_mode().unwrap();
    let error = (0..400)
        .find_map(|i| fmu.do_step(i as f64 * 0.01, 0.01).err())
        .expect("a step fails");
    assert!(
        error.contains("rope N2 of navy-planar (constraint `hoist`) has the length"),
        "{error}"
    );
    let mut status = [0];
    fmu.get_integer(&[2], &mut status).unwrap();
    assert_eq!(status, [2], "the status output says it");
}

/// The coupled trolley's built-in move is played back as its bounded
/// solution: from the default experiment's start, 2.33 s before the move,
/// nothing to warn of (`status` 0 throughout, inputs below 200 N); a start
/// time after the pre-actuation begins is refused at
/// `fmi2ExitInitializationMode`, with the time to start at.
#[test]
fn the_coupled_trolleys_built_in_move_plays_back_its_bounded_inputs() {
    type D = crane_models::coupled_trolley::Description;
    let (start, stop) = default_experiment::<D, 4, 1, 2>(&Start::default_for::<D, 4, 1>());
    assert!(
        (start + 2.33).abs() < 1e-9 && (stop - 6.81).abs() < 1e-9,
        "{start} {stop}"
    );
    let mut fmu = started::<D, 4, 1, 2>();
    assert_eq!(fmu.take_warning(), None);
    let steps = ((stop - start) / 0.01).round() as usize;
    let mut status = [9];
    let mut peak = 0.0f64;
    for k in 0..steps + 10 {
        fmu.do_step(start + k as f64 * 0.01, 0.01).unwrap();
        assert_eq!(fmu.take_warning(), None, "step {k}");
        peak = peak.max(outputs(&fmu)[0].abs());
    }
    fmu.get_integer(&[2], &mut status).unwrap();
    assert_eq!(status, [0]);
    assert!(peak > 100.0 && peak < 200.0, "peak |u1| {peak}");
    let mut late = Instance::<D, 4, 1, 2>::new().unwrap();
    late.setup_experiment(0.0).unwrap();
    late.enter_initialization_mode().unwrap();
    let error = late.exit_initialization_mode().unwrap_err();
    assert!(
        error.contains("act from t = -2.33 s") && error.contains("set the start time to -2.33 s"),
        "{error}"
    );
}

/// On an external target the coupled trolley runs the causal eqs. (22):
/// its internal dynamics are unstable from the start, and
/// `fmi2ExitInitializationMode` says so as a warning (`status` 1); where
/// its inputs run away on the default move's path given step by step
/// (beyond 1e6 times their size at the start) `fmi2DoStep` is an error and
/// `status` reads 2, where the FMU used to return the inputs with fmi2OK.
#[test]
fn unstable_internal_dynamics_are_a_warning_and_the_runaway_an_error() {
    type D = crane_models::coupled_trolley::Description;
    let path = Case::<D, 4, 1, 2>::maneuver().unwrap().path().clone();
    let refs: Vec<u32> = (0..2)
        .flat_map(|k| (0..3).map(move |o| (k, o)))
        .map(|(k, o)| vr::<D, 4, 1, 2>(Role::Target(k, o)))
        .collect();
    let target = |t: f64| -> Vec<f64> {
        (0..2)
            .flat_map(|k| (0..3).map(move |o| (k, o)))
            .map(|(k, o)| path.derivative(t, o)[k])
            .collect()
    };
    let mut fmu = Instance::<D, 4, 1, 2>::new().unwrap();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    fmu.set_integer(&[1], &[3]).unwrap();
    fmu.set_real(&refs, &target(0.0)).unwrap();
    fmu.exit_initialization_mode().unwrap();
    let warning = fmu.take_warning().expect("a warning at the start");
    assert!(
        warning.contains("coupled-trolley has unstable internal dynamics along this path (dimension 2"),
        "{warning}"
    );
    assert_eq!(fmu.take_warning(), None, "taken once");
    let mut status = [0];
    fmu.get_integer(&[2], &mut status).unwrap();
    assert_eq!(status, [1]);
    let (k, error) = (0..500)
        .find_map(|k| {
            fmu.set_real(&refs, &target((k + 1) as f64 * 0.01)).unwrap();
            fmu.do_step(k as f64 * 0.01, 0.01).err().map(|e| (k, e))
        })
        .expect("the runaway is an error");
    println!("step {k}: {error}");
    assert!(k < 250, "before t = 2.5 s: {k}");
    assert!(error.contains("exceeds 1e6 times its size at the start"), "{error}");
    fmu.get_integer(&[2], &mut status).unwrap();
    assert_eq!(status, [2]);
    fmu.reset();
    fmu.get_integer(&[2], &mut status).unwrap();
    assert_eq!(status, [0], "reset clears it");
}

/// A flat crane on its default move: nothing to report, `status` 0 at
/// every step.
#[test]
fn a_regular_run_reports_nothing() {
    type D = navy_planar::Description;
    let mut fmu = started::<D, 7, 3, 2>();
    assert_eq!(fmu.take_warning(), None);
    let mut status = [9];
    for k in 0..400 {
        fmu.do_step(k as f64 * 0.01, 0.01).unwrap();
        assert_eq!(fmu.take_warning(), None, "step {k}");
    }
    fmu.get_integer(&[2], &mut status).unwrap();
    assert_eq!(status, [0]);
}

/// A three-phase move whose ramps (tau0 = 0.01 s) are shorter than four
/// steps of dt = 0.01 s: the steps miss the inputs' peaks inside them
/// (`crane run` warns the same): `fmi2ExitInitializationMode` says so as a
/// warning, with the step that resolves them, and `status` reads 1; with
/// tau0 = 0.04 s nothing is said.
#[test]
fn ramps_shorter_than_the_step_resolves_are_a_warning_at_the_start() {
    type D = navy_planar::Description;
    for (tau0, warned) in [(0.01, true), (0.04, false)] {
        let mut fmu = Instance::<D, 7, 3, 2>::new().unwrap();
        fmu.setup_experiment(0.0).unwrap();
        fmu.enter_initialization_mode().unwrap();
        fmu.set_integer(&[1], &[1]).unwrap();
        fmu.set_real(&[vr::<D, 7, 3, 2>(Role::Tau0)], &[tau0]).unwrap();
        fmu.exit_initialization_mode().unwrap();
        let warning = fmu.take_warning();
        let mut status = [9];
        fmu.get_integer(&[2], &mut status).unwrap();
        if warned {
            let warning = warning.expect("a warning at the start");
            assert!(
                warning.contains("the path's ramps last tau0 = 0.01 s, fewer than 4 steps of dt = 0.01 s")
                    && warning.contains("take dt <= 0.0025 s"),
                "{warning}"
            );
            assert_eq!(status, [1]);
        } else {
            assert_eq!(warning, None);
            assert_eq!(status, [0]);
        }
    }
}

/// The load moved to straight below the boom tip (end (0, -5)) leaves rope
/// N1 without tension and Newton's matrix singular at almost every step
/// (`crane run` warns: 378 of 400 steps): once more than 1 % of the steps
/// and more than two are singular, `fmi2DoStep` returns a warning naming
/// them (once) and `status` reads 1; the run goes on.
#[test]
fn a_path_that_does_not_determine_the_inputs_is_a_warning() {
    type D = navy_planar::Description;
    let mut fmu = Instance::<D, 7, 3, 2>::new().unwrap();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    let end: Vec<u32> = (0..2).map(|k| vr::<D, 7, 3, 2>(Role::End(k))).collect();
    fmu.set_real(&end, &[0.0, -5.0]).unwrap();
    fmu.exit_initialization_mode().unwrap();
    assert_eq!(fmu.take_warning(), None);
    let mut warnings = Vec::new();
    for k in 0..400 {
        fmu.do_step(k as f64 * 0.01, 0.01).unwrap();
        warnings.extend(fmu.take_warning().map(|w| (k, w)));
    }
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(
        warnings[0]
            .1
            .contains("steps of navy-planar met an iteration matrix singular"),
        "{warnings:?}"
    );
    let mut status = [0];
    fmu.get_integer(&[2], &mut status).unwrap();
    assert_eq!(status, [1]);
}

/// A long internal step stays on the move's branch: navy-planar's FMU with
/// the parameter dt = 0.5 s and 1 s, stepped to t = 1e5 s, holds the end
/// of the move from t = 4 s on with u1 = -43.345 N m (Appendix A's end; it
/// returned +133.21 N m, the mirror configuration with a pushing rope, and
/// a warning that rope N1 goes slack). The same equations solved at the
/// same point: round-off of the 1e2 N m inputs, 1e-9 relative bounds it.
#[test]
fn a_long_internal_step_stays_on_the_moves_branch() {
    for dt in [0.5, 1.0] {
        let mut fmu = navy_planar_started(1, dt);
        let mut t = 0.0;
        while t < 1e5 {
            let h = if t < 4.0 { dt } else { 1000.0 };
            fmu.do_step(t, h)
                .unwrap_or_else(|e| panic!("dt = {dt} at t = {t}: {e}"));
            t += h;
            if t >= 4.0 {
                let u1 = outputs(&fmu)[0];
                assert!(
                    (u1 + 43.345_043_319_952).abs() < 1e-9 * 43.3,
                    "dt = {dt}, t = {t}: u1 = {u1}"
                );
            }
        }
    }
}

/// The per-step audit of the FMU reports a state the crane cannot take:
/// with the external target (`path = 3`, which runs eqs. (22)) and one
/// internal step of 1e6 s to the move's end at rest, Newton solves the step
/// on the mirror side of the hoist rope (it once stopped at states 1.8 m off
/// constraint `rope0`, its iteration matrix in mixed units taken for
/// singular), and `fmi2DoStep` is an error naming the rope and its
/// length; the default built-in move (the exact reduced system) takes the
/// same step.
#[test]
fn one_step_of_a_million_seconds_on_the_mirror_side_is_an_fmi_error() {
    for path in [1, 3] {
        let mut fmu = navy_planar_started(path, 1e6);
        if path == 3 {
            fmu.set_real(&target_refs(), &[-3.0, 0.0, 0.0, -14.0, 0.0, 0.0])
                .unwrap();
        }
        let step = fmu.do_step(0.0, 1e6);
        if path == 3 {
            let error = step.unwrap_err();
            assert!(
                error.contains("rope N2 of navy-planar (constraint `hoist`) has the length -7.7178 m"),
                "{error}"
            );
        } else {
            assert!(step.is_ok(), "{step:?}");
        }
    }
}
