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

#[cfg(feature = "foxglove-live")]
pub mod live;
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

/// How many channels a frame is published on.
pub const CHANNELS: usize = 7;

/// One channel: its topic, schema (name, encoding, data) and message encoding.
#[derive(Debug, Clone)]
pub struct ChannelSpec {
    /// The topic.
    pub topic: &'static str,
    /// Schema name.
    pub schema_name: String,
    /// Schema encoding: `ros2msg`, `jsonschema` or `protobuf`.
    pub schema_encoding: String,
    /// The schema itself.
    pub schema: Vec<u8>,
    /// Message encoding: `cdr`, `json` or `protobuf`.
    pub message_encoding: String,
}

/// A channel for the Foxglove protobuf message type `T`.
fn protobuf<T: Encode>(topic: &'static str) -> Result<ChannelSpec, Error> {
    let schema = T::get_schema()
        .ok_or_else(|| Error::Setup(format!("{topic}: the foxglove crate gave no schema")))?;
    Ok(ChannelSpec {
        topic,
        schema_name: schema.name,
        schema_encoding: schema.encoding,
        schema: schema.data.into_owned(),
        message_encoding: T::get_message_encoding(),
    })
}

/// The channels of a frame, in the order of [`payloads`].
pub fn channels() -> Result<[ChannelSpec; CHANNELS], Error> {
    let ros = |topic, name: &str, def: String| ChannelSpec {
        topic,
        schema_name: name.into(),
        schema_encoding: msg::SCHEMA_ENCODING.into(),
        schema: def.into_bytes(),
        message_encoding: msg::MESSAGE_ENCODING.into(),
    };
    Ok([
        ros(TOPIC_DEPTH, msg::IMAGE, msg::image_msgdef()),
        ros(
            TOPIC_CAMERA_INFO,
            msg::CAMERA_INFO,
            msg::camera_info_msgdef(),
        ),
        ChannelSpec {
            topic: TOPIC_VERDICT,
            schema_name: "rover_terrain.Verdict".into(),
            schema_encoding: "jsonschema".into(),
            schema: VERDICT_SCHEMA.as_bytes().to_vec(),
            message_encoding: "json".into(),
        },
        protobuf::<foxglove::messages::PointCloud>(TOPIC_CLOUD)?,
        protobuf::<foxglove::messages::Grid>(TOPIC_GRID)?,
        protobuf::<foxglove::messages::SceneUpdate>(TOPIC_SCENE)?,
        protobuf::<foxglove::messages::FrameTransform>(TOPIC_TF)?,
    ])
}

fn encoded<T: Encode>(msg: &T) -> Result<Vec<u8>, Error> {
    let mut buf = Vec::with_capacity(msg.encoded_len().unwrap_or(1024));
    msg.encode(&mut buf)
        .map_err(|e| Error::Setup(format!("encoding a Foxglove message: {e}")))?;
    Ok(buf)
}

/// One analysed frame's messages, in the order of [`channels`]: its depth image and
/// calibration, its verdict (the JSON `analyze` prints), cloud, grid, drawing and
/// camera transform, all stamped with the frame's own time.
pub fn payloads(
    frame: &DepthFrame,
    scene: &Scene<'_>,
    verdict: &serde_json::Value,
    frames: &Frames,
) -> Result<[Vec<u8>; CHANNELS], Error> {
    let t = frame.timestamp_s;
    let stamp = messages::timestamp(t);
    let ros_stamp = msg::Time::from_secs(t);
    let image = Image::from_depth(frame, ros_stamp, &frames.camera);
    let k = scene.config.intrinsics_for(frame.width(), frame.height());
    let info = CameraInfo::pinhole(&k, ros_stamp, &frames.camera);
    Ok([
        msg::encode(&image),
        msg::encode(&info),
        verdict.to_string().into_bytes(),
        encoded(&messages::cloud(scene, stamp, frames))?,
        encoded(&messages::grid(scene, stamp, frames))?,
        encoded(&messages::scene_update(scene, stamp, frames))?,
        encoded(&messages::camera_transform(scene.config, stamp, frames))?,
    ])
}

/// An MCAP file of analysed frames.
#[derive(Debug)]
pub struct McapOut {
    file: McapFile,
    channels: [u16; CHANNELS],
    frames: Frames,
    written: u64,
}

impl McapOut {
    /// Create `path` (replacing it), its messages in the TF frames `frames`.
    pub fn create(path: &Path, frames: Frames) -> Result<Self, Error> {
        let mut file = McapFile::create(path, "")?;
        let mut ids = [0u16; CHANNELS];
        for (id, c) in ids.iter_mut().zip(channels()?) {
            *id = file.channel(
                c.topic,
                (&c.schema_name, &c.schema_encoding, &c.schema),
                &c.message_encoding,
            )?;
        }
        Ok(McapOut {
            file,
            channels: ids,
            frames,
            written: 0,
        })
    }

    /// Write one analysed frame (see [`payloads`]).
    pub fn write(
        &mut self,
        frame: &DepthFrame,
        scene: &Scene<'_>,
        verdict: &serde_json::Value,
    ) -> Result<(), Error> {
        let out = payloads(frame, scene, verdict, &self.frames)?;
        for (&channel, data) in self.channels.iter().zip(out) {
            self.file.write(channel, frame.timestamp_s, &data)?;
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
