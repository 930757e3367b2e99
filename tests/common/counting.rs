//! A global allocator that counts allocations while [`COUNTING`] is set, for the
//! zero-allocation tests. Each test binary installs it with
//! `#[global_allocator] static GLOBAL: Counting = Counting;`.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Defers to the system allocator; counts `alloc` and `realloc` calls.
pub struct Counting;

/// Count while this is set.
pub static COUNTING: AtomicBool = AtomicBool::new(false);
/// Allocations counted.
pub static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// Safety: defers every operation to the system allocator; only counts calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // Safety: same contract as ours.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // Safety: same contract as ours.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // Safety: same contract as ours.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}
