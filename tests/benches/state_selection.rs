//! Criterion benchmarks of state selection: the damped swing's move (4 s at
//! dt = 0.01 s, 400 steps) with its free swing integrated by BDF-2 and
//! everything else exact, against the same move in eqs. (22) with BDF-2,
//! and a flat crane's exact step of the reduced formulation (navy-planar,
//! 400 steps): the cost per step is each median divided by 400.
//!
//! Run with `cargo bench -p crane-tests --bench state_selection`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};

use crane_models::navy_planar;
use crane_models::study::Formulation;
use crane_runtime::nalgebra::vector;
use crane_runtime::redundant::Redundant;
use crane_runtime::trajectory::Poly9;
use crane_runtime::{Options, Scheme, driver, init, state_selection};
use crane_tests::damped::DampedSwing;

fn runs(c: &mut Criterion) {
    let crane = DampedSwing::default();
    let path = Poly9::new(0.0, 4.0, vector![0.0, -5.0], vector![3.0, -4.0]).unwrap();
    let start = init::static_equilibrium(&crane, &path, 0.0, &[0.0, 5.0, 0.0, -2.0]).unwrap();
    let options = Options::new(0.01, 4.0).unwrap().with_scheme(Scheme::bdf(2).unwrap());
    let mut group = c.benchmark_group("state_selection");
    group.sample_size(30);
    group.bench_function("damped swing, state selection, BDF-2 (400 steps)", |b| {
        b.iter(|| black_box(state_selection::simulate(&crane, &path, &start, &options, &mut |_, _| {}).unwrap()))
    });
    group.bench_function("damped swing, eqs. (22), BDF-2 (400 steps)", |b| {
        b.iter(|| black_box(driver::solve(Redundant::new(&crane, &path), &start, &options, &mut |_, _| {}).unwrap()))
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
