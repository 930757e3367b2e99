use crate::{DepthFrame, DriverError};

/// What [`DepthCamera::next_frame`] produced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameStatus {
    /// The caller's frame now holds a new depth image.
    Frame,
    /// The source has no more frames (a recording played to its end, not looping).
    /// The caller's frame is left untouched.
    EndOfStream,
}

/// A depth camera: the whole contract between a source and the pipeline.
///
/// - **Buffers**: the caller owns the [`DepthFrame`] and passes it in; the camera
///   writes into it (reshaping it to the camera's size) and keeps no reference to it.
///   With a frame whose capacity fits, no allocation happens in the frame buffer.
/// - **Blocking**: `next_frame` blocks until a frame is there, the stream ends, or the
///   source fails. A live camera with nothing to deliver within its own timeout
///   returns an error rather than blocking forever.
/// - **Errors**: a frame that cannot be decoded is an error naming the file or device;
///   the caller decides whether to skip it or stop. It is never delivered as a frame.
pub trait DepthCamera {
    /// Start streaming. Called once before the first `next_frame`.
    fn start(&mut self) -> Result<(), DriverError>;
    /// Stop streaming. `start` may be called again afterwards.
    fn stop(&mut self) -> Result<(), DriverError>;
    /// Fill `frame` with the next depth image, its sequence number and timestamp.
    fn next_frame(&mut self, frame: &mut DepthFrame) -> Result<FrameStatus, DriverError>;
    /// A short human-readable name of the source (for logs and errors).
    fn describe(&self) -> String;
    /// The file the last frame came from, for sources that read files.
    fn last_source(&self) -> Option<&std::path::Path> {
        None
    }
    /// The colour image that goes with the last depth frame, for cameras that have
    /// colour: `Ok(true)` when `frame` now holds it, `Ok(false)` when the camera has no
    /// colour (or none has arrived yet). Never blocks; the caller owns the buffer, as
    /// for depth.
    fn next_colour(&mut self, frame: &mut crate::ColourFrame) -> Result<bool, DriverError> {
        let _ = frame;
        Ok(false)
    }
    /// The camera's tilt state (accelerometer) now, or as recorded with the last
    /// frame; `None` for cameras without one. May block briefly (a USB control
    /// transfer on a Kinect): call it about once a second, not every frame.
    fn tilt_state(&mut self) -> Option<crate::fakenect::TiltState> {
        None
    }
}

/// Which camera to open: the `--camera` argument.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CameraSpec {
    /// `freenect[:INDEX]`: a Kinect v1 through libfreenect (feature `freenect`).
    Freenect(u32),
    /// `v4l:PATH`: a V4L2 depth camera.
    V4l(std::path::PathBuf),
    /// `fake:PATH`: a depth image, a directory of them, or a fakenect session.
    Fake(std::path::PathBuf),
}

impl std::str::FromStr for CameraSpec {
    type Err = DriverError;

    fn from_str(s: &str) -> Result<Self, DriverError> {
        let bad = |why: &str| DriverError::BadSpec {
            spec: s.to_string(),
            why: why.to_string(),
        };
        let (kind, rest) = match s.split_once(':') {
            Some((k, r)) => (k, Some(r)),
            None => (s, None),
        };
        match (kind, rest) {
            ("freenect", None) => Ok(CameraSpec::Freenect(0)),
            ("freenect", Some(i)) => i
                .parse()
                .map(CameraSpec::Freenect)
                .map_err(|_| bad("the index must be a number")),
            ("v4l", Some(p)) if !p.is_empty() => Ok(CameraSpec::V4l(p.into())),
            ("fake", Some(p)) if !p.is_empty() => Ok(CameraSpec::Fake(p.into())),
            ("v4l" | "fake", _) => Err(bad("needs a path after ':'")),
            _ => Err(bad("expected freenect[:INDEX], v4l:PATH or fake:PATH")),
        }
    }
}

/// The V4L2 device nodes, `/dev/video*`, sorted.
pub(crate) fn video_nodes() -> Vec<std::path::PathBuf> {
    let mut nodes: Vec<_> = std::fs::read_dir("/dev")
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("video"))
        })
        .collect();
    nodes.sort();
    nodes
}

