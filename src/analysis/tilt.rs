//! The rover body's roll and pitch, predicted from the wheel-track heights along the
//! corridor (issue 12; the paper has no tilt rule).
//!
//! How: per cell row, each track's height is the median, over the track's seen strips
//! that are not past the sensor's horizon, of the surface the step test followed there
//! (crest or foot: a face along the band edge does not lift it). Rows without data
//! are filled linearly between the rows that have it; the ground under the rover, up
//! to the first seen row, is taken to rise linearly from the rover's own ground
//! (z = 0 at x = 0). With the front axle at a row's x:
//!
//! - roll = atan((left − right) / track spacing), the spacing being between the
//!   tracks' centre lines (`belly_half_width_m + track_outer_m`);
//! - pitch = atan((h(x) − h(x − wheelbase)) / wheelbase), h the mean of the two
//!   tracks (only where both are known).
//!
//! Limits: a rigid body on its wheel-track centre lines. A rocker-bogie shares a
//! one-track rise between its wheels (less roll than predicted when only one wheel
//! climbs); the rear axle's roll is taken as the front's (an upper bound for a
//! twist). Nothing is predicted past the last seen row, nor in the blind zone behind
//! the nearest seen ground beyond the interpolation from z = 0.

use super::Frame;
use crate::verdict::{Hazard, HazardKind, Side, Tilt, Verdict};

/// Per-row track heights, metres, `[left, right]`, NaN where unknown.
pub(crate) type Profile = [[f32; 2]];

/// Fill `profile` (one entry per cell row) with each track's height; `surface` holds,
/// per cell, the height the step test followed (NaN where it followed none: unseen
/// or past the horizon).
pub fn track_profile(f: &Frame, surface: &[f32], values: &mut Vec<f32>, profile: &mut Profile) {
    super::crossing::track_medians(f, values, profile, |c| {
        Some(surface[c]).filter(|z| z.is_finite())
    });
}

/// Fill each track's unknown rows between known ones linearly in x, and the rows
/// before its first known one from z = 0 at x = 0. Rows past the last known one stay
/// unknown. `x_of(ix)` is a row's centre x, metres.
pub fn fill(profile: &mut Profile, x_of: impl Fn(usize) -> f32) {
    for k in 0..2 {
        let mut last: (f32, f32) = (0.0, 0.0); // (x, z) of the last known row
        let mut pending = 0usize; // first row of the unknown run since then
        for ix in 0..profile.len() {
            let z = profile[ix][k];
            if z.is_nan() {
                continue;
            }
            let x = x_of(ix);
            for (j, row) in profile.iter_mut().enumerate().take(ix).skip(pending) {
                let t = ((x_of(j) - last.0) / (x - last.0)).clamp(0.0, 1.0);
                row[k] = last.1 + t * (z - last.1);
            }
            last = (x, z);
            pending = ix + 1;
        }
    }
}

/// The body's height under its centre line at `x`: the mean of the tracks there,
/// interpolated between rows (row `ix` at `x0 + ix·dx`); z = 0 at and behind x = 0
/// (the rover's own ground); `None` where either track is unknown.
fn height_at(profile: &Profile, x0: f32, dx: f32, x: f32) -> Option<f32> {
    // Both tracks: where one is unknown (past its horizon) the other alone would
    // be a false rise or fall of the body.
    let mean = |r: [f32; 2]| (!r[0].is_nan() && !r[1].is_nan()).then(|| 0.5 * (r[0] + r[1]));
    if x <= 0.0 {
        return Some(0.0);
    }
    let u = (x - x0) / dx;
    if u < 0.0 {
        // Between the rover's ground and the first row.
        let z0 = mean(*profile.first()?)?;
        return Some(z0 * x / x0);
    }
    let i = u as usize;
    let t = u - i as f32;
    let a = mean(*profile.get(i)?)?;
    if t == 0.0 {
        return Some(a);
    }
    let b = mean(*profile.get(i + 1)?)?;
    Some(a + t * (b - a))
}

