//! CAN frames (classic CAN 2.0A, 11-bit identifiers, 8 data bytes each). A verdict
//! is two frames, core then extension, with the same sequence byte; a receiver that
//! reads only the core still has the decision, hazard, workcase, distance and
//! gradient. `config/rover-terrain.dbc` describes the same layout for CAN tools.

use crate::message::{DecodeError, Heartbeat, Verdict};
use crate::odometry::Odometry;

/// Verdict core.
pub const VERDICT_ID: u16 = 0x310;
/// Verdict extension.
pub const VERDICT_EXT_ID: u16 = 0x311;
/// Heartbeat.
pub const HEARTBEAT_ID: u16 = 0x312;
/// Odometry, from the motor controller to the terrain service.
pub const ODOMETRY_ID: u16 = 0x320;

/// One CAN frame: identifier and 8 data bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Frame {
    /// 11-bit identifier.
    pub id: u16,
    /// Data.
    pub data: [u8; 8],
}

/// The two frames of a verdict, core first.
pub fn verdict_frames(v: &Verdict) -> [Frame; 2] {
    [
        Frame {
            id: VERDICT_ID,
            data: v.core(),
        },
        Frame {
            id: VERDICT_EXT_ID,
            data: v.ext(),
        },
    ]
}

/// The frame of a heartbeat.
pub fn heartbeat_frame(h: &Heartbeat) -> Frame {
    Frame {
        id: HEARTBEAT_ID,
        data: h.encode(),
    }
}

/// The frame of an odometry message.
pub fn odometry_frame(o: &Odometry) -> Frame {
    Frame {
        id: ODOMETRY_ID,
        data: o.encode(),
    }
}

/// Reassembles verdicts from core and extension frames; a core without its
/// extension is still delivered (with the low sequence byte), never lost.
#[derive(Debug, Default)]
pub struct Assembler {
    pending: Option<[u8; 8]>,
}

/// What one CAN frame completed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Received {
    /// A verdict with its extension.
    Verdict(Verdict),
    /// A verdict core whose extension did not follow (the previous core, when a
    /// new core arrives).
    CoreOnly(Verdict),
    /// A heartbeat.
    Heartbeat(Heartbeat),
    /// The controller's odometry.
    Odometry(Odometry),
    /// A frame with another identifier.
    Other,
}

impl Assembler {
    /// Take one frame; the result and, when a core was left without its extension,
    /// that core too.
    pub fn push(&mut self, f: &Frame) -> (Result<Received, DecodeError>, Option<Received>) {
        match f.id {
            VERDICT_ID => {
                let orphan = self
                    .pending
                    .replace(f.data)
                    .and_then(|c| Verdict::from_core(&c).ok())
                    .map(Received::CoreOnly);
                (Ok(Received::Other), orphan)
            }
            VERDICT_EXT_ID => match self.pending.take() {
                Some(core) => (
                    Verdict::from_parts(&core, &f.data).map(Received::Verdict),
                    None,
                ),
                None => (Err(DecodeError::Inconsistent), None),
            },
            HEARTBEAT_ID => (Heartbeat::decode(&f.data).map(Received::Heartbeat), None),
            ODOMETRY_ID => (Odometry::decode(&f.data).map(Received::Odometry), None),
            _ => (Ok(Received::Other), None),
        }
    }
}
