//! The systemd notify protocol (`sd_notify(3)`): datagrams such as `READY=1`,
//! `WATCHDOG=1`, `STATUS=...` and `STOPPING=1` to the socket named by
//! `NOTIFY_SOCKET`, and the watchdog period from `WATCHDOG_USEC`.
//!
//! Written by hand rather than with the `sd-notify` crate: this keeps one connected
//! socket for the life of the service and sends from a caller's stack buffer, so the
//! watchdog pings on the hot path allocate nothing (the crate opens a socket and
//! builds a `String` per call). It is 60 lines.

use std::io::Write;
use std::os::unix::net::UnixDatagram;
use std::time::Duration;

use crate::Error;

/// A connection to the service manager, or nothing when not run under one.
#[derive(Debug, Default)]
pub struct Notifier {
    socket: Option<UnixDatagram>,
    watchdog: Option<Duration>,
}

impl Notifier {
    /// No service manager: every notification is a no-op.
    pub fn disabled() -> Self {
        Notifier::default()
    }

    /// From the environment: `NOTIFY_SOCKET` (a path, or `@name` for an abstract
    /// socket; unset = disabled) and `WATCHDOG_USEC` (ignored if `WATCHDOG_PID` names
    /// another process). A socket that cannot be reached is an error.
    pub fn from_env() -> Result<Self, Error> {
        let watchdog = std::env::var("WATCHDOG_USEC")
            .ok()
            .filter(|_| {
                std::env::var("WATCHDOG_PID")
                    .ok()
                    .and_then(|p| p.parse::<u32>().ok())
                    .is_none_or(|p| p == std::process::id())
            })
            .and_then(|u| u.parse::<u64>().ok())
            .filter(|&u| u > 0)
            .map(Duration::from_micros);
        let Some(path) = std::env::var_os("NOTIFY_SOCKET") else {
            return Ok(Notifier {
                socket: None,
                watchdog,
            });
        };
        let err = |e: std::io::Error| {
            Error::Setup(format!("NOTIFY_SOCKET={}: {e}", path.to_string_lossy()))
        };
        let socket = UnixDatagram::unbound().map_err(err)?;
        let bytes = path.as_encoded_bytes();
        if let Some(name) = bytes.strip_prefix(b"@") {
            use std::os::linux::net::SocketAddrExt;
            let addr = std::os::unix::net::SocketAddr::from_abstract_name(name).map_err(err)?;
            socket.connect_addr(&addr).map_err(err)?;
        } else {
            socket.connect(&path).map_err(err)?;
        }
        Ok(Notifier {
            socket: Some(socket),
            watchdog,
        })
    }

    /// Whether a service manager listens.
    pub fn enabled(&self) -> bool {
        self.socket.is_some()
    }

    /// The watchdog timeout systemd enforces, if it asked for pings.
    pub fn watchdog(&self) -> Option<Duration> {
        self.watchdog.filter(|_| self.enabled())
    }

    /// Send one notification (newline-separated `KEY=VALUE` lines). Failures are
    /// logged and otherwise ignored: the service keeps running.
    pub fn notify(&self, state: &[u8]) {
        if let Some(s) = &self.socket {
            if let Err(e) = s.send(state) {
                log::warn!("sd_notify: {e}");
            }
        }
    }

    /// Send `STATUS=` followed by `args`, formatted into a stack buffer (truncated to
    /// 255 bytes).
    pub fn status(&self, args: std::fmt::Arguments<'_>) {
        if !self.enabled() {
            return;
        }
        let mut buf = [0u8; 256];
        let mut cursor = std::io::Cursor::new(&mut buf[..]);
        let _ = cursor.write_all(b"STATUS=");
        let _ = cursor.write_fmt(args);
        let n = cursor.position() as usize;
        self.notify(&buf[..n]);
    }
}
