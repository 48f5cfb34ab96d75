//! Criterion benchmarks of the `navy-planar` inverse dynamics: a full run at
//! dt = 0.01 (400 steps) and dt = 0.001 (4000 steps), and a single step, for
//! the generated model and the hand-written one (the target: generated code
//! costs no more than hand-written code).
//!
//! Run with `cargo bench -p crane-tests`.

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use std::hint::black_box;

use crane_models::Case;
use crane_models::navy_planar::PaperCase;
use crane_runtime::newton::NewtonOptions;
use crane_runtime::{CraneModel, Options, RedundantStepper, State, simulate};
use crane_tests::handwritten::HandNavyPlanar;

fn full_runs<Mdl: CraneModel<7, 3, 2>>(c: &mut Criterion, label: &str, model: &Mdl) {
    let case = PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    for dt in [0.01, 0.001] {
        let options = Options::new(dt, 4.0);
        c.bench_function(&format!("navy-planar/{label}/run dt={dt}"), |b| {
            b.iter(|| simulate(black_box(model), case.path(), &start, &options).unwrap())
        });
    }
    // one step at t = 1.5 s, dt = 0.01, from the state a run reaches there
    let solution = simulate(model, case.path(), &start, &Options::new(0.01, 4.0)).unwrap();
    let state: State<7, 3, 2> = solution.states[150];
    c.bench_function(&format!("navy-planar/{label}/one step dt=0.01"), |b| {
        b.iter_batched_ref(
            || RedundantStepper::new(model, case.path(), &state, 0.01, NewtonOptions::default()).unwrap(),
            |stepper| stepper.step().unwrap(),
            BatchSize::SmallInput,
        )
    });
}

fn benches(c: &mut Criterion) {
    full_runs(c, "generated", &crane_models::navy_planar::NavyPlanar::default());
    full_runs(c, "hand-written", &HandNavyPlanar::default());
}

criterion_group!(navy_planar, benches);
criterion_main!(navy_planar);