/// The largest predicted roll and pitch over the filled `profile`, and a `tilt`
/// hazard at the first row where either passes the configured limit.
pub fn predict(f: &Frame, profile: &Profile, verdict: &mut Verdict) -> Option<Tilt> {
    let s = f.spec;
    let r = &f.cfg.rover;
    let spacing = (r.belly_half_width_m + r.track_outer_m) as f32;
    let wheelbase = r.wheelbase_m as f32;
    let (x0, dx) = (s.x_centre(0), s.voxel_m);
    let mut tilt: Option<Tilt> = None;
    let mut first_over: Option<f32> = None;
    let over = |v: f32, limit: Option<f64>| limit.is_some_and(|l| v.abs() > l as f32);
    for (ix, row) in profile.iter().enumerate() {
        let x = s.x_centre(ix);
        if x <= 0.0 {
            continue;
        }
        let roll = (!row[0].is_nan() && !row[1].is_nan())
            .then(|| (row[0] - row[1]).atan2(spacing).to_degrees());
        let pitch = height_at(profile, x0, dx, x)
            .zip(height_at(profile, x0, dx, x - wheelbase))
            .map(|(front, rear)| (front - rear).atan2(wheelbase).to_degrees());
        if roll.is_none() && pitch.is_none() {
            continue;
        }
        let t = tilt.get_or_insert(Tilt {
            roll_at_m: x,
            pitch_at_m: x,
            ..Tilt::default()
        });
        if let Some(roll) = roll {
            if roll.abs() > t.roll_deg.abs() {
                (t.roll_deg, t.roll_at_m) = (roll, x);
            }
            if over(roll, r.max_roll_deg) {
                first_over.get_or_insert(x);
            }
        }
        if let Some(pitch) = pitch {
            if pitch.abs() > t.pitch_deg.abs() {
                (t.pitch_deg, t.pitch_at_m) = (pitch, x);
            }
            if over(pitch, r.max_pitch_deg) {
                first_over.get_or_insert(x);
            }
        }
    }
    if let Some(x) = first_over {
        verdict.add_hazard(Hazard {
            kind: HazardKind::Tilt,
            side: Side::Centre,
            distance_m: x,
        });
    }
    tilt
}

#[cfg(test)]
mod tests {
    use super::*;

    const NAN: f32 = f32::NAN;

    #[test]
    fn fill_interpolates_between_known_rows_and_from_the_rovers_ground() {
        let x_of = |ix: usize| 0.5 + 0.1 * ix as f32;
        let mut p = [[0.1, NAN], [NAN, NAN], [0.3, 0.2], [NAN, NAN]];
        fill(&mut p, x_of);
        assert_eq!(p[0][0], 0.1);
        assert!((p[1][0] - 0.2).abs() < 1e-6, "{}", p[1][0]);
        // Right track: from z = 0 at x = 0 to 0.2 at x = 0.7.
        assert!((p[0][1] - 0.2 * 0.5 / 0.7).abs() < 1e-6, "{}", p[0][1]);
        assert!((p[1][1] - 0.2 * 0.6 / 0.7).abs() < 1e-6, "{}", p[1][1]);
        // Past the last known row nothing is predicted.
        assert!(p[3][0].is_nan() && p[3][1].is_nan());
    }

    #[test]
    fn height_at_is_zero_behind_the_origin_and_unknown_past_the_profile() {
        let p = [[0.2, 0.4], [0.4, 0.4], [0.5, NAN]];
        assert_eq!(height_at(&p, 1.0, 1.0, -0.3), Some(0.0));
        assert!((height_at(&p, 1.0, 1.0, 0.5).unwrap() - 0.15).abs() < 1e-6);
        assert!((height_at(&p, 1.0, 1.0, 1.0).unwrap() - 0.3).abs() < 1e-6);
        assert!((height_at(&p, 1.0, 1.0, 1.5).unwrap() - 0.35).abs() < 1e-6);
        assert_eq!(height_at(&p, 1.0, 1.0, 2.0), Some(0.4));
        // One track unknown: no body height.
        assert_eq!(height_at(&p, 1.0, 1.0, 2.5), None);
        assert_eq!(height_at(&p, 1.0, 1.0, 3.5), None);
    }
}
