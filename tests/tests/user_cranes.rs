//! A user's crane gets every formulation its declaration supports, with
//! nothing in its `impl Crane` beyond the model, the name and the
//! manoeuvre: the reduced (dummy-derivative) formulation for a flat crane,
//! as the default where its inputs need more than the path's 4th
//! derivative; the minimal formulation where the model declares a map; a
//! crane with internal dynamics is refused with their dimension, by the
//! study, the case and the runtime alike.

use crane_macros::crane_model;
use crane_models::coupled_trolley;
use crane_models::registry::Entry;
use crane_models::study::{self, Formulation, RunSettings, StudyError};
use crane_models::{Case, Crane, Maneuver, PathSpec, Profile};
use crane_runtime::nalgebra::SVector;
use crane_runtime::{Error, NoDummyDerivatives, Options, Scheme, State, dummy_derivative};

crane_model! {
    /// A planar gantry with a minimal map (trolley, rope length, angle).
    pub struct UserGantry {
        params { m_t: positive = 50.0, m_l: positive = 200.0, J: positive = 0.05, r: positive = 0.1,
                 g: positive = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: -m_l*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
        minimal [y | l, th] {
            s = y;  L = l;  x = y + l*sin(th);  z = -l*cos(th);
        }
    }
}

crane_model! {
    /// A double-pendulum overhead crane: the inputs need the path's 6th derivative.
    pub struct UserHook {
        params { m_t: positive = 120.0, m_h: positive = 15.0, m_l: positive = 400.0, J: positive = 0.2,
                 r: positive = 0.08, l_s: positive = 1.5, g: positive = 9.81 }
        robot  [s, L, xh, zh]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2
                + 0.5*m_h*(dot(xh)^2 + dot(zh)^2) + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, zh: -m_h*g, z: -m_l*g }
        constraints {
            #[rope(N1 = L)]
            hoist: 0.5*((xh - s)^2 + zh^2 - L^2),
            #[rope(N2 = l_s)]
            sling: 0.5*((x - xh)^2 + (z - zh)^2 - l_s^2),
        }
    }
}

/// The gantry: only the model, the name and the manoeuvre (and a guess of
/// its minimal coordinates, which it may leave out where zero is a good
/// guess; here the rope length is not).
struct Gantry;

impl Crane<4, 1, 2> for Gantry {
    type Model = UserGantry;
    const NAME: &'static str = "user-gantry";

    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec {
                profile: Profile::Poly9,
                t0: 0.0,
                t1: 5.0,
                start: SVector::from([0.0, -5.0]),
                end: SVector::from([4.0, -3.0]),
            },
            p0: vec![0.0, 5.0],
        }
    }

    fn minimal_guess(_: &UserGantry, start: &State<4, 1, 2>) -> Vec<f64> {
        vec![start.q[0], start.q[1], 0.0]
    }
}

/// The double pendulum: only the model, the name and the manoeuvre.
struct Hook;

impl Crane<6, 2, 2> for Hook {
    type Model = UserHook;
    const NAME: &'static str = "user-hook";

    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec {
                profile: Profile::SmoothThreePhase { tau0: 2.5 },
                t0: 0.0,
                t1: 8.0,
                start: SVector::from([0.0, -4.5]),
                end: SVector::from([3.0, -3.5]),
            },
            p0: vec![0.0, 3.0, 0.0, -3.0],
        }
    }
}

#[test]
fn a_user_crane_has_the_formulations_its_declaration_supports() {
    // the sizes of the reduced systems come from the declarations (the
    // jets 0..=c of each robot coordinate, multiplier and input, with
    // Pryce's offsets c): the gantry's s, L need their 2nd derivatives
    // (offset 2: 3 jets each), the rope's multiplier 2 (3), the inputs 0
    // (1 each): 11; the hook crane's s, L 2 (3 each), the hook 4 (5 each),
    // the hoist's multiplier 4 (5), the sling's 2 (3), the inputs 0: 26
    assert_eq!(dummy_derivative::system_size::<UserGantry, 4, 1, 2>(), Ok(11));
    assert_eq!(dummy_derivative::system_size::<UserHook, 6, 2, 2>(), Ok(26));
    assert!(Entry::of::<Gantry, 4, 1, 2>().minimal);
    assert!(!Entry::of::<Hook, 6, 2, 2>().minimal);
    // both flat: the exact reduced formulation by default, whatever the
    // path order (4 and 6)
    assert_eq!(
        Formulation::default_for::<Gantry, 4, 1, 2>(),
        Formulation::DummyDerivative
    );
    assert_eq!(
        Formulation::default_for::<Hook, 6, 2, 2>(),
        Formulation::DummyDerivative
    );
}

