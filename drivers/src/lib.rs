//! Depth sources for rover-terrain.
//!
//! Every source yields [`DepthFrame`]s: row-major `u16` depth in millimetres along the
//! camera's optical axis (Z, not ray length), `0` meaning "no return". One small trait,
//! [`DepthCamera`], is the whole contract; [`FakeCamera`] is the file-backed source
//! that replays recordings (single PGM/PNG images, image directories, and libfreenect
//! `fakenect` sessions, ROS 2 bags in MCAP) and is what the tests and the bench use.
#![deny(missing_docs)]

mod camera;
mod error;
mod fake;
pub mod fakenect;
mod frame;
#[cfg(feature = "freenect")]
pub mod freenect;
pub mod image;
mod nodes;
pub mod odometry_file;
pub mod ros2;
mod source;
#[cfg(feature = "v4l")]
pub mod v4l;

pub use camera::{CameraOptions, DepthCamera, FrameStatus, Intrinsics};
pub use error::DriverError;
pub use fake::{FakeCamera, Faults, Pace};
pub use frame::{ColourFrame, DepthFrame, MAX_HEIGHT, MAX_WIDTH};
pub use source::{list_cameras, open, open_with, probe_intrinsics, CameraSpec};
