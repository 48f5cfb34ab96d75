//! Internal dynamics: which cranes are flat, and the coupled trolley crane
//! (a trolley-load coupling the path does not fix) whose causal inverse explodes (`crane_runtime::internal`).

use crane_models::coupled_trolley::CoupledTrolley as Coupled;
use crane_runtime::internal::internal_dynamics;
use crane_runtime::nalgebra::vector;
use crane_runtime::trajectory::Poly9;
use crane_runtime::{Trajectory, init};
use crane_tests::damped::DampedDrive;

/// The coupled crane at rest, load straight below the trolley at depth |z|:
/// the load's row reads c s'' - lambda s = -lambda x - m x'' with
/// lambda = -m (g + z'')/z (the load's vertical balance), so the trolley follows
/// s'' = (lambda/c) s: eigenvalues +-sqrt(lambda/c), real for a hanging load
/// (unstable), imaginary for a load held above the trolley (z > 0, lambda < 0:
/// a strut instead of a rope; stable, oscillating). Both to 1 %, dimension 2.
#[test]
fn the_coupled_crane_has_the_internal_dynamics_of_its_derivation() {
    let crane = Coupled::default();
    for (z0, unstable) in [(-5.0, true), (5.0, false)] {
        let path = Poly9::new(0.0, 5.0, vector![0.0, z0], vector![4.0, z0 + 2.0]).unwrap();
        let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, z0.abs()]).unwrap();
        let diagnosis = internal_dynamics(&crane, &start).unwrap();
        let z_dd = path.derivative(0.0, 2)[1];
        let lambda = -crane.m * (crane.g + z_dd) / z0;
        let rate = (lambda.abs() / crane.c).sqrt();
        println!(
            "z0 = {z0}: {diagnosis:?}, expected rate {rate:.4} 1/s ({})",
            if unstable { "real" } else { "imaginary" }
        );
        assert_eq!(diagnosis.dimension, 2);
        for &(re, im) in &diagnosis.eigenvalues {
            let (along, across) = if unstable {
                (re.abs(), im.abs())
            } else {
                (im.abs(), re.abs())
            };
            assert!(
                (along - rate).abs() <= 0.01 * rate,
                "z0 = {z0}: eigenvalue ({re}, {im}) against {rate}"
            );
            assert!(across <= 1e-6 * rate, "z0 = {z0}: eigenvalue ({re}, {im})");
        }
        assert_eq!(diagnosis.is_stable(), !unstable, "{diagnosis:?}");
    }
}

/// Without the coupling (c = 0) the same crane is flat: no inertia left in
/// the directions the load path leaves free.
#[test]
fn without_the_coupling_the_crane_is_flat() {
    let crane = Coupled {
        c: 0.0,
        ..Coupled::default()
    };
    let path = Poly9::new(0.0, 5.0, vector![0.0, -5.0], vector![4.0, -3.0]).unwrap();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0]).unwrap();
    let diagnosis = internal_dynamics(&crane, &start).unwrap();
    assert_eq!(diagnosis.dimension, 0, "{diagnosis:?}");
    assert!(diagnosis.is_stable());
}

