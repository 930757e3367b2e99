//! Reading depth frames from a ROS 2 bag in MCAP (`--camera mcap:PATH[#TOPIC]`).
//!
//! Opening scans the whole file once (the `mcap` crate's sans-I/O reader, chunks
//! decompressed, zstd and lz4): which channels hold `sensor_msgs/msg/Image` in CDR,
//! which of those are depth (their first message's encoding), how many messages each
//! has and when, and the first `CameraInfo` of each topic. A file that ends early
//! (truncated) keeps every message before the damage; the damage is reported as the
//! next frame's error. Frames are then read in order by streaming the file again,
//! so a bag of any length needs memory for one chunk, not the whole file.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::Read;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};

use mcap::records::{op, Record};
use mcap::sans_io::linear_reader::{LinearReadEvent, LinearReader};

use super::msg::{self, CameraInfo, DepthEncoding, Image};
use crate::camera::Intrinsics;
use crate::{DepthFrame, DriverError};

/// What a scan learns of one channel.
#[derive(Debug, Default)]
struct ChannelScan {
    topic: String,
    schema: String,
    message_encoding: String,
    /// Log time of each message, nanoseconds.
    times_ns: Vec<u64>,
    /// The first message's image encoding and size, or why it did not decode.
    first: Option<Result<(String, usize, usize), String>>,
    /// The first message as a camera calibration, for CameraInfo channels.
    info: Option<Result<CameraInfo, String>>,
}

impl ChannelScan {
    fn is_image(&self) -> bool {
        self.schema == msg::IMAGE && self.message_encoding == msg::MESSAGE_ENCODING
    }

    fn depth_encoding(&self) -> Option<&str> {
        match &self.first {
            Some(Ok((e, ..))) if DepthEncoding::of(e).is_some() => Some(e),
            _ => None,
        }
    }

    fn describe(&self) -> String {
        let what = match &self.first {
            Some(Ok((e, w, h))) => format!("{e} {w}x{h}"),
            Some(Err(e)) => e.clone(),
            None => "no messages".into(),
        };
        format!("{} ({what}, {} messages)", self.topic, self.times_ns.len())
    }
}

/// Feed `file` through `reader`, handing each record (opcode, body) to `each` until
/// it breaks or the file ends. Errors are the file's (I/O, truncation, bad chunks).
fn for_each_record(
    file: &mut File,
    reader: &mut LinearReader,
    mut each: impl FnMut(u8, &[u8]) -> ControlFlow<()>,
) -> Result<ControlFlow<()>, String> {
    while let Some(event) = reader.next_event() {
        match event.map_err(|e| e.to_string())? {
            LinearReadEvent::ReadRequest(need) => {
                let n = file.read(reader.insert(need)).map_err(|e| e.to_string())?;
                reader.notify_read(n);
            }
            LinearReadEvent::Record { opcode, data } => {
                if each(opcode, data).is_break() {
                    return Ok(ControlFlow::Break(()));
                }
            }
        }
    }
    Ok(ControlFlow::Continue(()))
}

/// The open stream frames are read from, and which depth message comes next.
struct Stream {
    file: File,
    reader: LinearReader,
    next: usize,
}

impl std::fmt::Debug for Stream {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Stream {{ next: {} }}", self.next)
    }
}

/// A ROS 2 bag's depth topic, read frame by frame.
#[derive(Debug)]
pub struct Bag {
    path: PathBuf,
    topic: String,
    channel: u16,
    times_ns: Vec<u64>,
    intrinsics: Intrinsics,
    calibration: Option<String>,
    damage: Option<String>,
    stream: Option<Stream>,
}

/// What one pass over a bag learned: its channels, and where it is damaged.
#[derive(Debug, Default)]
struct Scan {
    channels: BTreeMap<u16, ChannelScan>,
    damage: Option<String>,
}

