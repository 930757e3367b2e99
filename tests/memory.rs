//! Terrain memory on rendered drives (issue 14): the camera moves along the rover's
//! path frame by frame, the odometry says how far, and hazards keep their place as
//! they pass into the blind zone before the wheels.

use rover_terrain::memory::odometry::Untrusted;
use rover_terrain::memory::{MemoryState, Motion};
use rover_terrain::sim::{self, Element, Extent, Pose, Terrain};
use rover_terrain::{Config, Decision, HazardKind, Pipeline, Side, Verdict};
use rover_terrain_drivers::DepthFrame;
use std::sync::OnceLock;

#[path = "common/hazards.rs"]
mod hazards;
use hazards::hazard;

/// Forward step per frame of the straight drives, metres.
const STEP: f64 = 0.05;

/// The frames of a drive over `terrain` from the origin: before each frame after the
/// first the rover goes `steps[k - 1].0` metres forward, then turns `steps[k - 1].1`
/// radians. Each frame comes with the pose it was rendered from.
fn render(terrain: &Terrain, steps: &[(f64, f64)]) -> Vec<(Pose, DepthFrame)> {
    let config = Config::default();
    let mut pose = Pose::default();
    let mut out = Vec::with_capacity(steps.len() + 1);
    for k in 0..=steps.len() {
        if k > 0 {
            let (fwd, turn) = steps[k - 1];
            pose.x += fwd * pose.heading.cos();
            pose.y += fwd * pose.heading.sin();
            pose.heading += turn;
        }
        out.push((pose, sim::render_from(terrain, &config, pose)));
    }
    out
}

/// Replay a drive's `frames` ([`render`]ed from `steps`) through one pipeline, told
/// `odometry` × the true forward travel (or no odometry). Returns each frame's pose
/// and verdict.
fn replay(
    frames: &[(Pose, DepthFrame)],
    steps: &[(f64, f64)],
    odometry: Option<f64>,
) -> Vec<(Pose, Verdict)> {
    assert_eq!(frames.len(), steps.len() + 1, "frames and steps disagree");
    let mut p = Pipeline::new(Config::default()).unwrap();
    let mut out = Vec::with_capacity(frames.len());
    for (k, (pose, frame)) in frames.iter().enumerate() {
        let motion = match (k, odometry) {
            (0, _) | (_, None) => Err(Untrusted::NoOdometry),
            (_, Some(scale)) => Ok(Motion {
                forward_m: (steps[k - 1].0 * scale) as f32,
                dheading_rad: steps[k - 1].1 as f32,
                dt_s: 0.1,
                ..Motion::default()
            }),
        };
        out.push((*pose, p.process_moved(frame, motion).unwrap().clone()));
    }
    out
}

/// [`render`] then [`replay`]: each frame's pose and verdict.
fn drive(terrain: &Terrain, steps: &[(f64, f64)], odometry: Option<f64>) -> Vec<(Pose, Verdict)> {
    replay(&render(terrain, steps), steps, odometry)
}

/// Where the near edge x = `edge` (terrain frame) of what stands in the left track
/// (0.2 ≤ y ≤ 0.7 m at the start) is nearest ahead of the rover at `pose`, metres.
fn edge_ahead(pose: Pose, edge: f64) -> f64 {
    let (s, c) = pose.heading.sin_cos();
    // A terrain point (edge, y) in the rover frame: x_r = c·(edge − px) + s·(y − py).
    (0..=50)
        .map(|i| 0.2 + 0.01 * f64::from(i))
        .map(|y| c * (edge - pose.x) + s * (y - pose.y))
        .fold(f64::INFINITY, f64::min)
}

/// Near edge of [`block_ahead`], metres.
const EDGE: f64 = 1.515;

/// The straight drive at [`block_ahead`]: [`STEP`]s until its edge is 0.165 m ahead.
const BLOCK_STEPS: [(f64, f64); 27] = [(STEP, 0.0); 27];

/// [`BLOCK_STEPS`]' frames, rendered once for the tests that replay them with
/// different odometry.
fn block_drive() -> &'static [(Pose, DepthFrame)] {
    static FRAMES: OnceLock<Vec<(Pose, DepthFrame)>> = OnceLock::new();
    FRAMES.get_or_init(|| render(&block_ahead(), &BLOCK_STEPS))
}

/// A 0.15 m block in the left track, its near edge at [`EDGE`].
fn block_ahead() -> Terrain {
    Terrain::new(vec![Element::Block {
        x_m: EDGE,
        y_m: 0.45,
        length_m: 0.3,
        width_m: 0.3,
        height_m: 0.15,
    }])
}

