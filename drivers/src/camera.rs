//! The camera contract: what every depth source implements and is asked for. It
//! knows no backend; [`crate::source`] picks and opens one.

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
    /// The camera's own account of its optics, for sources that carry one (a ROS 2
    /// bag's image size and `CameraInfo`): the caller sizes its analysis to it and
    /// uses its pinhole intrinsics instead of the configured ones. `None` = use the
    /// configuration.
    fn intrinsics(&self) -> Option<Intrinsics> {
        None
    }
}

/// A camera's image size and, when calibrated, its pinhole intrinsics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Intrinsics {
    /// Image width, pixels.
    pub width: usize,
    /// Image height, pixels.
    pub height: usize,
    /// Focal lengths and principal point (fx, fy, cx, cy) for this size, pixels.
    pub pinhole: Option<(f64, f64, f64, f64)>,
}

impl Intrinsics {
    /// The same camera for `width × height` images (binned or resized): the pinhole
    /// scaled along each axis. A size of 0 (uncalibrated size) scales nothing.
    pub fn scaled_to(&self, width: usize, height: usize) -> Self {
        let ratio = |to: usize, from: usize| {
            if from > 0 {
                to as f64 / from as f64
            } else {
                1.0
            }
        };
        let (sx, sy) = (ratio(width, self.width), ratio(height, self.height));
        Intrinsics {
            width,
            height,
            pinhole: self
                .pinhole
                .map(|(fx, fy, cx, cy)| (fx * sx, fy * sy, cx * sx, cy * sy)),
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intrinsics_scale_with_the_image_and_an_unknown_size_scales_nothing() {
        let k = Intrinsics {
            width: 640,
            height: 480,
            pinhole: Some((580.0, 570.0, 320.0, 240.0)),
        };
        let half = k.scaled_to(320, 240);
        assert_eq!((half.width, half.height), (320, 240));
        assert_eq!(half.pinhole, Some((290.0, 285.0, 160.0, 120.0)));
        let unknown = Intrinsics {
            width: 0,
            height: 0,
            ..k
        };
        assert_eq!(unknown.scaled_to(320, 240).pinhole, k.pinhole);
    }
}
