//! Criterion benchmarks of stable inversion against the causal runs: the
//! coupled trolley's default move at dt = 0.01 s solved whole by stable
//! inversion (914 nodes from t0 - T_pre to tf + T_post, 3 Newton
//! iterations of one sparse LU each), the same move causally in eqs. (22)
//! with backward Euler (500 steps; inputs that run away), and navy-planar's
//! flat move in its reduced formulation (400 steps): the cost per node or
//! step is each median divided by its count.
//!
//! Run with `cargo bench -p crane-tests --bench stable_inversion`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};

use crane_models::study::Formulation;
use crane_models::{coupled_trolley, navy_planar};
use crane_runtime::Options;

fn runs(c: &mut Criterion) {
    let coupled = coupled_trolley::DefaultCase::maneuver().unwrap();
    let start = coupled.start().unwrap();
    let options = Options::new(0.01, coupled.tf()).unwrap();
    let mut group = c.benchmark_group("stable_inversion");
    group.sample_size(20);
    group.bench_function("coupled-trolley stable inversion (914 nodes)", |b| {
        b.iter(|| black_box(coupled.simulate_stable_inversion(&start, &options).unwrap()))
    });
    group.bench_function("coupled-trolley eqs. (22) causal (500 steps)", |b| {
        b.iter(|| {
            black_box(
                Formulation::Redundant
                    .simulate(&coupled, &start, &options, &mut |_, _| {})
                    .unwrap(),
            )
        })
    });
    let paper = navy_planar::PaperCase::new(4.0).unwrap();
    let paper_start = paper.start().unwrap();
    let paper_options = Options::new(0.01, 4.0).unwrap();
    group.bench_function("navy-planar reduced (400 steps)", |b| {
        b.iter(|| {
            black_box(
                Formulation::DummyDerivative
                    .simulate(&paper, &paper_start, &paper_options, &mut |_, _| {})
                    .unwrap(),
            )
        })
    });
    group.finish();
}

criterion_group!(benches, runs);
criterion_main!(benches);