#[test]
fn the_renderer_draws_the_same_ground_from_a_pose_as_the_moved_ground() {
    // Standing 0.5 m on, the block 1.5 m out is the block 1.0 m out from the origin.
    let config = Config::default();
    let moved = sim::render_from(
        &block_ahead(),
        &config,
        Pose {
            x: 0.5,
            ..Pose::default()
        },
    );
    let near = Terrain::new(vec![Element::Block {
        x_m: EDGE - 0.5,
        y_m: 0.45,
        length_m: 0.3,
        width_m: 0.3,
        height_m: 0.15,
    }]);
    let here = sim::render(&near, &config);
    let differ = moved
        .pixels()
        .iter()
        .zip(here.pixels())
        .filter(|(a, b)| a.abs_diff(**b) > 1)
        .count();
    assert!(differ < 20, "{differ} pixels differ by more than 1 mm");
    // Turned 90° left at the origin, the ground ahead is the terrain's +y: a step up
    // 1 m along +y shows as a step 1 m ahead.
    let side_step = Terrain::new(vec![Element::Block {
        x_m: -5.0,
        y_m: 5.0 + 1.0,
        length_m: 10.0,
        width_m: 10.0,
        height_m: 0.2,
    }]);
    let turned = Pose {
        heading: std::f64::consts::FRAC_PI_2,
        ..Pose::default()
    };
    let ahead = Terrain::new(vec![Element::Step {
        x_m: 1.0,
        height_m: 0.2,
        extent: Extent::Full,
    }]);
    let a = sim::render_from(&side_step, &config, turned);
    let b = sim::render(&ahead, &config);
    let differ = a
        .pixels()
        .iter()
        .zip(b.pixels())
        .filter(|(x, y)| x.abs_diff(**y) > 1)
        .count();
    assert!(differ < 50, "{differ} pixels differ by more than 1 mm");
}

/// Checks a drive toward [`block_ahead`]: the step is reported in every frame, where
/// the first frame put it less the travel since (± `tol(true distance)` metres),
/// never behind the rover.
fn assert_tracked(run: &[(Pose, Verdict)], tol: impl Fn(f64) -> f64) {
    let d0 = f64::from(hazard(&run[0].1, HazardKind::Step, Side::Left).expect("seen at the start"));
    // The wheel meets the block this far before its edge (the first frame shows it).
    let offset = edge_ahead(run[0].0, EDGE) - d0;
    for (k, (pose, v)) in run.iter().enumerate() {
        let want = edge_ahead(*pose, EDGE) - offset;
        let got = hazard(v, HazardKind::Step, Side::Left).unwrap_or_else(|| {
            panic!(
                "frame {k}: the block is lost at {want:.3} m: {:?}",
                v.hazards
            )
        });
        let got = f64::from(got);
        assert!(
            (got - want).abs() <= tol(want),
            "frame {k}: {got:.3} m, expected {want:.3}"
        );
        assert!(got >= 0.0, "frame {k}: behind the rover");
        let state = if k == 0 {
            MemoryState::SingleFrame
        } else {
            MemoryState::Fused
        };
        assert_eq!(v.memory.state, state, "frame {k}");
    }
}

#[test]
fn a_block_keeps_its_place_into_the_blind_zone_down_to_the_wheels() {
    let fused = replay(block_drive(), &BLOCK_STEPS, Some(1.0));
    assert_tracked(&fused, |_| 0.02);
    assert!(fused.last().unwrap().1.memory.remembered_cells > 0);
    // Alone, each frame loses the block's near edge in the blind zone (from 0.64 m):
    // it reports what it sees of the block (its far part), or nothing.
    let single = replay(block_drive(), &BLOCK_STEPS, None);
    let lost = single.iter().filter(|(pose, v)| {
        let want = edge_ahead(*pose, EDGE) - 0.1;
        hazard(v, HazardKind::Step, Side::Left).is_none_or(|d| f64::from(d) > want + 0.1)
    });
    assert!(lost.count() >= 8, "single frames keep the near edge?");
    for (_, v) in &single {
        assert_eq!(v.memory.state, MemoryState::SingleFrame);
        assert_eq!(v.memory.reason, Some("no_odometry"));
    }
}

#[test]
fn steps_of_two_to_ten_centimetres_with_turns_keep_the_block_in_place() {
    // Uneven steps, with a turn of up to 2° now and then (heading within ±4°).
    let steps: Vec<(f64, f64)> = (0..30)
        .map(|k| {
            let fwd = [0.02, 0.07, 0.04, 0.1, 0.03][k % 5];
            let turn = [0.0, 2.0, 0.0, -1.5, 0.0, -2.0, 1.0][k % 7];
            (fwd, f64::to_radians(turn))
        })
        .take_while({
            let mut x = 0.0;
            move |s| {
                x += s.0;
                x < EDGE - 0.2
            }
        })
        .collect();
    assert!(steps.len() > 20);
    // Steps that are not whole cells move the edge within the 5 cm grid, and turns
    // slant it across the cells: a single frame's distance is off by up to 4 cm. The
    // memory reports the mean of the last frames' views, each carried exactly by the
    // odometry: within the ± 2 cm the straight drive holds.
    assert_tracked(&drive(&block_ahead(), &steps, Some(1.0)), |_| 0.02);
}

