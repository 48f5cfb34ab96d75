//! The forward problem (`crane_runtime::forward`) on the scheme seam: the
//! crane driven by given inputs. Replaying the analytical inputs of
//! Appendix B on the planar crane with pulley mass keeps its flat outputs on
//! the prescribed path, with a deviation that shrinks at the scheme's order
//! (backward Euler 1.00, BDF-2 2.00; measured below).

use crane_models::navy_planar_pulley::PaperCase;
use crane_models::navy_planar_pulley::reference::reference_at;
use crane_runtime::forward::simulate_forward;
use crane_runtime::{Options, Scheme, Solution, Trajectory};

/// The largest deviation of the flat outputs `[x, z, z0]` from the path over
/// the run.
fn largest_deviation(case: &PaperCase, run: &Solution<8, 4, 3>) -> f64 {
    run.states
        .iter()
        .map(|s| (s.q.fixed_rows::<3>(5) - case.path().derivative(s.t, 0)).amax())
        .fold(0.0, f64::max)
}

/// Appendix B's torques, evaluated at each forward step, drive the crane
/// from the paper's start (a regular equilibrium, eq. 66 as corrected):
/// the outputs follow gamma to O(dt^k). Measured for dt = 0.01, 0.005:
/// the orders must lie in [k - 0.3, k + 0.7].
#[test]
fn replaying_the_analytical_inputs_keeps_the_load_on_the_path() {
    let case = PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let model = *case.model();
    let path = case.path().clone();
    // BDF-3..5 show order 2 here: see the next test for why
    for scheme in [Scheme::BackwardEuler, Scheme::Bdf2] {
        let deviations: Vec<f64> = [0.01, 0.005]
            .iter()
            .map(|&dt| {
                let inputs = |t: f64| reference_at(&model, &path, t).u;
                let run = simulate_forward(
                    case.model(),
                    inputs,
                    &start,
                    &Options::new(dt, 4.0).unwrap().with_scheme(scheme),
                )
                .unwrap_or_else(|e| panic!("{scheme} dt = {dt}: {e}"));
                largest_deviation(&case, &run)
            })
            .collect();
        let order = (deviations[0] / deviations[1]).log2();
        let k = scheme.order() as f64;
        println!(
            "forward {scheme}: largest |x - gamma| = {:.3e} / {:.3e} m, order {order:.2}",
            deviations[0], deviations[1]
        );
        assert!((k - 0.3..=k + 0.7).contains(&order), "{scheme}: {deviations:?}");
    }
}

/// Why BDF-3..5 replay the paper's Poly9 move with order 2 only: unlike the
/// load (C4 at t0, x ~ t^5), the trolley of a gantry follows X = x - z x''/
/// (z'' + g) with x'' ~ t^3, so its third derivative jumps at t0 and the
/// crane's rest before t0 is only a C2 history for it. In the servo problem
/// the trolley is fixed algebraically and the kink is harmless; in the
/// forward problem it is integrated, and a constant-step multistep method
/// across the kink keeps order 2 (measured on the gantry: 1.96e-4 / 4.9e-5
/// / 1.2e-5 m for dt = 0.02 / 0.01 / 0.005, the same for k = 3, 4, 5). On
/// the C6 profile the trolley is C4 at the phase switches and BDF-k replays
/// the gantry's move with order k up to k = 4: measured 0.96, 1.99, 2.93,
/// 4.02 (and 4.08 for BDF-5, limited by that C4) between dt = 0.02 and 0.01.
#[test]
fn on_a_smooth_path_the_replay_has_order_k() {
    use crane_models::gantry_3d::{DefaultCase, reference::reference_at as gantry_reference};
    use crane_models::{Path, PathSpec, Profile};
    let mut case = DefaultCase::maneuver().unwrap();
    case.path = Path::new(PathSpec {
        profile: Profile::SmoothThreePhase { tau0: 3.0 },
        ..*case.path.spec()
    })
    .unwrap();
    let start = case.start().unwrap();
    let (model, path) = (*case.model(), case.path().clone());
    for scheme in [Scheme::BackwardEuler, Scheme::Bdf2, Scheme::Bdf3, Scheme::Bdf4] {
        let d: Vec<f64> = [0.02, 0.01]
            .iter()
            .map(|&dt| {
                let inputs = |t: f64| gantry_reference(&model, &path, t).u;
                let run = simulate_forward(
                    case.model(),
                    inputs,
                    &start,
                    &Options::new(dt, 8.0).unwrap().with_scheme(scheme),
                )
                .unwrap();
                run.states
                    .iter()
                    .map(|s| (s.q.fixed_rows::<3>(3) - path.derivative(s.t, 0)).amax())
                    .fold(0.0, f64::max)
            })
            .collect();
        let (order, k) = ((d[0] / d[1]).log2(), scheme.order() as f64);
        println!(
            "gantry, C6 path, forward {scheme}: largest |x - gamma| = {:.3e} / {:.3e} m, order {order:.2}",
            d[0], d[1]
        );
        assert!((k - 0.3..=k + 0.7).contains(&order), "{scheme}: {d:?}");
    }
}

