//! Criterion benchmarks of the exact inputs against the approximate ones:
//! per flat built-in crane, one step of its reduced (dummy-derivative)
//! system solved stage by stage, the same step solved whole (one LU of all
//! the jets), and one step of eqs. (22) with backward Euler, each from a
//! stepper that ran to t = 1.5 s itself (dt = 0.01 s).
//!
//! After criterion's lines, `reduced/table` prints per crane the median
//! time per step of whole runs of its default move in those three ways
//! and a fourth, the reduced system as the product runs it
//! (`DummyDerivativeStepper`: stage by stage, with the redundant problem
//! following each step to take over at a degenerate state), measured side
//! by side in interleaved rounds (each run's construction included), and
//! their ratios to eqs. (22).
//!
//! Run with `cargo bench -p crane-tests --bench reduced` (`-- table` for
//! the table alone).

use std::hint::black_box;
use std::time::Instant;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};

use crane_models::registry::{BuiltIn, Registry, Visit};
use crane_models::{Case, Crane};
use crane_runtime::dummy_derivative::{DummyDerivative, DummyDerivativeStepper};
use crane_runtime::model::{DummyDerivatives, VisitDummyDerivatives};
use crane_runtime::redundant::Redundant;
use crane_runtime::{Advance, CraneModel, Options, Stepper};

/// The three ways of one crane, with the system's size `J`.
struct Ways<'a, 'c, C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> {
    case: &'a Case<C, N, M, A>,
    c: &'c mut Criterion,
    table: bool,
}

impl<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> VisitDummyDerivatives<C::Model, N, M, A>
    for Ways<'_, '_, C, N, M, A>
{
    type Output = ();
    fn visit<const J: usize>(self)
    where
        C::Model: DummyDerivatives<N, M, A, J>,
    {
        let (model, path, name) = (self.case.model(), self.case.path(), C::NAME);
        let start = self.case.start().unwrap();
        let options = Options::new(0.01, self.case.tf()).unwrap();
        let staged = || Stepper::new(DummyDerivative::new(model, path), &start, &options).unwrap();
        let whole = || Stepper::new(DummyDerivative::new(model, path).solved_whole(), &start, &options).unwrap();
        let redundant = || Stepper::new(Redundant::new(model, path), &start, &options).unwrap();
        let as_run = || DummyDerivativeStepper::new(model, path, &start, &options).unwrap();
        if !self.table {
            let (mut a, mut b, mut r) = (staged(), whole(), redundant());
            for _ in 0..150 {
                a.step().unwrap();
                b.step().unwrap();
                r.step().unwrap();
            }
            // a fresh clone per timed step (see navy_planar.rs)
            self.c
                .bench_function(&format!("reduced/{name}/stage by stage/one step"), |bench| {
                    bench.iter_batched_ref(|| a.clone(), |s| s.step().unwrap(), BatchSize::PerIteration)
                });
            self.c
                .bench_function(&format!("reduced/{name}/whole/one step"), |bench| {
                    bench.iter_batched_ref(|| b.clone(), |s| s.step().unwrap(), BatchSize::PerIteration)
                });
            self.c
                .bench_function(&format!("reduced/{name}/eqs22 backward Euler/one step"), |bench| {
                    bench.iter_batched_ref(|| r.clone(), |s| s.step().unwrap(), BatchSize::PerIteration)
                });
            return;
        }
        // whole runs, interleaved: the median time per step of each way
        let tf = self.case.tf();
        let steps = ((tf - start.t) / 0.01).round() as usize;
        let run = |s: &mut dyn Advance<N, M, A, Model = C::Model>| {
            let clock = Instant::now();
            for _ in 0..steps {
                black_box(s.step().unwrap());
            }
            clock.elapsed().as_secs_f64()
        };
        let mut times = [Vec::new(), Vec::new(), Vec::new(), Vec::new()];
        for _ in 0..41 {
            let clock = Instant::now();
            let mut s = as_run();
            times[0].push(clock.elapsed().as_secs_f64() + run(&mut s));
            let clock = Instant::now();
            let mut s = staged();
            times[1].push(clock.elapsed().as_secs_f64() + run(&mut s));
            let clock = Instant::now();
            let mut s = whole();
            times[2].push(clock.elapsed().as_secs_f64() + run(&mut s));
            let clock = Instant::now();
            let mut s = redundant();
            times[3].push(clock.elapsed().as_secs_f64() + run(&mut s));
        }
        let [as_run, staged, whole, redundant] = times.map(|mut t| {
            t.sort_by(f64::total_cmp);
            t[t.len() / 2] / steps as f64 * 1e6
        });
        println!(
            "| {name} | {J} | {redundant:.2} | {whole:.2} | {staged:.2} | {as_run:.2} | {:.2} | {:.2} | {:.2} |",
            whole / redundant,
            staged / redundant,
            as_run / redundant
        );
    }
}

struct OnCrane<'c> {
    c: &'c mut Criterion,
    table: bool,
}

impl Visit for OnCrane<'_> {
    type Output = ();
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) {
        let case = Case::<C, N, M, A>::maneuver().unwrap();
        let ways = Ways {
            case: &case,
            c: self.c,
            table: self.table,
        };
        // cranes with internal dynamics have no flat reduced system
        if crane_runtime::dummy_derivative::system_size::<C::Model, N, M, A>().is_ok() {
            let _ = <C::Model as CraneModel<N, M, A>>::visit_dummy_derivatives(ways);
        }
    }
}

fn each_crane(c: &mut Criterion, table: bool) {
    let registry = BuiltIn;
    for entry in registry.entries() {
        registry.visit(entry.name, OnCrane { c: &mut *c, table });
    }
}

fn one_step(c: &mut Criterion) {
    each_crane(c, false);
}

/// Whether the command line's filter (criterion's, a substring of a
/// benchmark's name) asks for the table: no filter, or one in
/// `reduced/table`.
fn wants_table() -> bool {
    let filters: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    filters.is_empty() || filters.iter().any(|f| "reduced/table".contains(f.as_str()))
}

fn table(c: &mut Criterion) {
    if wants_table() {
        println!(
            "reduced/table: us per step, medians of 41 interleaved whole runs of each default move at dt = 0.01 s\n\
             | crane | J | eqs. (22), BE | reduced, whole | reduced, stage by stage | reduced, as run | whole / (22) | \
             stage by stage / (22) | as run / (22) |\n|---|---|---|---|---|---|---|---|---|"
        );
        each_crane(c, true);
    }
}

criterion_group!(reduced, one_step, table);
criterion_main!(reduced);
