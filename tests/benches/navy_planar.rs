//! Criterion benchmarks of the inverse dynamics of the paper's planar cranes:
//! full runs at dt = 0.01 (400 steps) and dt = 0.001 (4000 steps) and single
//! steps, in redundant (eqs. 22a-d) and minimal (eqs. 24a-e) coordinates (one
//! step at t = 1.5 s side by side for both planar cranes), and
//! for `navy-planar` the generated model against a hand-written one (the
//! target: generated code costs no more than hand-written code); per scheme
//! (backward Euler, BDF-2..5) a full run and one step (`schemes/...`).
//!
//! `floor/...`: the project's backward-Euler run of navy-planar against the
//! hand-written static-nalgebra solver of the same scheme, predictor and
//! stopping rule (`crane_tests::floor`), with the ratio of their medians
//! over interleaved rounds printed after criterion's lines.
//!
//! Run with `cargo bench -p crane-tests` (`-- floor` for that group alone).

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use std::hint::black_box;

use crane_models::{Case, Crane, navy_planar, navy_planar_pulley};
use crane_runtime::nalgebra::SVector;
use crane_runtime::redundant::Redundant;
use crane_runtime::{CraneModel, MinimalMap, Options, Scheme, State, Stepper, minimal, simulate};
use crane_tests::floor;
use crane_tests::handwritten::HandNavyPlanar;

/// Redundant runs and one step with `model` on the navy-planar maneuver.
fn redundant_runs<Mdl: CraneModel<7, 3, 2>>(c: &mut Criterion, label: &str, model: &Mdl) {
    let case = navy_planar::PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    for dt in [0.01, 0.001] {
        let options = Options::new(dt, 4.0).unwrap();
        c.bench_function(&format!("navy-planar/{label}/run dt={dt}"), |b| {
            b.iter(|| simulate(black_box(model), case.path(), &start, &options).unwrap())
        });
    }
    // one step at t = 1.5 s, dt = 0.01, from the state a run reaches there
    let solution = simulate(model, case.path(), &start, &Options::new(0.01, 4.0).unwrap()).unwrap();
    let state: State<7, 3, 2> = solution.states[150];
    c.bench_function(&format!("navy-planar/{label}/one step dt=0.01"), |b| {
        b.iter_batched_ref(
            || {
                Stepper::new(
                    Redundant::new(model, case.path()),
                    &state,
                    &Options::stepping(0.01).unwrap(),
                )
                .unwrap()
            },
            |stepper| stepper.step().unwrap(),
            BatchSize::SmallInput,
        )
    });
}

/// Full runs at dt = 0.01 of a case in both formulations.
fn formulations<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    c: &mut Criterion,
    name: &str,
    case: &Case<C, N, M, A>,
) {
    let start = case.start().unwrap();
    let options = Options::new(0.01, case.tf()).unwrap();
    c.bench_function(&format!("{name}/redundant/run dt=0.01"), |b| {
        b.iter(|| simulate(black_box(case.model()), case.path(), &start, &options).unwrap())
    });
    if case.simulate_minimal(&start, &options).is_some() {
        c.bench_function(&format!("{name}/minimal/run dt=0.01"), |b| {
            b.iter(|| case.simulate_minimal(black_box(&start), &options).unwrap().unwrap())
        });
    }
}

/// One step at t = 1.5 s, dt = 0.01, in both formulations, from steppers
/// that got there themselves (the target: a minimal step costs at most 2x a
/// redundant one).
fn one_step_each<const N: usize, const M: usize, const A: usize, const F: usize, Mdl>(
    c: &mut Criterion,
    name: &str,
    model: &Mdl,
    path: &crane_models::Path<A>,
    start: &State<N, M, A>,
    mu_guess: &SVector<f64, F>,
) where
    Mdl: MinimalMap<N, M, A, F> + Clone,
{
    let options = Options::stepping(0.01).unwrap();
    let mut redundant = Stepper::new(Redundant::new(model, path), start, &options).unwrap();
    let mut minimal = minimal::stepper(model, path, start, mu_guess, &options).unwrap();
    for _ in 0..150 {
        redundant.step().unwrap();
        minimal.step().unwrap();
    }
    // a fresh clone per timed step (PerIteration): with batches of clones
    // made up front, each step found its stepper out of cache, and the
    // minimal one (more workspace) by more (measured 1.4x to 3.0x over runs)
    c.bench_function(&format!("{name}/redundant/one step dt=0.01"), |b| {
        b.iter_batched_ref(
            || redundant.clone(),
            |stepper| stepper.step().unwrap(),
            BatchSize::PerIteration,
        )
    });
    c.bench_function(&format!("{name}/minimal/one step dt=0.01"), |b| {
        b.iter_batched_ref(
            || minimal.clone(),
            |stepper| stepper.step().unwrap(),
            BatchSize::PerIteration,
        )
    });
}

