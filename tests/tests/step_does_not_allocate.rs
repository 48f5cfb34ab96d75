//! The per-step path of the integrator does not allocate: a counting global
//! allocator sees zero allocations across 400 steps of `navy-planar`,
//! including the first steps from the degenerate start where Newton falls
//! back to the minimum-norm solve.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use crane_models::Case;
use crane_models::navy_planar::PaperCase;
use crane_runtime::RedundantStepper;
use crane_runtime::newton::NewtonOptions;

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn stepping_does_not_allocate() {
    for dt in [0.01, 0.001] {
        let case = PaperCase::new(4.0).unwrap();
        let start = case.start().unwrap();
        let mut stepper = RedundantStepper::new(case.model(), case.path(), &start, dt, NewtonOptions::default()).unwrap();
        let steps = (4.0 / dt).round() as usize;
        let mut min_norm = 0;
        let before = ALLOCATIONS.load(Ordering::SeqCst);
        for _ in 0..steps {
            min_norm += stepper.step().unwrap().min_norm_steps;
        }
        let allocations = ALLOCATIONS.load(Ordering::SeqCst) - before;
        assert_eq!(allocations, 0, "dt = {dt}: {allocations} allocations in {steps} steps");
        assert!((stepper.state().t - 4.0).abs() < 1e-9);
        println!("dt = {dt}: {steps} steps, {min_norm} minimum-norm Newton steps, 0 allocations");
    }
}
