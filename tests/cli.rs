//! The real binary: output format, exit codes, and a clear error for every kind of bad
//! input, never a panic and never a verdict for a frame that could not be read.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use rover_terrain::sim::{self, Element, Extent, Terrain};
use rover_terrain::Config;
use rover_terrain_drivers::fakenect::{Registration, SessionWriter};
use rover_terrain_drivers::image::{encode_pgm_depth, encode_png_depth};
use rover_terrain_drivers::DepthFrame;
use serde_json::Value;

fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_rover-terrain"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output().expect("binary runs")
}

fn fixture(rel: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures")
        .join(rel)
        .display()
        .to_string()
}

fn lines(o: &Output) -> Vec<Value> {
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).expect("each stdout line is JSON"))
        .collect()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn no_panic(o: &Output) {
    assert!(!stderr(o).contains("panicked"), "{}", stderr(o));
}

#[test]
fn analyze_without_input_runs_the_bundled_fixtures() {
    let o = run(&["analyze"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let pngs = std::fs::read_dir(fixture("scenes"))
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "png")
        })
        .count();
    let out = lines(&o);
    assert_eq!(out.len(), pngs);
    for (i, v) in out.iter().enumerate() {
        assert_eq!(v["frame"], i as u64);
        for key in [
            "verdict",
            "traversable",
            "workcase",
            "distance_m",
            "gradient_deg",
            "alpha_deg",
            "hazards",
            "seen_fraction",
            "points_in",
            "voxels",
            "timing_us",
        ] {
            assert!(v.get(key).is_some(), "{key} missing in {v}");
        }
        let verdict = v["verdict"].as_str().unwrap();
        assert!(["go", "stop", "unknown"].contains(&verdict));
        assert_eq!(v["traversable"], verdict == "go");
        assert_eq!(v["workcase"].is_null(), verdict != "go");
        for stage in ["bin", "voxels", "crossing", "feature", "memory", "total"] {
            assert!(v["timing_us"][stage].as_f64().is_some(), "{stage}");
        }
    }
}

#[test]
fn analyze_reports_the_measures_of_a_ramp() {
    let o = run(&["analyze", &fixture("scenes/uphill_straight.png")]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v = &lines(&o)[0];
    assert_eq!(v["verdict"], "go");
    assert_eq!(v["workcase"], 2);
    assert!(
        (v["distance_m"].as_f64().unwrap() - 0.675).abs() < 0.01,
        "{v}"
    );
    assert!(
        (v["gradient_deg"].as_f64().unwrap() - 20.0).abs() < 0.5,
        "{v}"
    );
    assert!(v["alpha_deg"].is_null());
    // A stop is still exit 0.
    let o = run(&["analyze", &fixture("scenes/step_15cm.png")]);
    assert!(o.status.success());
    let v = &lines(&o)[0];
    assert_eq!(v["verdict"], "stop");
    assert_eq!(v["hazards"][0]["kind"], "step");
    // The step's edge is at 1.3 m; the wheel meets it up to a wheel radius before.
    let d = v["hazards"][0]["distance_m"].as_f64().unwrap();
    assert!((1.3 - 0.11 - 0.05..=1.3 + 0.05).contains(&d), "{v}");
}

fn config_error(text: &str, must_contain: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("bad.toml");
    std::fs::write(&p, text).unwrap();
    let o = run(&[
        "analyze",
        "--config",
        p.to_str().unwrap(),
        &fixture("scenes/flat.png"),
    ]);
    no_panic(&o);
    assert_eq!(o.status.code(), Some(2), "{text}: {}", stderr(&o));
    assert!(o.stdout.is_empty());
    for m in must_contain {
        assert!(
            stderr(&o).contains(m),
            "{text}: {:?} lacks {m:?}",
            stderr(&o)
        );
    }
}

#[test]
fn bad_configs_exit_2_naming_key_and_line() {
    config_error(
        "[camera]\nhfov_deg = 57\nwidht = 640\n",
        &["widht", "line 3"],
    );
    config_error("[camera]\nwidth = \"640\"\n", &["width", "line 2"]);
    config_error("[camera]\nhfov_deg = 190\n", &["camera.hfov_deg", "line 2"]);
    config_error(
        "[camera]\nmin_range_m = 3.0\nmax_range_m = 2.0\n",
        &["camera.min_range_m"],
    );
    config_error(
        "[analysis]\nvoxel_m = 0\n",
        &["analysis.voxel_m", "positive"],
    );
    config_error("[rover]\nmax_slope_deg = -5\n", &["rover.max_slope_deg"]);
    config_error("[mount]\npitch_deg = nan\n", &["mount.pitch_deg", "finite"]);
    config_error("[mount\n", &["line 1"]);
    // A mount that sees none of the corridor is a setup error (exit 1), not a panic.
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("sky.toml");
    std::fs::write(&p, "[mount]\npitch_deg = -60\n").unwrap();
    let o = run(&[
        "analyze",
        "--config",
        p.to_str().unwrap(),
        &fixture("scenes/flat.png"),
    ]);
    no_panic(&o);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("sees none of the corridor"),
        "{}",
        stderr(&o)
    );
    let o = run(&[
        "analyze",
        "--config",
        "/nonexistent.toml",
        &fixture("scenes/flat.png"),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("/nonexistent.toml"));
}

fn bad_input(name: &str, bytes: &[u8], must_contain: &str) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join(name);
    std::fs::write(&p, bytes).unwrap();
    let o = run(&["analyze", p.to_str().unwrap()]);
    no_panic(&o);
    assert_eq!(o.status.code(), Some(1), "{name}");
    assert!(o.stdout.is_empty(), "no verdict for an unreadable frame");
    let e = stderr(&o);
    assert!(
        e.contains(name) && e.contains(must_contain),
        "{name}: {e:?} lacks {must_contain:?}"
    );
}

