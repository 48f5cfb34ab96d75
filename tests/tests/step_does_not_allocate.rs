//! The per-step path of the steppers does not allocate: a counting global
//! allocator sees zero allocations across the steps of `navy-planar` (4 s),
//! for every scheme, in redundant and in minimal coordinates, including the
//! first steps from the degenerate start where Newton falls back to the
//! minimum-norm solve (and the minimal stepper's retry from the last step);
//! the dummy-derivative stepper, its long steps by continuation and its
//! steps of eqs. (22) where a rope is nearly slack included;
//! the forward problem's stepper; and state selection's (a crane with a
//! damped free swing).
//! One test function, so that no other test allocates while one counts.

use crane_models::navy_planar::{PaperCase, minimal_guess};
use crane_runtime::dummy_derivative::DummyDerivativeStepper;
use crane_runtime::forward::Forward;
use crane_runtime::nalgebra::vector;
use crane_runtime::redundant::Redundant;
use crane_runtime::state_selection::SelectedStatesStepper;
use crane_runtime::trajectory::Poly9;
use crane_runtime::{Advance, Options, Scheme, Stepper, init, minimal};
use crane_tests::counting::{Counting, allocations_during, assert_counter_works};
use crane_tests::damped::DampedSwing;

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations during `steps` steps of `stepper`.
fn allocations_in(stepper: &mut impl Advance<7, 3, 2>, steps: usize) -> (usize, usize) {
    let (allocations, min_norm) = allocations_during(|| {
        let mut min_norm = 0;
        for _ in 0..steps {
            min_norm += stepper.step().map(|r| r.min_norm_steps).unwrap_or(usize::MAX);
        }
        min_norm
    });
    assert!(min_norm < usize::MAX, "a step failed");
    (allocations, min_norm)
}

#[test]
fn stepping_does_not_allocate() {
    assert_counter_works();
    let case = PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let guess = minimal_guess(case.model(), &start);
    for scheme in Scheme::ALL {
        for dt in [0.01f64, 0.001] {
            let steps = (4.0 / dt).round() as usize;
            let options = Options::stepping(dt).unwrap().with_scheme(scheme);
            let mut redundant = Stepper::new(Redundant::new(case.model(), case.path()), &start, &options).unwrap();
            let (allocations, min_norm) = allocations_in(&mut redundant, steps);
            assert_eq!(
                allocations, 0,
                "redundant {scheme} dt = {dt}: {allocations} allocations in {steps} steps"
            );
            assert!((redundant.state().t - 4.0).abs() < 1e-9);
            println!(
                "redundant {scheme} dt = {dt}: {steps} steps, {min_norm} minimum-norm Newton steps, 0 allocations"
            );
            let mut minimal = minimal::stepper(case.model(), case.path(), &start, &guess, &options).unwrap();
            let (allocations, min_norm) = allocations_in(&mut minimal, steps);
            assert_eq!(
                allocations, 0,
                "minimal {scheme} dt = {dt}: {allocations} allocations in {steps} steps"
            );
            println!("minimal {scheme} dt = {dt}: {steps} steps, {min_norm} minimum-norm Newton steps, 0 allocations");
            let mut reduced = DummyDerivativeStepper::new(case.model(), case.path(), &start, &options).unwrap();
            let (allocations, _) = allocations_in(&mut reduced, steps);
            assert_eq!(
                allocations, 0,
                "dummy-derivative {scheme} dt = {dt}: {allocations} allocations in {steps} steps"
            );
            // the forward problem, driven by the inputs of the inverse run's last state
            let u = redundant.state().u;
            let end = *redundant.state();
            let mut forward = Stepper::new(Forward::new(case.model(), move |_t: f64| u), &end, &options).unwrap();
            let (allocations, _) = allocations_in(&mut forward, steps.min(400));
            assert_eq!(allocations, 0, "forward {scheme} dt = {dt}: {allocations} allocations");
        }
    }
    // steps by continuation (a long step's prediction lands on the mirror
    // configuration at t = 4 s) take their shorter steps without allocating
    for dt in [0.5, 4.0] {
        let options = Options::stepping(dt).unwrap();
        let mut reduced = DummyDerivativeStepper::new(case.model(), case.path(), &start, &options).unwrap();
        let steps = (4.0 / dt).round() as usize;
        let (allocations, substeps) = allocations_during(|| {
            (0..steps)
                .map(|_| reduced.step().map(|r| r.substeps).unwrap_or(usize::MAX))
                .fold(0, usize::saturating_add)
        });
        assert!(substeps > 0 && substeps < usize::MAX, "dt = {dt}: {substeps} substeps");
        assert_eq!(allocations, 0, "dummy-derivative dt = {dt}: {allocations} allocations");
        println!("dummy-derivative dt = {dt}: {substeps} shorter steps by continuation, 0 allocations");
    }
    // steps of eqs. (22) that the reduced stepper takes and follows where a
    // rope is nearly slack (the paper's move slowed to 1000 s: its rope N1
    // starts at zero tension) allocate nothing either
    let slow = PaperCase::new(1000.0).unwrap();
    let start = slow.start().unwrap();
    let options = Options::stepping(0.001).unwrap();
    let mut reduced = DummyDerivativeStepper::new(slow.model(), slow.path(), &start, &options).unwrap();
    let (allocations, _) = allocations_in(&mut reduced, 2000);
    assert!(
        reduced.fallback_steps() > 0,
        "no step fell back: the check checks nothing"
    );
    assert_eq!(allocations, 0, "dummy-derivative, slow move: {allocations} allocations");
    println!(
        "dummy-derivative, slow move: {} of 2000 steps in eqs. (22), 0 allocations",
        reduced.fallback_steps()
    );

    // state selection: the damped swing's free swing by BDF-1..5
    let crane = DampedSwing::default();
    let path = Poly9::new(0.0, 4.0, vector![0.0, -5.0], vector![3.0, -4.0]).unwrap();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0, 0.0, -2.0]).unwrap();
    for k in 1..=5 {
        let scheme = Scheme::bdf(k).unwrap();
        let options = Options::new(0.01, 4.0).unwrap().with_scheme(scheme);
        let mut stepper = SelectedStatesStepper::new(&crane, &path, &start, &options).unwrap();
        let (allocations, _) = allocations_during(|| {
            for _ in 0..400 {
                stepper.step().unwrap();
            }
        });
        assert_eq!(
            allocations, 0,
            "state selection {scheme}: {allocations} allocations in 400 steps"
        );
        println!("state selection {scheme}: 400 steps, 0 allocations");
    }
}
