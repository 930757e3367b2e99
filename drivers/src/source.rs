//! Which camera to open (the `--camera` argument), opening it, and listing the
//! cameras attached: the one place that knows every backend.

use crate::camera::{CameraOptions, DepthCamera};
use crate::DriverError;

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
    let video = crate::nodes::video_nodes();
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