#[test]
fn wheel_slip_errs_by_the_slip_only_and_never_behind_the_rover() {
    // The odometry says 10 % more than the wheels made good: remembered cells run
    // ahead of the truth by 10 % of the travel since they were seen: in view, over
    // the ~5 frames (0.25 m) a cell's views are averaged; out of view (from ~0.7 m),
    // plus the travel since.
    let slipping = replay(block_drive(), &BLOCK_STEPS, Some(1.1));
    assert_tracked(&slipping, |truth| {
        0.02 + 0.1 * (0.25 + (0.75 - truth).max(0.0))
    });
}

#[test]
fn an_obstacle_in_one_frame_only_is_gone_at_once() {
    let config = Config::default();
    let mut p = Pipeline::new(config.clone()).unwrap();
    let flat = Terrain::flat();
    let block = Terrain::new(vec![Element::Block {
        x_m: 1.2,
        y_m: -0.45,
        length_m: 0.2,
        width_m: 0.2,
        height_m: 0.2,
    }]);
    let step = Motion {
        forward_m: 0.02,
        dt_s: 0.05,
        ..Motion::default()
    };
    for k in 0..8 {
        let t = if k == 3 { &block } else { &flat };
        let pose = Pose {
            x: 0.02 * k as f64,
            ..Pose::default()
        };
        let frame = sim::render_from(t, &config, pose);
        let motion = if k == 0 {
            Err(Untrusted::NoOdometry)
        } else {
            Ok(step)
        };
        let v = p.process_moved(&frame, motion).unwrap();
        let blocked = hazard(v, HazardKind::Step, Side::Right).is_some();
        assert_eq!(blocked, k == 3, "frame {k}: {:?}", v.hazards);
    }
}

#[test]
fn ground_remembered_long_ago_counts_less_until_it_is_forgotten() {
    let config = Config::default();
    let mut fused = Pipeline::new(config.clone()).unwrap();
    let mut single = Pipeline::new(config.clone()).unwrap();
    let flat = Terrain::flat();
    // Drive 0.6 m in 5 cm steps over flat ground: the blind zone fills from memory.
    let mut pose = Pose::default();
    for k in 0..=12 {
        pose.x = 0.05 * f64::from(k);
        let frame = sim::render_from(&flat, &config, pose);
        let motion = if k == 0 {
            Err(Untrusted::NoOdometry)
        } else {
            Ok(Motion {
                forward_m: 0.05,
                dt_s: 0.1,
                ..Motion::default()
            })
        };
        fused.process_moved(&frame, motion).unwrap();
    }
    let frame = sim::render_from(&flat, &config, pose);
    let alone = single.process(&frame).unwrap().clone();
    // Parked, 5 s a frame: what was remembered loses weight with time, and so does
    // the seen fraction, until max_age_s (30 s) forgets it.
    let parked = Motion {
        dt_s: 5.0,
        ..Motion::default()
    };
    let mut last = fused.process_moved(&frame, Ok(parked)).unwrap().clone();
    assert_eq!(last.decision, alone.decision);
    assert!(last.memory.remembered_cells > 100, "{:?}", last.memory);
    assert!(last.memory.remembered_confidence > 0.3, "{:?}", last.memory);
    assert!(last.seen_fraction < alone.seen_fraction);
    for _ in 0..4 {
        let v = fused.process_moved(&frame, Ok(parked)).unwrap().clone();
        assert_eq!(v.memory.remembered_cells, last.memory.remembered_cells);
        assert!(
            v.memory.remembered_confidence < last.memory.remembered_confidence - 0.1,
            "{:?} after {:?}",
            v.memory,
            last.memory
        );
        assert!(v.seen_fraction < last.seen_fraction, "{v:?}");
        assert_eq!(v.decision, alone.decision);
        last = v;
    }
    for _ in 0..2 {
        last = fused.process_moved(&frame, Ok(parked)).unwrap().clone();
    }
    // What is left is what the camera sees in part now (the image's edges), kept
    // fresh by it: the blind zone is forgotten.
    assert!(last.memory.remembered_cells > 0);
    assert!(
        last.memory.remembered_confidence > 0.99,
        "{:?}",
        last.memory
    );
    assert!(
        (last.seen_fraction - alone.seen_fraction).abs() < 1e-3,
        "{last:?}"
    );
    let again = fused.process_moved(&frame, Ok(parked)).unwrap().clone();
    assert_eq!(again.memory, last.memory);
}

