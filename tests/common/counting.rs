//! A global allocator that counts allocations while [`COUNTING`] is set, for the
//! zero-allocation tests. Each test binary installs it with
//! `#[global_allocator] static GLOBAL: Counting = Counting;`.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// Defers to the system allocator; counts `alloc` and `realloc` calls, except on
/// the service's `viewer` thread (`run --mcap`, `--foxglove`: it builds pictures off
/// the hot path and may allocate), threads whose names start with `viewer` (a test's
/// Foxglove client), and the live server's tokio threads (`tokio-*`).
pub struct Counting;

thread_local! {
    /// This thread: 0 not yet asked, 1 the viewer (not counted), 2 counted,
    /// 3 being asked (an allocation while finding out counts).
    static EXEMPT: std::cell::Cell<u8> = const { std::cell::Cell::new(0) };
}

/// Whether allocations on this thread are not counted.
fn exempt() -> bool {
    EXEMPT
        .try_with(|e| match e.get() {
            0 => {
                e.set(3);
                let viewer = std::thread::current()
                    .name()
                    .is_some_and(|n| n.starts_with("viewer") || n.starts_with("tokio-"));
                e.set(if viewer { 1 } else { 2 });
                viewer
            }
            1 => true,
            _ => false,
        })
        .unwrap_or(false)
}

/// Count while this is set.
pub static COUNTING: AtomicBool = AtomicBool::new(false);
/// Allocations counted.
pub static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// Safety: defers every operation to the system allocator; only counts calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) && !exempt() {
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
        if COUNTING.load(Ordering::Relaxed) && !exempt() {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // Safety: same contract as ours.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}
