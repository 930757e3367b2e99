//! Drives: the camera moving along the rover's path over a terrain, frame by frame,
//! with the odometry a controller would send, written as a recording the fake camera
//! replays (`frame-NNNN.png` and `odometry.txt`).

use std::path::Path;

use rover_terrain_drivers::image::encode_png_depth;
use rover_terrain_drivers::odometry_file;
use rover_terrain_drivers::DepthFrame;
use rover_terrain_proto::Odometry;

use super::{render_from, Pose, Terrain};
use crate::memory::odometry::Tracker;
use crate::{Config, Error, Pipeline, Verdict};

/// One step of a drive: forward travel along the rover's heading, metres, then a
/// turn, radians counter-clockwise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// Forward travel, metres.
    pub forward_m: f64,
    /// Turn after it, radians.
    pub turn_rad: f64,
}

/// Frames of a drive and the odometry at each: the first frame at the origin, then
/// one after each step. `odometry_scale` is what the odometry claims per metre the
/// wheels made good (1.1: 10 % slip). Frames are `1 / rate_hz` apart.
pub fn render_drive(
    terrain: &Terrain,
    config: &Config,
    steps: &[Step],
    odometry_scale: f64,
    rate_hz: f64,
) -> Vec<(DepthFrame, Pose, Odometry)> {
    render_drive_from(
        terrain,
        config,
        Pose::default(),
        steps,
        odometry_scale,
        rate_hz,
    )
}

/// [`render_drive`] starting at `start` (terrain coordinates) instead of the origin:
/// e.g. behind a scene, to drive up to it. The odometry counts from the start, its
/// heading relative to the start's.
pub fn render_drive_from(
    terrain: &Terrain,
    config: &Config,
    start: Pose,
    steps: &[Step],
    odometry_scale: f64,
    rate_hz: f64,
) -> Vec<(DepthFrame, Pose, Odometry)> {
    let mut pose = start;
    let mut claimed = 0.0;
    let mut out = Vec::with_capacity(steps.len() + 1);
    for k in 0..=steps.len() {
        if k > 0 {
            let s = steps[k - 1];
            pose.x += s.forward_m * pose.heading.cos();
            pose.y += s.forward_m * pose.heading.sin();
            pose.heading += s.turn_rad;
            claimed += s.forward_m * odometry_scale;
        }
        let time_ms = (k as f64 * 1000.0 / rate_hz).round() as u64;
        let heading = pose.heading - start.heading;
        let odometry = Odometry::from_pose(k as u8, time_ms, claimed, 0.0, heading);
        let mut frame = render_from(terrain, config, pose);
        frame.seq = k as u64;
        frame.timestamp_s = k as f64 / rate_hz;
        frame.odometry = Some(odometry.encode());
        out.push((frame, pose, odometry));
    }
    out
}

/// Write a drive as a recording in `dir` (created): `frame-NNNN.png` (16-bit
/// millimetres) and `odometry.txt`.
pub fn write_recording(dir: &Path, drive: &[(DepthFrame, Pose, Odometry)]) -> Result<(), Error> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| Error::Io { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let mut lines = String::from("# frame file, odometry (PROTOCOL.md bytes, hex)\n");
    for (k, (frame, _, odometry)) in drive.iter().enumerate() {
        let name = format!("frame-{k:04}.png");
        let path = dir.join(&name);
        std::fs::write(&path, encode_png_depth(frame)).map_err(io(&path))?;
        lines.push_str(&odometry_file::line(&name, &odometry.encode()));
    }
    let path = dir.join(odometry_file::FILE_NAME);
    std::fs::write(&path, lines).map_err(io(&path))
}

/// Analyse a drive's frames in turn as `rover-terrain run` replays a recording: each
/// frame's recorded odometry goes to an odometry tracker, whose motion moves the
/// terrain memory (with `[memory] enabled`), so the verdicts are the fused ones the
/// service would give. `drive` as [`render_drive`] makes it.
pub fn analyse_drive(
    drive: &[(DepthFrame, Pose, Odometry)],
    config: &Config,
) -> Result<Vec<Verdict>, Error> {
    let mut pipeline = Pipeline::new(config.clone())?;
    let mut tracker = Tracker::new(&config.memory);
    drive
        .iter()
        .map(|(frame, _, _)| {
            tracker.on_recorded(frame.odometry, frame.timestamp_s);
            let motion = tracker.motion(frame.timestamp_s);
            pipeline.process_moved(frame, motion).cloned()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::verdict::MemoryState;

    fn small() -> Config {
        let mut c = Config::default();
        c.camera.width = 160;
        c.camera.height = 120;
        c
    }

    #[test]
    fn a_drive_is_analysed_with_its_odometry_moving_the_memory() {
        let c = small();
        let steps = vec![
            Step {
                forward_m: 0.1,
                turn_rad: 0.0,
            };
            3
        ];
        let drive = render_drive(&Terrain::flat(), &c, &steps, 1.0, 10.0);
        let v = analyse_drive(&drive, &c).unwrap();
        assert_eq!(v.len(), 4);
        // The first frame has no motion before it; every later one is fused.
        assert_eq!(v[0].memory.state, MemoryState::SingleFrame);
        assert!(v[1..].iter().all(|v| v.memory.state == MemoryState::Fused));
        assert!(v[2..].iter().all(|v| v.memory.remembered_cells > 0));
        // Without odometry in the frames, nothing is fused.
        let bare: Vec<_> = drive
            .into_iter()
            .map(|(mut f, p, o)| {
                f.odometry = None;
                (f, p, o)
            })
            .collect();
        let v = analyse_drive(&bare, &c).unwrap();
        assert!(v.iter().all(|v| v.memory.state == MemoryState::SingleFrame));
    }
}