/// The built-in cranes are flat (dimension 0) along their manoeuvres,
/// checked at the start and at every 0.5 s of a backward-Euler run at
/// dt = 0.01. Five of them because in the directions the load path leaves
/// free their only inertia is the load's (winch and trolley inertias sit on
/// actuated coordinates, the pulley of `navy-planar-pulley` moves with the
/// actuated rope L1), so `Q^T M Z = 0`. `navy-3d-pulley` has its pulley mass
/// m0 = 20 kg in a free direction (`Q^T M Z` of rank 1), yet it is flat too:
/// the constraints fix that direction at higher derivatives, which the
/// structural count (0) and the regular Pryce Jacobian along the move
/// (reciprocal condition 1.0e-2 to 2.0e-2) establish; the frozen-time
/// reduction alone gave spurious pairs such as +-64.6 1/s there.
#[test]
fn the_built_in_cranes_are_flat_along_their_manoeuvres() {
    fn check<C: crane_models::Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
        case: &crane_models::Case<C, N, M, A>,
    ) {
        let start = case.start().unwrap();
        let run = case
            .simulate(&start, &crane_runtime::Options::new(0.01, case.tf()).unwrap())
            .unwrap();
        let mut checked = 0;
        for state in run.states.iter().step_by(50) {
            match internal_dynamics(case.model(), state) {
                Ok(d) => assert_eq!(d.dimension, 0, "{} at t = {}: {d:?}", C::NAME, state.t),
                Err(e) => panic!("{} at t = {}: {e}", C::NAME, state.t),
            }
            checked += 1;
        }
        println!("{}: dimension 0 at {checked} states", C::NAME);
    }
    check(&crane_models::navy_planar::PaperCase::new(4.0).unwrap());
    check(&crane_models::navy_planar_pulley::PaperCase::new(4.0).unwrap());
    check(&crane_models::navy_3d::PaperCase::maneuver().unwrap());
    check(&crane_models::navy_3d_pulley::PaperCase::maneuver().unwrap());
    check(&crane_models::gantry_3d::DefaultCase::maneuver().unwrap());
    check(&crane_models::tower_crane::DefaultCase::maneuver().unwrap());
    check(&crane_models::double_pendulum::DefaultCase::maneuver().unwrap());
    check(&crane_models::elastic_drive::DefaultCase::maneuver().unwrap());
}

/// What the causal inverse does with the unstable coupled crane: the run
/// "succeeds" with torques that grow like exp(9.9 t) (printed for docs/internal-dynamics.md;
/// asserted only to be beyond any physical scale, 1e6 x the static torque).
#[test]
fn the_unstable_inverse_explodes() {
    let crane = Coupled::default();
    let path = Poly9::new(0.0, 5.0, vector![0.0, -5.0], vector![4.0, -3.0]).unwrap();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0]).unwrap();
    let run = crane_runtime::simulate(&crane, &path, &start, &crane_runtime::Options::new(0.01, 5.0).unwrap()).unwrap();
    let mid = run.state_near(2.5).unwrap();
    let scale = start.u.amax();
    println!(
        "coupled crane, dt = 0.01: u(2.5 s) = {:?} (static |u| = {scale:.1})",
        mid.u.as_slice()
    );
    assert!(mid.u.amax() > 1e6 * scale);
}

/// The structural count the macro writes into every model
/// (`CraneModel::INTERNAL_DIMENSION`, Pryce's signature method on eqs.
/// 22a-d): the coupled crane leaves 2 states free (s and s', the ODE of its
/// derivation), the paper's cranes and the other built-ins none.
#[test]
fn the_declarations_state_their_structure() {
    use crane_runtime::CraneModel;
    fn dimension<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(_: &Mdl) -> Option<usize> {
        Mdl::STRUCTURE.map(|s| s.dimension)
    }
    assert_eq!(dimension(&Coupled::default()), Some(2));
    let built_in = [
        (
            "navy-planar",
            dimension(&crane_models::navy_planar::NavyPlanar::default()),
        ),
        (
            "navy-planar-pulley",
            dimension(&crane_models::navy_planar_pulley::NavyPlanarPulley::default()),
        ),
        ("navy-3d", dimension(&crane_models::navy_3d::Navy3d::default())),
        (
            "navy-3d-pulley",
            dimension(&crane_models::navy_3d_pulley::Navy3dPulley::default()),
        ),
        ("gantry-3d", dimension(&crane_models::gantry_3d::Gantry3d::default())),
        (
            "tower-crane",
            dimension(&crane_models::tower_crane::TowerCrane::default()),
        ),
        (
            "double-pendulum",
            dimension(&crane_models::double_pendulum::DoublePendulum::default()),
        ),
        (
            "elastic-drive",
            dimension(&crane_models::elastic_drive::ElasticDrive::default()),
        ),
    ];
    println!("{built_in:?}");
    for (name, d) in built_in {
        assert_eq!(d, Some(0), "{name}");
    }
}

