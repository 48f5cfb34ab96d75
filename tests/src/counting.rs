//! A counting global allocator for the tests that check the per-step path
//! does not allocate: install it in the test binary with
//! `#[global_allocator] static GLOBAL: Counting = Counting;` and measure with
//! [`allocations_during`]. Only the allocations of the measuring thread
//! count: the test harness's own thread allocates now and then while a test
//! runs (seen: 4 allocations in one of three runs).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, counting allocations and reallocations.
pub struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    static COUNTED: Cell<bool> = const { Cell::new(false) };
}

fn count() {
    if COUNTED.with(Cell::get) {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
    }
}

// SAFETY: every call is forwarded to the system allocator unchanged
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// The allocations of this thread while `f` runs, and its result.
pub fn allocations_during<R>(f: impl FnOnce() -> R) -> (usize, R) {
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    COUNTED.with(|c| c.set(true));
    let result = f();
    COUNTED.with(|c| c.set(false));
    (ALLOCATIONS.load(Ordering::SeqCst) - before, result)
}

/// Panics unless the counter sees the one allocation of a `Vec` (else a
/// test of zero allocations could not fail; with [`Counting`] installed).
pub fn assert_counter_works() {
    let (allocations, v) = allocations_during(|| std::hint::black_box(vec![1u8; 16]));
    drop(v);
    assert_eq!(allocations, 1, "the counting allocator missed an allocation");
}
