//! Index reduction by dummy derivatives (`Formulation::DummyDerivative`):
//! cranes whose inputs need the path's 6th derivative (the double pendulum,
//! the elastic drive, the 3D crane with pulley mass) get the exact inputs
//! at every step, where the paper's minimal extension (eqs. 22) approaches
//! them at the scheme's order; and on the paper's cranes the reduced formulation agrees
//! with the analytical references and with eqs. (22) to the scheme's error.
//!
//! Measured: the largest relative error of `u` over every step of every
//! run is at most 1.8e-15 (double pendulum) and 2.75e-14 (elastic drive),
//! whatever the scheme and dt; each crane is held to about ten times its
//! own ([`exactness_bound`]).

use crane_models::study::Formulation::{DummyDerivative, Redundant};
use crane_models::{Case, Crane, double_pendulum, elastic_drive, gantry_3d, navy_3d, navy_3d_pulley, navy_planar};
use crane_models::{navy_planar_pulley, tower_crane};
use crane_runtime::dummy_derivative::DummyDerivativeStepper;
use crane_runtime::linsolve::DenseSolver;
use crane_runtime::newton::NonlinearSystem;
use crane_runtime::redundant::Redundant as Redundant22;
use crane_runtime::{CraneModel, Options, Scheme, Solution, Stepper};
use crane_tests::kit::{e_u, exactness_bound, run, run_to};
use nalgebra::{DMatrix, DVector};

/// The steps of the convergence study of a crane of path order 6.
const DTS: [f64; 5] = [0.02, 0.01, 0.005, 0.0025, 0.001];

/// The largest relative error `|u - u_ref| / |u_ref|` over the steps of
/// `solution` from step `from` on, and where.
fn worst_error<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    case: &Case<C, N, M, A>,
    solution: &Solution<N, M, A>,
    from: usize,
) -> (f64, f64) {
    solution.states[from..]
        .iter()
        .map(|s| (case.relative_input_error(s).expect("a reference at every step"), s.t))
        .fold((0.0, 0.0), |w, e| if e.0 > w.0 { e } else { w })
}

/// The inputs of a flat crane from its dummy-derivative system are exact
/// at every step: for every scheme and every dt of the study, the largest
/// relative error of `u` over the whole run against the analytical
/// reference is round-off: within the crane's [`exactness_bound`], about
/// ten times the largest measured (1.8e-15 on the double pendulum, 2.75e-14
/// on the elastic drive).
fn exact_at_every_step<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>() {
    let case = Case::<C, N, M, A>::maneuver().unwrap();
    for scheme in Scheme::ALL {
        for dt in DTS {
            let solution = run(&case, DummyDerivative, scheme, dt);
            let (worst, at) = worst_error(&case, &solution, 0);
            println!("{} {scheme} dt = {dt}: largest e_u {worst:.2e} at t = {at}", C::NAME);
            assert!(
                worst < exactness_bound(C::NAME),
                "{} {scheme} dt = {dt}: e_u {worst:e} at t = {at}",
                C::NAME
            );
            assert_eq!(solution.redundant_start_steps, 0, "no step fell back on eqs. (22)");
        }
    }
}

#[test]
fn double_pendulum_inputs_are_exact_at_every_step_and_step_size() {
    let path_order = <double_pendulum::DoublePendulum as CraneModel<6, 2, 2>>::STRUCTURE.map(|s| s.path_order(2));
    assert_eq!(path_order, Some(6));
    exact_at_every_step::<double_pendulum::Description, 6, 2, 2>();
}

#[test]
fn elastic_drive_inputs_are_exact_at_every_step_and_step_size() {
    let path_order = <elastic_drive::ElasticDrive as CraneModel<5, 1, 2>>::STRUCTURE.map(|s| s.path_order(2));
    assert_eq!(path_order, Some(6));
    exact_at_every_step::<elastic_drive::Description, 5, 1, 2>();
}