impl Scan {
    /// Read the whole file once (chunks decompressed): schemas, channels, message
    /// times, the first image's encoding and size and the first calibration per
    /// channel. An error ends the scan and is kept as the damage.
    fn of(file: &mut File) -> Self {
        let mut schemas: BTreeMap<u16, String> = BTreeMap::new();
        let mut scan = Scan::default();
        let channels = &mut scan.channels;
        let mut parse_error = None;
        let mut reader = LinearReader::new();
        let read = for_each_record(file, &mut reader, |opcode, body| {
            if !matches!(opcode, op::SCHEMA | op::CHANNEL | op::MESSAGE) {
                return ControlFlow::Continue(());
            }
            match mcap::parse_record(opcode, body) {
                Ok(Record::Schema { header, .. }) => {
                    schemas.insert(header.id, header.name);
                }
                Ok(Record::Channel(c)) => {
                    let ch = channels.entry(c.id).or_default();
                    ch.topic = c.topic;
                    ch.schema = schemas.get(&c.schema_id).cloned().unwrap_or_default();
                    ch.message_encoding = c.message_encoding;
                }
                Ok(Record::Message { header, data }) => {
                    let Some(ch) = channels.get_mut(&header.channel_id) else {
                        return ControlFlow::Continue(());
                    };
                    ch.times_ns.push(header.log_time);
                    if ch.times_ns.len() == 1 && ch.message_encoding == msg::MESSAGE_ENCODING {
                        if ch.schema == msg::IMAGE {
                            ch.first = Some(
                                msg::decode::<Image>(&data)
                                    .map(|i| (i.encoding, i.width as usize, i.height as usize)),
                            );
                        } else if ch.schema == msg::CAMERA_INFO {
                            ch.info = Some(msg::decode::<CameraInfo>(&data));
                        }
                    }
                }
                Ok(_) => {}
                Err(e) => {
                    parse_error = Some(e.to_string());
                    return ControlFlow::Break(());
                }
            }
            ControlFlow::Continue(())
        });
        scan.damage = match (read, parse_error) {
            (Err(e), _) | (_, Some(e)) => Some(e),
            _ => None,
        };
        scan
    }

    /// The image topics, described, for errors ("none" when there are none).
    fn image_topics(&self) -> String {
        let images: Vec<String> = self
            .channels
            .values()
            .filter(|c| c.is_image())
            .map(ChannelScan::describe)
            .collect();
        if images.is_empty() {
            "none".into()
        } else {
            images.join(", ")
        }
    }

