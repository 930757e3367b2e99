//! V4L2 depth cameras (feature `v4l`): UVC devices that stream 16-bit depth as `Z16`
//! (RealSense D4xx, Orbbec) or `Y16`, through the `v4l` crate with memory-mapped
//! buffers. Each buffer is converted to millimetres with the camera's depth scale
//! (RealSense: 1 unit = 1 mm by default) as soon as it is dequeued; nothing refers to
//! the driver's buffer afterwards.

use std::path::{Path, PathBuf};

use v4l::buffer::Type;
use v4l::io::mmap::Stream as MmapStream;
use v4l::io::traits::CaptureStream;
use v4l::video::Capture;
use v4l::{Device, FourCC};

use crate::{DepthCamera, DepthFrame, DriverError, FrameStatus, MAX_HEIGHT, MAX_WIDTH};

/// A 16-bit depth pixel format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthFormat {
    /// `Z16 `: 16-bit depth, little-endian.
    Z16,
    /// `Y16 `: 16-bit greyscale used for depth by some cameras, little-endian.
    Y16,
}

impl DepthFormat {
    /// The V4L2 four-character code.
    pub fn fourcc(self) -> [u8; 4] {
        match self {
            DepthFormat::Z16 => *b"Z16 ",
            DepthFormat::Y16 => *b"Y16 ",
        }
    }

    /// The format for a four-character code, if it is a depth format we read.
    pub fn from_fourcc(code: [u8; 4]) -> Option<Self> {
        match &code {
            b"Z16 " => Some(DepthFormat::Z16),
            b"Y16 " => Some(DepthFormat::Y16),
            _ => None,
        }
    }
}

/// How a buffer is laid out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    /// Width, pixels.
    pub width: usize,
    /// Height, pixels.
    pub height: usize,
    /// Bytes per line (≥ 2 × width).
    pub stride: usize,
    /// Millimetres per depth unit.
    pub scale_mm: f32,
}

/// Convert one 16-bit depth buffer to millimetres (0 stays "no data"; a depth beyond
/// 65535 mm is "no data" too). Fails, naming what is wrong, on a short buffer or a
/// layout that cannot be.
pub fn convert(buf: &[u8], layout: Layout, out: &mut [u16]) -> Result<(), String> {
    let Layout {
        width,
        height,
        stride,
        scale_mm,
    } = layout;
    if width == 0 || height == 0 || width > MAX_WIDTH || height > MAX_HEIGHT || stride < 2 * width {
        return Err(format!(
            "impossible layout {width}×{height}, stride {stride}"
        ));
    }
    if !(scale_mm.is_finite() && scale_mm > 0.0) {
        return Err(format!("depth scale {scale_mm} mm/unit is not positive"));
    }
    let need = stride * (height - 1) + 2 * width;
    if buf.len() < need {
        return Err(format!(
            "buffer of {} bytes, a {width}×{height} frame needs {need}",
            buf.len()
        ));
    }
    if out.len() != width * height {
        return Err(format!(
            "output of {} pixels for a {width}×{height} frame",
            out.len()
        ));
    }
    let exact = scale_mm == 1.0;
    for (row, dst) in out.chunks_exact_mut(width).enumerate() {
        let src = &buf[row * stride..row * stride + 2 * width];
        for (d, pair) in dst.iter_mut().zip(src.chunks_exact(2)) {
            let v = u16::from_le_bytes([pair[0], pair[1]]);
            *d = if exact {
                v
            } else {
                let mm = (f32::from(v) * scale_mm).round();
                if mm <= 65535.0 {
                    mm as u16
                } else {
                    0
                }
            };
        }
    }
    Ok(())
}

/// One line for `rover-terrain cameras`: the device's card name and the formats it
/// offers, the depth ones (Z16/Y16) marked; or why it cannot be read.
pub fn describe_device(path: &Path) -> String {
    let dev = match Device::with_path(path) {
        Ok(d) => d,
        Err(e) => return format!("v4l:{}  cannot open ({e})", path.display()),
    };
    let card = match dev.query_caps() {
        Ok(c) => c.card,
        Err(e) => return format!("v4l:{}  not a V4L2 device ({e})", path.display()),
    };
    let formats = match dev.enum_formats() {
        Ok(f) => f,
        Err(e) => return format!("v4l:{}  {card}: cannot list formats ({e})", path.display()),
    };
    let mut listed = Vec::new();
    let mut depth = false;
    for f in &formats {
        let code = String::from_utf8_lossy(&f.fourcc.repr).into_owned();
        let is_depth = DepthFormat::from_fourcc(f.fourcc.repr).is_some();
        depth |= is_depth;
        let sizes: Vec<String> = dev
            .enum_framesizes(f.fourcc)
            .unwrap_or_default()
            .into_iter()
            .flat_map(|s| s.size.to_discrete())
            .map(|d| format!("{}x{}", d.width, d.height))
            .collect();
        listed.push(format!(
            "{code}{}{}",
            if is_depth { " (depth)" } else { "" },
            if sizes.is_empty() {
                String::new()
            } else {
                format!(" {}", sizes.join(","))
            }
        ));
    }
    format!(
        "v4l:{}  {card}: {}{}",
        path.display(),
        if listed.is_empty() {
            "no formats".to_string()
        } else {
            listed.join("; ")
        },
        if depth {
            ""
        } else {
            " (no depth stream: not usable)"
        }
    )
}

