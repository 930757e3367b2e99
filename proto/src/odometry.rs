//! Odometry: the motor controller's wheel odometry, sent to the terrain service so
//! that it can move what it saw with the rover.
//!
//! Every field is a *cumulative* counter that wraps: the receiver takes the
//! difference to the last message it has, modulo the counter's range, read as a signed
//! number. A lost message costs nothing (the next one carries the whole travel since),
//! and a wrap-around is an ordinary step. The differences are unambiguous while less
//! than half of each range passes between two received messages: 32.7 m forward,
//! 0.256 m sideways, 180° of heading, 32.7 s, 128 messages. A receiver that hears
//! nothing for longer than its timeout (well under all of these) must not trust the
//! next difference: it starts again from that message.

use crate::message::DecodeError;

/// Range of the forward counter, millimetres (16 bits).
pub const FORWARD_WRAP_MM: u32 = 1 << 16;
/// Range of the lateral counter, millimetres (8 bits of 2 mm).
pub const LATERAL_WRAP_MM: u32 = 512;
/// Heading units per turn (16 bits).
pub const HEADING_UNITS_PER_TURN: u32 = 1 << 16;
/// Range of the timestamp, milliseconds (16 bits).
pub const TIME_WRAP_MS: u32 = 1 << 16;

/// One odometry message, in wire units: all counters wrap.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Odometry {
    /// Message counter (wraps).
    pub seq: u8,
    /// The controller's clock when the counters were read, ms (wraps every 65.536 s).
    pub time_ms: u16,
    /// Forward travel of the rover's reference point along its own x axis, summed,
    /// mm (wraps every 65.536 m; backwards travel counts down).
    pub forward_mm: u16,
    /// Sideways travel along the rover's y axis (left positive), summed, 2 mm units
    /// (wraps every 0.512 m). Wheel odometry of a skid-steered rover reads 0 here.
    pub lateral_2mm: u8,
    /// Heading, counter-clockwise seen from above, 1/65536 turn (wraps every turn).
    pub heading: u16,
}

/// The motion between two odometry messages, from the wrapped differences of their
/// counters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// Messages between the two (1 when consecutive; more when some were lost).
    pub messages: u8,
    /// Controller time between the two, ms.
    pub dt_ms: i32,
    /// Forward travel, mm.
    pub forward_mm: i32,
    /// Sideways travel, mm.
    pub lateral_mm: i32,
    /// Heading change, radians, counter-clockwise positive, in (−π, π].
    pub dheading_rad: f32,
}

/// The signed difference `b − a` of two counters of range `wrap` (a power of two).
fn wrapped(a: u32, b: u32, wrap: u32) -> i32 {
    let d = b.wrapping_sub(a) & (wrap - 1);
    if d >= wrap / 2 {
        d as i32 - wrap as i32
    } else {
        d as i32
    }
}

impl Odometry {
    /// The 8 bytes (CAN frame `can::ODOMETRY_ID`, serial type `TYPE_ODOMETRY`):
    ///
    /// ```text
    /// byte 0    message counter (wraps)
    /// byte 1-2  controller time, ms, u16 LE (wraps)
    /// byte 3-4  forward travel, mm, u16 LE (wraps)
    /// byte 5    lateral travel, 2 mm, u8 (wraps)
    /// byte 6-7  heading, 1/65536 turn, u16 LE, counter-clockwise (wraps)
    /// ```
    pub fn encode(&self) -> [u8; 8] {
        let t = self.time_ms.to_le_bytes();
        let f = self.forward_mm.to_le_bytes();
        let h = self.heading.to_le_bytes();
        [
            self.seq,
            t[0],
            t[1],
            f[0],
            f[1],
            self.lateral_2mm,
            h[0],
            h[1],
        ]
    }

