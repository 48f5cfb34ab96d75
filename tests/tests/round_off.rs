//! Refining the step never makes the inputs worse, except down to the
//! round-off floor the run itself shows. Eqs. (22) get the inputs from the
//! scheme's second divided differences of the coordinates, so the
//! coordinates' round-off (~1e-16 of their size per step) reaches the
//! inputs amplified like `(c/dt)^2`: on tower-crane with BDF-4 the error
//! against the exact reduced inputs is 1.7e-3 N m at dt = 0.02 and 0.01 s
//! and then *grows*, 6.6e-3 at 0.005, 0.16 at 0.001, 0.90 at 0.0005 (of a
//! 21075 N m peak), as step-to-step noise of random sign. That noise is
//! measured from the run alone by its sixth differences, `max |Delta^6 u|
//! / 32`, which see almost nothing of a smooth input (`u^(6) dt^6`) and
//! about 3 sigma of white noise; where the error is noise, it was measured
//! at 0.55 to 0.61 of that estimate (tower-crane BDF-4 at dt = 0.005 ..
//! 0.001, navy-planar-pulley BDF-5 at 0.001).
//!
//! The check, on every flat built-in crane (whose reduced formulation
//! gives its exact inputs) with every scheme, refining dt = 0.02 .. 0.001:
//! the error at each step is at most the error at the coarser one, or at
//! most twice the round-off floor measured in its own run where that floor
//! grew as the step shrank (a transient at a feature of the path also
//! shows in the sixth differences, but shrinks with the step). An error
//! that grows smoothly as dt shrinks (a bug, not round-off) fails it.

use crane_models::registry::{BuiltIn, Registry, Visit};
use crane_models::study::Formulation;
use crane_models::study::convergence::round_off_floor;
use crane_models::{Case, Crane};
use crane_runtime::{CraneModel, Options, Scheme};

const DTS: [f64; 5] = [0.02, 0.01, 0.005, 0.002, 0.001];

/// Per dt: the largest `|u - u_exact|` and the round-off floor `max
/// |Delta^6 u| / 32`, both over the middle 60 % of the run (away from the
/// schemes' start-up steps and the end of the move).
struct Refinement {
    scheme: Scheme,
}

impl Visit for Refinement {
    type Output = Option<Vec<(f64, f64, f64)>>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let case = Case::<C, N, M, A>::maneuver().expect("the default move");
        let path_order = <C::Model as CraneModel<N, M, A>>::STRUCTURE.map(|s| s.path_order(A));
        if path_order.is_none_or(|order| order > 4)
            || crane_runtime::dummy_derivative::system_size::<C::Model, N, M, A>().is_err()
        {
            // no exact inputs to compare with, or eqs. (22) do not reduce
            // the crane (its inputs need a higher path order)
            return None;
        }
        let start = case.start().expect("the default start");
        let (t0, tf) = (case.t0(), case.tf());
        let window = (t0 + 0.2 * (tf - t0), tf - 0.2 * (tf - t0));
        let rows = DTS
            .iter()
            .map(|&dt| {
                let options = Options::new(dt, tf).expect("a step");
                let exact = case
                    .simulate_dummy_derivative(&start, &options, &mut |_, _| {})
                    .expect("the reduced run");
                let run = case
                    .simulate(&start, &options.with_scheme(self.scheme))
                    .expect("the run of eqs. (22)");
                let s = &run.states;
                let error = (s.iter().zip(&exact.states))
                    .filter(|(a, _)| a.t >= window.0 && a.t <= window.1)
                    .map(|(a, b)| (a.u - b.u).amax())
                    .fold(0.0f64, f64::max);
                (dt, error, round_off_floor(s, window.0, window.1))
            })
            .collect();
        Some(rows)
    }
}

#[test]
fn refining_the_step_never_makes_the_inputs_worse_beyond_round_off() {
    let mut checked = 0;
    for entry in BuiltIn.entries() {
        for scheme in Scheme::ALL {
            let Some(rows) = BuiltIn.visit(entry.name, Refinement { scheme }).expect("a built-in") else {
                continue;
            };
            checked += 1;
            for pair in rows.windows(2) {
                let ((_, coarse, coarse_floor), (dt, fine, floor)) = (pair[0], pair[1]);
                println!(
                    "{} {scheme} dt = {dt}: error {fine:.3e} (coarser {coarse:.3e}), round-off floor {floor:.3e}",
                    entry.name
                );
                // round-off grows as dt shrinks; a transient at a feature
                // of the path (navy-3d's second phase at t = 15 s) also
                // shows in the sixth differences, but shrinks with dt
                let round_off = fine <= 2.0 * floor && floor > coarse_floor;
                assert!(
                    fine <= coarse * (1.0 + 1e-6) || round_off,
                    "{} {scheme}: the error grows from {coarse:.3e} to {fine:.3e} at dt = {dt} above the round-off \
                     floor {floor:.3e}",
                    entry.name
                );
            }
        }
    }
    // navy-planar, navy-planar-pulley, navy-3d, gantry-3d and tower-crane,
    // with five schemes each (the others' inputs need a higher path order,
    // or they have no reduced system)
    assert!(checked >= 5 * 5, "{checked} cranes and schemes checked");
}

