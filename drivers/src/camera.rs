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
}
