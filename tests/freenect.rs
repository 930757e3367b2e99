//! The libfreenect backend, through the real FFI, with libfreenect's own replay
//! library (fakenect) standing in for a Kinect. Needs `--features freenect` and
//! `apt-get install libfreenect-dev` (which ships the replay library).
#![cfg(feature = "freenect")]

use std::path::Path;
use std::process::{Command, Output};

const FAKENECT_LIB: &str = "/usr/lib/x86_64-linux-gnu/fakenect";

fn session() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/fakenect/ramp-step")
        .display()
        .to_string()
}

fn run(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_rover-terrain"));
    c.args(args)
        .env_remove("FAKENECT_PATH")
        .env_remove("LD_LIBRARY_PATH");
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("binary runs")
}

#[test]
fn fakenect_through_the_real_ffi_gives_the_fake_cameras_verdicts() {
    assert!(
        Path::new(FAKENECT_LIB).join("libfreenect.so.0.5").exists(),
        "libfreenect-dev's replay library is installed"
    );
    let s = session();
    let live = run(
        &[
            "analyze", "--camera", "freenect", "--frames", "3", "--format", "wire",
        ],
        &[("LD_LIBRARY_PATH", FAKENECT_LIB), ("FAKENECT_PATH", &s)],
    );
    assert!(
        live.status.success(),
        "{}",
        String::from_utf8_lossy(&live.stderr)
    );
    let fake = run(
        &[
            "analyze",
            "--camera",
            &format!("fake:{s}"),
            "--frames",
            "3",
            "--format",
            "wire",
        ],
        &[],
    );
    assert!(fake.status.success());
    let live = String::from_utf8(live.stdout).unwrap();
    assert_eq!(live, String::from_utf8(fake.stdout).unwrap());
    let verdicts: Vec<&str> = live.lines().collect();
    assert_eq!(verdicts.len(), 3);
    assert!(
        verdicts[1].contains("\"workcase\":2") && verdicts[2].contains("\"verdict\":\"stop\""),
        "{live}"
    );
}

#[test]
fn without_a_kinect_the_error_is_clear() {
    let o = run(&["analyze", "--camera", "freenect:0", "--frames", "1"], &[]);
    assert_eq!(o.status.code(), Some(1));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("Kinect") || e.contains("libfreenect"), "{e}");
    assert!(o.stdout.is_empty(), "no verdict without a camera");
}

#[test]
fn the_tilt_state_comes_through_the_real_ffi_for_auto_level() {
    // The session's a-*.dump files say the camera is pitched 30° down; the config says
    // 36°. With auto-level, libfreenect's replayed tilt state wins.
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("auto.toml");
    std::fs::write(&cfg, "[mount]\npitch_deg = 36.0\nauto_level = true\n").unwrap();
    let s = session();
    let out = run(
        &[
            "analyze",
            "--config",
            cfg.to_str().unwrap(),
            "--camera",
            "freenect",
            "--frames",
            "3",
        ],
        &[("LD_LIBRARY_PATH", FAKENECT_LIB), ("FAKENECT_PATH", &s)],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let text = String::from_utf8(out.stdout).unwrap();
    // fakenect replays a tilt dump when it reaches it in the index, after the frame
    // before it: from the second frame on, the recorded attitude is in use.
    for line in text.lines().skip(1) {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        assert_eq!(v["mount"]["source"], "accelerometer", "{line}");
        let pitch = v["mount"]["pitch_deg"].as_f64().unwrap();
        assert!((pitch - 30.0).abs() < 0.2, "{pitch}");
    }
    assert_eq!(text.lines().count(), 3);
}

#[test]
fn colour_comes_through_the_real_ffi_and_record_keeps_it() {
    // Recording libfreenect's replay of the session writes its colour frames back
    // byte for byte (the RGB stream through our video callback).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rec");
    let s = session();
    let o = run(
        &[
            "record",
            "--camera",
            "freenect",
            "--frames",
            "3",
            "--out",
            out.to_str().unwrap(),
        ],
        &[("LD_LIBRARY_PATH", FAKENECT_LIB), ("FAKENECT_PATH", &s)],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let ppm = |dir: &Path| -> Vec<Vec<u8>> {
        let mut names: Vec<_> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.file_name().unwrap().to_string_lossy().starts_with("r-"))
            .collect();
        names.sort();
        names.iter().map(|p| std::fs::read(p).unwrap()).collect()
    };
    let (ours, original) = (ppm(&out), ppm(Path::new(&s)));
    assert_eq!(original.len(), 3);
    assert!(!ours.is_empty(), "colour frames were recorded");
    // fakenect delivers a colour frame when it reaches it in the index: each one we
    // recorded is one of the session's.
    for frame in &ours {
        assert!(
            original.contains(frame),
            "a recorded colour frame is the session's"
        );
    }
}
