//! The ROS 2 messages a depth bag holds, `sensor_msgs/msg/Image` and
//! `sensor_msgs/msg/CameraInfo`, as serde types for the `cdr` crate, and their
//! conversions to and from our frames.
//!
//! The message definitions (`IMAGE_MSGDEF`, `CAMERA_INFO_MSGDEF`) are the text ROS 2
//! tooling stores as an MCAP schema (`ros2msg` encoding), dependencies appended.

use serde::{Deserialize, Serialize};

use crate::camera::Intrinsics;
use crate::{ColourFrame, DepthFrame, MAX_HEIGHT, MAX_WIDTH};

/// Schema name of a ROS 2 image.
pub const IMAGE: &str = "sensor_msgs/msg/Image";
/// Schema name of a ROS 2 camera calibration.
pub const CAMERA_INFO: &str = "sensor_msgs/msg/CameraInfo";
/// Schema encoding of ROS 2 message definitions in MCAP.
pub const SCHEMA_ENCODING: &str = "ros2msg";
/// Message encoding of ROS 2 messages in MCAP.
pub const MESSAGE_ENCODING: &str = "cdr";

const HEADER_MSGDEF: &str = "
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
";

/// `sensor_msgs/msg/Image`'s definition as ROS 2 stores it in a bag.
pub fn image_msgdef() -> String {
    format!(
        "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\n\
         uint8 is_bigendian\nuint32 step\nuint8[] data\n{HEADER_MSGDEF}"
    )
}

/// `sensor_msgs/msg/CameraInfo`'s definition as ROS 2 stores it in a bag.
pub fn camera_info_msgdef() -> String {
    format!(
        "std_msgs/Header header\nuint32 height\nuint32 width\nstring distortion_model\n\
         float64[] d\nfloat64[9] k\nfloat64[9] r\nfloat64[12] p\nuint32 binning_x\n\
         uint32 binning_y\nsensor_msgs/RegionOfInterest roi\n{HEADER_MSGDEF}\
         ================================================================================\n\
         MSG: sensor_msgs/RegionOfInterest\nuint32 x_offset\nuint32 y_offset\n\
         uint32 height\nuint32 width\nbool do_rectify\n"
    )
}

/// `builtin_interfaces/Time`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Time {
    /// Seconds since the epoch.
    pub sec: i32,
    /// Nanoseconds past `sec`.
    pub nanosec: u32,
}

impl Time {
    /// A time `seconds` after the epoch (negative and non-finite become 0).
    pub fn from_secs(seconds: f64) -> Self {
        let s = if seconds.is_finite() {
            seconds.max(0.0)
        } else {
            0.0
        };
        let sec = s.floor();
        Time {
            sec: sec.min(f64::from(i32::MAX)) as i32,
            nanosec: (((s - sec) * 1e9) as u32).min(999_999_999),
        }
    }

    /// Seconds since the epoch.
    pub fn secs(&self) -> f64 {
        f64::from(self.sec) + f64::from(self.nanosec) * 1e-9
    }
}

/// `std_msgs/Header`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// Capture time.
    pub stamp: Time,
    /// The TF frame the data is in.
    pub frame_id: String,
}

/// `sensor_msgs/msg/Image`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Image {
    /// Stamp and frame.
    pub header: Header,
    /// Rows.
    pub height: u32,
    /// Columns.
    pub width: u32,
    /// Pixel encoding: `16UC1` (mm), `32FC1` (m), `rgb8`, ...
    pub encoding: String,
    /// Whether multi-byte pixels are big-endian.
    pub is_bigendian: u8,
    /// Bytes per row.
    pub step: u32,
    /// The pixels, `height × step` bytes.
    #[serde(with = "serde_bytes")]
    pub data: Vec<u8>,
}

/// `sensor_msgs/RegionOfInterest`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RegionOfInterest {
    /// Left column.
    pub x_offset: u32,
    /// Top row.
    pub y_offset: u32,
    /// Rows.
    pub height: u32,
    /// Columns.
    pub width: u32,
    /// Whether the region is to be rectified.
    pub do_rectify: bool,
}

