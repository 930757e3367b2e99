//! ROS 2 bags in MCAP: the messages (`sensor_msgs/msg/Image`, `CameraInfo`, in CDR)
//! and reading a bag's depth topic as frames.

pub mod bag;
pub mod msg;

pub use bag::Bag;
