//! ROS 2 bags in MCAP as a camera (`--camera mcap:PATH[#TOPIC]`), read from bags that
//! independent tools wrote: `tests/ros2/make_bag.py` (the Python `mcap` and
//! `mcap-ros2-support` packages) turned three bundled fixtures into
//! `tests/ros2/depth-zstd.mcap` (zstd chunks) and `tests/ros2/depth-lz4.mcap` (lz4
//! chunks, its second 16UC1 message one row short). CI writes them again with the
//! current Python packages and runs these tests on those (`ROS2_BAGS=DIR`).

use std::path::{Path, PathBuf};

use rover_terrain::{Config, Pipeline, Verdict};
use rover_terrain_drivers::{DepthCamera, DepthFrame, DriverError, FakeCamera, FrameStatus};

const FIXTURES: [&str; 3] = ["flat", "step_15cm", "uphill_straight"];
const RAW: &str = "/camera/depth/image_raw";
const FLOAT: &str = "/camera/depth/image_float";

fn bag(name: &str) -> PathBuf {
    let dir = std::env::var_os("ROS2_BAGS").map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/ros2"),
        PathBuf::from,
    );
    dir.join(name)
}

/// Every frame of `camera` analysed (each frame's error as `Err`), the config sized
/// by the camera's own intrinsics as the CLI does.
fn verdicts(mut camera: FakeCamera) -> Vec<Result<Verdict, String>> {
    let mut config = Config::default();
    if let Some(k) = camera.intrinsics() {
        config.apply_intrinsics(&k);
    }
    let mut pipeline = Pipeline::new(config).unwrap();
    let mut frame = DepthFrame::default();
    let mut out = Vec::new();
    loop {
        match camera.next_frame(&mut frame) {
            Ok(FrameStatus::Frame) => out.push(Ok(pipeline.process(&frame).unwrap().clone())),
            Ok(FrameStatus::EndOfStream) => return out,
            Err(e) => out.push(Err(e.to_string())),
        }
    }
}

fn fixture_verdicts() -> Vec<Verdict> {
    let mut pipeline = Pipeline::new(Config::default()).unwrap();
    FIXTURES
        .iter()
        .map(|f| {
            let p = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("fixtures/scenes/{f}.png"));
            let mut cam = FakeCamera::open(&p).unwrap();
            let mut frame = DepthFrame::default();
            cam.next_frame(&mut frame).unwrap();
            pipeline.process(&frame).unwrap().clone()
        })
        .collect()
}

/// The same verdict: decision, workcase, hazards, measures (to the millimetre and
/// the hundredth of a degree: the bag's pinhole and the fixture's field-of-view model
/// are the same rays, up to rounding).
fn assert_same(got: &Verdict, want: &Verdict, what: &str) {
    assert_eq!(got.decision, want.decision, "{what}");
    assert_eq!(
        got.hazards.len(),
        want.hazards.len(),
        "{what}: {:?}",
        got.hazards
    );
    for (g, w) in got.hazards.iter().zip(&want.hazards) {
        assert_eq!((g.kind, g.side), (w.kind, w.side), "{what}");
        assert!(
            (g.distance_m - w.distance_m).abs() < 1e-3,
            "{what}: {g:?} {w:?}"
        );
    }
    let close = |a: Option<f32>, b: Option<f32>, tol: f32| match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() <= tol,
        (a, b) => a == b,
    };
    match (&got.feature, &want.feature) {
        (Some(g), Some(w)) => {
            assert_eq!(g.workcase, w.workcase, "{what}");
            assert!(
                close(g.distance_m, w.distance_m, 1e-3),
                "{what}: {g:?} {w:?}"
            );
            assert!(
                close(g.gradient_deg, w.gradient_deg, 0.01),
                "{what}: {g:?} {w:?}"
            );
        }
        (g, w) => assert_eq!(g.is_some(), w.is_some(), "{what}"),
    }
    assert_eq!(got.points_in, want.points_in, "{what}");
}

