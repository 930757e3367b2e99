//! Tier 2: a real camera attached. Compiled with `--features hardware-tests`, run
//! only when asked (`-- --ignored`), on the camera `ROVER_TERRAIN_CAMERA` names, e.g.
//!
//! ```sh
//! ROVER_TERRAIN_CAMERA=freenect:0 cargo test --release --features hardware-tests,freenect -- --ignored
//! ROVER_TERRAIN_CAMERA=v4l:/dev/video2 cargo test --release --features hardware-tests,v4l -- --ignored
//! ```
//!
//! Point the camera at open ground, still, as mounted on the rover.
#![cfg(feature = "hardware-tests")]

use std::process::Command;

use rover_terrain::Config;
use rover_terrain_drivers::{CameraSpec, DepthFrame, FrameStatus};

fn camera() -> CameraSpec {
    let spec = std::env::var("ROVER_TERRAIN_CAMERA").expect(
        "set ROVER_TERRAIN_CAMERA to the camera under test (freenect:0, v4l:/dev/video2, ...)",
    );
    spec.parse()
        .unwrap_or_else(|e| panic!("ROVER_TERRAIN_CAMERA: {e}"))
}

#[test]
#[ignore = "needs a camera: ROVER_TERRAIN_CAMERA=... cargo test --features hardware-tests,<backend> -- --ignored"]
fn frames_arrive_in_order_at_the_configured_size_with_depth() {
    let config = Config::default();
    let options = rover_terrain_drivers::CameraOptions::default();
    let mut cam = rover_terrain_drivers::open_with(&camera(), &options).unwrap();
    cam.start().unwrap();
    let mut f = DepthFrame::with_capacity(640, 480);
    let mut last: Option<(u64, f64)> = None;
    for _ in 0..60 {
        assert_eq!(cam.next_frame(&mut f).unwrap(), FrameStatus::Frame);
        assert_eq!(
            (f.width(), f.height()),
            (config.camera.width as usize, config.camera.height as usize)
        );
        let valid = f.pixels().iter().filter(|&&p| p != 0).count();
        assert!(
            valid * 10 > f.pixels().len(),
            "at least 10 % of the pixels have depth ({valid})"
        );
        if let Some((seq, t)) = last {
            assert!(f.seq > seq && f.timestamp_s > t, "sequence and time go up");
        }
        last = Some((f.seq, f.timestamp_s));
    }
    cam.stop().unwrap();
}

#[test]
#[ignore = "needs a Kinect: ROVER_TERRAIN_CAMERA=freenect:0 ... -- --ignored"]
fn a_kinect_reports_a_still_one_g() {
    let spec = camera();
    if !matches!(spec, CameraSpec::Freenect(_)) {
        panic!("this test is for a Kinect (freenect:INDEX)");
    }
    let mut cam = rover_terrain_drivers::open(&spec).unwrap();
    cam.start().unwrap();
    let mut f = DepthFrame::default();
    cam.next_frame(&mut f).unwrap();
    let tilt = cam.tilt_state().expect("a tilt state");
    let a = tilt.accel_mps2();
    let g = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    assert!(
        (g - 9.81).abs() < 1.0,
        "still: about 1 g, got {g} m/s² ({a:?})"
    );
    let att = rover_terrain::level::attitude(tilt.accel.map(f64::from), 819.0)
        .expect("upright and still");
    eprintln!("attitude: {att:?}");
}

#[test]
#[ignore = "needs a camera: ROVER_TERRAIN_CAMERA=... -- --ignored"]
fn the_service_runs_on_the_camera() {
    let out = Command::new(env!("CARGO_BIN_EXE_rover-terrain"))
        .args(["run", "--frames", "90", "--camera"])
        .arg(std::env::var("ROVER_TERRAIN_CAMERA").unwrap())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let verdicts = String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter(|l| l.contains("\"type\":\"verdict\""))
        .count();
    assert!(
        verdicts >= 91,
        "90 frames and the final stop (and unknown ones while the camera started): {stderr}"
    );
}
