//! Writing MCAP files: [`McapFile`], a thin layer over the `mcap` crate's writer
//! (zstd chunks, one schema and channel per topic, messages stamped in nanoseconds),
//! and [`BagWriter`], a ROS 2 bag of depth (and colour) frames as
//! `sensor_msgs/msg/Image` with a `CameraInfo`, for `record --format mcap`.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use super::msg::{self, CameraInfo, Image, Time};
use crate::camera::Intrinsics;
use crate::{ColourFrame, DepthFrame, DriverError};

/// `time_s` seconds since the epoch as MCAP's nanoseconds (negative and non-finite
/// become 0).
pub fn nanos(time_s: f64) -> u64 {
    if time_s.is_finite() && time_s > 0.0 {
        (time_s * 1e9) as u64
    } else {
        0
    }
}

/// An MCAP file being written.
pub struct McapFile {
    path: PathBuf,
    writer: mcap::Writer<BufWriter<File>>,
    schemas: BTreeMap<String, u16>,
    sequence: u32,
}

impl std::fmt::Debug for McapFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "McapFile({})", self.path.display())
    }
}

impl McapFile {
    /// Create `path` (replacing it), with the given MCAP profile (`ros2`, or empty).
    pub fn create(path: &Path, profile: &str) -> Result<Self, DriverError> {
        let file = File::create(path).map_err(|e| DriverError::io(path, e))?;
        let writer = mcap::WriteOptions::new()
            .compression(Some(mcap::Compression::Zstd))
            .profile(profile)
            .library(concat!("rover-terrain ", env!("CARGO_PKG_VERSION")))
            .create(BufWriter::new(file))
            .map_err(|e| DriverError::malformed(path, e.to_string()))?;
        Ok(McapFile {
            path: path.to_path_buf(),
            writer,
            schemas: BTreeMap::new(),
            sequence: 0,
        })
    }

    fn err(&self, e: mcap::McapError) -> DriverError {
        DriverError::malformed(&self.path, format!("writing MCAP: {e}"))
    }

    /// Add a channel on `topic` whose messages are `message_encoding` under the schema
    /// `schema` (`name`, `encoding`, `data`; the same schema is stored once).
    pub fn channel(
        &mut self,
        topic: &str,
        schema: (&str, &str, &[u8]),
        message_encoding: &str,
    ) -> Result<u16, DriverError> {
        let (name, encoding, data) = schema;
        let id = match self.schemas.get(name) {
            Some(&id) => id,
            None => {
                let id = self
                    .writer
                    .add_schema(name, encoding, data)
                    .map_err(|e| self.err(e))?;
                self.schemas.insert(name.to_string(), id);
                id
            }
        };
        self.writer
            .add_channel(id, topic, message_encoding, &BTreeMap::new())
            .map_err(|e| self.err(e))
    }

    /// Write one message on `channel`, logged and published at `time_s` (seconds since
    /// the epoch; negative and non-finite become 0).
    pub fn write(&mut self, channel: u16, time_s: f64, data: &[u8]) -> Result<(), DriverError> {
        let ns = nanos(time_s);
        self.sequence = self.sequence.wrapping_add(1);
        let header = mcap::records::MessageHeader {
            channel_id: channel,
            sequence: self.sequence,
            log_time: ns,
            publish_time: ns,
        };
        self.writer
            .write_to_known_channel(&header, data)
            .map_err(|e| self.err(e))
    }

    /// Write the summary and close the file (a file not finished has no index, and
    /// readers see it as truncated).
    pub fn finish(mut self) -> Result<(), DriverError> {
        self.writer.finish().map_err(|e| self.err(e))?;
        Ok(())
    }
}

/// The ROS 2 topics and frame ids a recording is written under.
#[derive(Debug, Clone)]
pub struct BagTopics {
    /// Depth images (`sensor_msgs/msg/Image`, 16UC1).
    pub depth: String,
    /// Their calibration (`sensor_msgs/msg/CameraInfo`).
    pub depth_info: String,
    /// Colour images (rgb8).
    pub colour: String,
    /// The depth camera's optical frame.
    pub depth_frame_id: String,
    /// The colour camera's optical frame.
    pub colour_frame_id: String,
}

impl Default for BagTopics {
    /// The topics a ROS 2 depth camera driver publishes.
    fn default() -> Self {
        BagTopics {
            depth: "/camera/depth/image_raw".into(),
            depth_info: "/camera/depth/camera_info".into(),
            colour: "/camera/color/image_raw".into(),
            depth_frame_id: "camera_depth_optical_frame".into(),
            colour_frame_id: "camera_color_optical_frame".into(),
        }
    }
}