#[test]
fn a_ros2_bag_gives_the_fixtures_verdicts_in_millimetres_and_in_metres() {
    let want = fixture_verdicts();
    for topic in [RAW, FLOAT] {
        let cam = FakeCamera::open_bag(&bag("depth-zstd.mcap"), Some(topic)).unwrap();
        let k = cam.intrinsics().expect("a bag knows its image size");
        assert_eq!((k.width, k.height), (640, 480));
        let (fx, fy, cx, cy) = k.pinhole.expect("the bag has a CameraInfo");
        assert!((fx - 320.0 / 28.5f64.to_radians().tan()).abs() < 1e-9);
        assert!((fy - 240.0 / 21.5f64.to_radians().tan()).abs() < 1e-9);
        assert_eq!((cx, cy), (320.0, 240.0));
        let got = verdicts(cam);
        assert_eq!(got.len(), FIXTURES.len(), "{topic}");
        for ((g, w), name) in got.iter().zip(&want).zip(FIXTURES) {
            assert_same(g.as_ref().unwrap(), w, &format!("{topic} {name}"));
        }
    }
}

#[test]
fn lz4_chunks_read_and_a_bad_message_is_its_own_error_the_rest_analysed() {
    let want = fixture_verdicts();
    let cam = FakeCamera::open_bag(&bag("depth-lz4.mcap"), Some(RAW)).unwrap();
    let got = verdicts(cam);
    assert_eq!(got.len(), 3);
    let e = got[1].as_ref().unwrap_err();
    assert!(
        e.contains(RAW) && e.contains("message 1") && e.contains("expected height 480 × step 1280"),
        "{e}"
    );
    assert_same(got[0].as_ref().unwrap(), &want[0], "frame 0");
    assert_same(got[2].as_ref().unwrap(), &want[2], "frame 2");
    // The other depth topic of that bag is whole.
    let float = verdicts(FakeCamera::open_bag(&bag("depth-lz4.mcap"), Some(FLOAT)).unwrap());
    assert!(float.iter().all(Result::is_ok));
}

#[test]
fn without_a_topic_the_only_depth_topic_is_read_or_the_candidates_listed() {
    let e = FakeCamera::open_bag(&bag("depth-zstd.mcap"), None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("2 depth image topics") && e.contains(RAW) && e.contains(FLOAT),
        "{e}"
    );
    // Not a candidate: the colour image.
    assert!(!e.contains("/camera/color/image_raw"), "{e}");
}

#[test]
fn wrong_topics_are_clear_errors_naming_what_is_there() {
    let path = bag("depth-zstd.mcap");
    let cases = [
        ("/nope", "no topic \"/nope\" in the bag"),
        (
            "/camera/color/image_raw",
            "rgb8 640x480, 3 messages) is not a depth image topic",
        ),
        (
            "/camera/depth/camera_info",
            "carries sensor_msgs/msg/CameraInfo",
        ),
    ];
    for (topic, says) in cases {
        let e = FakeCamera::open_bag(&path, Some(topic)).unwrap_err();
        assert!(matches!(e, DriverError::Malformed { .. }), "{e:?}");
        assert!(e.to_string().contains(says), "{topic}: {e}");
    }
}