#[test]
fn malformed_frames_get_clear_errors() {
    bad_input("a.pgm", b"P2 640 480 65535\n", "magic");
    bad_input("b.pgm", b"P5 640 480 255\n", "maxval 255");
    bad_input("c.pgm", b"P5 640 480 65535\n\x00\x01", "truncated");
    bad_input("d.pgm", b"P5 200000 200000 65535\n", "absurd");
    bad_input("e.png", b"\x89PNG\r\n\x1a\nnot really", "PNG");
    bad_input("f.jpg", b"\xff\xd8", "unknown image type");
    let small = DepthFrame::from_pixels(320, 240, vec![1500; 320 * 240]);
    bad_input("g.png", &encode_png_depth(&small), "expects 640×480");
    let o = run(&["analyze", "/nonexistent/depth.pgm"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("/nonexistent/depth.pgm"));
}

#[test]
fn a_bad_frame_in_a_sequence_does_not_stop_the_others() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(fixture("scenes/flat.png"), dir.path().join("a.png")).unwrap();
    std::fs::write(dir.path().join("b.pgm"), b"P5 640 480 65535\n\x00").unwrap();
    std::fs::copy(fixture("scenes/step_15cm.png"), dir.path().join("c.png")).unwrap();
    let o = run(&["analyze", dir.path().to_str().unwrap()]);
    no_panic(&o);
    assert_eq!(o.status.code(), Some(1));
    let out = lines(&o);
    assert_eq!(out.len(), 2);
    assert_eq!(out[0]["verdict"], "go");
    assert_eq!(out[1]["verdict"], "stop");
    assert!(stderr(&o).contains("b.pgm"));
}