/// The reduced formulation of the user's gantry agrees with BDF-4 of eqs.
/// (22) at dt = 0.005 after BDF-4's start-up steps (its error there is
/// O(dt^4) ~ 1e-9 of the peak; measured 7e-8 with the start-up's O(dt)
/// steps still echoing), and the minimal formulation with both.
#[test]
fn the_reduced_run_of_a_user_gantry_agrees_with_bdf4() {
    let case = Case::<Gantry, 4, 1, 2>::maneuver().unwrap();
    let start = case.start().unwrap();
    let options = Options::new(0.005, case.tf()).unwrap();
    let reduced = case
        .simulate_dummy_derivative(&start, &options, &mut |_, _| {})
        .unwrap();
    let bdf4 = case.simulate(&start, &options.with_scheme(Scheme::Bdf4)).unwrap();
    let minimal = case
        .simulate_minimal(&start, &options.with_scheme(Scheme::Bdf4))
        .expect("the model declares a minimal map")
        .unwrap();
    let peak = reduced.states.iter().map(|s| s.u.amax()).fold(0.0, f64::max);
    let worst = |other: &crane_runtime::Solution<4, 1, 2>| {
        reduced
            .states
            .iter()
            .zip(&other.states)
            .filter(|(s, _)| s.t >= 0.05)
            .map(|(a, b)| (a.u - b.u).amax())
            .fold(0.0, f64::max)
            / peak
    };
    let (e_bdf4, e_minimal) = (worst(&bdf4), worst(&minimal));
    println!("reduced vs BDF-4: {e_bdf4:.2e}, vs minimal BDF-4: {e_minimal:.2e} of the peak {peak:.1}");
    assert!(e_bdf4 < 1e-6, "{e_bdf4}");
    assert!(e_minimal < 1e-6, "{e_minimal}");
}

/// The user's double pendulum runs its default (reduced) formulation
/// through the study, and its inputs do not depend on the step: each step
/// solves the exact inverse dynamics at its time (measured 7e-16 of the
/// peak between dt = 0.02 and 0.01; Newton's relative tolerance is 1e-10).
#[test]
fn a_user_double_pendulum_gets_exact_inputs_at_any_step() {
    let case = Case::<Hook, 6, 2, 2>::maneuver().unwrap();
    let run = |dt: f64| {
        let settings = RunSettings {
            dt,
            formulation: Formulation::default_for::<Hook, 6, 2, 2>(),
            ..RunSettings::default()
        };
        study::run(&case, &settings, &mut |_, _| {}).unwrap().solution
    };
    let (coarse, fine) = (run(0.02), run(0.01));
    let peak = coarse.states.iter().map(|s| s.u.amax()).fold(0.0, f64::max);
    let worst = coarse
        .states
        .iter()
        .zip(fine.states.iter().step_by(2))
        .map(|(a, b)| {
            assert!((a.t - b.t).abs() < 1e-9);
            (a.u - b.u).amax()
        })
        .fold(0.0, f64::max);
    println!("max |u(0.02) - u(0.01)| = {worst:.2e} of the peak {peak:.1}");
    assert!(worst <= 1e-10 * peak, "{worst}");
}

/// A crane with internal dynamics (the coupled trolley: 2 states the path
/// leaves free) has no reduced formulation, and every way in says so.
#[test]
fn a_crane_with_internal_dynamics_is_refused_with_their_dimension() {
    type Model = coupled_trolley::CoupledTrolley;
    let expected = NoDummyDerivatives::InternalDynamics { dimension: 2 };
    assert_eq!(dummy_derivative::system_size::<Model, 4, 1, 2>(), Err(expected));
    let case = coupled_trolley::DefaultCase::maneuver().unwrap();
    let start = case.start().unwrap();
    let options = Options::new(0.01, case.tf()).unwrap();
    match case.simulate_dummy_derivative(&start, &options, &mut |_, _| {}) {
        Err(Error::NoDummyDerivatives { reason, .. }) => assert_eq!(reason, expected),
        other => panic!("{:?}", other.map(|s| s.states.len())),
    }
    let settings = RunSettings {
        formulation: Formulation::DummyDerivative,
        ..RunSettings::default()
    };
    match study::run(&case, &settings, &mut |_, _| {}) {
        Err(error @ StudyError::NoDummyDerivatives { .. }) => {
            let message = error.to_string();
            assert!(message.contains("internal dynamics of dimension 2"), "{message}");
        }
        other => panic!("{:?}", other.map(|o| o.summary.steps)),
    }
    let boxed = dummy_derivative::boxed_stepper(Box::new(*case.model()), case.path().clone(), &start, &options);
    assert!(matches!(boxed, Err(Error::NoDummyDerivatives { reason, .. }) if reason == expected));
}