/// A V4L2 depth camera.
pub struct V4lCamera {
    path: PathBuf,
    stream: MmapStream<'static>,
    // Declared after the stream: dropped after it.
    _device: Device,
    layout: Layout,
    seq: u64,
}

/// Find the device: a path (`/dev/video2`), or the name of its card
/// (`Intel(R) RealSense(TM) Depth Camera 435`), matched case-insensitively as a part.
fn find(spec: &Path) -> Result<(PathBuf, Device), DriverError> {
    let spec_str = spec.display().to_string();
    if spec_str.starts_with('/') {
        let dev = Device::with_path(spec)
            .map_err(|e| DriverError::NoDevice(format!("v4l:{spec_str}: cannot open ({e})")))?;
        return Ok((spec.to_path_buf(), dev));
    }
    let want = spec_str.to_lowercase();
    let nodes = crate::nodes::video_nodes();
    for p in nodes {
        if let Ok(dev) = Device::with_path(&p) {
            if dev
                .query_caps()
                .is_ok_and(|c| c.card.to_lowercase().contains(&want))
            {
                return Ok((p, dev));
            }
        }
    }
    Err(DriverError::NoDevice(format!(
        "v4l:{spec_str}: no V4L2 device whose name contains {spec_str:?}"
    )))
}

impl V4lCamera {
    /// Open `spec` (a path or a card name) at `width`×`height`, `fps`, in a 16-bit
    /// depth format the device offers, with `scale_mm` millimetres per unit.
    pub fn open(
        spec: &Path,
        width: u32,
        height: u32,
        fps: u32,
        scale_mm: f32,
    ) -> Result<Self, DriverError> {
        let (path, device) = find(spec)?;
        let name = format!("v4l:{}", path.display());
        let err =
            |what: &str, e: std::io::Error| DriverError::NoDevice(format!("{name}: {what} ({e})"));
        let offered = device
            .enum_formats()
            .map_err(|e| err("cannot list formats", e))?;
        let format = offered
            .iter()
            .find_map(|d| DepthFormat::from_fourcc(d.fourcc.repr))
            .ok_or_else(|| {
                DriverError::NoDevice(format!("{name}: offers no Z16 or Y16 depth stream"))
            })?;
        let mut fmt = device
            .format()
            .map_err(|e| err("cannot read the format", e))?;
        fmt.width = width;
        fmt.height = height;
        fmt.fourcc = FourCC::new(&format.fourcc());
        let got = device
            .set_format(&fmt)
            .map_err(|e| err("refuses the format", e))?;
        if got.width != width
            || got.height != height
            || DepthFormat::from_fourcc(got.fourcc.repr) != Some(format)
        {
            return Err(DriverError::NoDevice(format!(
                "{name}: asked for {width}×{height} {:?}, the device gives {}×{} {}",
                format, got.width, got.height, got.fourcc
            )));
        }
        let params = v4l::video::capture::Parameters::with_fps(fps);
        device
            .set_params(&params)
            .map_err(|e| err("refuses the frame rate", e))?;
        let stream = MmapStream::with_buffers(&device, Type::VideoCapture, 4)
            .map_err(|e| err("cannot map buffers", e))?;
        Ok(V4lCamera {
            path,
            stream,
            _device: device,
            layout: Layout {
                width: width as usize,
                height: height as usize,
                stride: got.stride as usize,
                scale_mm,
            },
            seq: 0,
        })
    }
}

impl DepthCamera for V4lCamera {
    fn start(&mut self) -> Result<(), DriverError> {
        Ok(()) // the stream starts with the first dequeue
    }

    fn stop(&mut self) -> Result<(), DriverError> {
        Ok(())
    }

