//! SocketCAN (feature `socketcan`): the kernel's CAN interfaces (`can0`, `vcan0`).

use rover_terrain_proto::can::{self, Frame};
use socketcan::{CanFrame, CanSocket, EmbeddedFrame, Socket, StandardId};

use super::{link_err, proto, Transport};
use crate::Error;

/// The classic CAN frame for one protocol frame.
pub fn to_socketcan(f: &Frame) -> Option<CanFrame> {
    CanFrame::new(StandardId::new(f.id)?, &f.data)
}

/// Verdicts as CAN frames on a SocketCAN interface.
pub struct SocketCanTransport {
    iface: String,
    socket: CanSocket,
}

impl SocketCanTransport {
    /// Open interface `iface`.
    pub fn open(iface: &str) -> Result<Self, Error> {
        let socket = CanSocket::open(iface).map_err(|e| link_err(&format!("can:{iface}"), e))?;
        socket
            .set_write_timeout(super::WRITE_TIMEOUT)
            .map_err(|e| link_err(&format!("can:{iface}"), e))?;
        Ok(SocketCanTransport {
            iface: iface.to_string(),
            socket,
        })
    }

    fn write(&mut self, frames: &[Frame]) -> Result<(), Error> {
        for f in frames {
            let frame = to_socketcan(f).ok_or_else(|| {
                link_err(&format!("can:{}", self.iface), "identifier out of range")
            })?;
            self.socket
                .write_frame(&frame)
                .map_err(|e| link_err(&format!("can:{}", self.iface), e))?;
        }
        Ok(())
    }
}

impl Transport for SocketCanTransport {
    fn send_verdict(&mut self, v: &proto::Verdict) -> Result<(), Error> {
        self.write(&can::verdict_frames(v))
    }

    fn send_heartbeat(&mut self, h: &proto::Heartbeat) -> Result<(), Error> {
        self.write(&[can::heartbeat_frame(h)])
    }

    fn send_odometry(&mut self, o: &proto::Odometry) -> Result<(), Error> {
        self.write(&[can::odometry_frame(o)])
    }

    fn receive_odometry(&mut self, sink: &mut dyn FnMut(proto::Odometry)) -> Result<(), Error> {
        let err = |e: &dyn std::fmt::Display| link_err(&format!("can:{}", self.iface), e);
        self.socket.set_nonblocking(true).map_err(|e| err(&e))?;
        let result = loop {
            match self.socket.read_frame() {
                Ok(f) => {
                    let id = match f.id() {
                        socketcan::Id::Standard(id) => id.as_raw(),
                        socketcan::Id::Extended(_) => continue,
                    };
                    if id != can::ODOMETRY_ID || f.data().len() != 8 {
                        continue;
                    }
                    let mut data = [0u8; 8];
                    data.copy_from_slice(f.data());
                    if let Ok(o) = proto::Odometry::decode(&data) {
                        sink(o);
                    }
                }
                Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => break Ok(()),
                Err(e) => break Err(err(&e)),
            }
        };
        self.socket.set_nonblocking(false).map_err(|e| err(&e))?;
        result
    }

    fn flush(&mut self) -> Result<(), Error> {
        Ok(())
    }
}

/// One frame in candump's log format: `(seconds.micros) IFACE ID#DATA`.
pub fn candump_line(timestamp_s: f64, iface: &str, f: &Frame) -> String {
    let data: String = f.data.iter().map(|b| format!("{b:02X}")).collect();
    format!("({timestamp_s:.6}) {iface} {:03X}#{data}", f.id)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn protocol_frames_become_classic_can_frames() {
        let f = Frame {
            id: can::VERDICT_ID,
            data: [1, 2, 3, 4, 5, 6, 7, 8],
        };
        let c = to_socketcan(&f).unwrap();
        assert_eq!(c.data(), &f.data);
        assert!(!c.is_extended());
        assert_eq!(
            candump_line(1.5, "can0", &f),
            "(1.500000) can0 310#0102030405060708"
        );
        assert!(
            to_socketcan(&Frame {
                id: 0x800,
                data: [0; 8]
            })
            .is_none(),
            "11-bit IDs only"
        );
    }

    #[test]
    fn a_missing_interface_is_a_clear_error() {
        let e = SocketCanTransport::open("rtnocan0")
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("can:rtnocan0"), "{e}");
    }
}