/// The guide's recipe (docs/minimal-coordinates.md) for a minimal run on a user's gantry: a start from
/// `init::static_equilibrium` and the exact guess of `mu`. The start's
/// constraint residual must not be larger than the minimal start's own
/// tolerance (`phi(mu0) = q0` to 1e-12 of |q0|): it once was 1.5e-10 and the
/// run was refused ("no minimal coordinates mu0 ... residual 1.3e-11").
#[test]
fn a_static_equilibrium_start_runs_in_minimal_coordinates() {
    use crane_runtime::trajectory::Poly9;
    use crane_runtime::{CraneModel, init, simulate_minimal};
    let crane = UserGantry::default();
    for (start, end, guess) in [
        ([0.0, -5.0], [4.0, -3.0], [0.3, 4.5]),
        ([1.0, -7.3], [-2.0, -2.1], [0.0, 1.0]),
        ([-3.3, -2.2], [5.1, -9.7], [-3.0, 9.0]),
        ([0.0, -5.0], [4.0, -3.0], [2.0, 1.0]),
        ([0.0, -5.0], [4.0, -3.0], [-7.0, 20.0]),
        ([0.001, -0.3], [4.0, -3.0], [0.0, 1.0]),
    ] {
        let path = Poly9::new(0.0, 5.0, SVector::from(start), SVector::from(end)).unwrap();
        let q0 = init::static_equilibrium(&crane, &path, 0.0, &guess).unwrap();
        let residual = crane.constraints(&q0.q).amax();
        let scale = q0.q.amax();
        let mu = SVector::from([q0.q[0], q0.q[1], 0.0]);
        let run = simulate_minimal(&crane, &path, &q0, &mu, &Options::new(0.01, 5.0).unwrap());
        println!("start {start:?}: g(q0) = {residual:.1e}, {:?}", run.as_ref().err());
        // g = (|d|^2 - L^2)/2 is off by about |q| times a length error:
        // a start at round-off has |g| ~ 1e-15 |q|^2
        assert!(residual <= 1e-13 * scale * scale, "g(q0) = {residual:e}");
        assert!(run.is_ok(), "{:?}", run.err());
        // a start typed to 10 digits (the rope 2e-10 m long; the
        // consistency checks allow 1e-9 of |q|) has no mu with phi(mu) = q0
        // to round-off: the closest one starts the run
        let mut typed = q0;
        typed.q[1] += 2e-10;
        let run = simulate_minimal(&crane, &path, &typed, &mu, &Options::new(0.01, 5.0).unwrap());
        assert!(run.is_ok(), "{:?}", run.err());
    }
}

crane_model! {
    #[crane(no_dummy_derivatives)]
    /// The gantry without its dummy-derivative system.
    pub struct WithoutReduction {
        params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: -m_l*g }
        constraints { #[rope(N = L)] rope: 0.5*((x - s)^2 + z^2 - L^2) }
    }
}

/// A declaration may turn the reduced system off; the runtime then says so.
#[test]
fn a_declaration_can_leave_out_the_reduced_system() {
    assert_eq!(
        dummy_derivative::system_size::<WithoutReduction, 4, 1, 2>(),
        Err(NoDummyDerivatives::OptedOut)
    );
}

