//! The rover-terrain verdict protocol, for the service and the motor-controller
//! firmware alike: `no_std`, no allocation, no panics on any input.
//!
//! - [`Verdict`] and [`Heartbeat`]: the messages, in fixed-point units (cm, 0.1°,
//!   0.1 %, 10 ms). The verdict's core fits one classic 8-byte CAN frame.
//! - [`Odometry`]: the other way, the controller's wheel odometry as wrapping
//!   cumulative counters, and [`Motion`], the difference of two.
//! - [`serial`]: framing for a byte stream: version, type, payload, CRC-16/IBM-3740,
//!   COBS-encoded and ended by a 0x00 byte; a streaming decoder that resynchronises.
//! - [`can`]: the CAN identifiers and 8-byte frames.
//! - [`Freshness`]: the controller's fail-safe: stop unless a valid go verdict arrived
//!   within the deadline, and count sequence gaps.
//!
//! Byte layouts, CRC parameters, CAN IDs and test vectors are in `PROTOCOL.md`.
#![no_std]
#![deny(missing_docs)]
#![forbid(unsafe_code)]

pub mod can;
mod freshness;
mod message;
mod odometry;
pub mod serial;
pub mod vectors;

pub use freshness::{Command, Freshness};
pub use message::{Decision, DecodeError, HazardKind, Heartbeat, ServiceState, Side, Verdict};
pub use odometry::{
    Motion, Odometry, FORWARD_WRAP_MM, HEADING_UNITS_PER_TURN, LATERAL_WRAP_MM, TIME_WRAP_MS,
};

/// Protocol version carried in every serial frame.
pub const VERSION: u8 = 1;
