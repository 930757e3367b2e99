//! The verdict link: the wire form of a verdict, and the transports that carry it to
//! the motor controller (serial with COBS framing, SLCAN over a serial port,
//! SocketCAN, stdout), each behind [`Transport`], wrapped in [`Resilient`] so that a
//! failing link is reopened with backoff and never blocks the pipeline.

mod resilient;
mod serial;
pub mod slcan;
#[cfg(feature = "socketcan")]
pub mod socketcan;
mod stdout;
pub mod wire;

use std::str::FromStr;
use std::time::Duration;

pub use resilient::{Resilient, BACKOFF_MAX, BACKOFF_MIN};
pub use rover_terrain_proto as proto;
pub use serial::SerialTransport;
pub use slcan::SlcanTransport;
pub use stdout::{JsonLines, StdoutTransport};

use crate::Error;

/// Default serial speed, baud.
pub const DEFAULT_BAUD: u32 = 115_200;

/// Where verdicts go: the `--link` argument.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LinkTarget {
    /// `serial:PATH`: COBS-framed messages on a serial port.
    Serial(String),
    /// `slcan:PATH`: CAN frames through an SLCAN (Lawicel) adapter on a serial port.
    Slcan(String),
    /// `can:IFACE`: a SocketCAN interface (feature `socketcan`).
    Can(String),
    /// `stdout`: the wire form as JSON lines.
    Stdout,
}

impl FromStr for LinkTarget {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self, Error> {
        let bad = |why: &str| Error::Link {
            target: s.to_string(),
            message: why.to_string(),
        };
        if s == "stdout" {
            return Ok(LinkTarget::Stdout);
        }
        let (kind, rest) = s
            .split_once(':')
            .ok_or_else(|| bad("expected serial:PATH, slcan:PATH, can:IFACE or stdout"))?;
        if rest.is_empty() {
            return Err(bad("missing the path or interface after ':'"));
        }
        match kind {
            "serial" => Ok(LinkTarget::Serial(rest.to_string())),
            "slcan" => Ok(LinkTarget::Slcan(rest.to_string())),
            "can" => Ok(LinkTarget::Can(rest.to_string())),
            _ => Err(bad("unknown link kind (serial, slcan, can, stdout)")),
        }
    }
}

impl std::fmt::Display for LinkTarget {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LinkTarget::Serial(p) => write!(f, "serial:{p}"),
            LinkTarget::Slcan(p) => write!(f, "slcan:{p}"),
            LinkTarget::Can(i) => write!(f, "can:{i}"),
            LinkTarget::Stdout => write!(f, "stdout"),
        }
    }
}

/// One way to the motor controller. Sends do not block for long: a transport that
/// cannot take the bytes (unplugged adapter, full buffer past its timeout) returns
/// an error, and [`Resilient`] decides what to do.
pub trait Transport: Send {
    /// Send one verdict.
    fn send_verdict(&mut self, v: &proto::Verdict) -> Result<(), Error>;
    /// Send one heartbeat.
    fn send_heartbeat(&mut self, h: &proto::Heartbeat) -> Result<(), Error>;
    /// Send one odometry message (the controller's direction: the bench's controller
    /// simulator uses the same transports).
    fn send_odometry(&mut self, o: &proto::Odometry) -> Result<(), Error>;
    /// Hand every odometry message that has arrived from the controller to `sink`,
    /// without waiting (other messages and corrupt frames are skipped). A transport
    /// with no way back (stdout) has none.
    fn receive_odometry(&mut self, sink: &mut dyn FnMut(proto::Odometry)) -> Result<(), Error> {
        let _ = sink;
        Ok(())
    }
    /// Push buffered bytes out.
    fn flush(&mut self) -> Result<(), Error>;
}

/// How long a serial write may wait before the link counts as failed.
pub const WRITE_TIMEOUT: Duration = Duration::from_millis(50);

/// Open the transport for `target`.
pub fn open(target: &LinkTarget, baud: u32) -> Result<Box<dyn Transport>, Error> {
    Ok(match target {
        LinkTarget::Serial(path) => Box::new(SerialTransport::open(path, baud)?),
        LinkTarget::Slcan(path) => Box::new(SlcanTransport::open(path, baud)?),
        LinkTarget::Stdout => Box::new(StdoutTransport::new()),
        #[cfg(feature = "socketcan")]
        LinkTarget::Can(iface) => Box::new(socketcan::SocketCanTransport::open(iface)?),
        #[cfg(not(feature = "socketcan"))]
        LinkTarget::Can(_) => {
            return Err(Error::Link {
                target: target.to_string(),
                message: "built without the `socketcan` feature (cargo build --features socketcan)"
                    .into(),
            })
        }
    })
}

/// Read every byte waiting on a serial port, without waiting for more, handing each
/// to `each` (the controller's messages coming back on a serial or SLCAN link). The
/// link's name (`kind:path`) is only put together for an error: nothing allocates.
pub(crate) fn read_waiting(
    port: &mut dyn serialport::SerialPort,
    (kind, path): (&str, &str),
    mut each: impl FnMut(u8),
) -> Result<(), Error> {
    let err = |e: serialport::Error| link_err(&format!("{kind}:{path}"), e);
    let mut buf = [0u8; 256];
    loop {
        let waiting = port.bytes_to_read().map_err(err)? as usize;
        if waiting == 0 {
            return Ok(());
        }
        let n = port
            .read(&mut buf[..waiting.min(256)])
            .map_err(|e| err(e.into()))?;
        if n == 0 {
            return Ok(());
        }
        buf[..n].iter().for_each(|&b| each(b));
    }
}

pub(crate) fn link_err(target: &str, e: impl std::fmt::Display) -> Error {
    Error::Link {
        target: target.to_string(),
        message: e.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn targets_parse_and_print() {
        for s in [
            "serial:/dev/ttyUSB0",
            "slcan:/dev/ttyACM0",
            "can:can0",
            "stdout",
        ] {
            assert_eq!(s.parse::<LinkTarget>().unwrap().to_string(), s);
        }
        for bad in ["", "serial:", "udp:1.2.3.4", "ttyUSB0"] {
            let e = bad.parse::<LinkTarget>().unwrap_err().to_string();
            assert!(e.contains(bad), "{e}");
        }
    }

    #[cfg(not(feature = "socketcan"))]
    #[test]
    fn can_without_the_feature_says_how_to_get_it() {
        let e = open(&LinkTarget::Can("can0".into()), DEFAULT_BAUD)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("--features socketcan"), "{e}");
    }
}