    fn next_frame(&mut self, frame: &mut DepthFrame) -> Result<FrameStatus, DriverError> {
        let name = self.describe();
        let (buf, meta) = self
            .stream
            .next()
            .map_err(|e| DriverError::Disconnected(format!("{name}: {e}")))?;
        let used = (meta.bytesused as usize).min(buf.len());
        let layout = self.layout;
        let pixels = frame.reshape(layout.width, layout.height);
        convert(&buf[..used], layout, pixels).map_err(|what| DriverError::Malformed {
            path: self.path.clone(),
            what,
        })?;
        frame.seq = self.seq;
        self.seq += 1;
        frame.timestamp_s = meta.timestamp.sec as f64 + meta.timestamp.usec as f64 * 1e-6;
        Ok(FrameStatus::Frame)
    }

    fn describe(&self) -> String {
        format!("v4l:{}", self.path.display())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn describing_a_missing_or_non_video_device_says_why() {
        let d = describe_device(Path::new("/dev/video-none"));
        assert!(
            d.starts_with("v4l:/dev/video-none") && d.contains("cannot open"),
            "{d}"
        );
        let d = describe_device(Path::new("/dev/null"));
        assert!(d.contains("not a V4L2 device"), "{d}");
    }

    fn z16(rows: &[&[u16]], pad: usize) -> (Vec<u8>, usize) {
        let stride = rows[0].len() * 2 + pad;
        let mut buf = Vec::new();
        for r in rows {
            for v in *r {
                buf.extend_from_slice(&v.to_le_bytes());
            }
            buf.extend(std::iter::repeat_n(0xAB, pad));
        }
        (buf, stride)
    }

    #[test]
    fn converts_recorded_buffers_with_stride_and_scale() {
        let (buf, stride) = z16(&[&[0, 1000, 65535], &[250, 2, 4000]], 6);
        let mut out = vec![9; 6];
        convert(
            &buf,
            Layout {
                width: 3,
                height: 2,
                stride,
                scale_mm: 1.0,
            },
            &mut out,
        )
        .unwrap();
        assert_eq!(out, [0, 1000, 65535, 250, 2, 4000]);
        // A camera reporting 0.1 mm units (e.g. a D405 at depth scale 0.0001 m).
        convert(
            &buf,
            Layout {
                width: 3,
                height: 2,
                stride,
                scale_mm: 0.1,
            },
            &mut out,
        )
        .unwrap();
        assert_eq!(out, [0, 100, 6554, 25, 0, 400]);
        // 2 mm units: 65535 units is beyond u16 millimetres, so no data.
        convert(
            &buf,
            Layout {
                width: 3,
                height: 2,
                stride,
                scale_mm: 2.0,
            },
            &mut out,
        )
        .unwrap();
        assert_eq!(out, [0, 2000, 0, 500, 4, 8000]);
    }

    #[test]
    fn rejects_short_buffers_and_impossible_layouts() {
        let (buf, stride) = z16(&[&[1, 2, 3], &[4, 5, 6]], 0);
        let mut out = vec![0; 6];
        let l = Layout {
            width: 3,
            height: 2,
            stride,
            scale_mm: 1.0,
        };
        assert!(convert(&buf[..buf.len() - 1], l, &mut out)
            .unwrap_err()
            .contains("needs 12"));
        assert!(convert(&buf, Layout { stride: 4, ..l }, &mut out)
            .unwrap_err()
            .contains("impossible"));
        assert!(convert(
            &buf,
            Layout {
                scale_mm: f32::NAN,
                ..l
            },
            &mut out
        )
        .unwrap_err()
        .contains("scale"));
        assert!(convert(&buf, l, &mut out[..5])
            .unwrap_err()
            .contains("output"));
        assert!(convert(
            &buf,
            Layout {
                width: 100_000,
                ..l
            },
            &mut out
        )
        .is_err());
    }

    #[test]
    fn formats_by_fourcc() {
        assert_eq!(DepthFormat::from_fourcc(*b"Z16 "), Some(DepthFormat::Z16));
        assert_eq!(DepthFormat::from_fourcc(*b"YUYV"), None);
        assert_eq!(
            DepthFormat::from_fourcc(DepthFormat::Y16.fourcc()),
            Some(DepthFormat::Y16)
        );
    }

    #[test]
    fn a_missing_device_is_a_clear_error() {
        let e = V4lCamera::open(Path::new("/dev/video-none"), 640, 480, 30, 1.0)
            .err()
            .unwrap()
            .to_string();
        assert!(
            e.contains("/dev/video-none") && e.contains("cannot open"),
            "{e}"
        );
        let e = V4lCamera::open(Path::new("NoSuchDepthCam"), 640, 480, 30, 1.0)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("NoSuchDepthCam"), "{e}");
    }
}