/// Eqs. (22) on the double pendulum, beyond their index reduction (its
/// inputs need the path's 6th derivative): with the coordinates, history
/// and residual held in double-double, BDF-4 converges at order 4 (e_u at
/// 1.5 s measured 1.716e-7 at dt = 0.01, 1.717e-11 at 0.001). In `f64`
/// the rounding of the coordinates, amplified by the scheme's differences,
/// had made it diverge (5.1e-7 at 0.01, 8.8e-6 at 0.005, 2.9e-3 at 0.001).
/// The dummy-derivative formulation is at round-off at any step.
#[test]
fn eqs_22_converge_on_the_double_pendulum_once_held_beyond_double_precision() {
    let case = double_pendulum::DefaultCase::maneuver().unwrap();
    let error = |dt| e_u(&case, &run_to(&case, Redundant, Scheme::Bdf4, dt, 1.5));
    let (coarse, fine) = (error(0.01), error(0.001));
    println!("eqs. (22), BDF-4: e_u(0.01) = {coarse:.3e}, e_u(0.001) = {fine:.3e}");
    // order 4 over a factor 10 is 1e4; order 3 would leave 1e-3
    assert!(fine < 1e-3 * coarse, "eqs. (22) with BDF-4 do not converge at order 4");
    let reduced = e_u(&case, &run_to(&case, DummyDerivative, Scheme::Bdf4, 0.001, 1.5));
    assert!(reduced < 1e-12, "{reduced:e}");
}

/// On the paper's cranes (path order 4) and the other flat built-ins with a
/// reference, the reduced formulation reproduces the analytical reference
/// at every step (within [`exactness_bound`]: measured 8.4e-16 on
/// navy-planar, 1.3e-15 on the pulley crane, 3.0e-15 on gantry-3d, 4.0e-14
/// on navy-3d),
/// the paper's degenerate start of the 3D crane included: its minimum-norm
/// steps, by QR of the regularised system, no longer need the fallback on
/// eqs. (22) that the normal equations (condition squared) needed there.
#[test]
fn paper_cranes_match_their_references_at_every_step() {
    fn check<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(fallback: usize) {
        let case = Case::<C, N, M, A>::maneuver().unwrap();
        let solution = run(&case, DummyDerivative, Scheme::Bdf2, 0.01);
        assert_eq!(solution.redundant_start_steps, fallback, "{}", C::NAME);
        let (worst, at) = worst_error(&case, &solution, 1 + fallback);
        println!(
            "{}: largest e_u {worst:.2e} at t = {at} ({fallback} fallback steps)",
            C::NAME
        );
        assert!(
            worst < exactness_bound(C::NAME),
            "{}: e_u {worst:e} at t = {at}",
            C::NAME
        );
    }
    check::<navy_planar::Description, 7, 3, 2>(0);
    check::<navy_planar_pulley::Description, 8, 4, 3>(0);
    check::<navy_3d::Description, 11, 4, 3>(0);
    check::<gantry_3d::Description, 6, 1, 3>(0);
}

