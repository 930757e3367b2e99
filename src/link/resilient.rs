use std::time::{Duration, Instant};

use super::{open, proto, LinkTarget, Transport};
use crate::Error;

/// First wait before reopening a failed link.
pub const BACKOFF_MIN: Duration = Duration::from_millis(100);
/// Longest wait between reopen attempts.
pub const BACKOFF_MAX: Duration = Duration::from_secs(5);

/// A transport that survives failures: a send that fails drops the transport, logs
/// and counts the failure, and later sends try to reopen it no more often than the
/// backoff allows (doubling from [`BACKOFF_MIN`] to [`BACKOFF_MAX`]). Between
/// attempts, sends return at once: the pipeline is never blocked by a dead link.
pub struct Resilient {
    target: LinkTarget,
    baud: u32,
    inner: Option<Box<dyn Transport>>,
    backoff: Duration,
    next_attempt: Instant,
    failures: u64,
    dropped: u64,
    reopened: u64,
}

impl Resilient {
    /// Open the link now if possible; if not, the first send retries.
    pub fn new(target: LinkTarget, baud: u32) -> Self {
        let mut r = Resilient {
            target,
            baud,
            inner: None,
            backoff: BACKOFF_MIN,
            next_attempt: Instant::now(),
            failures: 0,
            dropped: 0,
            reopened: 0,
        };
        r.ensure_open(Instant::now());
        r
    }

    /// Link failures (open or send) so far.
    pub fn failures(&self) -> u64 {
        self.failures
    }

    /// Messages not sent because the link was down.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }

    /// Times the link was reopened after a failure.
    pub fn reopened(&self) -> u64 {
        self.reopened
    }

    /// Whether the link is open now.
    pub fn is_open(&self) -> bool {
        self.inner.is_some()
    }

    fn fail(&mut self, now: Instant, e: &Error) {
        self.failures += 1;
        self.inner = None;
        log::warn!("link {}: {e}; retrying in {:?}", self.target, self.backoff);
        self.next_attempt = now + self.backoff;
        self.backoff = (self.backoff * 2).min(BACKOFF_MAX);
    }

    fn ensure_open(&mut self, now: Instant) -> bool {
        if self.inner.is_some() {
            return true;
        }
        if now < self.next_attempt {
            return false;
        }
        match open(&self.target, self.baud) {
            Ok(t) => {
                if self.failures > 0 {
                    self.reopened += 1;
                    log::info!("link {}: reopened", self.target);
                }
                self.inner = Some(t);
                self.backoff = BACKOFF_MIN;
                true
            }
            Err(e) => {
                self.fail(now, &e);
                false
            }
        }
    }

    fn send(
        &mut self,
        now: Instant,
        f: impl FnOnce(&mut dyn Transport) -> Result<(), Error>,
    ) -> bool {
        if !self.ensure_open(now) {
            self.dropped += 1;
            return false;
        }
        let Some(t) = self.inner.as_mut() else {
            return false;
        };
        match f(t.as_mut()) {
            Ok(()) => true,
            Err(e) => {
                self.dropped += 1;
                self.fail(now, &e);
                false
            }
        }
    }

    /// Send a verdict; `false` if it could not be sent (counted, logged).
    pub fn send_verdict(&mut self, v: &proto::Verdict) -> bool {
        self.send_verdict_at(Instant::now(), v)
    }

    /// [`Self::send_verdict`] at a given time (tests advance the clock by hand).
    pub fn send_verdict_at(&mut self, now: Instant, v: &proto::Verdict) -> bool {
        self.send(now, |t| t.send_verdict(v))
    }

    /// Send a heartbeat; `false` if it could not be sent.
    pub fn send_heartbeat(&mut self, h: &proto::Heartbeat) -> bool {
        self.send(Instant::now(), |t| t.send_heartbeat(h))
    }

    /// Hand the odometry that arrived on the open transport to `sink` (nothing while
    /// the link is down; a read that fails fails the link like a send).
    pub fn receive_odometry(&mut self, sink: &mut dyn FnMut(proto::Odometry)) -> bool {
        let now = Instant::now();
        let Some(t) = self.inner.as_mut() else {
            return false;
        };
        match t.receive_odometry(sink) {
            Ok(()) => true,
            Err(e) => {
                self.fail(now, &e);
                false
            }
        }
    }

    /// Flush the open transport, if any.
    pub fn flush(&mut self) -> bool {
        self.send(Instant::now(), |t| t.flush())
    }

    /// The wait before the next reopen attempt after another failure.
    pub fn backoff(&self) -> Duration {
        self.backoff
    }
}