/// `sensor_msgs/msg/CameraInfo`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct CameraInfo {
    /// Stamp and frame.
    pub header: Header,
    /// Calibrated image rows.
    pub height: u32,
    /// Calibrated image columns.
    pub width: u32,
    /// Distortion model name (`plumb_bob`, ...).
    pub distortion_model: String,
    /// Distortion coefficients.
    pub d: Vec<f64>,
    /// Intrinsic matrix, row-major: fx 0 cx / 0 fy cy / 0 0 1, pixels.
    pub k: [f64; 9],
    /// Rectification rotation, row-major.
    pub r: [f64; 9],
    /// Projection matrix, row-major 3×4.
    pub p: [f64; 12],
    /// Horizontal binning.
    pub binning_x: u32,
    /// Vertical binning.
    pub binning_y: u32,
    /// Region of interest.
    pub roi: RegionOfInterest,
}

impl CameraInfo {
    /// A distortion-free pinhole calibration for `k`, stamped `stamp` in `frame_id`.
    pub fn pinhole(k: &Intrinsics, stamp: Time, frame_id: &str) -> Self {
        let (fx, fy, cx, cy) = k.pinhole.unwrap_or_default();
        CameraInfo {
            header: Header {
                stamp,
                frame_id: frame_id.into(),
            },
            height: k.height as u32,
            width: k.width as u32,
            distortion_model: "plumb_bob".into(),
            d: vec![0.0; 5],
            k: [fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0],
            r: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
            p: [fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0],
            ..Default::default()
        }
    }

    /// Its pinhole intrinsics, or why they are unusable.
    pub fn intrinsics(&self) -> Result<Intrinsics, String> {
        let [fx, _, cx, _, fy, cy, ..] = self.k;
        let ok = |v: f64| v.is_finite();
        if !(fx > 0.0 && fy > 0.0 && ok(fx) && ok(fy) && ok(cx) && ok(cy)) {
            return Err(format!(
                "camera info K has fx {fx}, fy {fy}, cx {cx}, cy {cy} (an uncalibrated camera?)"
            ));
        }
        Ok(Intrinsics {
            width: self.width as usize,
            height: self.height as usize,
            pinhole: Some((fx, fy, cx, cy)),
        })
    }
}

/// Decode a CDR-encoded message (with its 4-byte encapsulation header).
pub fn decode<T: serde::de::DeserializeOwned>(bytes: &[u8]) -> Result<T, String> {
    cdr::deserialize(bytes).map_err(|e| format!("not a valid CDR message: {e}"))
}

/// Encode a message as little-endian CDR with its encapsulation header.
pub fn encode<T: Serialize>(msg: &T) -> Vec<u8> {
    // Serialising plain structs to memory cannot fail: no size limit, no I/O.
    cdr::serialize::<_, _, cdr::CdrLe>(msg, cdr::Infinite).unwrap_or_default()
}

/// Depth pixel encodings we read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthEncoding {
    /// `16UC1` / `mono16`: unsigned 16-bit millimetres.
    Millimetres,
    /// `32FC1`: 32-bit float metres.
    Metres,
}

impl DepthEncoding {
    /// The encoding an image's `encoding` string names, if a depth one.
    pub fn of(encoding: &str) -> Option<Self> {
        match encoding {
            "16UC1" | "mono16" => Some(DepthEncoding::Millimetres),
            "32FC1" => Some(DepthEncoding::Metres),
            _ => None,
        }
    }

    fn bytes(self) -> usize {
        match self {
            DepthEncoding::Millimetres => 2,
            DepthEncoding::Metres => 4,
        }
    }
}

/// The image's rows as slices of `row_bytes`, after checking its size: width and
/// height within our limits, `step` at least a row, and `height × step` bytes of data.
fn rows(img: &Image, bytes_per_pixel: usize) -> Result<impl Iterator<Item = &[u8]>, String> {
    let (w, h, step) = (img.width as usize, img.height as usize, img.step as usize);
    if w == 0 || h == 0 || w > MAX_WIDTH || h > MAX_HEIGHT {
        return Err(format!(
            "image is {w}x{h} (expected 1x1 to {MAX_WIDTH}x{MAX_HEIGHT})"
        ));
    }
    if step < w * bytes_per_pixel {
        return Err(format!(
            "step {step} is shorter than a row of {w} {} pixels",
            img.encoding
        ));
    }
    if img.data.len() != h * step {
        return Err(format!(
            "data is {} bytes, expected height {h} × step {step} = {}",
            img.data.len(),
            h * step
        ));
    }
    let row = w * bytes_per_pixel;
    Ok(img.data.chunks_exact(step).map(move |r| &r[..row]))
}

