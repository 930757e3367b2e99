//! Any byte stream into the serial decoder and the CAN reassembler: never a panic,
//! and every message it accepts re-encodes to the very frame it came from.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rover_terrain_proto::can::{Assembler, Frame};
use rover_terrain_proto::serial::{encode, Decoder, Message};

fuzz_target!(|data: &[u8]| {
    let mut decoder = Decoder::new();
    let mut since_delimiter: Vec<u8> = Vec::new();
    for &b in data {
        if b != 0 {
            since_delimiter.push(b);
        }
        if let Some(Ok(msg)) = decoder.push(b) {
            let mut frame = encode(&msg).to_vec();
            frame.pop();
            assert_eq!(frame, since_delimiter, "accepted {msg:?} from bytes that do not re-encode to it");
            if let Message::Verdict(v) = msg {
                assert!(v.workcase <= 10);
            }
        }
        if b == 0 {
            since_delimiter.clear();
        }
    }
    let mut assembler = Assembler::default();
    for chunk in data.chunks_exact(10) {
        let id = u16::from_le_bytes([chunk[0], chunk[1]]) & 0x7FF;
        let mut d = [0u8; 8];
        d.copy_from_slice(&chunk[2..]);
        let _ = assembler.push(&Frame { id, data: d });
    }
});
