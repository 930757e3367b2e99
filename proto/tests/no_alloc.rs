//! Encoding and decoding allocate nothing (a counting global allocator watches).
//! Only the test's own thread is counted: the test harness's threads allocate when
//! they please (reporting, timing), and counting them made the test flaky on a busy
//! machine.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

use rover_terrain_proto::can::{self, Assembler};
use rover_terrain_proto::serial::{encode, Decoder, Message};
use rover_terrain_proto::{Decision, Heartbeat, ServiceState, Verdict};

struct Counting;
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    /// Whether this thread's allocations count (a const initialiser: reading it
    /// allocates nothing).
    static COUNTING: Cell<bool> = const { Cell::new(false) };
}

// Safety: defers to the system allocator; only counts.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        }
        // Safety: same contract as ours.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // Safety: same contract as ours.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn encode_and_decode_allocate_nothing() {
    let v = Verdict {
        decision: Decision::Go,
        hazard: None,
        workcase: 2,
        seq: 5,
        age_10ms: 1,
        distance_cm: Some(68),
        gradient_ddeg: Some(200),
        alpha_ddeg: None,
        seen_permille: 580,
    };
    let h = Heartbeat {
        state: ServiceState::Running,
        camera_ok: true,
        memory_fused: true,
        frame_rate_chz: 3000,
        dropped: 0,
        seq: 1,
    };
    let mut decoder = Decoder::new();
    let mut assembler = Assembler::default();
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    COUNTING.with(|c| c.set(true));
    let mut delivered = 0;
    for k in 0..1000u32 {
        let mut v = v;
        v.seq = k;
        let o = rover_terrain_proto::Odometry::from_pose(
            k as u8,
            u64::from(k) * 20,
            f64::from(k) * 0.01,
            0.0,
            0.1,
        );
        for msg in [
            Message::Verdict(v),
            Message::Heartbeat(h),
            Message::Odometry(o),
        ] {
            for &b in encode(&msg).iter() {
                if let Some(Ok(m)) = decoder.push(b) {
                    delivered += usize::from(m == msg);
                }
            }
        }
        for f in can::verdict_frames(&v) {
            let _ = assembler.push(&f);
        }
        let _ = assembler.push(&can::odometry_frame(&o));
    }
    COUNTING.with(|c| c.set(false));
    assert_eq!(ALLOCATIONS.load(Ordering::SeqCst) - before, 0);
    assert_eq!(delivered, 3000);
}