#[test]
fn a_truncated_bag_gives_its_whole_frames_then_an_error_then_ends() {
    let whole = std::fs::read(bag("depth-zstd.mcap")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let want = fixture_verdicts();
    // Cut inside the data: some frames survive, the damage shows where the file ends.
    let mut seen_damage = false;
    for keep in [whole.len() * 2 / 3, whole.len() - 100] {
        let p = dir.path().join("cut.mcap");
        std::fs::write(&p, &whole[..keep]).unwrap();
        let cam = FakeCamera::open_bag(&p, Some(RAW)).unwrap();
        let got = verdicts(cam);
        let (ok, bad): (Vec<_>, Vec<_>) = got.iter().partition(|r| r.is_ok());
        for (g, w) in ok.iter().zip(&want) {
            assert_same(g.as_ref().unwrap(), w, &format!("cut at {keep}"));
        }
        assert!(bad.len() <= 1, "cut at {keep}: {bad:?}");
        if let Some(Err(e)) = bad.first() {
            assert!(e.contains(RAW) && e.contains("ends early"), "{e}");
            assert_eq!(got.last(), bad.first().copied(), "the error comes last");
            seen_damage = true;
        }
    }
    assert!(seen_damage, "a cut inside the data must be reported");
    // Not an MCAP file at all.
    let p = dir.path().join("not.mcap");
    std::fs::write(&p, b"P5 640 480 65535\n").unwrap();
    let e = FakeCamera::open_bag(&p, None).unwrap_err().to_string();
    assert!(e.contains("not a readable MCAP file"), "{e}");
    let e = FakeCamera::open_bag(&dir.path().join("missing.mcap"), None).unwrap_err();
    assert!(matches!(e, DriverError::NotFound { .. }), "{e:?}");
}

#[test]
fn a_bag_loops_preloads_and_keeps_its_recorded_clock() {
    let cam = FakeCamera::open_bag(&bag("depth-zstd.mcap"), Some(RAW))
        .unwrap()
        .looping(true)
        .preload(usize::MAX);
    assert!(cam.is_preloaded());
    let mut cam = cam;
    let mut frame = DepthFrame::default();
    let mut stamps = Vec::new();
    for _ in 0..5 {
        assert_eq!(cam.next_frame(&mut frame).unwrap(), FrameStatus::Frame);
        stamps.push(frame.timestamp_s);
    }
    // The header stamps the writer gave: 1.7e9 s, 33.3 ms apart, then again.
    let t0 = 1_700_000_000.0;
    for (i, t) in stamps.iter().enumerate() {
        let want = t0 + (i % 3) as f64 * 0.033_333_333;
        assert!((t - want).abs() < 1e-6, "frame {i}: {t} vs {want}");
    }
    assert_eq!(
        cam.describe(),
        format!("mcap:{}#{RAW}", bag("depth-zstd.mcap").display())
    );
}

#[test]
fn record_format_mcap_writes_a_bag_that_replays_to_the_same_verdicts() {
    let exe = env!("CARGO_BIN_EXE_rover-terrain");
    let session = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/fakenect/ramp-step");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rec.mcap");
    let rec = std::process::Command::new(exe)
        .args(["record", "--format", "mcap", "--frames", "10", "--camera"])
        .arg(format!("fake:{}", session.display()))
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        rec.status.success(),
        "{}",
        String::from_utf8_lossy(&rec.stderr)
    );
    let analyse = |camera: String| {
        let o = std::process::Command::new(exe)
            .args(["analyze", "--camera", &camera])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8(o.stdout)
            .unwrap()
            .lines()
            .map(|l| {
                let mut v: serde_json::Value = serde_json::from_str(l).unwrap();
                // Timing varies; the session names each frame's file, a bag has one.
                v.as_object_mut().unwrap().remove("timing_us");
                v.as_object_mut().unwrap().remove("source");
                v
            })
            .collect::<Vec<_>>()
    };
    let from_bag = analyse(format!("mcap:{}", out.display()));
    let from_session = analyse(format!("fake:{}", session.display()));
    assert_eq!(from_bag.len(), 3);
    assert_eq!(from_bag, from_session);
    // The colour came along, on its own topic, not a depth candidate.
    let e = FakeCamera::open_bag(&out, Some("/camera/color/image_raw")).unwrap_err();
    assert!(e.to_string().contains("rgb8 640x480, 3 messages"), "{e}");
    // An --odometry-link is for fakenect sessions only.
    let o = std::process::Command::new(exe)
        .args([
            "record",
            "--format",
            "mcap",
            "--frames",
            "1",
            "--odometry-link",
            "serial:/dev/null",
        ])
        .arg(format!("--camera=fake:{}", session.display()))
        .arg("--out")
        .arg(dir.path().join("x.mcap"))
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("fakenect sessions only"));
}
