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
