use std::io::Write;

use super::{proto, wire, Transport};
use crate::Error;

/// The wire form as JSON lines on stdout (the bench's link).
#[derive(Debug, Default)]
pub struct StdoutTransport;

impl StdoutTransport {
    /// A transport to this process's stdout.
    pub fn new() -> Self {
        StdoutTransport
    }

    fn line(&mut self, value: serde_json::Value) -> Result<(), Error> {
        writeln!(std::io::stdout().lock(), "{value}").map_err(|e| super::link_err("stdout", e))
    }
}

impl Transport for StdoutTransport {
    fn send_verdict(&mut self, v: &proto::Verdict) -> Result<(), Error> {
        self.line(wire::verdict_json(v))
    }

    fn send_heartbeat(&mut self, h: &proto::Heartbeat) -> Result<(), Error> {
        self.line(wire::heartbeat_json(h))
    }

    fn flush(&mut self) -> Result<(), Error> {
        std::io::stdout()
            .flush()
            .map_err(|e| super::link_err("stdout", e))
    }
}
