//! ROS 2 bags in MCAP: the messages (`sensor_msgs/msg/Image`, `CameraInfo`, in CDR),
//! reading a bag's depth topic as frames, and writing MCAP files and bags.

pub mod bag;
pub mod msg;
pub mod writer;

pub use bag::Bag;
pub use writer::{BagTopics, BagWriter, McapFile};