/// Replay (`crane_runtime::replay`) of the inverse runs' own torques on the
/// pulley crane (the paper's 4 s move, then 9 s at rest: about twice the
/// load pendulum's period, 2 pi sqrt(5 m / g) = 4.5 s): on the exact plant
/// the load follows the path to the inverse scheme's accuracy, BDF-4's
/// torques at dt = 0.01 at least 100 times closer than backward Euler's;
/// on a plant with a 10 % heavier load the deviation and the residual sway
/// are orders of magnitude larger (the winches hold the planned load only:
/// without feedback the heavier one sinks). The forward scheme is BDF-2 on
/// dt/4 with quadratic interpolation of the torques: with BDF-4 and quartic
/// interpolation the replay of BDF-4's torques is 20 times worse (6.0e-4 m,
/// whatever the refinement), the quartic through the inverse run's start-up
/// transient overshooting.
#[test]
fn replaying_the_inverse_runs_torques() {
    use crane_runtime::CraneModel;
    use crane_runtime::replay::{ReplayOptions, replay};
    let case = PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let inverse = |scheme: Scheme| {
        case.simulate(&start, &Options::new(0.01, 4.0).unwrap().with_scheme(scheme))
            .unwrap()
    };
    let options = ReplayOptions::new(9.0, Scheme::Bdf2);
    let be = replay(case.model(), case.path(), &inverse(Scheme::BackwardEuler), &options).unwrap();
    let bdf4 = replay(case.model(), case.path(), &inverse(Scheme::Bdf4), &options).unwrap();
    let mut heavy = *case.model();
    heavy.set_parameter("m_l", 110.0).unwrap();
    let mismatched = replay(&heavy, case.path(), &inverse(Scheme::Bdf4), &options).unwrap();
    for (name, r) in [
        ("backward Euler", &be),
        ("BDF-4", &bdf4),
        ("BDF-4, m_l + 10 %", &mismatched),
    ] {
        println!(
            "replay of {name}: max |x - gamma| = {:.3e} m, at tf {:.3e} m, residual sway {:.3e} m ({} forward steps)",
            r.max_load_deviation,
            r.deviation_at_tf,
            r.residual_sway,
            r.solution.steps()
        );
    }
    assert_eq!(bdf4.solution.steps(), 4 * 400 + 4 * 900, "dt/4 over 4 + 9 s");
    assert!(
        bdf4.max_load_deviation * 100.0 <= be.max_load_deviation,
        "{} vs {}",
        bdf4.max_load_deviation,
        be.max_load_deviation
    );
    assert!(mismatched.max_load_deviation > 100.0 * bdf4.max_load_deviation);
    assert!(mismatched.residual_sway > 100.0 * bdf4.residual_sway);
}

/// The default feedback (a critically damped PD on the robot coordinates
/// about the inverse run's p(t), sampled at the forward rate; gains from the
/// model, `crane_runtime::replay::Feedback::from_model`) takes away most of
/// what a 10 % heavier or lighter load does to the open-loop replay: at
/// least half of the largest deviation, and of the residual sway; on the
/// exact plant it changes little.
#[test]
fn feedback_takes_away_the_mismatch() {
    use crane_runtime::CraneModel;
    use crane_runtime::replay::{Feedback, ReplayOptions, replay, replay_with_feedback};
    let case = PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let inverse = case
        .simulate(&start, &Options::new(0.01, 4.0).unwrap().with_scheme(Scheme::Bdf4))
        .unwrap();
    let options = ReplayOptions::new(9.0, Scheme::Bdf2);
    let gains = Feedback::from_model(case.model(), &start);
    for m_l in [110.0, 90.0, 100.0] {
        let mut plant = *case.model();
        plant.set_parameter("m_l", m_l).unwrap();
        let open = replay(&plant, case.path(), &inverse, &options).unwrap();
        let closed = replay_with_feedback(&plant, case.path(), &inverse, &options, Some(&gains)).unwrap();
        println!(
            "m_l = {m_l}: open loop max |x - gamma| = {:.3e} m, sway {:.3e} m; with feedback {:.3e} m, sway {:.3e} m",
            open.max_load_deviation, open.residual_sway, closed.max_load_deviation, closed.residual_sway
        );
        if m_l != 100.0 {
            assert!(
                closed.max_load_deviation <= 0.5 * open.max_load_deviation,
                "m_l = {m_l}"
            );
            assert!(closed.residual_sway <= 0.5 * open.residual_sway, "m_l = {m_l}");
        } else {
            assert!(closed.max_load_deviation < 1e-3, "{}", closed.max_load_deviation);
        }
    }
}

