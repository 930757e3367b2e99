//! `analyze --mcap`: the MCAP file for Foxglove, read back with the `mcap` crate and the
//! Foxglove messages decoded (CI also reads it with the Python `mcap` readers,
//! `tests/ros2/check_mcap.py`).

use std::collections::BTreeMap;
use std::path::Path;

use foxglove::messages::{FrameTransform, Grid, PointCloud, SceneUpdate};
use foxglove::Decode;
use rover_terrain::foxglove::{self as fx, messages::CLOUD_STRIDE, messages::GRID_STRIDE};
use rover_terrain::inspect::cloud::read_pcd;
use rover_terrain::inspect::Scene;
use rover_terrain::{Config, Pipeline};
use rover_terrain_drivers::{DepthCamera, DepthFrame, FakeCamera};

const FRAMES: [&str; 3] = ["flat", "step_15cm", "uphill_straight"];

fn fixture(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("fixtures/scenes/{name}.png"))
}

#[test]
fn analyze_mcap_holds_every_channel_once_per_frame_and_the_cloud_of_cloud_pcd() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run.mcap");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_rover-terrain"))
        .arg("analyze")
        .args(FRAMES.map(fixture))
        .arg("--mcap")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let printed: Vec<serde_json::Value> = String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();

    let bytes = std::fs::read(&out).unwrap();
    let mut by_topic: BTreeMap<String, Vec<Vec<u8>>> = BTreeMap::new();
    let mut schemas = BTreeMap::new();
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        let s = m.channel.schema.as_ref().unwrap();
        schemas.insert(
            m.channel.topic.clone(),
            (s.name.clone(), s.encoding.clone()),
        );
        by_topic
            .entry(m.channel.topic.clone())
            .or_default()
            .push(m.data.into_owned());
    }
    let want = [
        (fx::TOPIC_DEPTH, "sensor_msgs/msg/Image", "ros2msg"),
        (
            fx::TOPIC_CAMERA_INFO,
            "sensor_msgs/msg/CameraInfo",
            "ros2msg",
        ),
        (fx::TOPIC_VERDICT, "rover_terrain.Verdict", "jsonschema"),
        (fx::TOPIC_CLOUD, "foxglove.PointCloud", "protobuf"),
        (fx::TOPIC_GRID, "foxglove.Grid", "protobuf"),
        (fx::TOPIC_SCENE, "foxglove.SceneUpdate", "protobuf"),
        (fx::TOPIC_TF, "foxglove.FrameTransform", "protobuf"),
    ];
    assert_eq!(by_topic.len(), want.len(), "{:?}", by_topic.keys());
    for (topic, schema, encoding) in want {
        assert_eq!(
            schemas[topic],
            (schema.to_string(), encoding.to_string()),
            "{topic}"
        );
        assert_eq!(by_topic[topic].len(), FRAMES.len(), "{topic}");
    }
    // The verdicts are what was printed.
    for (m, p) in by_topic[fx::TOPIC_VERDICT].iter().zip(&printed) {
        let v: serde_json::Value = serde_json::from_slice(m).unwrap();
        assert_eq!(&v, p);
    }
    // Each cloud is that frame's cloud.pcd, point for point; the grid, drawing and
    // transform decode and agree with the frame's analysis.
    let config = Config::default();
    let mut pipeline = Pipeline::new(config.clone()).unwrap();
    for (i, name) in FRAMES.iter().enumerate() {
        let mut cam = FakeCamera::open(&fixture(name)).unwrap();
        let mut frame = DepthFrame::default();
        cam.next_frame(&mut frame).unwrap();
        let verdict = pipeline.process(&frame).unwrap().clone();
        let scene = Scene::of(&pipeline, &verdict);
        let pcd = read_pcd(&rover_terrain::inspect::cloud::pcd(&scene)).unwrap();
        let cloud = PointCloud::decode(&by_topic[fx::TOPIC_CLOUD][i][..]).unwrap();
        assert_eq!(cloud.frame_id, "base_link");
        assert_eq!(cloud.data.len(), pcd.len() * CLOUD_STRIDE, "{name}");
        for (p, chunk) in pcd.iter().zip(cloud.data.chunks_exact(CLOUD_STRIDE)) {
            let f = |k: usize| f32::from_le_bytes(chunk[4 * k..4 * k + 4].try_into().unwrap());
            assert_eq!([f(0), f(1), f(2)], [p.x, p.y, p.z], "{name}");
            assert_eq!(chunk[12..15], p.rgb, "{name}");
        }
        let grid = Grid::decode(&by_topic[fx::TOPIC_GRID][i][..]).unwrap();
        let spec = pipeline.grid().spec();
        assert_eq!(grid.column_count as usize, spec.nx);
        assert_eq!(grid.data.len(), spec.nx * spec.ny * GRID_STRIDE);
        let update = SceneUpdate::decode(&by_topic[fx::TOPIC_SCENE][i][..]).unwrap();
        let entity = &update.entities[0];
        assert_eq!(entity.cubes.len(), verdict.hazards.len(), "{name}");
        assert_eq!(
            entity.lines.len(),
            usize::from(scene.toe_line().is_some()),
            "{name}"
        );
        let tf = FrameTransform::decode(&by_topic[fx::TOPIC_TF][i][..]).unwrap();
        assert_eq!(
            (tf.parent_frame_id.as_str(), tf.child_frame_id.as_str()),
            ("base_link", "camera_depth_optical_frame")
        );
        assert_eq!(tf.translation.unwrap().z, config.mount.z_m);
    }
}

