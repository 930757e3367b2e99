//! From the controller's odometry messages to the rover's motion between frames.

use rover_terrain_proto::Odometry;

use super::Motion;
use crate::config::MemoryConfig;

/// Why the motion since the last frame is not known (the verdict falls back to its
/// own frame, and the map starts again).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Untrusted {
    /// No odometry message yet, or none since the previous frame's.
    NoOdometry,
    /// The last message is older than `memory.odometry_timeout_s`.
    Timeout,
    /// The odometry implies a speed or turn rate the rover cannot have (a reset
    /// controller, a corrupted counter, lost messages spanning a wrap).
    Jump,
}

impl Untrusted {
    /// A short name for logs and the verdict.
    pub fn as_str(self) -> &'static str {
        match self {
            Untrusted::NoOdometry => "no_odometry",
            Untrusted::Timeout => "odometry_timeout",
            Untrusted::Jump => "odometry_jump",
        }
    }
}

/// Turns odometry messages (as they arrive) into the motion between frames (as they
/// are analysed). Allocation-free.
#[derive(Debug, Clone)]
pub struct Tracker {
    timeout_s: f64,
    max_speed_mps: f64,
    max_turn_rad_s: f64,
    /// The latest message and when it arrived (service clock, seconds).
    latest: Option<(Odometry, f64)>,
    /// The message the previous frame's motion ended at.
    at_last_frame: Option<Odometry>,
}

/// Slack on the speed and turn limits for timing jitter: metres and radians.
const SLACK_M: f64 = 0.05;
const SLACK_RAD: f64 = 0.05;

impl Tracker {
    /// A tracker with the limits of `[memory]`.
    pub fn new(m: &MemoryConfig) -> Self {
        Tracker {
            timeout_s: m.odometry_timeout_s,
            max_speed_mps: m.max_speed_mps,
            max_turn_rad_s: m.max_turn_dps.to_radians(),
            latest: None,
            at_last_frame: None,
        }
    }

    /// An odometry message arrived at `now_s` (service clock).
    pub fn on_odometry(&mut self, o: Odometry, now_s: f64) {
        self.latest = Some((o, now_s));
    }

    /// A frame arrived at `now_s` carrying the odometry recorded with it (a replayed
    /// drive): as if the message had just arrived. Bytes that are not an odometry
    /// message, or none, change nothing.
    pub fn on_recorded(&mut self, bytes: Option<[u8; 8]>, now_s: f64) {
        if let Some(o) = bytes.and_then(|b| Odometry::decode(&b).ok()) {
            self.on_odometry(o, now_s);
        }
    }

    /// The motion since the previous call, for a frame analysed at `now_s`: the
    /// difference of the latest message to the one the previous frame ended at.
    /// Every call moves the reference on, so an untrusted answer costs one frame.
    pub fn motion(&mut self, now_s: f64) -> Result<Motion, Untrusted> {
        let Some((latest, at)) = self.latest else {
            return Err(Untrusted::NoOdometry);
        };
        if now_s - at > self.timeout_s {
            self.at_last_frame = None;
            return Err(Untrusted::Timeout);
        }
        let Some(prev) = self.at_last_frame.replace(latest) else {
            return Err(Untrusted::NoOdometry);
        };
        let m = latest.since(&prev);
        let dt = f64::from(m.dt_ms) / 1000.0;
        let dist = f64::from(m.forward_mm).hypot(f64::from(m.lateral_mm)) / 1000.0;
        let turn = f64::from(m.dheading_rad).abs();
        // Time must not run backwards; the controller's dt bounds the motion (with a
        // little slack for the frame's own timing).
        let dt_ok = dt >= 0.0 && dt <= self.timeout_s + 1.0;
        if !dt_ok
            || dist > self.max_speed_mps * dt + SLACK_M
            || turn > self.max_turn_rad_s * dt + SLACK_RAD
        {
            return Err(Untrusted::Jump);
        }
        Ok(Motion {
            forward_m: m.forward_mm as f32 / 1000.0,
            lateral_m: m.lateral_mm as f32 / 1000.0,
            dheading_rad: m.dheading_rad,
            dt_s: dt as f32,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn odo(seq: u8, t_ms: u64, fwd: f64, heading: f64) -> Odometry {
        Odometry::from_pose(seq, t_ms, fwd, 0.0, heading)
    }

    #[test]
    fn motion_between_frames_across_lost_messages_and_wraps() {
        let mut t = Tracker::new(&MemoryConfig::default());
        assert_eq!(t.motion(0.0), Err(Untrusted::NoOdometry));
        t.on_odometry(odo(250, 65_500, 65.50, 0.0), 0.0);
        assert_eq!(
            t.motion(0.01),
            Err(Untrusted::NoOdometry),
            "the first is a start"
        );
        // Some messages lost, counters wrapped: 0.1 m and 2° in 100 ms.
        t.on_odometry(odo(3, 65_600, 65.60, 2f64.to_radians()), 0.1);
        let m = t.motion(0.11).unwrap();
        assert!((m.forward_m - 0.1).abs() < 1e-3 && (m.dt_s - 0.1).abs() < 1e-6);
        assert!((m.dheading_rad - 2f32.to_radians()).abs() < 2e-4);
        // No new message: no motion, not an error.
        let m = t.motion(0.15).unwrap();
        assert_eq!((m.forward_m, m.dheading_rad), (0.0, 0.0));
    }

    #[test]
    fn silence_and_jumps_are_not_trusted() {
        let cfg = MemoryConfig::default();
        let mut t = Tracker::new(&cfg);
        t.on_odometry(odo(0, 0, 0.0, 0.0), 0.0);
        let _ = t.motion(0.0);
        assert_eq!(t.motion(0.6), Err(Untrusted::Timeout), "0.5 s timeout");
        // It starts again from the next message.
        t.on_odometry(odo(1, 700, 0.1, 0.0), 0.7);
        assert_eq!(t.motion(0.7), Err(Untrusted::NoOdometry));
        // 1 m in 20 ms: 50 m/s, a jump.
        t.on_odometry(odo(2, 720, 1.1, 0.0), 0.72);
        assert_eq!(t.motion(0.72), Err(Untrusted::Jump));
        // 30° in 20 ms: a jump too.
        t.on_odometry(odo(3, 740, 1.1, 30f64.to_radians()), 0.74);
        assert_eq!(t.motion(0.74), Err(Untrusted::Jump));
        // Then ordinary motion is trusted again.
        t.on_odometry(odo(4, 760, 1.11, 30f64.to_radians()), 0.76);
        assert!(t.motion(0.76).is_ok());
    }
}