#[test]
fn with_the_memory_off_the_verdicts_are_the_single_frames() {
    let mut config = Config::default();
    config.memory.enabled = false;
    let mut off = Pipeline::new(config.clone()).unwrap();
    let mut on = Pipeline::new(Config::default()).unwrap();
    let terrain = block_ahead();
    for k in 0..4 {
        let pose = Pose {
            x: 0.1 * k as f64,
            ..Pose::default()
        };
        let frame = sim::render_from(&terrain, &config, pose);
        let motion = Motion {
            forward_m: 0.1,
            dt_s: 0.1,
            ..Motion::default()
        };
        let a = off.process_moved(&frame, Ok(motion)).unwrap().clone();
        let b = on.process(&frame).unwrap().clone();
        assert_eq!(a.memory.state, MemoryState::Off);
        assert_eq!(
            (a.decision, &a.hazards, a.feature),
            (b.decision, &b.hazards, b.feature)
        );
    }
}

/// The binary, run from the repository.
fn bin() -> std::process::Command {
    let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_rover-terrain"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

#[test]
fn a_recorded_drive_with_its_odometry_replays_with_the_memory() {
    use rover_terrain::sim::drive::{render_drive, write_recording, Step};
    let config = Config::default();
    let steps = [Step {
        forward_m: STEP,
        turn_rad: 0.0,
    }; 24];
    let drive = render_drive(&block_ahead(), &config, &steps, 1.0, 10.0);
    let dir = tempfile::tempdir().unwrap();
    write_recording(dir.path(), &drive).unwrap();

    // analyze replays the frames with odometry.txt: every frame after the first is
    // fused, and the block's step keeps falling by the step into the blind zone.
    let out = bin().arg("analyze").arg(dir.path()).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines: Vec<serde_json::Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 25);
    let step_left = |v: &serde_json::Value| {
        v["hazards"]
            .as_array()
            .unwrap()
            .iter()
            .find(|h| h["kind"] == "step" && h["side"] == "left")
            .map(|h| h["distance_m"].as_f64().unwrap())
    };
    let d0 = step_left(&lines[0]).unwrap();
    for (k, v) in lines.iter().enumerate() {
        let state = if k == 0 { "single_frame" } else { "fused" };
        assert_eq!(v["memory"]["state"], state, "frame {k}");
        let want = d0 - k as f64 * STEP;
        let got = step_left(v).unwrap_or_else(|| panic!("frame {k}: lost"));
        assert!(
            (got - want).abs() <= 0.02,
            "frame {k}: {got}, expected {want}"
        );
    }

    // run on the same recording: heartbeats say the memory is fused.
    let out = bin()
        .args(["run", "--link", "stdout", "--camera"])
        .arg(format!("fake:{}", dir.path().display()))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let fused = text
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .filter(|v| v["type"] == "heartbeat" && v["memory_fused"] == true)
        .count();
    assert!(fused > 0, "{text}");
}

