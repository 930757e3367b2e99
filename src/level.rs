//! Auto-level (beyond the paper): the camera's pitch and roll against gravity from
//! its accelerometer, to use instead of the configured mount angles when
//! `mount.auto_level` is on. Yaw is not observable from gravity and stays configured.
//!
//! The Kinect's accelerometer axes are x to the camera's left, y up, z forward
//! (optical axis); still, it reads the reaction to gravity, +1 g along "up". With the
//! mount convention of [`crate::projection::camera_to_rover`] (roll, then pitch, then
//! yaw; pitch positive looking down, roll positive left side up), "up" seen from the
//! camera is `(x, y, z) = (sin r·cos p, cos r·cos p, −sin p)`, so
//! `pitch = atan2(−z, √(x² + y²))` and `roll = atan2(x, y)`, exactly.

use rover_terrain_drivers::fakenect::TiltState;

/// Readings averaged for one estimate.
pub const WINDOW: usize = 8;
/// A reading whose magnitude is off 1 g by more than this fraction is ignored (the
/// rover is accelerating or shaking).
pub const MAX_G_ERROR: f64 = 0.1;
/// The mount in use changes only when the estimate moves by more than this, degrees
/// (each change rebuilds the ray tables).
pub const MIN_CHANGE_DEG: f64 = 0.5;

/// Read the tilt state once every this many frames (0.5 s at 30 Hz; on a Kinect each
/// read is a USB control transfer). Counted in frames, so replays are deterministic.
pub const READ_EVERY_FRAMES: u64 = 15;
/// ... and with every one of the first this many frames, so that an attitude is
/// adopted as soon as the first still reading arrives.
pub const READ_ALL_FIRST: u64 = 30;

/// Whether to read the tilt state with frame number `n` (counting from 0).
pub fn read_due(n: u64) -> bool {
    n < READ_ALL_FIRST || n % READ_EVERY_FRAMES == 0
}

/// A camera attitude against gravity, degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attitude {
    /// Pitch, positive looking down.
    pub pitch_deg: f64,
    /// Roll, positive left side up.
    pub roll_deg: f64,
}

/// The attitude a still accelerometer reading (any unit, Kinect axes) says, or `None`
/// if it is not about 1 g in `counts_per_g` units or the camera is not upright (y
/// must carry gravity's larger part: within ±90° of level).
pub fn attitude(a: [f64; 3], counts_per_g: f64) -> Option<Attitude> {
    let [x, y, z] = a;
    let g = (x * x + y * y + z * z).sqrt();
    if !g.is_finite() || (g / counts_per_g - 1.0).abs() > MAX_G_ERROR || y <= 0.0 {
        return None;
    }
    Some(Attitude {
        pitch_deg: (-z).atan2(x.hypot(y)).to_degrees(),
        roll_deg: x.atan2(y).to_degrees(),
    })
}

/// Smooths tilt readings and says when the mount in use should change.
#[derive(Debug, Clone)]
pub struct Leveler {
    window: [[f64; 3]; WINDOW],
    filled: usize,
    next: usize,
    in_use: Option<Attitude>,
    rejected: u64,
}

impl Default for Leveler {
    fn default() -> Self {
        Self::new()
    }
}

impl Leveler {
    /// No readings yet.
    pub fn new() -> Self {
        Leveler {
            window: [[0.0; 3]; WINDOW],
            filled: 0,
            next: 0,
            in_use: None,
            rejected: 0,
        }
    }

    /// Readings ignored (not about 1 g, or not upright).
    pub fn rejected(&self) -> u64 {
        self.rejected
    }

    /// The attitude in use, once one was adopted.
    pub fn in_use(&self) -> Option<Attitude> {
        self.in_use
    }

    /// Take one reading; returns the new attitude when the mount should change to it.
    pub fn update(&mut self, tilt: &TiltState) -> Option<Attitude> {
        use rover_terrain_drivers::fakenect::COUNTS_PER_G;
        let a = tilt.accel.map(f64::from);
        if attitude(a, COUNTS_PER_G).is_none() {
            self.rejected += 1;
            return None;
        }
        self.window[self.next] = a;
        self.next = (self.next + 1) % WINDOW;
        self.filled = (self.filled + 1).min(WINDOW);
        let mut mean = [0.0; 3];
        for r in &self.window[..self.filled] {
            for k in 0..3 {
                mean[k] += r[k] / self.filled as f64;
            }
        }
        let est = attitude(mean, COUNTS_PER_G)?;
        let changed = self.in_use.is_none_or(|u| {
            (u.pitch_deg - est.pitch_deg).abs() > MIN_CHANGE_DEG
                || (u.roll_deg - est.roll_deg).abs() > MIN_CHANGE_DEG
        });
        if changed {
            self.in_use = Some(est);
            Some(est)
        } else {
            None
        }
    }
}