/// Eqs. (22) approach the exact inputs at the scheme's order: the largest
/// difference of `u` between eqs. (22) with BDF-k and the reduced
/// formulation shrinks like dt^k, k = 1..4 (the ratio between dt = 0.04 and
/// 0.02 within 25 % of 2^k), on the planar crane and the tower crane (which
/// has no analytical reference: the reduced formulation stands in for it).
/// Measured from t = 1 s to tf - 1 s: the Poly9 path's 5th derivative jumps
/// at t0 and tf, where the inputs of a crane of path order 4 have a kink
/// and BDF-k loses order for its next steps (and the first steps off the
/// paper's degenerate start are of first order in eqs. 22).
#[test]
fn eqs_22_approach_the_reduced_inputs_at_the_schemes_order() {
    fn difference<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(scheme: Scheme, dt: f64) -> f64 {
        let case = Case::<C, N, M, A>::maneuver().unwrap();
        let reduced = run(&case, DummyDerivative, scheme, dt);
        let redundant = run(&case, Redundant, scheme, dt);
        let scale = reduced.states.iter().map(|s| s.u.amax()).fold(0.0, f64::max);
        let inside = |t: f64| t >= 1.0 && t <= case.tf() - 1.0;
        let worst = reduced
            .states
            .iter()
            .zip(&redundant.states)
            .filter(|(a, _)| inside(a.t))
            .map(|(a, b)| (a.u - b.u).amax())
            .fold(0.0, f64::max);
        worst / scale
    }
    for scheme in [Scheme::BackwardEuler, Scheme::Bdf2, Scheme::Bdf3, Scheme::Bdf4] {
        for (name, coarse, fine) in [
            (
                "navy-planar",
                difference::<navy_planar::Description, 7, 3, 2>(scheme, 0.04),
                difference::<navy_planar::Description, 7, 3, 2>(scheme, 0.02),
            ),
            (
                "tower-crane",
                difference::<tower_crane::Description, 8, 3, 3>(scheme, 0.04),
                difference::<tower_crane::Description, 8, 3, 3>(scheme, 0.02),
            ),
        ] {
            println!("{name} {scheme}: |u22 - u_reduced| / max|u| = {coarse:.3e} (0.04), {fine:.3e} (0.02)");
            crane_tests::kit::assert_ratio_of_order(name, scheme, coarse / fine);
        }
    }
}

/// The 3D crane with pulley mass on its C6 profile (no analytical
/// reference): every input, the slewing torque u4 included, is the same at
/// the common times of dt = 0.04, 0.02 and 0.01 to round-off (relative
/// 1e-12 of the largest input; measured below 1e-13), and the states
/// satisfy the declared equations of motion `M q'' = f + B^T u - G^T
/// lambda` with `q''` from central differences of the computed `q'` at
/// dt = 0.001 at times between the ramps' ends: the residual is the
/// difference quotient's error dt^2/6 q'''' (it falls by 4 when dt halves;
/// measured 4.0e-6 of the largest term of a row at dt = 0.001: bound 1e-5;
/// terms below 1 N are compared absolutely).
#[test]
fn navy_3d_pulley_inputs_are_independent_of_dt_and_satisfy_the_equations() {
    let case = navy_3d_pulley::PaperCase::smooth(navy_3d_pulley::TF).unwrap();
    let runs: Vec<_> = [0.04, 0.02, 0.01]
        .map(|dt| run(&case, DummyDerivative, Scheme::Bdf4, dt))
        .into();
    let scale = runs[2].states.iter().map(|s| s.u.amax()).fold(0.0, f64::max);
    for pair in runs.windows(2) {
        let differences = pair[0].input_difference(&pair[1], |_| true).unwrap();
        for (k, (d, t)) in differences.iter().enumerate() {
            println!(
                "u{}: largest difference dt = {} vs {}: {d:.2e} at t = {t}",
                k + 1,
                pair[0].dt,
                pair[1].dt
            );
            assert!(*d < 1e-12 * scale, "u{} differs by {d:e} at t = {t}", k + 1);
        }
    }
    // the residual of the equations of motion with q'' from central
    // differences of the computed q' at dt
    let residual = |dt: f64| {
        let fine = run_to(&case, DummyDerivative, Scheme::BackwardEuler, dt, 12.0);
        let model = case.model();
        let mass = model.mass_matrix::<f64>();
        let mut worst: f64 = 0.0;
        // off the ramps' ends at 5 s and 15 s, where q''' jumps (the path is
        // C6, q needs its 4th derivative) and central differences are O(dt)
        for t in (0..20).map(|k| 1.25 + 0.5 * k as f64) {
            let i = (t / dt).round() as usize;
            let (before, state, after) = (&fine.states[i - 1], &fine.states[i], &fine.states[i + 1]);
            let a = (after.v - before.v) / (2.0 * dt);
            let inertia = mass * a;
            let applied = model.forces(&state.q, &state.v) + model.input_matrix(&state.q) * state.u;
            let constraint = model.constraint_jacobian(&state.q).transpose() * state.lambda;
            for row in 0..12 {
                let size = inertia[row].abs().max(applied[row].abs()).max(constraint[row].abs());
                let residual = (inertia[row] - applied[row] + constraint[row]).abs();
                worst = worst.max(residual / size.max(1.0));
            }
            assert!(model.constraints(&state.q).amax() < 1e-10);
        }
        worst
    };
    let (coarse, worst) = (residual(0.002), residual(0.001));
    println!("equations of motion: largest relative residual {coarse:.2e} (dt = 0.002), {worst:.2e} (dt = 0.001)");
    assert!(
        (coarse / worst - 4.0).abs() < 1.0,
        "the residual is the difference quotient's, O(dt^2)"
    );
    assert!(worst < 1e-5, "{worst:e}");
}

