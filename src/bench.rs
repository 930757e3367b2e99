//! The `bench` subcommand: the whole pipeline many times on one frame, per-stage
//! median and 99th percentile. The rover is taken to drive 3 cm and turn 0.5° between
//! frames, so the terrain memory (when enabled) moves and fuses its map every frame as
//! it does on a drive. (Criterion benches live in `benches/`.)

use rover_terrain_drivers::DepthFrame;

use crate::memory::Motion;
use crate::verdict::StageTimes;
use crate::{Error, Pipeline};

/// Frames processed before timing starts.
pub const WARMUP: usize = 20;

fn percentile(sorted: &[f32], q: f64) -> f32 {
    if sorted.is_empty() {
        return 0.0;
    }
    let i = ((sorted.len() - 1) as f64 * q).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}

/// Run `iterations` timed passes after a warm-up; the JSON line `bench` prints.
pub fn run(
    pipeline: &mut Pipeline,
    frame: &DepthFrame,
    iterations: usize,
) -> Result<serde_json::Value, Error> {
    let motion = Motion {
        forward_m: 0.03,
        lateral_m: 0.0,
        dheading_rad: 0.5f32.to_radians(),
        dt_s: 1.0 / 30.0,
    };
    for _ in 0..WARMUP {
        pipeline.process_moved(frame, Ok(motion))?;
    }
    let mut times: Vec<StageTimes> = Vec::with_capacity(iterations);
    let (mut points_in, mut voxels) = (0, 0);
    for _ in 0..iterations {
        let v = pipeline.process_moved(frame, Ok(motion))?;
        times.push(v.timing_us);
        points_in = v.points_in;
        voxels = v.voxels;
    }
    let stage = |get: fn(&StageTimes) -> f32| {
        let mut v: Vec<f32> = times.iter().map(get).collect();
        v.sort_unstable_by(f32::total_cmp);
        let r = |x: f32| (f64::from(x) * 10.0).round() / 10.0;
        serde_json::json!({"median": r(percentile(&v, 0.5)), "p99": r(percentile(&v, 0.99))})
    };
    Ok(serde_json::json!({
        "iterations": iterations,
        "points_in": points_in,
        "voxels": voxels,
        "us": {
            "bin": stage(|t| t.bin),
            "voxels": stage(|t| t.voxels),
            "crossing": stage(|t| t.crossing),
            "feature": stage(|t| t.feature),
            "memory": stage(|t| t.memory),
            "total": stage(|t| t.total),
        }
    }))
}
