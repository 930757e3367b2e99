//! The messages and their 8-byte encodings.

/// The decision.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Decision {
    /// The corridor can be crossed.
    Go = 0,
    /// A hazard makes it impassable.
    Stop = 1,
    /// Too little is known; treat as stop.
    Unknown = 2,
}

/// The kind of the hazard that decided a stop or unknown.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HazardKind {
    /// Slope at or above the maximum in a wheel track.
    Slope = 1,
    /// Step higher than the wheel radius.
    Step = 2,
    /// Something too tall under the belly.
    Belly = 3,
    /// The ground ends.
    DropOff = 4,
    /// Ground that should be seen is not.
    Unknown = 5,
    /// The rover's predicted roll or pitch passes the operator's limit.
    Tilt = 6,
}

/// Where the hazard is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Side {
    /// Left wheel track.
    Left = 0,
    /// Under the belly, or the whole corridor.
    Centre = 1,
    /// Right wheel track.
    Right = 2,
}

/// One verdict, in wire units.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Verdict {
    /// Go, stop or unknown.
    pub decision: Decision,
    /// The deciding hazard, if any.
    pub hazard: Option<(HazardKind, Side)>,
    /// Workcase 1-10, or 0 when not go.
    pub workcase: u8,
    /// Sequence number (frame number); the CAN core carries its low byte.
    pub seq: u32,
    /// Frame age when sent (capture to send), 10 ms units; 255 = 2.55 s or more.
    pub age_10ms: u8,
    /// Distance to the toe line (go) or to the deciding hazard, cm; `None` if none.
    pub distance_cm: Option<u16>,
    /// Gradient, 0.1°, negative downhill; `None` if none.
    pub gradient_ddeg: Option<i16>,
    /// Toe-line angle, 0.1°; `None` if none.
    pub alpha_ddeg: Option<i16>,
    /// Fraction of the corridor seen, 0.1 % (0-1000).
    pub seen_permille: u16,
}

/// The service's state, as a heartbeat tells it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ServiceState {
    /// Starting: camera not open yet.
    Starting = 0,
    /// Running: frames flowing, verdicts sent.
    Running = 1,
    /// Degraded: no frames within the frame timeout (verdicts are unknown).
    Degraded = 2,
    /// Stopping: shutting down.
    Stopping = 3,
}

/// The heartbeat/status message: lets the controller tell "no verdicts" from "no
/// service".
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Heartbeat {
    /// Service state.
    pub state: ServiceState,
    /// Whether the camera delivers frames.
    pub camera_ok: bool,
    /// Whether the last verdict was fused with the terrain memory (odometry
    /// trusted); false when the memory is off or fell back to single frames.
    pub memory_fused: bool,
    /// Frame rate, 0.01 Hz.
    pub frame_rate_chz: u16,
    /// Frames dropped since start (saturating).
    pub dropped: u16,
    /// Heartbeat counter (wraps).
    pub seq: u8,
}

/// Why bytes are not a valid message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DecodeError {
    /// The COBS encoding is broken.
    Cobs,
    /// A frame longer than any message (bytes lost until the next delimiter).
    TooLong,
    /// A frame too short to hold a header and a CRC.
    TooShort,
    /// An unknown protocol version.
    Version(u8),
    /// An unknown message type.
    Type(u8),
    /// The payload length does not fit the message type.
    Length {
        /// Message type.
        kind: u8,
        /// Payload bytes received.
        got: u8,
    },
    /// The CRC does not match.
    Crc {
        /// CRC computed over the frame.
        computed: u16,
        /// CRC carried by the frame.
        received: u16,
    },
    /// A field holds a value the protocol does not define (byte offset in payload).
    Field(u8),
    /// The verdict's core and extension disagree (sequence number).
    Inconsistent,
}

const NONE_U16: u16 = 0xFFFF;
const NONE_I16: i16 = i16::MIN;

fn opt_u16(v: u16) -> Option<u16> {
    (v != NONE_U16).then_some(v)
}

fn opt_i16(v: i16) -> Option<i16> {
    (v != NONE_I16).then_some(v)
}

impl Decision {
    fn from_bits(b: u8) -> Option<Self> {
        match b {
            0 => Some(Decision::Go),
            1 => Some(Decision::Stop),
            2 => Some(Decision::Unknown),
            _ => None,
        }
    }
}

impl HazardKind {
    fn from_bits(b: u8) -> Option<Option<Self>> {
        match b {
            0 => Some(None),
            1 => Some(Some(HazardKind::Slope)),
            2 => Some(Some(HazardKind::Step)),
            3 => Some(Some(HazardKind::Belly)),
            4 => Some(Some(HazardKind::DropOff)),
            5 => Some(Some(HazardKind::Unknown)),
            6 => Some(Some(HazardKind::Tilt)),
            _ => None,
        }
    }
}

impl Side {
    fn from_bits(b: u8) -> Option<Self> {
        match b {
            0 => Some(Side::Left),
            1 => Some(Side::Centre),
            2 => Some(Side::Right),
            _ => None,
        }
    }
}