/// How smooth a path the inputs need: the servo constraints are
/// differentiated 4 times for the paper's cranes with a massless pulley
/// (u needs the 4th derivative of the load path, the flatness result for a
/// load on a rope), 6 times for navy-3d-pulley (the pulley's mass adds
/// two), 6 for the double pendulum (the hook adds two) and the elastic
/// drive (the belt adds two), 2 for the coupled crane. The profiles: poly9 and three-phase are
/// continuous up to the 4th derivative, the smooth three-phase up to the 6th.
#[test]
fn the_structure_says_how_smooth_the_path_must_be() {
    use crane_runtime::CraneModel;
    fn order<Mdl: CraneModel<N, M, A>, const N: usize, const M: usize, const A: usize>(_: &Mdl) -> usize {
        Mdl::STRUCTURE.unwrap().path_order(A)
    }
    assert_eq!(order(&crane_models::navy_planar::NavyPlanar::default()), 4);
    assert_eq!(order(&crane_models::navy_planar_pulley::NavyPlanarPulley::default()), 4);
    assert_eq!(order(&crane_models::navy_3d::Navy3d::default()), 4);
    assert_eq!(order(&crane_models::navy_3d_pulley::Navy3dPulley::default()), 6);
    assert_eq!(order(&crane_models::gantry_3d::Gantry3d::default()), 4);
    assert_eq!(order(&crane_models::tower_crane::TowerCrane::default()), 4);
    assert_eq!(order(&crane_models::double_pendulum::DoublePendulum::default()), 6);
    assert_eq!(order(&crane_models::elastic_drive::ElasticDrive::default()), 6);
    assert_eq!(order(&Coupled::default()), 2);
    use crane_models::{Path, PathSpec, Profile};
    let path = |profile| {
        Path::new(PathSpec {
            profile,
            t0: 0.0,
            t1: 20.0,
            start: vector![0.0],
            end: vector![1.0],
        })
        .unwrap()
    };
    assert_eq!(path(Profile::Poly9).continuity(), Some(4));
    assert_eq!(path(Profile::ThreePhase { tau0: 5.0 }).continuity(), Some(4));
    assert_eq!(path(Profile::SmoothThreePhase { tau0: 5.0 }).continuity(), Some(6));
    // the claim checked on the profiles themselves: the derivative past the
    // continuity jumps at the start of the motion, the one at it does not
    for (profile, k) in [
        (Profile::Poly9, 4),
        (Profile::ThreePhase { tau0: 5.0 }, 4),
        (Profile::SmoothThreePhase { tau0: 5.0 }, 6),
    ] {
        let p = path(profile.clone());
        let jump = |order: usize| (p.derivative(1e-7, order)[0] - p.derivative(-1e-7, order)[0]).abs();
        assert!(
            jump(k) < 1e-6 && jump(k + 1) > 1e-6,
            "{profile:?}: {} {}",
            jump(k),
            jump(k + 1)
        );
    }
}