impl Image {
    /// Fill `frame` with this depth image (millimetres; 32FC1 metres rounded to the
    /// millimetre, NaN, infinite, non-positive and beyond-65.535 m values become 0, no
    /// return). Errors say what is wrong; `frame` is then unspecified.
    pub fn to_depth(&self, frame: &mut DepthFrame) -> Result<(), String> {
        let enc = DepthEncoding::of(&self.encoding).ok_or_else(|| {
            format!(
                "encoding {:?} is not a depth encoding (expected 16UC1, mono16 or 32FC1)",
                self.encoding
            )
        })?;
        let rows = rows(self, enc.bytes())?;
        let big = self.is_bigendian != 0;
        let out = frame.reshape(self.width as usize, self.height as usize);
        let mut out = out.iter_mut();
        for row in rows {
            match enc {
                DepthEncoding::Millimetres => {
                    for (b, px) in row.chunks_exact(2).zip(out.by_ref()) {
                        let b = [b[0], b[1]];
                        *px = if big {
                            u16::from_be_bytes(b)
                        } else {
                            u16::from_le_bytes(b)
                        };
                    }
                }
                DepthEncoding::Metres => {
                    for (b, px) in row.chunks_exact(4).zip(out.by_ref()) {
                        let b = [b[0], b[1], b[2], b[3]];
                        let m = if big {
                            f32::from_be_bytes(b)
                        } else {
                            f32::from_le_bytes(b)
                        };
                        let mm = (f64::from(m) * 1000.0).round();
                        *px = if mm.is_finite() && mm > 0.0 && mm <= f64::from(u16::MAX) {
                            mm as u16
                        } else {
                            0
                        };
                    }
                }
            }
        }
        Ok(())
    }

    /// Fill `frame` with this colour image (`rgb8` or `bgr8`).
    pub fn to_colour(&self, frame: &mut ColourFrame) -> Result<(), String> {
        let bgr = match self.encoding.as_str() {
            "rgb8" => false,
            "bgr8" => true,
            e => return Err(format!("encoding {e:?} is not rgb8 or bgr8")),
        };
        let rows = rows(self, 3)?;
        let out = frame.reshape(self.width as usize, self.height as usize);
        for (dst, src) in out.chunks_exact_mut(3 * self.width as usize).zip(rows) {
            dst.copy_from_slice(src);
            if bgr {
                dst.chunks_exact_mut(3).for_each(|p| p.swap(0, 2));
            }
        }
        Ok(())
    }

    /// A `16UC1` little-endian image of `frame`, stamped `stamp` in `frame_id`.
    pub fn from_depth(frame: &DepthFrame, stamp: Time, frame_id: &str) -> Self {
        let mut data = Vec::with_capacity(frame.pixels().len() * 2);
        for px in frame.pixels() {
            data.extend_from_slice(&px.to_le_bytes());
        }
        Self::packed(
            (frame.width(), frame.height()),
            "16UC1",
            2,
            data,
            stamp,
            frame_id,
        )
    }

    /// An `rgb8` image of `frame`, stamped `stamp` in `frame_id`.
    pub fn from_colour(frame: &ColourFrame, stamp: Time, frame_id: &str) -> Self {
        let data = frame.rgb().to_vec();
        Self::packed(
            (frame.width(), frame.height()),
            "rgb8",
            3,
            data,
            stamp,
            frame_id,
        )
    }