    /// Decode 8 bytes. Every bit pattern is a valid message (all fields are wrapping
    /// counters); the `Result` is for symmetry with the other messages.
    pub fn decode(b: &[u8; 8]) -> Result<Self, DecodeError> {
        Ok(Odometry {
            seq: b[0],
            time_ms: u16::from_le_bytes([b[1], b[2]]),
            forward_mm: u16::from_le_bytes([b[3], b[4]]),
            lateral_2mm: b[5],
            heading: u16::from_le_bytes([b[6], b[7]]),
        })
    }

    /// Counters for a pose: cumulative travel in metres and heading in radians, as a
    /// controller would send them (rounded to the wire's units, wrapped).
    pub fn from_pose(
        seq: u8,
        time_ms: u64,
        forward_m: f64,
        lateral_m: f64,
        heading_rad: f64,
    ) -> Self {
        let turn = heading_rad / core::f64::consts::TAU;
        Odometry {
            seq,
            time_ms: time_ms as u16,
            forward_mm: round(forward_m * 1000.0) as i64 as u16,
            lateral_2mm: round(lateral_m * 500.0) as i64 as u8,
            heading: round((turn - floor(turn)) * f64::from(HEADING_UNITS_PER_TURN)) as i64 as u16,
        }
    }

    /// The motion from `earlier` to `self`, by the counters' wrapped differences.
    pub fn since(&self, earlier: &Odometry) -> Motion {
        let dh = wrapped(
            u32::from(earlier.heading),
            u32::from(self.heading),
            HEADING_UNITS_PER_TURN,
        );
        Motion {
            messages: self.seq.wrapping_sub(earlier.seq),
            dt_ms: wrapped(
                u32::from(earlier.time_ms),
                u32::from(self.time_ms),
                TIME_WRAP_MS,
            ),
            forward_mm: wrapped(
                u32::from(earlier.forward_mm),
                u32::from(self.forward_mm),
                FORWARD_WRAP_MM,
            ),
            lateral_mm: 2 * wrapped(
                u32::from(earlier.lateral_2mm),
                u32::from(self.lateral_2mm),
                256,
            ),
            dheading_rad: (f64::from(dh) * core::f64::consts::TAU
                / f64::from(HEADING_UNITS_PER_TURN)) as f32,
        }
    }
}

/// `f64::round` without `std`: half away from zero.
fn round(x: f64) -> f64 {
    let t = x as i64 as f64; // truncation toward zero; counters stay far inside i64
    let r = x - t;
    if r >= 0.5 {
        t + 1.0
    } else if r <= -0.5 {
        t - 1.0
    } else {
        t
    }
}

/// `f64::floor` without `std`.
fn floor(x: f64) -> f64 {
    let t = x as i64 as f64;
    if t > x {
        t - 1.0
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn differences_cross_every_wrap() {
        let a = Odometry::from_pose(250, 65_500, 65.5, 0.5, -0.01);
        let b = Odometry::from_pose(4, 65_600, 65.6, 0.52, 0.02);
        let m = b.since(&a);
        assert_eq!(m.messages, 10);
        assert_eq!(m.dt_ms, 100);
        assert_eq!(m.forward_mm, 100);
        assert_eq!(m.lateral_mm, 20);
        assert!((m.dheading_rad - 0.03).abs() < 1e-4, "{}", m.dheading_rad);
        // Backwards is the same difference, negated.
        let back = a.since(&b);
        assert_eq!(
            (back.forward_mm, back.lateral_mm, back.dt_ms),
            (-100, -20, -100)
        );
        assert!((back.dheading_rad + 0.03).abs() < 1e-4);
    }

    #[test]
    fn bytes_round_trip_and_every_pattern_decodes() {
        let o = Odometry::from_pose(7, 1234, -1.5, -0.1, 3.0);
        assert_eq!(Odometry::decode(&o.encode()), Ok(o));
        for b in [[0u8; 8], [0xFF; 8], [0x80, 0, 0xFF, 1, 2, 3, 4, 5]] {
            assert_eq!(Odometry::decode(&b).unwrap().encode(), b);
        }
    }
}