/// Per scheme on navy-planar: the full run at dt = 0.01 and one step at
/// t = 1.5 s from a stepper that got there itself (so its history is full);
/// and the runs of the work-precision table: per scheme the largest dt
/// (dividing 1.5 s and 4 s) with e_u(1.5 s) <= 1e-6 (docs/benchmarks.md).
fn schemes(c: &mut Criterion) {
    let case = navy_planar::PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    for scheme in Scheme::ALL {
        let options = Options::new(0.01, 4.0).unwrap().with_scheme(scheme);
        c.bench_function(&format!("schemes/navy-planar/{scheme}/run dt=0.01"), |b| {
            b.iter(|| simulate(black_box(case.model()), case.path(), &start, &options).unwrap())
        });
        let mut at_1_5 = Stepper::new(Redundant::new(case.model(), case.path()), &start, &options).unwrap();
        for _ in 0..150 {
            at_1_5.step().unwrap();
        }
        c.bench_function(&format!("schemes/navy-planar/{scheme}/one step dt=0.01"), |b| {
            b.iter_batched_ref(
                || at_1_5.clone(),
                |stepper| stepper.step().unwrap(),
                BatchSize::SmallInput,
            )
        });
    }
    for (scheme, dt) in [
        (Scheme::Bdf2, 0.00125),
        (Scheme::Bdf3, 0.00625),
        (Scheme::Bdf4, 0.02),
        (Scheme::Bdf5, 0.02),
    ] {
        let options = Options::new(dt, 4.0).unwrap().with_scheme(scheme);
        c.bench_function(&format!("schemes/navy-planar/{scheme}/run dt={dt}"), |b| {
            b.iter(|| simulate(black_box(case.model()), case.path(), &start, &options).unwrap())
        });
    }
}

fn benches(c: &mut Criterion) {
    redundant_runs(c, "generated", &navy_planar::NavyPlanar::default());
    redundant_runs(c, "hand-written", &HandNavyPlanar::default());
    formulations(c, "navy-planar", &navy_planar::PaperCase::new(4.0).unwrap());
    formulations(
        c,
        "navy-planar-pulley",
        &navy_planar_pulley::PaperCase::new(4.0).unwrap(),
    );
    let planar = navy_planar::PaperCase::new(4.0).unwrap();
    let start = planar.start().unwrap();
    let guess = navy_planar::minimal_guess(planar.model(), &start);
    one_step_each(c, "navy-planar", planar.model(), planar.path(), &start, &guess);
    let pulley = navy_planar_pulley::PaperCase::new(4.0).unwrap();
    let start = pulley.start().unwrap();
    let guess = navy_planar_pulley::minimal_guess(pulley.model(), &start);
    one_step_each(c, "navy-planar-pulley", pulley.model(), pulley.path(), &start, &guess);
}

/// The project's run against the hand-written floor, navy-planar, backward
/// Euler, dt = 0.01, 400 steps, the generated model in both.
fn floor_group(c: &mut Criterion) {
    let case = navy_planar::PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let options = Options::new(0.01, 4.0).unwrap();
    let project = || simulate(black_box(case.model()), case.path(), &start, &options).unwrap();
    let hand = || floor::backward_euler(black_box(case.model()), case.path(), &start, 0.01, 400).unwrap();
    c.bench_function("floor/navy-planar/project run dt=0.01", |b| b.iter(project));
    c.bench_function("floor/navy-planar/hand-written 10x10 dt=0.01", |b| b.iter(hand));
    // interleaved rounds: the ratio of the medians, measured side by side
    let mut times = [Vec::new(), Vec::new()];
    for _ in 0..300 {
        let clock = std::time::Instant::now();
        black_box(project());
        times[0].push(clock.elapsed().as_secs_f64());
        let clock = std::time::Instant::now();
        black_box(hand());
        times[1].push(clock.elapsed().as_secs_f64());
    }
    let [project_median, hand_median] = times.map(|mut t| {
        t.sort_by(f64::total_cmp);
        t[t.len() / 2]
    });
    println!(
        "floor/navy-planar: project {:.3} ms, hand-written 10x10 {:.3} ms per run (medians of 300 interleaved \
         rounds): ratio {:.2}",
        project_median * 1e3,
        hand_median * 1e3,
        project_median / hand_median
    );
}

criterion_group!(navy_planar, benches, schemes, floor_group);
criterion_main!(navy_planar);