#[test]
fn the_shipped_foxglove_layout_is_json_and_shows_only_topics_we_write() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/foxglove/rover-terrain-layout.json");
    let layout: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let ours = [
        fx::TOPIC_DEPTH,
        fx::TOPIC_CAMERA_INFO,
        fx::TOPIC_VERDICT,
        fx::TOPIC_CLOUD,
        fx::TOPIC_GRID,
        fx::TOPIC_SCENE,
        fx::TOPIC_TF,
    ];
    // Every string in the layout that looks like a topic (or a topic's field path)
    // names one of ours; and the 3D panel shows the cloud, grid and drawing.
    fn strings<'a>(v: &'a serde_json::Value, out: &mut Vec<&'a str>) {
        match v {
            serde_json::Value::String(s) => out.push(s),
            serde_json::Value::Array(a) => a.iter().for_each(|v| strings(v, out)),
            serde_json::Value::Object(o) => o.iter().for_each(|(k, v)| {
                out.push(k);
                strings(v, out)
            }),
            _ => {}
        }
    }
    let mut all = Vec::new();
    strings(&layout, &mut all);
    let topics: Vec<&str> = all.into_iter().filter(|s| s.starts_with('/')).collect();
    assert!(!topics.is_empty());
    for t in &topics {
        let topic = t.split('.').next().unwrap();
        assert!(
            ours.contains(&topic),
            "the layout names {t}, which we do not write"
        );
    }
    let shown = &layout["configById"]["3D!rover"]["topics"];
    for t in [fx::TOPIC_CLOUD, fx::TOPIC_GRID, fx::TOPIC_SCENE] {
        assert_eq!(shown[t]["visible"], true, "{t}");
    }
    assert_eq!(layout["configById"]["3D!rover"]["followTf"], "base_link");
}

#[test]
fn run_mcap_writes_every_frame_and_refuses_a_file_it_cannot_write() {
    let exe = env!("CARGO_BIN_EXE_rover-terrain");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run.mcap");
    let verdicts = |o: &std::process::Output| {
        String::from_utf8_lossy(&o.stdout)
            .lines()
            .filter(|l| l.contains("\"type\":\"verdict\""))
            .count()
    };
    let ok = std::process::Command::new(exe)
        .args(["run", "--mcap"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    // The bundled fixtures: 20 frames, each written, then the final stop verdict.
    let bytes = std::fs::read(&out).unwrap();
    let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
    let stats = summary.stats.unwrap();
    assert_eq!(stats.channel_message_counts.len(), 7);
    assert!(
        stats.channel_message_counts.values().all(|&n| n == 20),
        "{stats:?}"
    );
    assert_eq!(verdicts(&ok), 21);
    // A file that cannot be written is refused at the start, naming it.
    let full = std::process::Command::new(exe)
        .args(["run", "--mcap", "/dev/full"])
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&full.stderr);
    assert!(!full.status.success(), "{log}");
    assert!(log.contains("/dev/full: writing MCAP"), "{log}");
}

#[cfg(not(feature = "foxglove-live"))]
#[test]
fn run_foxglove_without_the_feature_says_how_to_get_it() {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_rover-terrain"))
        .args(["run", "--frames", "1", "--foxglove"])
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{log}");
    assert!(
        log.contains("127.0.0.1:8765") && log.contains("--features foxglove-live"),
        "{log}"
    );
}