/// The equilibrated condition number of an iteration matrix at the unknowns
/// `z` of `system`'s last step.
fn condition(system: &(impl NonlinearSystem + Clone), z: &DVector<f64>) -> f64 {
    let mut system = system.clone();
    let n = system.dim();
    let (mut r, mut jac) = (DVector::zeros(n), DMatrix::zeros(n, n));
    system.evaluate(z, &mut r, &mut jac);
    DenseSolver::equilibrated(n).equilibrated_condition(&jac)
}

/// Along the double pendulum's move (every 0.5 s) the reduced system's
/// iteration matrix is the same at dt = 0.01 and 0.001 (no dt enters it)
/// and its equilibrated condition number stays below 100 (measured 5.3 to
/// 8.3), while that of eqs. (22), scaled by dt^2 as it is, grows like
/// dt^-4 where the load accelerates (at t = 1.5 s: 2.4e4 at dt = 0.01,
/// 2.3e8 at dt = 0.001): the index the scheme does not tolerate.
#[test]
fn the_reduced_iteration_matrix_does_not_depend_on_dt() {
    let case = double_pendulum::DefaultCase::maneuver().unwrap();
    let start = case.start().unwrap();
    let mut conditions = Vec::new();
    for dt in [0.01, 0.001] {
        let options = Options::new(dt, case.tf()).unwrap();
        let mut reduced = DummyDerivativeStepper::new(case.model(), case.path(), &start, &options).unwrap();
        let mut redundant = Stepper::new(Redundant22::new(case.model(), case.path()), &start, &options).unwrap();
        let mut along = Vec::new();
        let every = (0.5 / dt).round() as usize;
        for step in 1..=(case.tf() / dt).round() as usize {
            reduced.step().unwrap();
            redundant.step().unwrap();
            if step % every == 0 {
                let eqs_22 = condition(redundant.problem(), redundant.unknowns());
                along.push((reduced.state().t, reduced.condition(), eqs_22));
            }
        }
        for (t, c, c22) in &along {
            println!("dt = {dt} t = {t:.1}: reduced {c:.3e}, eqs. (22) {c22:.3e}");
            assert!(*c < 100.0, "dt = {dt}, t = {t}: condition {c:e}");
        }
        conditions.push(along);
    }
    for (coarse, fine) in conditions[0].iter().zip(&conditions[1]) {
        assert!((coarse.0 - fine.0).abs() < 1e-9, "the same times");
        assert!(
            (coarse.1 / fine.1 - 1.0).abs() < 1e-6,
            "t = {}: {} vs {}",
            coarse.0,
            coarse.1,
            fine.1
        );
    }
    let at = |along: &[(f64, f64, f64)]| along.iter().find(|c| (c.0 - 1.5).abs() < 1e-9).unwrap().2;
    let growth = at(&conditions[1]) / at(&conditions[0]);
    assert!(
        growth > 1e3,
        "eqs. (22): condition grows by {growth} from dt = 0.01 to 0.001"
    );
}