/// A ROS 2 bag (MCAP, profile `ros2`, CDR) of depth frames with their `CameraInfo`,
/// and colour frames where the camera has them.
#[derive(Debug)]
pub struct BagWriter {
    file: McapFile,
    topics: BagTopics,
    depth: u16,
    info: u16,
    colour: Option<u16>,
}

impl BagWriter {
    /// Create the bag at `path`.
    pub fn create(path: &Path, topics: BagTopics) -> Result<Self, DriverError> {
        let mut file = McapFile::create(path, "ros2")?;
        let image = msg::image_msgdef();
        let image_schema = (msg::IMAGE, msg::SCHEMA_ENCODING, image.as_bytes());
        let depth = file.channel(&topics.depth, image_schema, msg::MESSAGE_ENCODING)?;
        let info_def = msg::camera_info_msgdef();
        let info = file.channel(
            &topics.depth_info,
            (msg::CAMERA_INFO, msg::SCHEMA_ENCODING, info_def.as_bytes()),
            msg::MESSAGE_ENCODING,
        )?;
        Ok(BagWriter {
            file,
            topics,
            depth,
            info,
            colour: None,
        })
    }

    /// Write a depth frame taken at `time_s` (seconds since the epoch) and the
    /// calibration `k` of the camera that took it.
    pub fn write_depth(
        &mut self,
        frame: &DepthFrame,
        time_s: f64,
        k: &Intrinsics,
    ) -> Result<(), DriverError> {
        let stamp = Time::from_secs(time_s);
        let img = Image::from_depth(frame, stamp, &self.topics.depth_frame_id);
        self.file.write(self.depth, time_s, &msg::encode(&img))?;
        let info = CameraInfo::pinhole(k, stamp, &self.topics.depth_frame_id);
        self.file.write(self.info, time_s, &msg::encode(&info))
    }

    /// Write a colour frame taken at `time_s`.
    pub fn write_colour(&mut self, frame: &ColourFrame, time_s: f64) -> Result<(), DriverError> {
        let channel = match self.colour {
            Some(c) => c,
            None => {
                let image = msg::image_msgdef();
                let c = self.file.channel(
                    &self.topics.colour,
                    (msg::IMAGE, msg::SCHEMA_ENCODING, image.as_bytes()),
                    msg::MESSAGE_ENCODING,
                )?;
                self.colour = Some(c);
                c
            }
        };
        let img = Image::from_colour(frame, Time::from_secs(time_s), &self.topics.colour_frame_id);
        self.file.write(channel, time_s, &msg::encode(&img))
    }

    /// Finish the bag (see [`McapFile::finish`]).
    pub fn finish(self) -> Result<(), DriverError> {
        self.file.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{DepthCamera, FakeCamera, FrameStatus};

    #[test]
    fn a_written_bag_reads_back_frame_for_frame_with_its_calibration() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("rec.mcap");
        let k = Intrinsics {
            width: 4,
            height: 3,
            pinhole: Some((5.0, 6.0, 2.0, 1.5)),
        };
        let mut w = BagWriter::create(&path, BagTopics::default()).unwrap();
        for i in 0..3u16 {
            let f = DepthFrame::from_pixels(4, 3, (0..12).map(|p| p * 100 + i).collect());
            w.write_depth(&f, 1_700_000_000.0 + f64::from(i) * 0.1, &k)
                .unwrap();
            let mut c = ColourFrame::default();
            c.reshape(4, 3).fill(7);
            w.write_colour(&c, 1_700_000_000.0).unwrap();
        }
        w.finish().unwrap();
        // Without a topic: the only depth topic (the colour one is not a candidate).
        let mut cam = FakeCamera::open_bag(&path, None).unwrap();
        assert_eq!(cam.intrinsics(), Some(k));
        let mut f = DepthFrame::default();
        for i in 0..3u16 {
            assert_eq!(cam.next_frame(&mut f).unwrap(), FrameStatus::Frame);
            assert_eq!(f.pixels()[5], 500 + i);
            assert!((f.timestamp_s - (1_700_000_000.0 + f64::from(i) * 0.1)).abs() < 1e-6);
        }
        assert_eq!(cam.next_frame(&mut f).unwrap(), FrameStatus::EndOfStream);
    }

    #[test]
    fn an_unwritable_path_is_an_error_naming_it() {
        let e = BagWriter::create(Path::new("/nonexistent/dir/x.mcap"), BagTopics::default())
            .unwrap_err();
        assert!(e.to_string().contains("/nonexistent/dir/x.mcap"), "{e}");
    }
}
