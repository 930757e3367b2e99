//! A firmware-shaped user of the protocol crate: no std, no allocator.
#![no_std]

use rover_terrain_proto::serial::{self, Decoder, Message};
use rover_terrain_proto::{Command, Freshness};

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

/// Feed `len` bytes received at `now_ms` to the decoder; returns 1 to drive, 0 to stop.
///
/// # Safety
/// `bytes` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn controller_step(bytes: *const u8, len: usize, now_ms: u64) -> u8 {
    static mut STATE: Option<(Decoder, Freshness)> = None;
    // Safety: the caller passes a valid buffer; the firmware calls this from one
    // context only, so the static is not aliased.
    let (data, state) = unsafe { (core::slice::from_raw_parts(bytes, len), &mut *core::ptr::addr_of_mut!(STATE)) };
    let (decoder, guard) = state.get_or_insert_with(|| (Decoder::new(), Freshness::new(200)));
    for &b in data {
        if let Some(Ok(Message::Verdict(v))) = decoder.push(b) {
            guard.on_verdict(now_ms, v);
        }
    }
    let _ = serial::MAX_WIRE;
    u8::from(guard.command(now_ms) == Command::Go)
}