/// Feed one tilt reading to `leveler`, and when the attitude moved, analyse with it
/// from now on (logged; a mount the pipeline cannot use is logged and ignored).
pub fn apply(leveler: &mut Leveler, tilt: &TiltState, pipeline: &mut crate::Pipeline) {
    if let Some(a) = leveler.update(tilt) {
        match pipeline.set_attitude(a) {
            Ok(()) => log::info!(
                "auto-level: pitch {:.2}°, roll {:.2}°",
                a.pitch_deg,
                a.roll_deg
            ),
            Err(e) => log::warn!("auto-level ignored: {e}"),
        }
    }
}

/// The tilt state a still Kinect mounted at `pitch_deg`/`roll_deg` reads (counts,
/// rounded), by the mount convention of the projector: for tests and recordings.
pub fn tilt_for(pitch_deg: f64, roll_deg: f64) -> TiltState {
    use rover_terrain_drivers::fakenect::COUNTS_PER_G;
    let mut c = crate::Config::default();
    c.mount.pitch_deg = pitch_deg;
    c.mount.roll_deg = roll_deg;
    c.mount.yaw_deg = 0.0;
    // "Up" in the optical frame (X right, Y up, Z forward), then Kinect axes (x left).
    let up = crate::projection::camera_to_rover(&c).transpose() * nalgebra::Vector3::z();
    let counts = |v: f64| (v * COUNTS_PER_G).round() as i16;
    TiltState {
        accel: [counts(-up.x), counts(up.y), counts(up.z)],
        tilt_angle: 0,
        tilt_status: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_attitude_inverts_the_projector_mount() {
        for pitch in [-20.0, 0.0, 12.5, 30.0, 40.0, 60.0] {
            for roll in [-15.0, 0.0, 3.0, 10.0] {
                let t = tilt_for(pitch, roll);
                let a = attitude(t.accel.map(f64::from), 819.0).unwrap();
                // Counts are rounded: 1/819 g is about 0.07°.
                assert!((a.pitch_deg - pitch).abs() < 0.15, "{pitch} {roll}: {a:?}");
                assert!((a.roll_deg - roll).abs() < 0.15, "{pitch} {roll}: {a:?}");
            }
        }
    }

    #[test]
    fn moving_or_upside_down_readings_are_ignored() {
        assert!(attitude([0.0, 819.0 * 1.3, 0.0], 819.0).is_none(), "1.3 g");
        assert!(attitude([0.0, 0.0, 0.0], 819.0).is_none());
        assert!(attitude([0.0, -819.0, 0.0], 819.0).is_none(), "upside down");
        assert!(attitude([f64::NAN, 819.0, 0.0], 819.0).is_none());
        let mut l = Leveler::new();
        let bump = TiltState {
            accel: [0, 1600, 0],
            ..TiltState::default()
        };
        assert_eq!(l.update(&bump), None);
        assert_eq!(l.rejected(), 1);
    }

    #[test]
    fn the_leveler_adopts_then_ignores_jitter_then_follows_a_change() {
        let mut l = Leveler::new();
        let first = l
            .update(&tilt_for(40.0, 0.0))
            .expect("the first reading is adopted");
        assert!((first.pitch_deg - 40.0).abs() < 0.15);
        for _ in 0..20 {
            assert_eq!(l.update(&tilt_for(40.2, 0.1)), None, "jitter below 0.5°");
        }
        let mut changed = None;
        for _ in 0..WINDOW {
            changed = changed.or(l.update(&tilt_for(33.0, 0.0)));
        }
        let c = changed.expect("a real change is followed");
        assert!(c.pitch_deg < 39.5, "{c:?}");
        assert!((l.in_use().unwrap().pitch_deg - 33.0).abs() < 3.5);
    }
}