    /// A little-endian image of `size` (width, height) with rows packed (step =
    /// width × bytes per pixel).
    fn packed(
        (width, height): (usize, usize),
        encoding: &str,
        bytes_per_pixel: usize,
        data: Vec<u8>,
        stamp: Time,
        frame_id: &str,
    ) -> Self {
        Image {
            header: Header {
                stamp,
                frame_id: frame_id.into(),
            },
            height: height as u32,
            width: width as u32,
            encoding: encoding.into(),
            is_bigendian: 0,
            step: (bytes_per_pixel * width) as u32,
            data,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn depth(encoding: &str, w: u32, h: u32, step: u32, data: Vec<u8>) -> Image {
        Image {
            encoding: encoding.into(),
            width: w,
            height: h,
            step,
            data,
            ..Default::default()
        }
    }

    #[test]
    fn cdr_round_trip_keeps_every_field() {
        let mut f = DepthFrame::from_pixels(3, 2, vec![1, 2, 3, 400, 500, 65535]);
        f.timestamp_s = 12.5;
        let img = Image::from_depth(&f, Time::from_secs(12.5), "cam");
        let back: Image = decode(&encode(&img)).unwrap();
        assert_eq!(back, img);
        let mut g = DepthFrame::default();
        back.to_depth(&mut g).unwrap();
        assert_eq!((g.width(), g.height(), g.pixels()), (3, 2, f.pixels()));
        assert_eq!(back.header.stamp.secs(), 12.5);
    }

    #[test]
    fn cdr_layout_matches_the_standard_by_hand() {
        // Encapsulation CDR_LE, then stamp (sec, nanosec), frame_id "a" (length 2
        // with its NUL), padding to 4, height 1, width 1, encoding "16UC1" (6 with NUL),
        // is_bigendian 0, padding to 4, step 2, data length 2, data.
        let img = depth("16UC1", 1, 1, 2, vec![0x34, 0x12]);
        let img = Image {
            header: Header {
                stamp: Time { sec: 7, nanosec: 9 },
                frame_id: "a".into(),
            },
            ..img
        };
        let mut want = vec![0u8, 1, 0, 0];
        want.extend([7, 0, 0, 0, 9, 0, 0, 0, 2, 0, 0, 0, b'a', 0, 0, 0]);
        want.extend([1, 0, 0, 0, 1, 0, 0, 0, 6, 0, 0, 0]);
        want.extend(b"16UC1\0");
        want.extend([0, 0, 2, 0, 0, 0, 2, 0, 0, 0, 0x34, 0x12]);
        assert_eq!(encode(&img), want);
    }

    #[test]
    fn metres_become_rounded_millimetres_and_bad_values_no_return() {
        let vals = [1.2345f32, f32::NAN, -1.0, 0.0, f32::INFINITY, 70.0, 0.0004];
        let data: Vec<u8> = vals.iter().flat_map(|v| v.to_le_bytes()).collect();
        let img = depth("32FC1", 7, 1, 28, data);
        let mut f = DepthFrame::default();
        img.to_depth(&mut f).unwrap();
        assert_eq!(f.pixels(), [1235, 0, 0, 0, 0, 0, 0]);
    }

    #[test]
    fn padded_rows_and_big_endian_pixels_are_read() {
        // Two rows of one pixel, each row padded to 4 bytes, big-endian.
        let img = Image {
            is_bigendian: 1,
            ..depth(
                "16UC1",
                1,
                2,
                4,
                vec![0x01, 0x02, 0xff, 0xff, 0x03, 0x04, 0xff, 0xff],
            )
        };
        let mut f = DepthFrame::default();
        img.to_depth(&mut f).unwrap();
        assert_eq!(f.pixels(), [0x0102, 0x0304]);
    }

    #[test]
    fn sizes_that_disagree_are_errors_that_say_so() {
        let mut f = DepthFrame::default();
        let short = depth("16UC1", 2, 2, 4, vec![0; 6]);
        let e = short.to_depth(&mut f).unwrap_err();
        assert!(
            e.contains("6 bytes") && e.contains("height 2 × step 4 = 8"),
            "{e}"
        );
        let narrow = depth("16UC1", 4, 1, 4, vec![0; 4]);
        assert!(narrow.to_depth(&mut f).unwrap_err().contains("step 4"));
        let huge = depth("16UC1", 5000, 1, 10000, vec![0; 10000]);
        assert!(huge.to_depth(&mut f).unwrap_err().contains("5000x1"));
        let colour = depth("rgb8", 1, 1, 3, vec![0; 3]);
        assert!(colour
            .to_depth(&mut f)
            .unwrap_err()
            .contains("not a depth encoding"));
        assert!(decode::<Image>(&[0, 1, 0, 0, 7]).is_err());
    }

    #[test]
    fn camera_info_gives_pinhole_intrinsics_and_refuses_an_empty_k() {
        let k = Intrinsics {
            width: 640,
            height: 480,
            pinhole: Some((525.0, 524.0, 319.5, 239.5)),
        };
        let info: CameraInfo =
            decode(&encode(&CameraInfo::pinhole(&k, Time::default(), "c"))).unwrap();
        assert_eq!(info.intrinsics().unwrap(), k);
        let empty = CameraInfo::default();
        assert!(empty.intrinsics().unwrap_err().contains("uncalibrated"));
    }

    #[test]
    fn bgr_colour_is_swapped_to_rgb() {
        let img = depth("bgr8", 1, 1, 3, vec![1, 2, 3]);
        let mut c = ColourFrame::default();
        img.to_colour(&mut c).unwrap();
        assert_eq!(c.rgb(), [3, 2, 1]);
    }
}