#[test]
fn record_keeps_a_drive_s_odometry_and_takes_the_controller_s_from_a_link() {
    use rover_terrain::link::proto::serial::{encode, Message};
    use rover_terrain::link::proto::Odometry;
    use rover_terrain::sim::drive::{render_drive, write_recording, Step};
    use rover_terrain_drivers::odometry_file;
    let config = Config::default();
    let steps = [Step {
        forward_m: 0.04,
        turn_rad: 0.01,
    }; 3];
    let drive = render_drive(&Terrain::flat(), &config, &steps, 1.0, 10.0);
    let src = tempfile::tempdir().unwrap();
    write_recording(src.path(), &drive).unwrap();
    // Re-recorded into a session: each depth frame keeps its odometry.
    let out = tempfile::tempdir().unwrap();
    let session = out.path().join("s");
    let o = bin()
        .args(["record", "--frames", "4", "--camera"])
        .arg(format!("fake:{}", src.path().display()))
        .arg("--out")
        .arg(&session)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let kept = odometry_file::read(&session).unwrap();
    let mut got: Vec<(String, [u8; 8])> = kept.into_iter().collect();
    got.sort();
    let want: Vec<[u8; 8]> = drive.iter().map(|(_, _, o)| o.encode()).collect();
    assert_eq!(got.iter().map(|g| g.1).collect::<Vec<_>>(), want);
    assert!(got
        .iter()
        .all(|(name, _)| name.starts_with("d-") && session.join(name).is_file()));

    // With --odometry-link, the controller's messages on a pty are recorded instead.
    let (mut master, slave) = serialport::TTYPort::pair().unwrap();
    use std::io::Write;
    let sent = Odometry::from_pose(9, 1234, 2.5, 0.0, 1.0);
    master.write_all(&encode(&Message::Odometry(sent))).unwrap();
    let session = out.path().join("t");
    let o = bin()
        .args(["record", "--frames", "2", "--camera"])
        .arg(format!("fake:{}", src.path().display()))
        .arg("--out")
        .arg(&session)
        .args([
            "--odometry-link",
            &format!("serial:{}", serialport::SerialPort::name(&slave).unwrap()),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let kept = odometry_file::read(&session).unwrap();
    assert_eq!(kept.len(), 2);
    assert!(kept.values().all(|b| *b == sent.encode()), "{kept:?}");
    drop(slave);
}

#[test]
fn the_pictures_show_what_was_remembered_and_how_long_ago() {
    use rover_terrain::inspect::Scene;
    let steps = [(STEP, 0.0); 20];
    let config = Config::default();
    let mut p = Pipeline::new(config.clone()).unwrap();
    let mut pose = Pose::default();
    for k in 0..=steps.len() {
        if k > 0 {
            pose.x += STEP;
        }
        let frame = sim::render_from(&block_ahead(), &config, pose);
        let m = if k == 0 {
            Err(Untrusted::NoOdometry)
        } else {
            Ok(Motion {
                forward_m: STEP as f32,
                dt_s: 0.1,
                ..Motion::default()
            })
        };
        p.process_moved(&frame, m).unwrap();
    }
    let v = p.verdict().clone();
    let scene = Scene::of(&p, &v);
    let spec = *p.grid().spec();
    // The blind zone before the wheels is remembered, the nearest longest ago.
    let travel = |x: f32| {
        let (ix, iy) = spec.cell_at(x, 0.45).unwrap();
        scene.remembered_travel(ix, iy)
    };
    let (near, far) = (travel(0.12).unwrap(), travel(0.52).unwrap());
    assert!(near > far && far > 0.0, "{near} {far}");
    // In view: not remembered.
    assert_eq!(travel(1.5), None);
    // The pictures fade remembered cells by their confidence: the nearest, seen
    // longest ago, the least.
    let confidence = |x: f32| {
        let (ix, iy) = spec.cell_at(x, 0.45).unwrap();
        scene.remembered_confidence(ix, iy)
    };
    let (near, far) = (confidence(0.12).unwrap(), confidence(0.52).unwrap());
    assert!(near < far && far < 1.0, "{near} {far}");
    assert_eq!(confidence(1.5), None);
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("topdown.png");
    std::fs::write(&png, rover_terrain::inspect::topdown::draw(&scene).png()).unwrap();
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
}

/// Drive straight at `terrain` in [`STEP`]s, the frames rendered once and replayed
/// with the memory and as single frames: the nearest `kind` hazard on any side per
/// frame, each way.
fn nearest_hazard_per_frame(
    terrain: &Terrain,
    frames: usize,
    kind: HazardKind,
) -> (Vec<Option<f32>>, Vec<Option<f32>>) {
    let steps = vec![(STEP, 0.0); frames - 1];
    let of = |run: Vec<(Pose, Verdict)>| -> Vec<Option<f32>> {
        run.iter()
            .map(|(_, v)| {
                v.hazards
                    .iter()
                    .filter(|h| h.kind == kind)
                    .map(|h| h.distance_m)
                    .reduce(f32::min)
            })
            .collect()
    };
    let frames = render(terrain, &steps);
    (
        of(replay(&frames, &steps, Some(1.0))),
        of(replay(&frames, &steps, None)),
    )
}

#[test]
fn a_drop_off_is_kept_down_to_the_wheels() {
    // The ground beyond the edge is never seen: nothing in the map finds the edge once
    // it is in the blind zone, so the drop-off itself is carried.
    let edge = 1.415;
    let terrain = Terrain::new(vec![Element::DropOff {
        x_m: edge,
        depth_m: 0.6,
    }]);
    let (fused, single) = nearest_hazard_per_frame(&terrain, 27, HazardKind::DropOff);
    assert_falls_with_the_travel(&fused, "drop-off");
    assert!(single.iter().any(Option::is_none), "single frames keep it?");
}

/// The hazard's distance per frame (`fused`, one frame per [`STEP`] driven) falls by
/// the step (± 2 cm) from its first frame to the last; the first, metres.
fn assert_falls_with_the_travel(fused: &[Option<f32>], what: &str) -> f64 {
    let d0 = f64::from(fused[0].unwrap_or_else(|| panic!("no {what} ahead")));
    for (k, d) in fused.iter().enumerate() {
        let want = d0 - k as f64 * STEP;
        let got =
            f64::from(d.unwrap_or_else(|| panic!("frame {k}: the {what} is lost at {want:.2} m")));
        assert!(
            (got - want).abs() <= 0.02,
            "frame {k}: {got:.3}, expected {want:.3}"
        );
    }
    d0
}

#[test]
fn a_step_across_the_corridor_is_kept_down_to_the_wheels() {
    // A 0.15 m step (over the 0.11 m wheel radius) under both tracks: once its foot is
    // in the blind zone the frame sees only its top, level ground it cannot place;
    // the map keeps the face, and its distance falls with the travel.
    let edge = 1.415;
    let terrain = Terrain::new(vec![Element::Step {
        x_m: edge,
        height_m: 0.15,
        extent: Extent::Full,
    }]);
    let (fused, single) = nearest_hazard_per_frame(&terrain, 27, HazardKind::Step);
    let d0 = assert_falls_with_the_travel(&fused, "step");
    // Reported where a wheel meets the face: within a wheel radius before the edge.
    assert!(d0 <= edge && d0 >= edge - 0.11, "first seen at {d0:.3}");
    // Alone, a frame whose view starts past the foot does not report the step there.
    let view_start = 0.64;
    assert!(
        single.iter().enumerate().any(|(k, d)| {
            let want = d0 - k as f64 * STEP;
            want < view_start && d.is_none_or(|d| (f64::from(d) - want).abs() > 0.05)
        }),
        "single frames keep the step in the blind zone? {single:?}"
    );
}

#[test]
fn a_ramp_toe_keeps_its_distance_into_the_blind_zone() {
    // A 20° ramp under the whole corridor, toe 1.2 m out: go, workcase 2, the toe's
    // distance falling with the travel as the toe passes out of view.
    let toe = 1.215;
    let terrain = Terrain::new(vec![Element::ramp(toe, 0.0, 20.0, 0.0, Extent::Full)]);
    let steps = [(STEP, 0.0); 18];
    for (k, (pose, v)) in drive(&terrain, &steps, Some(1.0)).iter().enumerate() {
        let f = v
            .feature
            .unwrap_or_else(|| panic!("frame {k}: {:?}", v.hazards));
        assert_eq!(f.workcase, 2, "frame {k}");
        let got = f64::from(f.distance_m.unwrap());
        let want = toe - pose.x;
        assert!(
            (got - want).abs() <= 0.02,
            "frame {k}: {got:.3}, expected {want:.3}"
        );
        let g = f64::from(f.gradient_deg.unwrap());
        assert!((g - 20.0).abs() <= 0.5, "frame {k}: gradient {g}");
    }
}

#[test]
fn a_noisy_drive_fused_has_quieter_cells_and_smaller_errors_within_the_noisy_bars() {
    // The validation report's drive: 20 frames with Kinect v1 noise toward a 20° ramp.
    let c =
        rover_terrain::validate::run_memory_drive(rover_terrain::validate::FAMILY_SEED).unwrap();
    assert_eq!((c.single.measured, c.fused.measured), (20, 20));
    // Averaging agreeing views: each cell's height is less noisy...
    assert!(
        c.fused.cell_rms_m < 0.8 * c.single.cell_rms_m,
        "cell RMS fused {} vs single {}",
        c.fused.cell_rms_m,
        c.single.cell_rms_m
    );
    // ...the toe's distance and gradient come out nearer the truth on average...
    assert!(
        c.fused.distance_mean < c.single.distance_mean
            && c.fused.gradient_mean < c.single.gradient_mean,
        "fused {:?} vs single {:?}",
        c.fused,
        c.single
    );
    // ...and the ramp is measured within the noisy bars in every frame, fused or not.
    for e in [c.single, c.fused] {
        assert!(e.distance_max < 0.03 && e.gradient_max < 1.5, "{e:?}");
    }
}

/// `n` frames of `terrain` from a camera driving straight ahead from `back` metres
/// behind the rover origin, 0.1 m a frame, each with the motion it was reached by (the
/// first with none).
fn straight_drive<'a>(
    terrain: &'a Terrain,
    config: &'a Config,
    back: f64,
    n: usize,
) -> impl Iterator<Item = (DepthFrame, Result<Motion, Untrusted>)> + 'a {
    let step = Motion {
        forward_m: 0.1,
        dt_s: 0.1,
        ..Motion::default()
    };
    (0..n).map(move |k| {
        let pose = Pose {
            x: -back + 0.1 * k as f64,
            ..Pose::default()
        };
        let motion = if k == 0 {
            Err(Untrusted::NoOdometry)
        } else {
            Ok(step)
        };
        (sim::render_from(terrain, config, pose), motion)
    })
}