/// A user's crane without an analytical reference gets the convergence
/// study all the same, against the exact inputs of its reduced
/// formulation: eqs. (22) with backward Euler converge with order 1 on the
/// gantry (path order 4). (The built-in tower crane, which has no
/// analytical reference either, shows orders 0.97 to 0.999 the same way:
/// `crane convergence tower-crane`.)
#[test]
fn a_user_crane_converges_against_its_reduced_inputs() {
    use crane_models::study::convergence::{self, Reference};
    let case = Case::<Gantry, 4, 1, 2>::maneuver().unwrap();
    assert_eq!(convergence::reference_inputs(&case).unwrap().1, Reference::Reduced);
    let rows = convergence::study(
        &case,
        Formulation::Redundant,
        Scheme::BackwardEuler,
        &[0.02, 0.01, 0.005],
        |row| println!("dt = {}: e_u = {:.3e}, order {:?}", row.dt, row.e_u, row.order),
    )
    .unwrap();
    // the observed order tends to 1 as the O(dt^2) term fades (measured
    // 1.12, then 1.06): every order within 0.2 of 1, the last within 0.1
    let orders: Vec<f64> = rows[1..].iter().map(|row| row.order.unwrap()).collect();
    assert!(orders.iter().all(|p| (p - 1.0).abs() < 0.2), "{orders:?}");
    assert!((orders[orders.len() - 1] - 1.0).abs() < 0.1, "{orders:?}");
}

crane_model! {
    /// The user's gantry with gravity declared upward (`z: +m_l*g`, z up).
    pub struct UpsideDown {
        params { m_t: positive = 50.0, m_l: positive = 200.0, J: positive = 0.05, r: positive = 0.1,
                 g: positive = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: m_l*g }
        constraints {
            #[rope(N = L)]
            rope: 0.5*((x - s)^2 + z^2 - L^2),
        }
    }
}

struct UpsideDownGantry;

impl Crane<4, 1, 2> for UpsideDownGantry {
    type Model = UpsideDown;
    const NAME: &'static str = "upside-down";

    fn maneuver() -> Maneuver<2> {
        Gantry::maneuver()
    }
}

/// Gravity declared upward: the load below the trolley pushes on its rope
/// (-1962 N = m_l g at rest). The run is refused before it starts, saying
/// so and what to check, where it once said only that the rope goes slack
/// at t = 0; the audit of a run says the same. The correct gantry's rope
/// stays taut.
#[test]
fn a_rope_that_pushes_all_along_points_at_gravity() {
    let settings = RunSettings::default();
    let case = Case::<UpsideDownGantry, 4, 1, 2>::maneuver().unwrap();
    let refused = study::run(&case, &settings, &mut |_, _| {}).unwrap_err().to_string();
    assert!(
        refused.starts_with(
            "upside-down cannot hold the load at the path's start: with the load held at rest at the path's point \
             of t = 0 s, every rope would have to push (N = -1.9620e3 N)"
        ) && refused.ends_with("check the sign of gravity in the crane's forces (with z up, `z: -m_l*g`)"),
        "{refused}"
    );
    let start = case.run_start().unwrap();
    let options = crane_runtime::Options::new(settings.dt, case.tf()).unwrap();
    let run = settings
        .formulation
        .simulate(&case, &start, &options, &mut |_, _| {})
        .unwrap();
    let summary = study::summarize_run(&case, &settings, &run, 0.0, study::DIAGNOSIS_SAMPLES);
    let rope = &summary.ropes[0];
    // the load's weight pushes: -1962 N at rest, between -2133 and -1837 N
    // along the move (measured)
    assert!(rope.max_tension < 0.0, "{}", rope.max_tension);
    let findings: Vec<String> = study::audit(&summary).iter().map(|f| f.to_string()).collect();
    assert!(
        findings.iter().any(|f| f.starts_with("rope N pushes for the whole run")
            && f.contains("check the sign of gravity in the crane's forces (with z up, `z: -m_l*g`)")),
        "{findings:?}"
    );
    let case = Case::<Gantry, 4, 1, 2>::maneuver().unwrap();
    let summary = study::run(&case, &settings, &mut |_, _| {}).unwrap().summary;
    assert!(summary.ropes[0].min_tension > 0.0);
    assert!(study::audit(&summary).is_empty());
}

/// The hook crane's reduced system (path order 6) solved stage by stage as
/// whole, as the built-ins' are (`tests/tests/stages.rs`).
#[test]
fn a_user_s_crane_of_path_order_6_is_solved_stage_by_stage_as_whole() {
    use crane_models::registry::Visit;
    let c = crane_tests::stages::OnCrane.visit::<Hook, 6, 2, 2>().unwrap();
    crane_tests::stages::check(&c);
    assert_eq!(c.steps, 800);
    // 22 jets of 8 unknowns in five stages: an LU of at most 8 x 8 each
    assert_eq!(c.blocks, [3, 3, 6, 6, 8]);
}
