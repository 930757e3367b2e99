use std::io::Write;

use rover_terrain_proto::serial::{encode, Decoder, Message};

use super::{link_err, proto, Transport, WRITE_TIMEOUT};
use crate::Error;

/// COBS-framed messages on a serial port (or any tty, e.g. a pseudo-terminal).
pub struct SerialTransport {
    path: String,
    port: Box<dyn serialport::SerialPort>,
    /// The controller's frames coming back (odometry).
    decoder: Decoder,
}

impl SerialTransport {
    /// Open `path` at `baud`, 8N1, no flow control.
    pub fn open(path: &str, baud: u32) -> Result<Self, Error> {
        let port = serialport::new(path, baud)
            .timeout(WRITE_TIMEOUT)
            .open()
            .map_err(|e| link_err(&format!("serial:{path}"), e))?;
        Ok(SerialTransport {
            path: path.to_string(),
            port,
            decoder: Decoder::new(),
        })
    }

    fn write(&mut self, msg: &Message) -> Result<(), Error> {
        let frame = encode(msg);
        self.port
            .write_all(&frame)
            .map_err(|e| link_err(&format!("serial:{}", self.path), e))
    }
}

impl Transport for SerialTransport {
    fn send_verdict(&mut self, v: &proto::Verdict) -> Result<(), Error> {
        self.write(&Message::Verdict(*v))
    }

    fn send_heartbeat(&mut self, h: &proto::Heartbeat) -> Result<(), Error> {
        self.write(&Message::Heartbeat(*h))
    }

    fn send_odometry(&mut self, o: &proto::Odometry) -> Result<(), Error> {
        self.write(&Message::Odometry(*o))
    }

    fn receive_odometry(&mut self, sink: &mut dyn FnMut(proto::Odometry)) -> Result<(), Error> {
        let decoder = &mut self.decoder;
        super::read_waiting(&mut *self.port, ("serial", &self.path), |b| {
            if let Some(Ok(Message::Odometry(o))) = decoder.push(b) {
                sink(o);
            }
        })
    }

    fn flush(&mut self) -> Result<(), Error> {
        self.port
            .flush()
            .map_err(|e| link_err(&format!("serial:{}", self.path), e))
    }
}
