//! Framing for a byte stream (a serial line, a pipe, a file).
//!
//! ```text
//! raw frame:  version (1) | type (1) | payload (verdict 16: core + ext; heartbeat 8;
//!             odometry 8) | CRC-16 (2, LE)
//! on the wire: COBS(raw frame) followed by one 0x00 delimiter
//! ```
//!
//! The CRC is CRC-16/IBM-3740 (also called CCITT-FALSE: width 16, polynomial 0x1021,
//! initial value 0xFFFF, no reflection, no final XOR, check value 0x29B1 for the
//! ASCII "123456789"), computed over version, type and payload.
//!
//! [`Decoder`] takes bytes one at a time: garbage before a delimiter is one rejected
//! frame, never more; a frame longer than any message is rejected at its delimiter.

use crate::message::{DecodeError, Heartbeat, Verdict};
use crate::odometry::Odometry;
use crate::VERSION;

/// Message type of a verdict frame.
pub const TYPE_VERDICT: u8 = 0x01;
/// Message type of a heartbeat frame.
pub const TYPE_HEARTBEAT: u8 = 0x02;
/// Message type of an odometry frame (controller to service).
pub const TYPE_ODOMETRY: u8 = 0x03;
/// The frame CRC: CRC-16/IBM-3740 (CCITT-FALSE).
pub const CRC: crc::Crc<u16> = crc::Crc::<u16>::new(&crc::CRC_16_IBM_3740);
/// Longest raw frame: header 2 + payload 16 + CRC 2.
pub const MAX_RAW: usize = 20;
/// Longest frame on the wire: COBS adds one byte per 254, plus the delimiter.
pub const MAX_WIRE: usize = MAX_RAW + 2;

/// A decoded message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Message {
    /// A verdict.
    Verdict(Verdict),
    /// A heartbeat.
    Heartbeat(Heartbeat),
    /// The controller's odometry.
    Odometry(Odometry),
}

/// One encoded frame, delimiter included.
pub type WireFrame = heapless::Vec<u8, MAX_WIRE>;

/// Encode a message into one wire frame (COBS, delimiter last). Never allocates.
pub fn encode(msg: &Message) -> WireFrame {
    let mut raw = [0u8; MAX_RAW];
    raw[0] = VERSION;
    let len = match msg {
        Message::Verdict(v) => {
            raw[1] = TYPE_VERDICT;
            raw[2..10].copy_from_slice(&v.core());
            raw[10..18].copy_from_slice(&v.ext());
            18
        }
        Message::Heartbeat(h) => {
            raw[1] = TYPE_HEARTBEAT;
            raw[2..10].copy_from_slice(&h.encode());
            10
        }
        Message::Odometry(o) => {
            raw[1] = TYPE_ODOMETRY;
            raw[2..10].copy_from_slice(&o.encode());
            10
        }
    };
    let crc = CRC.checksum(&raw[..len]).to_le_bytes();
    raw[len] = crc[0];
    raw[len + 1] = crc[1];
    let mut out = [0u8; MAX_WIRE];
    let n = cobs::encode(&raw[..len + 2], &mut out);
    let mut frame = WireFrame::new();
    // n ≤ MAX_RAW + 1 by COBS's bound; the delimiter makes MAX_WIRE.
    let _ = frame.extend_from_slice(&out[..n]);
    let _ = frame.push(0);
    frame
}

/// Decode one COBS-encoded frame (without its delimiter), in place.
pub fn decode_frame(encoded: &mut [u8]) -> Result<Message, DecodeError> {
    let n = cobs::decode_in_place(encoded).map_err(|_| DecodeError::Cobs)?;
    let raw = &encoded[..n];
    if raw.len() < 4 {
        return Err(DecodeError::TooShort);
    }
    let (body, crc) = raw.split_at(raw.len() - 2);
    if body[0] != VERSION {
        return Err(DecodeError::Version(body[0]));
    }
    let payload = &body[2..];
    let expected = match body[1] {
        TYPE_VERDICT => 16,
        TYPE_HEARTBEAT | TYPE_ODOMETRY => 8,
        t => return Err(DecodeError::Type(t)),
    };
    if payload.len() != expected {
        return Err(DecodeError::Length {
            kind: body[1],
            got: payload.len().min(255) as u8,
        });
    }
    let received = u16::from_le_bytes([crc[0], crc[1]]);
    let computed = CRC.checksum(body);
    if computed != received {
        return Err(DecodeError::Crc { computed, received });
    }
    let mut a = [0u8; 8];
    a.copy_from_slice(&payload[..8]);
    match body[1] {
        TYPE_HEARTBEAT => return Heartbeat::decode(&a).map(Message::Heartbeat),
        TYPE_ODOMETRY => return Odometry::decode(&a).map(Message::Odometry),
        _ => {}
    }
    let mut b = [0u8; 8];
    b.copy_from_slice(&payload[8..16]);
    Verdict::from_parts(&a, &b).map(Message::Verdict)
}

/// A streaming decoder: push bytes as they arrive, get a message (or the reason a
/// frame was rejected) at each delimiter.
#[derive(Debug, Default)]
pub struct Decoder {
    buf: heapless::Vec<u8, MAX_WIRE>,
    overflow: bool,
}

impl Decoder {
    /// A decoder waiting for a frame.
    pub const fn new() -> Self {
        Decoder {
            buf: heapless::Vec::new(),
            overflow: false,
        }
    }

    /// Take one byte. Returns `Some` at a delimiter that ends a non-empty frame.
    pub fn push(&mut self, byte: u8) -> Option<Result<Message, DecodeError>> {
        if byte != 0 {
            if self.buf.push(byte).is_err() {
                self.overflow = true;
            }
            return None;
        }
        let overflow = core::mem::replace(&mut self.overflow, false);
        if overflow {
            self.buf.clear();
            return Some(Err(DecodeError::TooLong));
        }
        if self.buf.is_empty() {
            return None;
        }
        let result = decode_frame(&mut self.buf);
        self.buf.clear();
        Some(result)
    }
}