/// With the inputs off the free crane keeps its energy `T + V`, `T = 1/2
/// q'^T M q'`, `V = m_l g z` (the gantry: the load falls, unwinding the
/// rope, from rest below the trolley) to the scheme's order: the largest
/// drift over 2 s falls with order 1 for backward Euler, which dissipates,
/// and 2 for BDF-2 (relative to the energy the load gains falling,
/// m_l g |z(2 s) - z(0)|).
#[test]
fn the_free_crane_keeps_its_energy_to_the_scheme_s_order() {
    use crane_models::gantry_3d::DefaultCase;
    use crane_runtime::CraneModel;
    let case = DefaultCase::maneuver().unwrap();
    let mut start = case.start().unwrap();
    start.u = nalgebra::SVector::zeros();
    let model = case.model();
    let mass = model.mass_matrix::<f64>();
    let energy = |s: &crane_runtime::State<6, 1, 3>| 0.5 * s.v.dot(&(mass * s.v)) + model.m_l * model.g * s.q[5];
    for scheme in [Scheme::BackwardEuler, Scheme::Bdf2] {
        let drifts: Vec<f64> = [0.01, 0.005]
            .iter()
            .map(|&dt| {
                let run = simulate_forward(
                    model,
                    |_t: f64| nalgebra::SVector::zeros(),
                    &start,
                    &Options::new(dt, 2.0).unwrap().with_scheme(scheme),
                )
                .unwrap();
                let e0 = energy(&run.states[0]);
                let fall = model.m_l * model.g * (run.states.last().unwrap().q[5] - start.q[5]).abs();
                run.states.iter().map(|s| (energy(s) - e0).abs()).fold(0.0, f64::max) / fall
            })
            .collect();
        let order = (drifts[0] / drifts[1]).log2();
        println!(
            "free gantry, {scheme}: relative energy drift over 2 s = {:.3e} / {:.3e} (dt = 0.01 / 0.005), order {order:.2}",
            drifts[0], drifts[1]
        );
        let k = scheme.order() as f64;
        assert!((k - 0.3..=k + 0.7).contains(&order), "{scheme}: {drifts:?}");
    }
}

/// Replaying an inverse run's torques: the deviation falls with the inverse
/// scheme's order as its step halves, as long as the inverse error dominates
/// the forward one (BDF-2 on dt/4): backward Euler and BDF-2, on the pulley
/// crane, navy-planar (its degenerate start: rope N1 exactly slack) and
/// navy-3d, between dt = 0.02 and 0.01.
#[test]
fn replay_deviation_falls_with_the_inverse_scheme_s_order() {
    use crane_models::{Case, Crane};
    use crane_runtime::replay::{ReplayOptions, replay};
    fn orders<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(case: &Case<C, N, M, A>) {
        let start = case.start().unwrap();
        for scheme in [Scheme::BackwardEuler, Scheme::Bdf2] {
            let d: Vec<f64> = [0.02, 0.01]
                .iter()
                .map(|&dt| {
                    let inverse = case
                        .simulate(&start, &Options::new(dt, case.tf()).unwrap().with_scheme(scheme))
                        .unwrap();
                    replay(
                        case.model(),
                        case.path(),
                        &inverse,
                        &ReplayOptions::new(0.0, Scheme::Bdf2),
                    )
                    .unwrap()
                    .max_load_deviation
                })
                .collect();
            let (order, k) = ((d[0] / d[1]).log2(), scheme.order() as f64);
            println!(
                "{} replay of {scheme} torques: max |x - gamma| = {:.3e} / {:.3e} m, order {order:.2}",
                C::NAME,
                d[0],
                d[1]
            );
            assert!((k - 0.3..=k + 0.7).contains(&order), "{} {scheme}: {d:?}", C::NAME);
        }
    }
    orders(&PaperCase::new(4.0).unwrap());
    orders(&crane_models::navy_planar::PaperCase::new(4.0).unwrap());
    orders(&crane_models::navy_3d::PaperCase::new(crane_models::navy_3d::TF).unwrap());
}