#[test]
fn empty_directories_and_broken_sessions_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(&["analyze", dir.path().to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("no depth frames"), "{}", stderr(&o));
    std::fs::write(dir.path().join("INDEX.txt"), "d-1.000000-5.pgm\n").unwrap();
    let o = run(&["analyze", dir.path().to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("d-1.000000-5.pgm") && stderr(&o).contains("missing"),
        "{}",
        stderr(&o)
    );
}

fn session_of(frames: &[DepthFrame], dir: &Path, reg: Option<Registration>) -> PathBuf {
    let mut w = SessionWriter::create(dir, reg).unwrap();
    for (i, f) in frames.iter().enumerate() {
        w.write_depth(f, 1000.0 + i as f64 / 30.0, 100 + i as u32)
            .unwrap();
    }
    dir.to_path_buf()
}

#[test]
fn a_fakenect_session_gives_the_verdicts_of_its_frames() {
    let config = Config::default();
    let ramp = Terrain::new(vec![Element::Ramp {
        toe_x_m: 1.0,
        ref_y_m: 0.0,
        gradient_deg: 15.0,
        alpha_deg: 0.0,
        extent: Extent::Full,
        cap_m: None,
        round_m: None,
    }]);
    let frames = [
        sim::render(&Terrain::flat(), &config),
        sim::render(&ramp, &config),
    ];
    let tmp = tempfile::tempdir().unwrap();
    for (sub, reg) in [
        ("with-device-json", Some(Registration::LIBFREENECT_DEFAULT)),
        ("standard", None),
    ] {
        let session = session_of(&frames, &tmp.path().join(sub), reg);
        let o = run(&["analyze", session.to_str().unwrap()]);
        assert!(o.status.success(), "{}", stderr(&o));
        let out = lines(&o);
        assert_eq!(out.len(), 2);
        assert_eq!(
            (out[0]["verdict"].as_str(), out[0]["workcase"].as_u64()),
            (Some("go"), Some(1)),
            "{sub}"
        );
        assert_eq!(
            (out[1]["verdict"].as_str(), out[1]["workcase"].as_u64()),
            (Some("go"), Some(2)),
            "{sub}"
        );
        // Disparity quantisation costs a little accuracy, not much.
        assert!(
            (out[1]["distance_m"].as_f64().unwrap() - 1.0).abs() < 0.03,
            "{sub}: {}",
            out[1]
        );
        assert!(
            (out[1]["gradient_deg"].as_f64().unwrap() - 15.0).abs() < 1.0,
            "{sub}: {}",
            out[1]
        );
    }
}

#[test]
fn pgm_and_png_of_the_same_frame_agree() {
    let dir = tempfile::tempdir().unwrap();
    let frame = sim::render(
        &Terrain::new(vec![Element::Step {
            x_m: 1.2,
            height_m: 0.2,
            extent: Extent::Left,
        }]),
        &Config::default(),
    );
    std::fs::write(dir.path().join("x.pgm"), encode_pgm_depth(&frame)).unwrap();
    std::fs::write(dir.path().join("x.png"), encode_png_depth(&frame)).unwrap();
    let o = run(&[
        "analyze",
        dir.path().join("x.pgm").to_str().unwrap(),
        dir.path().join("x.png").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut out = lines(&o);
    for v in &mut out {
        v.as_object_mut().unwrap().remove("timing_us");
        v.as_object_mut().unwrap().remove("source");
        v.as_object_mut().unwrap().remove("frame");
    }
    assert_eq!(out[0], out[1]);
    assert_eq!(out[0]["verdict"], "stop");
    assert_eq!(out[0]["hazards"][0]["side"], "left");
}

#[test]
fn bench_prints_one_json_line_with_every_stage() {
    let o = run(&["bench", "--iterations", "5", &fixture("scenes/flat.png")]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = lines(&o);
    assert_eq!(out.len(), 1);
    let v = &out[0];
    assert_eq!(v["iterations"], 5);
    assert!(v["points_in"].as_u64().unwrap() > 200_000);
    assert!(v["voxels"].as_u64().unwrap() > 1000);
    for stage in ["bin", "voxels", "crossing", "feature", "memory", "total"] {
        let s = &v["us"][stage];
        assert!(
            s["median"].as_f64().unwrap() <= s["p99"].as_f64().unwrap(),
            "{stage}: {s}"
        );
    }
    let o = run(&["bench", "--iterations", "0", &fixture("scenes/flat.png")]);
    assert_eq!(o.status.code(), Some(1));
}

#[test]
fn a_closed_stdout_is_an_error_not_a_panic() {
    // A pipe whose reader is gone (`rover-terrain bench … | head -c0` once head has
    // exited): each command that prints reports the failed write and exits 1.
    let bench_input = fixture("scenes/flat.png");
    let pictures = tempfile::tempdir().unwrap();
    let pictures = pictures.path().to_str().expect("a UTF-8 temporary path");
    let commands: [&[&str]; 5] = [
        &["bench", "--iterations", "2", &bench_input],
        &["check-config", "config/rover-terrain.toml"],
        &["cameras"],
        &["analyze", &bench_input],
        &["inspect", &bench_input, "--out", pictures],
    ];
    for args in commands {
        let (reader, writer) = std::io::pipe().expect("a pipe");
        drop(reader);
        let o = bin()
            .args(args)
            .stdout(writer)
            .stderr(std::process::Stdio::piped())
            .output()
            .expect("binary runs");
        no_panic(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("writing to stdout"),
            "{args:?}: {}",
            stderr(&o)
        );
    }
}

#[test]
fn validate_writes_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("v.md");
    // The family sweep is tested in tests/generality.rs; here the fixtures only.
    let o = run(&[
        "validate",
        &fixture(""),
        "--out",
        out.to_str().unwrap(),
        "--families",
        "0",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        text.contains("Table 2") && text.contains("| 4 | alpha_deg | -26 |"),
        "{text}"
    );
    assert!(!text.contains("FAIL"));
    // The plots beside the report, linked from it, of their documented sizes.
    use rover_terrain::inspect::plots::{CONFUSION_SIZE, ERROR_SIZE};
    use rover_terrain::validate::{CONFUSION_PLOT, ERROR_PLOT};
    for (name, size) in [(ERROR_PLOT, ERROR_SIZE), (CONFUSION_PLOT, CONFUSION_SIZE)] {
        assert!(text.contains(&format!("]({name})")), "linked: {name}");
        let file = std::fs::File::open(dir.path().join(name)).unwrap();
        let info = png::Decoder::new(std::io::BufReader::new(file))
            .read_info()
            .unwrap()
            .info()
            .clone();
        assert_eq!((info.width, info.height), size, "{name}");
    }
    let o = run(&[
        "validate",
        dir.path().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("no *.fixture.toml"), "{}", stderr(&o));
}

#[test]
fn record_then_replay_is_byte_identical() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    let src = fixture("fakenect/ramp-step");
    let o = run(&[
        "record",
        "--camera",
        &format!("fake:{src}"),
        "--out",
        a.to_str().unwrap(),
        "--frames",
        "3",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Replaying the recording gives the frames of the original, to the millimetre.
    let frames = |dir: &Path| {
        let mut cam = rover_terrain_drivers::FakeCamera::open(dir).unwrap();
        let mut out = Vec::new();
        let mut f = DepthFrame::default();
        while cam.next_frame(&mut f).unwrap() == rover_terrain_drivers::FrameStatus::Frame {
            out.push(f.pixels().to_vec());
        }
        out
    };
    use rover_terrain_drivers::DepthCamera;
    assert_eq!(frames(&a), frames(Path::new(&src)));
    // And a recording of the recording is the same bytes, file for file.
    let o = run(&[
        "record",
        "--camera",
        &format!("fake:{}", a.display()),
        "--out",
        b.to_str().unwrap(),
        "--frames",
        "3",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut names: Vec<_> = std::fs::read_dir(&a)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    names.sort();
    assert_eq!(
        names.len(),
        11,
        "INDEX.txt, device.json, 3 depth, 3 colour, 3 tilt states"
    );
    for n in names {
        assert_eq!(
            std::fs::read(a.join(&n)).unwrap(),
            std::fs::read(b.join(&n)).unwrap(),
            "{n:?}"
        );
    }
    // Recording into an existing session is refused, as libfreenect's recorder does.
    let o = run(&[
        "record",
        "--camera",
        &format!("fake:{src}"),
        "--out",
        a.to_str().unwrap(),
        "--frames",
        "1",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("already exists"), "{}", stderr(&o));
}

#[test]
fn camera_flag_and_its_errors() {
    let o = run(&[
        "analyze",
        "--camera",
        &format!("fake:{}", fixture("scenes")),
        "--frames",
        "2",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(lines(&o).len(), 2);
    let o = run(&["analyze", "--camera", "webcam:0"]);
    assert_eq!(o.status.code(), Some(2), "a bad argument is a usage error");
    assert!(stderr(&o).contains("webcam:0"));
    let o = run(&["analyze", "--camera", "v4l:/dev/video9", "--frames", "1"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("/dev/video9"), "{}", stderr(&o));
    let o = run(&["analyze", "--camera", "fake:x", &fixture("scenes/flat.png")]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("either --camera or input files"));
}
