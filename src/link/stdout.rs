use std::io::Write;

use serde::Serialize;

use super::{proto, wire, Transport};
use crate::Error;

/// The wire form as JSON lines (one [`wire::VerdictJson`] or [`wire::HeartbeatJson`]
/// object per line) on any writer: the README's and the bench's link on stdout.
///
/// Each line is serialised into a buffer kept between lines and written with one
/// `write_all`, so lines never interleave and, once warm, a verdict costs no heap
/// allocation (`tests/no_alloc.rs` checks it).
#[derive(Debug)]
pub struct JsonLines<W> {
    out: W,
    line: Vec<u8>,
    name: &'static str,
}

/// Room for the longest verdict line (about 200 bytes) with a margin.
const LINE_CAPACITY: usize = 512;

/// JSON lines on this process's stdout.
pub type StdoutTransport = JsonLines<std::io::Stdout>;

impl StdoutTransport {
    /// A transport to this process's stdout.
    pub fn new() -> Self {
        JsonLines::to_writer(std::io::stdout(), "stdout")
    }
}

impl Default for StdoutTransport {
    fn default() -> Self {
        Self::new()
    }
}

impl<W: Write> JsonLines<W> {
    /// JSON lines into `out`; `name` is how errors name it.
    pub fn to_writer(out: W, name: &'static str) -> Self {
        JsonLines {
            out,
            line: Vec::with_capacity(LINE_CAPACITY),
            name,
        }
    }

    /// The writer, back.
    pub fn into_inner(self) -> W {
        self.out
    }

    fn line(&mut self, value: impl Serialize) -> Result<(), Error> {
        self.line.clear();
        serde_json::to_writer(&mut self.line, &value).map_err(|e| super::link_err(self.name, e))?;
        self.line.push(b'\n');
        self.out
            .write_all(&self.line)
            .map_err(|e| super::link_err(self.name, e))
    }
}

impl<W: Write + Send> Transport for JsonLines<W> {
    fn send_verdict(&mut self, v: &proto::Verdict) -> Result<(), Error> {
        self.line(wire::VerdictJson::from(v))
    }

    fn send_heartbeat(&mut self, h: &proto::Heartbeat) -> Result<(), Error> {
        self.line(wire::HeartbeatJson::from(h))
    }

    fn send_odometry(&mut self, o: &proto::Odometry) -> Result<(), Error> {
        self.line(wire::odometry_json(o))
    }

    fn flush(&mut self) -> Result<(), Error> {
        self.out.flush().map_err(|e| super::link_err(self.name, e))
    }
}