/// The convergence study tells round-off from a bug: tower-crane with
/// BDF-4 at t = 1.5 s converges at order 4 down to dt = 0.005 s, and its
/// error grows at dt = 0.001 s (9.1e-10 from 2.1e-10, order -0.9) where it
/// is within twice the run's own round-off floor: that row is marked as
/// round-off and is no finding; an error that grew beyond the floor would
/// be one (and fail `crane convergence --strict`).
#[test]
fn the_convergence_study_marks_round_off_and_flags_growth_beyond_it() {
    use crane_models::study::convergence::{reference_inputs, study_against};
    let case = crane_models::tower_crane::DefaultCase::maneuver().unwrap();
    let (reference, _) = reference_inputs(&case).unwrap();
    let dts = [0.02, 0.01, 0.005, 0.001];
    let rows = study_against(&case, &reference, Formulation::Redundant, Scheme::Bdf4, &dts, |_| {}).unwrap();
    for row in &rows {
        println!(
            "dt = {}: e_u {:.3e}, order {:?}, floor {:.2e}",
            row.dt, row.e_u, row.order, row.floor
        );
        assert!(row.findings.is_empty(), "{:?}", row.findings);
    }
    for row in &rows[1..3] {
        let order = row.order.unwrap();
        assert!((3.9..5.5).contains(&order), "dt = {}: order {order}", row.dt);
    }
    let last = &rows[3];
    assert!(last.order.unwrap() < 0.0 && last.at_round_off(), "{last:?}");
}

/// A run says when round-off makes up most of its error: tower-crane in
/// eqs. (22) with BDF-4, against the exact inputs of the reduced
/// formulation over the middle of the move, has the error 1.75e-3 N m at
/// dt = 0.02 s, where the step-to-step noise is 3.5e-4 (the scheme's
/// error: no finding), and 0.157 N m at dt = 0.001 s, where the noise is
/// 0.277 (round-off: a warning that a finer step is less accurate); the
/// paper's crane with backward Euler at 0.01 s is the scheme's error
/// (0.153 N m against a floor of 8e-9).
#[test]
fn a_run_whose_error_is_round_off_says_so() {
    use crane_models::study::{Finding, RunSettings, Severity, run};
    let round_off = |case_dt: f64, tower: bool, scheme: Scheme| {
        let settings = RunSettings {
            dt: case_dt,
            formulation: Formulation::Redundant,
            scheme,
            ..RunSettings::default()
        };
        let outcome = if tower {
            let case = crane_models::tower_crane::DefaultCase::maneuver().unwrap();
            run(&case, &settings, &mut |_, _| {}).unwrap()
        } else {
            let case = crane_models::navy_planar::PaperCase::maneuver().unwrap();
            let outcome = run(&case, &settings, &mut |_, _| {}).unwrap();
            return (outcome.summary.round_off.unwrap(), outcome.findings.len(), false);
        };
        let flagged = outcome
            .findings
            .iter()
            .any(|f| matches!(f, Finding::RoundOffDominates { .. }) && f.severity() == Severity::Warning);
        (outcome.summary.round_off.unwrap(), outcome.findings.len(), flagged)
    };
    let (coarse, _, flagged) = round_off(0.02, true, Scheme::Bdf4);
    println!("tower-crane BDF-4 dt = 0.02: {coarse:?}");
    assert!(coarse.error > 2.0 * coarse.floor && !coarse.dominates() && !flagged);
    let (fine, _, flagged) = round_off(0.001, true, Scheme::Bdf4);
    println!("tower-crane BDF-4 dt = 0.001: {fine:?}");
    assert!(fine.dominates() && flagged, "{fine:?}");
    // the error grew as the step shrank: what the finding is about
    assert!(fine.error > 10.0 * coarse.error);
    let (paper, findings, _) = round_off(0.01, false, Scheme::BackwardEuler);
    println!("navy-planar backward Euler dt = 0.01: {paper:?}");
    assert!(!paper.dominates() && findings == 0, "{paper:?}");
}