#[test]
fn a_boulder_the_image_s_side_edge_cuts_off_near_the_rover_is_remembered() {
    // A camera yawed 9.7° to the right (Kinect v1 0.98 m high, pitched 40°) does not
    // see the left track's outer half 1 m ahead: an 18.9 cm boulder centred there shows
    // one frame only its inner flank, 8 cm high at the image's left edge, and that
    // frame alone is go (`sweep -- natural 100 5902 random` #95). Driving up to it
    // from 0.6 m farther back, the camera sees it whole, and the memory keeps it.
    let mut config = Config::default();
    (config.mount.x_m, config.mount.y_m, config.mount.z_m) = (0.178, -0.028, 0.977);
    (
        config.mount.roll_deg,
        config.mount.pitch_deg,
        config.mount.yaw_deg,
    ) = (-1.669, 40.443, -9.738);
    let boulder = Terrain::new(vec![Element::stone(
        0.979,
        0.506,
        0.161,
        0.189,
        sim::StoneShape::Mound,
    )]);
    let mut fused = Pipeline::new(config.clone()).unwrap();
    for (k, (frame, motion)) in straight_drive(&boulder, &config, 0.6, 7).enumerate() {
        let v = fused.process_moved(&frame, motion).unwrap().clone();
        assert_ne!(v.decision, Decision::Go, "frame {k}");
        assert!(
            v.hazards.iter().any(|h| h.side == Side::Left),
            "frame {k}: {:?}",
            v.hazards
        );
        if k == 6 {
            assert!(
                v.memory.remembered_hazards > 0,
                "the last frame's stop is not remembered"
            );
        }
    }
}