    /// The depth channel to read: `topic` when given (an Image topic in CDR in a depth
    /// encoding), else the only depth image topic; why not, in words.
    fn choose(&self, topic: Option<&str>, path: &Path) -> Result<(u16, &ChannelScan), String> {
        if let Some(t) = topic {
            let Some((&id, c)) = self.channels.iter().find(|(_, c)| c.topic == t) else {
                return Err(format!(
                    "no topic {t:?} in the bag; its image topics: {}",
                    self.image_topics()
                ));
            };
            if !c.is_image() {
                return Err(format!(
                    "topic {t} carries {} in {:?}, not {} in CDR",
                    c.schema,
                    c.message_encoding,
                    msg::IMAGE
                ));
            }
            if c.depth_encoding().is_none() {
                return Err(format!(
                    "topic {} is not a depth image topic (expected 16UC1, mono16 or 32FC1)",
                    c.describe()
                ));
            }
            return Ok((id, c));
        }
        let depth: Vec<(&u16, &ChannelScan)> = self
            .channels
            .iter()
            .filter(|(_, c)| c.is_image() && c.depth_encoding().is_some())
            .collect();
        match depth.as_slice() {
            [(&id, c)] => Ok((id, c)),
            [] => Err(format!(
                "no depth image topic (16UC1, mono16 or 32FC1 {}); image topics: {}{}",
                msg::IMAGE,
                self.image_topics(),
                self.damage
                    .as_ref()
                    .map(|d| format!("; the file is damaged: {d}"))
                    .unwrap_or_default()
            )),
            many => Err(format!(
                "{} depth image topics, pick one with mcap:{}#TOPIC: {}",
                many.len(),
                path.display(),
                many.iter()
                    .map(|(_, c)| c.describe())
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        }
    }

    /// The calibration of `chosen`'s `width × height` images from the CameraInfo in
    /// its namespace (`.../camera_info`), scaled if given for another size, and that
    /// topic; `None` without one.
    fn calibration(
        &self,
        chosen: &ChannelScan,
        width: usize,
        height: usize,
    ) -> Result<Option<(Intrinsics, String)>, String> {
        let info_topic = match chosen.topic.rsplit_once('/') {
            Some((ns, _)) => format!("{ns}/camera_info"),
            None => "camera_info".into(),
        };
        let info = self
            .channels
            .values()
            .find(|c| c.topic == info_topic && c.schema == msg::CAMERA_INFO)
            .and_then(|c| c.info.clone());
        match info {
            Some(Ok(info)) => match info.intrinsics() {
                Ok(k) => Ok(Some((k.scaled_to(width, height), info_topic))),
                Err(e) => Err(format!("{info_topic}: {e}")),
            },
            Some(Err(e)) => Err(format!("{info_topic} message 0: {e}")),
            None => Ok(None),
        }
    }
}

impl Bag {
    /// Open `path` and pick its depth topic: `topic` when given (it must be a
    /// `sensor_msgs/msg/Image` topic in a depth encoding), else the only depth image
    /// topic in the bag (several, or none, is an error listing the candidates).
    pub fn open(path: &Path, topic: Option<&str>) -> Result<Self, DriverError> {
        let bad = |what: String| DriverError::malformed(path, what);
        if !path.is_file() {
            return Err(DriverError::NotFound {
                path: path.to_path_buf(),
            });
        }
        let mut file = File::open(path).map_err(|e| DriverError::io(path, e))?;
        let scan = Scan::of(&mut file);
        if let (Some(d), true) = (&scan.damage, scan.channels.is_empty()) {
            return Err(bad(format!("not a readable MCAP file: {d}")));
        }
        let (channel, chosen) = scan.choose(topic, path).map_err(bad)?;
        let Some(Ok((_, width, height))) = chosen.first.clone() else {
            return Err(bad(format!(
                "topic {}: its first message does not decode",
                chosen.topic
            )));
        };
        let calibration = scan.calibration(chosen, width, height).map_err(bad)?;
        let intrinsics = match &calibration {
            Some((k, _)) => *k,
            None => Intrinsics {
                width,
                height,
                pinhole: None,
            },
        };
        Ok(Bag {
            path: path.to_path_buf(),
            topic: chosen.topic.clone(),
            channel,
            times_ns: chosen.times_ns.clone(),
            intrinsics,
            calibration: calibration.map(|(_, t)| t),
            damage: scan.damage.clone(),
            stream: None,
        })
    }

    /// The depth topic read.
    pub fn topic(&self) -> &str {
        &self.topic
    }

    /// The image size, and the pinhole intrinsics of the matching `CameraInfo` topic
    /// (the image topic's namespace + `/camera_info`) when the bag has one.
    pub fn intrinsics(&self) -> Intrinsics {
        self.intrinsics
    }

    /// The `CameraInfo` topic the intrinsics came from, if any.
    pub fn calibration_topic(&self) -> Option<&str> {
        self.calibration.as_deref()
    }

    /// Depth messages read whole, plus one for a damaged end (it reads as an error).
    pub fn len(&self) -> usize {
        self.times_ns.len() + usize::from(self.damage.is_some())
    }

    /// Whether there is nothing to read.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// When message `i` was logged, seconds (the damaged end: the last message's).
    pub fn time_s(&self, i: usize) -> f64 {
        let i = i.min(self.times_ns.len().saturating_sub(1));
        self.times_ns.get(i).map_or(0.0, |&t| t as f64 * 1e-9)
    }

    /// Read depth message `i` into `frame` (its timestamp the header's stamp, or the
    /// log time when unstamped). Reading in order streams on; going back reopens.
    pub fn read(&mut self, i: usize, frame: &mut DepthFrame) -> Result<(), DriverError> {
        let bad = |what: String| DriverError::Malformed {
            path: self.path.clone(),
            what: format!("topic {} message {i}: {what}", self.topic),
        };
        if i >= self.times_ns.len() {
            let damage = self
                .damage
                .clone()
                .unwrap_or_else(|| "no such message".into());
            return Err(bad(format!("the file ends early ({damage})")));
        }
        if self.stream.as_ref().is_none_or(|s| s.next > i) {
            let file = File::open(&self.path).map_err(|e| DriverError::io(&self.path, e))?;
            self.stream = Some(Stream {
                file,
                reader: LinearReader::new(),
                next: 0,
            });
        }
        let channel = self.channel;
        let Some(stream) = self.stream.as_mut() else {
            return Err(bad("the stream did not open".into()));
        };
        let mut outcome: Option<Result<(), String>> = None;
        let next = &mut stream.next;
        let read = for_each_record(&mut stream.file, &mut stream.reader, |opcode, body| {
            if opcode != op::MESSAGE {
                return ControlFlow::Continue(());
            }
            let Ok(Record::Message { header, data }) = mcap::parse_record(opcode, body) else {
                return ControlFlow::Continue(());
            };
            if header.channel_id != channel {
                return ControlFlow::Continue(());
            }
            let this = *next;
            *next += 1;
            if this < i {
                return ControlFlow::Continue(());
            }
            outcome = Some(msg::decode::<Image>(&data).and_then(|img| {
                img.to_depth(frame)?;
                let stamp = img.header.stamp.secs();
                frame.timestamp_s = if stamp > 0.0 {
                    stamp
                } else {
                    header.log_time as f64 * 1e-9
                };
                Ok(())
            }));
            ControlFlow::Break(())
        });
        match (outcome, read) {
            (Some(r), _) => r.map_err(bad),
            (None, Err(e)) => {
                self.stream = None;
                Err(bad(format!("the file ends early ({e})")))
            }
            (None, Ok(_)) => {
                self.stream = None;
                Err(bad(
                    "not found on a second reading (the file changed?)".into()
                ))
            }
        }
    }
}
