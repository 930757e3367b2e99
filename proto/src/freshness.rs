//! The controller's fail-safe.

use crate::message::{Decision, Verdict};

/// What the controller should do now.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Command {
    /// Drive: the last verdict is fresh and says go.
    Go,
    /// Stop: no verdict yet, the last one is stale, or it says stop or unknown.
    Stop,
}

/// Tracks the last valid verdict: stop unless a go verdict arrived within the
/// deadline; counts sequence gaps and lost verdicts. Time is passed in (ms, any
/// monotonic clock), so it needs no clock of its own and tests need no sleeps.
#[derive(Debug, Clone)]
pub struct Freshness {
    deadline_ms: u64,
    last: Option<(u64, Verdict)>,
    gaps: u32,
    lost: u64,
    stale_rejected: u32,
}

impl Freshness {
    /// A guard with a deadline, milliseconds.
    pub const fn new(deadline_ms: u64) -> Self {
        Freshness {
            deadline_ms,
            last: None,
            gaps: 0,
            lost: 0,
            stale_rejected: 0,
        }
    }

    /// A verdict arrived at `now_ms`. A verdict whose sequence number is not newer
    /// than the last (a replay or reordering) is ignored and counted.
    pub fn on_verdict(&mut self, now_ms: u64, v: Verdict) {
        if let Some((_, last)) = &self.last {
            let step = v.seq.wrapping_sub(last.seq);
            if step == 0 || step > u32::MAX / 2 {
                self.stale_rejected += 1;
                return;
            }
            if step > 1 {
                self.gaps += 1;
                self.lost += u64::from(step - 1);
            }
        }
        self.last = Some((now_ms, v));
    }

    /// What to do at `now_ms`.
    pub fn command(&self, now_ms: u64) -> Command {
        match &self.last {
            Some((t, v))
                if v.decision == Decision::Go && now_ms.saturating_sub(*t) <= self.deadline_ms =>
            {
                Command::Go
            }
            _ => Command::Stop,
        }
    }

    /// Whether the last verdict is older than the deadline (or there is none).
    pub fn stale(&self, now_ms: u64) -> bool {
        self.last
            .is_none_or(|(t, _)| now_ms.saturating_sub(t) > self.deadline_ms)
    }

    /// Times the sequence jumped by more than one.
    pub fn gaps(&self) -> u32 {
        self.gaps
    }

    /// Verdicts missing from the sequence.
    pub fn lost(&self) -> u64 {
        self.lost
    }

    /// Verdicts ignored as not newer than the last.
    pub fn stale_rejected(&self) -> u32 {
        self.stale_rejected
    }

    /// The last accepted verdict.
    pub fn last(&self) -> Option<&Verdict> {
        self.last.as_ref().map(|(_, v)| v)
    }
}