/// What too rough a path does: navy-3d-pulley on the paper's three-phase
/// profile (continuous to order 4, the inputs need 6) has an impulse in its
/// slewing torque u4 right after the start whose computed height grows like
/// 1/dt (halving dt doubles it, to 10 %; measured 894 and 1790 N m); on the
/// smooth profile it stays bounded: 0.17 and 0.19 N m, the change being
/// backward Euler's O(dt) error in a torque that is still building up
/// (asserted: a ratio below 1.5, far from the impulse's 2). Backward Euler
/// over the first 0.01 s.
#[test]
fn a_path_too_rough_for_the_crane_gives_impulses() {
    use crane_models::navy_3d_pulley::PaperCase;
    let peak = |case: &PaperCase, dt: f64| {
        let run = case
            .simulate(&case.start().unwrap(), &crane_runtime::Options::new(dt, 0.01).unwrap())
            .unwrap();
        run.states.iter().map(|s| s.u[3].abs()).fold(0.0, f64::max)
    };
    let rough = PaperCase::maneuver().unwrap();
    let smooth = PaperCase::smooth(crane_models::navy_3d_pulley::TF).unwrap();
    let (r1, r2) = (peak(&rough, 0.001), peak(&rough, 0.0005));
    let (s1, s2) = (peak(&smooth, 0.001), peak(&smooth, 0.0005));
    println!(
        "peak |u4| in the first 0.01 s: three-phase {r1:.1} / {r2:.1} N m, smooth {s1:.3e} / {s2:.3e} N m (dt = 0.001 / 0.0005 s)"
    );
    assert!((r2 / r1 - 2.0).abs() < 0.2, "{r1} {r2}");
    assert!(s2 / s1 < 1.5 && s2 < 1e-3 * r2, "{s1} {s2}");
    let rough_path =
        crane_runtime::internal::path_smoothness::<crane_models::navy_3d_pulley::Navy3dPulley, _, 12, 5, 4>(
            rough.path(),
        )
        .unwrap();
    assert!(!rough_path.is_sufficient());
    assert!(
        crane_runtime::internal::path_smoothness::<crane_models::navy_3d_pulley::Navy3dPulley, _, 12, 5, 4>(
            smooth.path()
        )
        .unwrap()
        .is_sufficient()
    );
}

/// A belt with a damper beside its spring leaves the motor angle a
/// first-order free state (eigenvalue -k/d = -0.5 1/s): one the frozen-time
/// reduction does not split (first derivatives in the rows without second
/// ones), so no sampled state is resolved. The diagnosis reads the
/// structural dimension, 1, and stability unknown, not "flat and stable"
/// as it did ("dimension": 0, "stable": true).
#[test]
fn an_unresolved_diagnosis_does_not_read_as_flat_and_stable() {
    use crane_runtime::CraneModel;
    use crane_runtime::internal::diagnose;
    let crane = DampedDrive::default();
    assert_eq!(
        <DampedDrive as CraneModel<5, 1, 2>>::STRUCTURE.map(|s| s.dimension),
        Some(1)
    );
    let path = Poly9::new(0.0, 4.0, vector![0.0, -5.0], vector![3.0, -4.0]).unwrap();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 0.0, 5.0]).unwrap();
    let run = crane_runtime::simulate(&crane, &path, &start, &crane_runtime::Options::new(0.01, 4.0).unwrap()).unwrap();
    let diagnosis = diagnose(&crane, &run, 100);
    assert_eq!(diagnosis.samples, 101, "{diagnosis:?}");
    assert_eq!(diagnosis.unresolved, 101, "{diagnosis:?}");
    assert_eq!(diagnosis.dimension, 1, "the structure's count: {diagnosis:?}");
    assert_eq!(diagnosis.stable, None, "{diagnosis:?}");
    assert!(diagnosis.max_real_part.is_none());
    // the run's audit says so, and calls nothing unstable (its other
    // finding: the damper makes the inputs need the path's 5th derivative,
    // beyond eqs. 22's 4th)
    use crane_models::study::{Finding, audit, summary::summarize};
    let mut summary = summarize("damped-drive", "redundant", &run, None, &[], 0.0);
    summary.internal_dynamics = diagnosis;
    let findings = audit(&summary);
    let unknown: Vec<String> = findings
        .iter()
        .filter(|f| matches!(f, Finding::InternalDynamicsUnknown { dimension: 1, .. }))
        .map(|f| f.to_string())
        .collect();
    assert_eq!(unknown.len(), 1, "{findings:?}");
    assert!(
        unknown[0].contains("dimension 1 by its structure") && unknown[0].contains("not known"),
        "{unknown:?}"
    );
    assert!(
        !findings
            .iter()
            .any(|f| matches!(f, Finding::UnstableInternalDynamics { .. })),
        "{findings:?}"
    );
}
