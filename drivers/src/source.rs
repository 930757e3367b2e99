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
    /// `mcap:PATH[#TOPIC]`: a ROS 2 bag's depth image topic (the only one when no
    /// topic is given), replayed like `fake:`.
    Mcap {
        /// The bag.
        path: std::path::PathBuf,
        /// The depth topic, e.g. `/camera/depth/image_raw`.
        topic: Option<String>,
    },
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
            ("mcap", Some(p)) if !p.is_empty() => {
                let (path, topic) = match p.rsplit_once('#') {
                    Some((path, topic)) if !topic.is_empty() => (path, Some(topic.to_string())),
                    Some(_) => return Err(bad("needs a topic after '#'")),
                    None => (p, None),
                };
                if path.is_empty() {
                    return Err(bad("needs a path after ':'"));
                }
                Ok(CameraSpec::Mcap {
                    path: path.into(),
                    topic,
                })
            }
            ("v4l" | "fake" | "mcap", _) => Err(bad("needs a path after ':'")),
            _ => Err(bad(
                "expected freenect[:INDEX], v4l:PATH, fake:PATH or mcap:PATH[#TOPIC]",
            )),
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

/// What the source `spec` names knows of its own optics before it is opened for
/// streaming (a ROS 2 bag: its image size and `CameraInfo`, see
/// [`crate::DepthCamera::intrinsics`]); `None` for every other source.
pub fn probe_intrinsics(spec: &CameraSpec) -> Result<Option<crate::Intrinsics>, DriverError> {
    match spec {
        CameraSpec::Mcap { path, topic } => Ok(Some(
            crate::ros2::Bag::open(path, topic.as_deref())?.intrinsics(),
        )),
        _ => Ok(None),
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
        CameraSpec::Mcap { path, topic } => Ok(Box::new(crate::FakeCamera::open_bag(
            path,
            topic.as_deref(),
        )?)),
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
            "mcap:run.mcap#/camera/depth/image_raw"
                .parse::<CameraSpec>()
                .unwrap(),
            CameraSpec::Mcap {
                path: "run.mcap".into(),
                topic: Some("/camera/depth/image_raw".into())
            }
        );
        assert_eq!(
            "mcap:day#1/run.mcap#/depth".parse::<CameraSpec>().unwrap(),
            CameraSpec::Mcap {
                path: "day#1/run.mcap".into(),
                topic: Some("/depth".into())
            }
        );
        assert_eq!(
            "mcap:run.mcap".parse::<CameraSpec>().unwrap(),
            CameraSpec::Mcap {
                path: "run.mcap".into(),
                topic: None
            }
        );
        assert_eq!(
            "v4l:/dev/video2".parse::<CameraSpec>().unwrap(),
            CameraSpec::V4l("/dev/video2".into())
        );
        for bad in [
            "freenect:x",
            "fake:",
            "v4l",
            "webcam:0",
            "",
            "mcap:",
            "mcap:a#",
            "mcap:#t",
        ] {
            let e = bad.parse::<CameraSpec>().unwrap_err().to_string();
            assert!(e.contains(&format!("{bad:?}")), "{e}");
        }
    }
}
