//! What the analysis saw and decided, for Foxglove (or Lichtblick) and ROS 2 tooling:
//! `analyze --mcap FILE` and `inspect --mcap FILE` write one MCAP file with, per frame:
//!
//! | topic | schema | encoding |
//! |---|---|---|
//! | [`TOPIC_DEPTH`] | `sensor_msgs/msg/Image` (16UC1, mm) | cdr |
//! | [`TOPIC_CAMERA_INFO`] | `sensor_msgs/msg/CameraInfo` | cdr |
//! | [`TOPIC_VERDICT`] | `rover_terrain.Verdict` (`verdict.schema.json`) | json |
//! | [`TOPIC_CLOUD`] | `foxglove.PointCloud` (voxel centroids by class) | protobuf |
//! | [`TOPIC_GRID`] | `foxglove.Grid` (height, view, class, colour) | protobuf |
//! | [`TOPIC_SCENE`] | `foxglove.SceneUpdate` (toe line, hazards, decision) | protobuf |
//! | [`TOPIC_TF`] | `foxglove.FrameTransform` (base → camera optical frame) | protobuf |
//!
//! The message contents are [`messages`]' pure functions of the frame's scene; this
//! module only names the channels and writes them (the `mcap` crate, through
//! [`McapFile`]).

pub mod messages;

use std::path::Path;

use foxglove::Encode;
use rover_terrain_drivers::ros2::msg::{self, CameraInfo, Image};
use rover_terrain_drivers::ros2::McapFile;
use rover_terrain_drivers::DepthFrame;

use crate::inspect::Scene;
use crate::Error;
pub use messages::Frames;

impl Frames {
    /// The frame names `[ros]` sets.
    pub fn of(config: &crate::Config) -> Self {
        Frames {
            base: config.ros.base_frame.clone(),
            camera: config.ros.camera_frame.clone(),
        }
    }
}

/// The depth images analysed.
pub const TOPIC_DEPTH: &str = "/camera/depth/image_raw";
/// Their calibration.
pub const TOPIC_CAMERA_INFO: &str = "/camera/depth/camera_info";
/// The verdict, as `analyze` prints it.
pub const TOPIC_VERDICT: &str = "/rover_terrain/verdict";
/// The voxel centroids.
pub const TOPIC_CLOUD: &str = "/rover_terrain/cloud";
/// The ground grid.
pub const TOPIC_GRID: &str = "/rover_terrain/grid";
/// The toe line, hazards and decision drawn in 3D.
pub const TOPIC_SCENE: &str = "/rover_terrain/scene";
/// The camera's mount.
pub const TOPIC_TF: &str = "/tf";

/// The verdict's JSON schema.
pub const VERDICT_SCHEMA: &str = include_str!("verdict.schema.json");

/// The channel ids of one output file.
#[derive(Debug, Clone, Copy)]
struct Channels {
    depth: u16,
    info: u16,
    verdict: u16,
    cloud: u16,
    grid: u16,
    scene: u16,
    tf: u16,
}

/// An MCAP file of analysed frames.
#[derive(Debug)]
pub struct McapOut {
    file: McapFile,
    channels: Channels,
    frames: Frames,
    written: u64,
}

/// A protobuf channel for the Foxglove message type `T`.
fn protobuf_channel<T: Encode>(file: &mut McapFile, topic: &str) -> Result<u16, Error> {
    let schema = T::get_schema()
        .ok_or_else(|| Error::Setup(format!("{topic}: the foxglove crate gave no schema")))?;
    Ok(file.channel(
        topic,
        (&schema.name, &schema.encoding, &schema.data),
        &T::get_message_encoding(),
    )?)
}

fn encoded<T: Encode>(msg: &T) -> Result<Vec<u8>, Error> {
    let mut buf = Vec::with_capacity(msg.encoded_len().unwrap_or(1024));
    msg.encode(&mut buf)
        .map_err(|e| Error::Setup(format!("encoding a Foxglove message: {e}")))?;
    Ok(buf)
}

impl McapOut {
    /// Create `path` (replacing it), its messages in the TF frames `frames`.
    pub fn create(path: &Path, frames: Frames) -> Result<Self, Error> {
        let mut file = McapFile::create(path, "")?;
        let image = msg::image_msgdef();
        let info = msg::camera_info_msgdef();
        let channels = Channels {
            depth: file.channel(
                TOPIC_DEPTH,
                (msg::IMAGE, msg::SCHEMA_ENCODING, image.as_bytes()),
                msg::MESSAGE_ENCODING,
            )?,
            info: file.channel(
                TOPIC_CAMERA_INFO,
                (msg::CAMERA_INFO, msg::SCHEMA_ENCODING, info.as_bytes()),
                msg::MESSAGE_ENCODING,
            )?,
            verdict: file.channel(
                TOPIC_VERDICT,
                (
                    "rover_terrain.Verdict",
                    "jsonschema",
                    VERDICT_SCHEMA.as_bytes(),
                ),
                "json",
            )?,
            cloud: protobuf_channel::<foxglove::messages::PointCloud>(&mut file, TOPIC_CLOUD)?,
            grid: protobuf_channel::<foxglove::messages::Grid>(&mut file, TOPIC_GRID)?,
            scene: protobuf_channel::<foxglove::messages::SceneUpdate>(&mut file, TOPIC_SCENE)?,
            tf: protobuf_channel::<foxglove::messages::FrameTransform>(&mut file, TOPIC_TF)?,
        };
        Ok(McapOut {
            file,
            channels,
            frames,
            written: 0,
        })
    }

    /// Write one analysed frame: its depth image and calibration, its verdict (the
    /// JSON `analyze` prints), cloud, grid, drawing and camera transform, all stamped
    /// with the frame's own time.
    pub fn write(
        &mut self,
        frame: &DepthFrame,
        scene: &Scene<'_>,
        verdict: &serde_json::Value,
    ) -> Result<(), Error> {
        let t = frame.timestamp_s;
        let stamp = messages::timestamp(t);
        let ros_stamp = msg::Time::from_secs(t);
        let c = self.channels;
        let f = &self.frames;
        let image = Image::from_depth(frame, ros_stamp, &f.camera);
        let k = scene.config.intrinsics_for(frame.width(), frame.height());
        let info = CameraInfo::pinhole(&k, ros_stamp, &f.camera);
        let out: [(u16, Vec<u8>); 7] = [
            (c.depth, msg::encode(&image)),
            (c.info, msg::encode(&info)),
            (c.verdict, verdict.to_string().into_bytes()),
            (c.cloud, encoded(&messages::cloud(scene, stamp, f))?),
            (c.grid, encoded(&messages::grid(scene, stamp, f))?),
            (c.scene, encoded(&messages::scene_update(scene, stamp, f))?),
            (
                c.tf,
                encoded(&messages::camera_transform(scene.config, stamp, f))?,
            ),
        ];
        for (channel, data) in out {
            self.file.write(channel, t, &data)?;
        }
        self.written += 1;
        Ok(())
    }

    /// Frames written so far.
    pub fn written(&self) -> u64 {
        self.written
    }

    /// Write the summary and close the file.
    pub fn finish(self) -> Result<(), Error> {
        Ok(self.file.finish()?)
    }
}