#[test]
fn a_cone_many_frames_found_is_not_lost_to_the_few_that_read_it_low() {
    // A Kinect v2 0.63 m high, pitched 34°, over lumpy ground with stones (`sweep --
    // natural 100 9202 random` #95): a 16.1 cm cone with 39° flanks in the left track,
    // driven up to, its apex from 2.7 m out to 0.7 m, in 0.1 m steps. Alone, the first
    // eleven frames find it a `step` at its foot (2.5 m to 1.5 m out); the next seven,
    // its apex 1.6 m to 1.0 m out, read its flank climbing under the slope limit (the
    // apex stands 12.7 cm over the ground before it: lumpy ground dips under it) and go, and so did the drive: the memory's hazards in view were the
    // frame's alone. One that many frames found is now dropped only once as many miss
    // it (up to a second's frames), and the drive stops in every frame.
    let mut config = Config::default();
    (config.camera.width, config.camera.height) = (512, 424);
    (config.camera.hfov_deg, config.camera.vfov_deg) = (70.6, 60.0);
    config.camera.min_range_m = 0.3438;
    (config.mount.x_m, config.mount.y_m, config.mount.z_m) = (0.2870, -0.0782, 0.6325);
    (
        config.mount.roll_deg,
        config.mount.pitch_deg,
        config.mount.yaw_deg,
    ) = (-0.2172, 34.0970, -1.2975);
    let stone = |x, y, r, h, shape| Element::stone(x, y, r, h, shape);
    let field = Terrain::new(vec![
        Element::Lumpy {
            amplitude_m: 0.025,
            spacing_m: 0.124_644_479,
            seed: 11_734_450_997_885_754_867,
        },
        stone(2.3359, -0.5062, 0.0839, 0.0540, sim::StoneShape::Boulder),
        stone(2.0437, 0.3857, 0.0856, 0.0517, sim::StoneShape::Boulder),
        stone(1.2906, -0.3633, 0.0962, 0.0610, sim::StoneShape::Cone),
        stone(2.0367, -0.5842, 0.1263, 0.0881, sim::StoneShape::Mound),
        stone(1.5108, 0.3867, 0.1964, 0.1608, sim::StoneShape::Cone),
    ]);
    let (mut fused, mut alone) = (
        Pipeline::new(config.clone()).unwrap(),
        Pipeline::new(config.clone()).unwrap(),
    );
    let (mut found_by, mut single_goes) = (0, 0);
    for (k, (frame, motion)) in straight_drive(&field, &config, 1.2, 21).enumerate() {
        let v = fused.process_moved(&frame, motion).unwrap().clone();
        let single = alone.process(&frame).unwrap().decision;
        if found_by >= 2 {
            assert_eq!(v.decision, Decision::Stop, "frame {k}: {:?}", v.hazards);
            assert!(
                hazard(&v, HazardKind::Step, Side::Left).is_some(),
                "frame {k}"
            );
            single_goes += usize::from(single == Decision::Go);
        }
        found_by = if hazard(&v, HazardKind::Step, Side::Left).is_some() {
            found_by + 1
        } else {
            0
        };
    }
    // The frames alone went where the drive kept the stop: the memory held it.
    assert!(single_goes >= 3, "{single_goes}");
}

