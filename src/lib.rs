//! rover-terrain: a planetary rover's eyes for the ground ahead.
//!
//! A depth frame (u16 millimetres) is projected into a point cloud, moved into the
//! rover frame (REP 103: x forward, y left, z up, metres, origin on the ground),
//! binned into a dense voxel grid over the corridor ahead, and analysed: can the
//! terrain be crossed (paper §3.1), and which obstacle feature lies ahead (§3.2). The
//! result is a [`Verdict`]. Angles are degrees, lengths metres, unless a name says
//! otherwise.
#![deny(missing_docs)]

pub mod analysis;
pub mod bench;
pub mod config;
pub mod coverage;
mod error;
pub mod foxglove;
pub mod grid;
pub mod inspect;
pub mod level;
pub mod link;
pub mod memory;
pub mod mixed_pixels;
pub mod pipeline;
pub mod projection;
pub mod service;
pub mod sim;
pub mod validate;
pub mod verdict;

pub use config::Config;
pub use error::Error;
pub use pipeline::Pipeline;
pub use verdict::{Decision, Feature, Hazard, HazardKind, Side, Verdict};