/// One line per depth camera attached, for `rover-terrain cameras`.
pub fn list_cameras() -> Vec<String> {
    let mut out = Vec::new();
    #[cfg(feature = "freenect")]
    match crate::freenect::count() {
        Ok(0) => out.push("freenect: no Kinect found".into()),
        Ok(n) => out
            .extend((0..n).map(|i| {
                format!("freenect:{i}  Kinect v1 (libfreenect), depth 640x480 11-bit/mm")
            })),
        Err(e) => out.push(format!("freenect: {e}")),
    }
    #[cfg(not(feature = "freenect"))]
    out.push("freenect: not built (rebuild with --features freenect)".into());
    let video = video_nodes();
    if video.is_empty() {
        out.push("v4l: no /dev/video* devices".into());
    }
    for p in video {
        #[cfg(feature = "v4l")]
        out.push(crate::v4l::describe_device(&p));
        #[cfg(not(feature = "v4l"))]
        out.push(format!(
            "v4l:{}  (formats not listed: rebuild with --features v4l)",
            p.display()
        ));
    }
    out
}

/// What a live camera is asked to deliver (from the `[camera]` config section).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraOptions {
    /// Image width, pixels (V4L2).
    pub width: u32,
    /// Image height, pixels (V4L2).
    pub height: u32,
    /// Frame rate, frames per second (V4L2).
    pub fps: u32,
    /// Millimetres per unit of a 16-bit depth pixel (V4L2 Z16/Y16).
    pub depth_scale_mm: f32,
}

impl Default for CameraOptions {
    /// A Kinect-like 640×480 at 30 Hz, 1 mm per unit.
    fn default() -> Self {
        CameraOptions {
            width: 640,
            height: 480,
            fps: 30,
            depth_scale_mm: 1.0,
        }
    }
}

/// Open the camera `spec` names, with the default [`CameraOptions`].
pub fn open(spec: &CameraSpec) -> Result<Box<dyn DepthCamera>, DriverError> {
    open_with(spec, &CameraOptions::default())
}

/// Open the camera `spec` names; a V4L2 camera is set to `options`' size, rate and
/// depth scale (a Kinect always streams 640×480 at 30 Hz in millimetres).
pub fn open_with(
    spec: &CameraSpec,
    options: &CameraOptions,
) -> Result<Box<dyn DepthCamera>, DriverError> {
    #[cfg(not(feature = "v4l"))]
    let _ = options;
    match spec {
        CameraSpec::Fake(p) => Ok(Box::new(crate::FakeCamera::open(p)?)),
        #[cfg(feature = "freenect")]
        CameraSpec::Freenect(i) => Ok(Box::new(crate::freenect::FreenectCamera::open(*i)?)),
        #[cfg(not(feature = "freenect"))]
        CameraSpec::Freenect(_) => Err(DriverError::NoDevice(
            "built without libfreenect support: rebuild with `--features freenect` (needs libfreenect-dev)".into(),
        )),
        #[cfg(feature = "v4l")]
        CameraSpec::V4l(p) => Ok(Box::new(crate::v4l::V4lCamera::open(
            p,
            options.width,
            options.height,
            options.fps,
            options.depth_scale_mm,
        )?)),
        #[cfg(not(feature = "v4l"))]
        CameraSpec::V4l(p) => Err(DriverError::NoDevice(format!(
            "v4l:{}: built without V4L2 support: rebuild with `--features v4l` (needs libclang-dev)",
            p.display()
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camera_specs_parse() {
        assert_eq!(
            "freenect".parse::<CameraSpec>().unwrap(),
            CameraSpec::Freenect(0)
        );
        assert_eq!(
            "freenect:2".parse::<CameraSpec>().unwrap(),
            CameraSpec::Freenect(2)
        );
        assert_eq!(
            "fake:a/b".parse::<CameraSpec>().unwrap(),
            CameraSpec::Fake("a/b".into())
        );
        assert_eq!(
            "v4l:/dev/video2".parse::<CameraSpec>().unwrap(),
            CameraSpec::V4l("/dev/video2".into())
        );
        for bad in ["freenect:x", "fake:", "v4l", "webcam:0", ""] {
            let e = bad.parse::<CameraSpec>().unwrap_err().to_string();
            assert!(e.contains(&format!("{bad:?}")), "{e}");
        }
    }
}
