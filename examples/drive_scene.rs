//! A drive up to a scene, as a recording `analyze` and the fake camera replay: the
//! camera starting `BACK` metres behind the scene's rover origin and moving straight
//! ahead `STEP` metres a frame, to `PAST` metres past it (default 0), with the
//! odometry of each frame (`frame-NNNN.png` and `odometry.txt` in `OUT`). The scene is
//! a terrain and a configuration as the `sweep` example's `DUMP` writes them:
//!
//! ```text
//! cargo run --release --example drive_scene -- N.json N.toml 1.5 0.1 OUT [PAST]
//! cargo run --release -- analyze --config N.toml OUT
//! ```
//!
//! The second command's verdicts are fused by the terrain memory from the second frame
//! on: how a scene that one frame judges looks to a rover driving up to it.
use rover_terrain::sim::drive::{render_drive_from, write_recording, Step};
use rover_terrain::sim::{Element, Pose, Terrain};
use rover_terrain::Config;

/// Frames a second the drive's timestamps and odometry times are spaced by.
const RATE_HZ: f64 = 10.0;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if !(5..=6).contains(&args.len()) {
        eprintln!("usage: drive_scene TERRAIN.json CONFIG.toml BACK_M STEP_M OUT_DIR [PAST_M]");
        std::process::exit(2);
    }
    let elements: Vec<Element> = serde_json::from_str(&std::fs::read_to_string(&args[0])?)?;
    let config: Config = toml::from_str(&std::fs::read_to_string(&args[1])?)?;
    let metres = |s: &str, what: &str| -> Result<f64, String> {
        s.parse::<f64>()
            .ok()
            .filter(|m| m.is_finite() && *m >= 0.0)
            .ok_or_else(|| format!("{what} must be a distance in metres, not {s:?}"))
    };
    let back = metres(&args[2], "BACK_M")?;
    let step = metres(&args[3], "STEP_M")?;
    let past = args.get(5).map_or(Ok(0.0), |s| metres(s, "PAST_M"))?;
    if step == 0.0 {
        return Err("STEP_M must be more than 0".into());
    }
    let terrain = Terrain::new(elements);
    let n = ((back + past) / step).round() as usize;
    let start = Pose {
        x: -back,
        ..Pose::default()
    };
    let straight = Step {
        forward_m: step,
        turn_rad: 0.0,
    };
    let drive = render_drive_from(&terrain, &config, start, &vec![straight; n], 1.0, RATE_HZ);
    write_recording(std::path::Path::new(&args[4]), &drive)?;
    Ok(())
}
