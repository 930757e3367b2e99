//! Auto-level with recorded accelerometer data: a fakenect session of a camera pitched
//! 40° down, with tilt-state dumps saying so, analysed with a config that says 30°.
//! With `mount.auto_level` the verdict is the one the true mount gives; without it,
//! the 30° config misplaces the terrain.

use std::path::Path;
use std::process::Command;

use rover_terrain::level::tilt_for;
use rover_terrain_drivers::fakenect::{Registration, SessionWriter};
use rover_terrain_drivers::{DepthCamera, DepthFrame, FakeCamera};
use serde_json::Value;

fn analyze(session: &Path, config: Option<&Path>) -> Vec<Value> {
    let mut c = Command::new(env!("CARGO_BIN_EXE_rover-terrain"));
    c.current_dir(env!("CARGO_MANIFEST_DIR")).arg("analyze");
    if let Some(cfg) = config {
        c.args(["--config", cfg.to_str().unwrap()]);
    }
    let out = c
        .args(["--camera", &format!("fake:{}", session.display())])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

#[test]
fn recorded_tilt_replaces_a_wrong_configured_pitch() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut frame = DepthFrame::default();
    FakeCamera::open(&root.join("fixtures/pitch40/uphill_left.png"))
        .unwrap()
        .next_frame(&mut frame)
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let session = dir.path().join("session");
    let mut w = SessionWriter::create(&session, Some(Registration::LIBFREENECT_DEFAULT)).unwrap();
    for k in 0..3u32 {
        let t = 100.0 + f64::from(k) / 30.0;
        w.write_depth(&frame, t, k).unwrap();
        // Still, with a little sensor jitter around 40° pitch.
        let tilt = tilt_for(40.0 + [0.1, -0.1, 0.0][k as usize], 0.0);
        w.write_tilt(&tilt, t + 0.001, k).unwrap();
    }
    let auto = dir.path().join("auto.toml");
    std::fs::write(&auto, "[mount]\nauto_level = true\n").unwrap();

    let truth = analyze(
        &session,
        Some(&root.join("fixtures/pitch40/rover-terrain.toml")),
    );
    let levelled = analyze(&session, Some(&auto));
    let wrong = analyze(&session, None);
    assert_eq!(truth.len(), 3);
    for ((t, l), x) in truth.iter().zip(&levelled).zip(&wrong) {
        assert_eq!(l["mount"]["source"], "accelerometer", "{l}");
        let pitch = l["mount"]["pitch_deg"].as_f64().unwrap();
        assert!((pitch - 40.0).abs() < 0.2, "estimated pitch {pitch}");
        assert_eq!(t["mount"]["source"], "config");
        assert_eq!(l["verdict"], t["verdict"]);
        assert_eq!(l["workcase"], t["workcase"], "{l}\n{t}");
        let d = |v: &Value| v["distance_m"].as_f64().unwrap();
        let g = |v: &Value| v["gradient_deg"].as_f64().unwrap();
        assert!((d(l) - d(t)).abs() < 0.01, "{} vs {}", d(l), d(t));
        assert!((g(l) - g(t)).abs() < 0.3, "{} vs {}", g(l), g(t));
        // The configured 30° would not see what the camera sees.
        assert_eq!(x["mount"]["pitch_deg"], 30.0);
        let off = x["workcase"] != t["workcase"]
            || x["distance_m"]
                .as_f64()
                .is_none_or(|dx| (dx - d(t)).abs() > 0.05);
        assert!(off, "the wrong pitch should matter: {x}");
    }
}

#[test]
fn a_new_attitude_bins_exactly_as_a_pipeline_built_for_it() {
    // The service starts with the configured mount and the accelerometer says the
    // camera is rolled: after `set_attitude` every ray, along rows and columns, must
    // be the new mount's, as in a pipeline configured with it from the start.
    use rover_terrain::sim::{self, Element, Terrain};
    use rover_terrain::{Config, Pipeline};
    let mut rolled = Config::default();
    (rolled.mount.pitch_deg, rolled.mount.roll_deg) = (33.0, 6.0);
    let terrain = Terrain::new(vec![Element::Rock {
        x_m: 1.5,
        y_m: 0.3,
        radius_m: 0.2,
        height_m: 0.12,
    }]);
    let frame = sim::render(&terrain, &rolled);
    let mut leveled = Pipeline::new(Config::default()).unwrap();
    leveled.process(&frame).unwrap();
    leveled
        .set_attitude(rover_terrain::level::Attitude {
            pitch_deg: 33.0,
            roll_deg: 6.0,
        })
        .unwrap();
    let got = leveled.process(&frame).unwrap().clone();
    let mut fresh = Pipeline::new(rolled).unwrap();
    let want = fresh.process(&frame).unwrap().clone();
    // Compared whole; printed only by count (thousands of voxels).
    let (a, b) = (leveled.grid().voxels(), fresh.grid().voxels());
    assert!(
        a == b,
        "{} voxels against {}, not the same",
        a.len(),
        b.len()
    );
    assert_eq!(got.decision, want.decision);
}