impl Verdict {
    /// The 8-byte core (CAN frame `can::VERDICT_ID`):
    ///
    /// ```text
    /// byte 0  bits 0-1 decision (0 go, 1 stop, 2 unknown)
    ///         bits 2-4 hazard kind (0 none, 1 slope, 2 step, 3 belly, 4 drop-off, 5 unknown)
    ///         bits 5-6 hazard side (0 left, 1 centre, 2 right; 0 when no hazard)
    ///         bit  7   0
    /// byte 1  workcase 0-10 (0 = none)
    /// byte 2  sequence number, low byte
    /// byte 3  frame age, 10 ms (255 = 2.55 s or more)
    /// byte 4-5  distance, cm, u16 LE (0xFFFF = none)
    /// byte 6-7  gradient, 0.1°, i16 LE (0x8000 = none)
    /// ```
    pub fn core(&self) -> [u8; 8] {
        let (kind, side) = match self.hazard {
            Some((k, s)) => (k as u8, s as u8),
            None => (0, 0),
        };
        let d = self.distance_cm.unwrap_or(NONE_U16).to_le_bytes();
        let g = self.gradient_ddeg.unwrap_or(NONE_I16).to_le_bytes();
        [
            self.decision as u8 | kind << 2 | side << 5,
            self.workcase,
            self.seq as u8,
            self.age_10ms,
            d[0],
            d[1],
            g[0],
            g[1],
        ]
    }

    /// The 8-byte extension (CAN frame `can::VERDICT_EXT_ID`):
    ///
    /// ```text
    /// byte 0-1  alpha, 0.1°, i16 LE (0x8000 = none)
    /// byte 2-3  seen fraction, 0.1 %, u16 LE (0-1000)
    /// byte 4-7  sequence number, u32 LE
    /// ```
    pub fn ext(&self) -> [u8; 8] {
        let a = self.alpha_ddeg.unwrap_or(NONE_I16).to_le_bytes();
        let s = self.seen_permille.to_le_bytes();
        let q = self.seq.to_le_bytes();
        [a[0], a[1], s[0], s[1], q[0], q[1], q[2], q[3]]
    }

    /// Decode a core alone (a CAN receiver without the extension): the sequence
    /// number is the low byte only, alpha and seen fraction are unknown (none, 0).
    pub fn from_core(b: &[u8; 8]) -> Result<Self, DecodeError> {
        let decision = Decision::from_bits(b[0] & 0b11).ok_or(DecodeError::Field(0))?;
        let kind = HazardKind::from_bits((b[0] >> 2) & 0b111).ok_or(DecodeError::Field(0))?;
        let side = Side::from_bits((b[0] >> 5) & 0b11).ok_or(DecodeError::Field(0))?;
        if b[0] & 0x80 != 0 || (kind.is_none() && side != Side::Left) {
            return Err(DecodeError::Field(0));
        }
        if b[1] > 10 || (decision == Decision::Go) != (b[1] != 0) {
            return Err(DecodeError::Field(1));
        }
        Ok(Verdict {
            decision,
            hazard: kind.map(|k| (k, side)),
            workcase: b[1],
            seq: u32::from(b[2]),
            age_10ms: b[3],
            distance_cm: opt_u16(u16::from_le_bytes([b[4], b[5]])),
            gradient_ddeg: opt_i16(i16::from_le_bytes([b[6], b[7]])),
            alpha_ddeg: None,
            seen_permille: 0,
        })
    }

    /// Decode core and extension together.
    pub fn from_parts(core: &[u8; 8], ext: &[u8; 8]) -> Result<Self, DecodeError> {
        let mut v = Self::from_core(core)?;
        let seen = u16::from_le_bytes([ext[2], ext[3]]);
        if seen > 1000 {
            return Err(DecodeError::Field(10));
        }
        let seq = u32::from_le_bytes([ext[4], ext[5], ext[6], ext[7]]);
        if seq as u8 != core[2] {
            return Err(DecodeError::Inconsistent);
        }
        v.seq = seq;
        v.alpha_ddeg = opt_i16(i16::from_le_bytes([ext[0], ext[1]]));
        v.seen_permille = seen;
        Ok(v)
    }
}

impl ServiceState {
    fn from_bits(b: u8) -> Option<Self> {
        match b {
            0 => Some(ServiceState::Starting),
            1 => Some(ServiceState::Running),
            2 => Some(ServiceState::Degraded),
            3 => Some(ServiceState::Stopping),
            _ => None,
        }
    }
}

impl Heartbeat {
    /// The 8 bytes (CAN frame `can::HEARTBEAT_ID`):
    ///
    /// ```text
    /// byte 0  state (0 starting, 1 running, 2 degraded, 3 stopping)
    /// byte 1  flags: bit 0 camera ok; bit 1 terrain memory fused; bits 2-7 0
    /// byte 2-3  frame rate, 0.01 Hz, u16 LE
    /// byte 4-5  dropped frames, u16 LE (saturating)
    /// byte 6  heartbeat counter
    /// byte 7  0
    /// ```
    pub fn encode(&self) -> [u8; 8] {
        let r = self.frame_rate_chz.to_le_bytes();
        let d = self.dropped.to_le_bytes();
        [
            self.state as u8,
            u8::from(self.camera_ok) | u8::from(self.memory_fused) << 1,
            r[0],
            r[1],
            d[0],
            d[1],
            self.seq,
            0,
        ]
    }

    /// Decode 8 bytes.
    pub fn decode(b: &[u8; 8]) -> Result<Self, DecodeError> {
        let state = ServiceState::from_bits(b[0]).ok_or(DecodeError::Field(0))?;
        if b[1] > 3 {
            return Err(DecodeError::Field(1));
        }
        if b[7] != 0 {
            return Err(DecodeError::Field(7));
        }
        Ok(Heartbeat {
            state,
            camera_ok: b[1] & 1 == 1,
            memory_fused: b[1] & 2 == 2,
            frame_rate_chz: u16::from_le_bytes([b[2], b[3]]),
            dropped: u16::from_le_bytes([b[4], b[5]]),
            seq: b[6],
        })
    }
}
