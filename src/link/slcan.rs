//! SLCAN: the Lawicel ASCII protocol that USB-CAN adapters (CANable, CANtact, ...)
//! speak over a serial port. A standard data frame is `t` + 3 hex digits of ID + one
//! digit of length + 2 hex digits per byte + `\r`; `C` closes the channel, `S6` sets
//! 500 kbit/s, `O` opens it.

use std::io::Write;

use rover_terrain_proto::can::{self, Frame};

use super::{link_err, proto, Transport, WRITE_TIMEOUT};
use crate::Error;

/// What opens an adapter's CAN channel: close it (`C`), set 500 kbit/s (`S6`), open
/// it (`O`).
pub const OPEN_COMMANDS: &[u8] = b"C\rS6\rO\r";

/// One frame as an SLCAN transmit command, `\r` included.
pub fn encode(f: &Frame) -> heapless::String<32> {
    const HEX: &[u8; 16] = b"0123456789ABCDEF";
    let mut s = heapless::String::new();
    let mut put = |c: u8| {
        let _ = s.push(c as char); // 1 + 3 + 1 + 16 + 1 = 22 < 32
    };
    put(b't');
    for shift in [8, 4, 0] {
        put(HEX[usize::from((f.id >> shift) & 0xF)]);
    }
    put(b'8');
    for b in f.data {
        put(HEX[usize::from(b >> 4)]);
        put(HEX[usize::from(b & 0xF)]);
    }
    put(b'\r');
    s
}

/// Parse one SLCAN line (without its `\r`) into a frame; `None` for anything that is
/// not a standard 8-byte data frame (acks, other commands, garbage).
pub fn parse(line: &[u8]) -> Option<Frame> {
    if line.len() != 1 + 3 + 1 + 16 || line[0] != b't' || line[4] != b'8' {
        return None;
    }
    let hex = |c: u8| (c as char).to_digit(16).map(|d| d as u8);
    let mut id: u16 = 0;
    for &c in &line[1..4] {
        id = id << 4 | u16::from(hex(c)?);
    }
    let mut data = [0u8; 8];
    for (i, d) in data.iter_mut().enumerate() {
        *d = hex(line[5 + 2 * i])? << 4 | hex(line[6 + 2 * i])?;
    }
    Some(Frame { id, data })
}

/// CAN frames through an SLCAN adapter on a serial port.
pub struct SlcanTransport {
    path: String,
    port: Box<dyn serialport::SerialPort>,
    /// The adapter's received-frame line so far (odometry from the controller).
    line: heapless::Vec<u8, 64>,
}

impl SlcanTransport {
    /// Open the adapter's serial port and open the CAN channel at 500 kbit/s.
    pub fn open(path: &str, baud: u32) -> Result<Self, Error> {
        let mut port = serialport::new(path, baud)
            .timeout(WRITE_TIMEOUT)
            .open()
            .map_err(|e| link_err(&format!("slcan:{path}"), e))?;
        port.write_all(OPEN_COMMANDS)
            .map_err(|e| link_err(&format!("slcan:{path}"), e))?;
        Ok(SlcanTransport {
            path: path.to_string(),
            port,
            line: heapless::Vec::new(),
        })
    }

    fn write(&mut self, frames: &[Frame]) -> Result<(), Error> {
        for f in frames {
            self.port
                .write_all(encode(f).as_bytes())
                .map_err(|e| link_err(&format!("slcan:{}", self.path), e))?;
        }
        Ok(())
    }
}

impl Transport for SlcanTransport {
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
        let line = &mut self.line;
        super::read_waiting(&mut *self.port, ("slcan", &self.path), |b| {
            if b != b'\r' {
                // An overlong line is garbage: it will not parse.
                let _ = line.push(b);
                return;
            }
            if let Some(f) = parse(line).filter(|f| f.id == can::ODOMETRY_ID) {
                if let Ok(o) = proto::Odometry::decode(&f.data) {
                    sink(o);
                }
            }
            line.clear();
        })
    }

    fn flush(&mut self) -> Result<(), Error> {
        self.port
            .flush()
            .map_err(|e| link_err(&format!("slcan:{}", self.path), e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_round_trip_through_slcan_text() {
        let f = Frame {
            id: 0x310,
            data: [0, 4, 4, 3, 0x64, 0, 0xc8, 0],
        };
        let s = encode(&f);
        assert_eq!(s.as_str(), "t31080004040364 00C800\r".replace(' ', ""));
        assert_eq!(parse(s.trim_end().as_bytes()), Some(f));
        for bad in [
            &b"z"[..],
            b"T0000031080000000000000000",
            b"t3108000404036400C8G0",
            b"t31070004040364",
            b"",
        ] {
            assert_eq!(parse(bad), None, "{:?}", String::from_utf8_lossy(bad));
        }
    }
}