/// `config` with the camera at `[x, y, z]` (metres) turned by `[roll, pitch, yaw]`
/// (degrees), `width`×`height` pixels over `[hfov, vfov]` (degrees), seeing from
/// `min_range_m`.
fn rig(
    [x, y, z]: [f64; 3],
    [roll, pitch, yaw]: [f64; 3],
    [width, height]: [u32; 2],
    [hfov, vfov]: [f64; 2],
    min_range_m: f64,
) -> Config {
    let mut c = Config::default();
    (c.mount.x_m, c.mount.y_m, c.mount.z_m) = (x, y, z);
    (c.mount.roll_deg, c.mount.pitch_deg, c.mount.yaw_deg) = (roll, pitch, yaw);
    (c.camera.width, c.camera.height) = (width, height);
    (c.camera.hfov_deg, c.camera.vfov_deg) = (hfov, vfov);
    c.camera.min_range_m = min_range_m;
    c
}

/// Drive `config`'s rover straight on from the scene's pose over `terrain`, 0.1 m a
/// frame for `n` frames, through one pipeline: each frame's verdict.
fn drive_on(terrain: &Terrain, config: &Config, n: usize) -> Vec<Verdict> {
    let mut fused = Pipeline::new(config.clone()).unwrap();
    straight_drive(terrain, config, 0.0, n)
        .map(|(frame, motion)| fused.process_moved(&frame, motion).unwrap().clone())
        .collect()
}

#[test]
fn an_obstacle_whose_front_the_view_ends_on_is_found_a_frame_nearer_and_kept() {
    // Two scenes whose one frame goes where a stop is due (`sweep -- hazards 100 3304
    // random` #32 and `natural 100 3310 random 10` #26, clean and noisy): the image's
    // top edge crosses the obstacle's front a few centimetres up, so its height is not
    // seen, and the verdict's `seen_to_m` ends at its foot. A rover driving on must
    // find it within two frames (0.2 m), well before it, and never go again; the same
    // drives without the obstacle go in every frame.
    //
    // A 0.56 m block 0.25 m square under the belly, 1.97 m ahead, seen by a Kinect v2
    // 0.52 m high pitched 43° and yawed −10°: 4.8 cm of its face are in the image.
    let kinect_v2 = rig(
        [0.117, 0.052, 0.5167],
        [-2.322, 43.194, -9.983],
        [512, 424],
        [70.6, 60.0],
        0.3374,
    );
    let block = Element::Block {
        x_m: 2.0959,
        y_m: -0.0216,
        length_m: 0.25,
        width_m: 0.25,
        height_m: 0.5566,
    };
    // A 15.6 cm mound 0.25 m up a smooth 14.7° ramp under the right track, seen by a
    // 320×240 camera 0.51 m high pitched 31° and rolled 9.8°: its front rises 2-4 cm
    // over the ramp where the view ends.
    let qvga = rig(
        [0.1712, -0.0645, 0.5075],
        [9.793, 31.152, -0.909],
        [320, 240],
        [57.0, 43.0],
        0.3578,
    );
    let ramp = Element::ramp(1.7511, 0.0, 14.661, 0.0, Extent::Full);
    let mound = Element::stone(2.1664, -0.456, 0.1713, 0.1561, sim::StoneShape::Mound);
    let scenes = [
        (vec![block], vec![], &kinect_v2, Side::Centre),
        (vec![ramp.clone(), mound], vec![ramp], &qvga, Side::Right),
    ];
    for (with, without, config, side) in scenes {
        let name = format!("{:?}", with.last().unwrap());
        let verdicts = drive_on(&Terrain::new(with), config, 8);
        let first = verdicts
            .iter()
            .position(|v| v.decision != Decision::Go)
            .unwrap_or(verdicts.len());
        assert!(first <= 2, "{name}: first not go at frame {first}");
        for (k, v) in verdicts.iter().enumerate().skip(first) {
            assert_ne!(v.decision, Decision::Go, "{name}: frame {k} goes again");
            assert!(
                v.hazards.iter().any(|h| h.side == side),
                "{name}: frame {k}: {:?}",
                v.hazards
            );
        }
        for (k, v) in drive_on(&Terrain::new(without), config, 8)
            .iter()
            .enumerate()
        {
            assert_eq!(
                v.decision,
                Decision::Go,
                "{name} alone: frame {k}: {:?}",
                v.hazards
            );
        }
    }
}
