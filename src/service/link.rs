//! The link thread: sends verdicts and heartbeats, talks to systemd (ready,
//! watchdog, status), logs metrics.

use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::thread;
use std::time::{Duration, Instant};

use crossbeam_channel::{bounded, Receiver, Sender};

use super::{get, Counters, Histogram, Notifier, Percentiles};
use crate::link::{proto, LinkTarget, Resilient};
use crate::{Config, Error};

/// Verdicts waiting for the link thread at most.
const LINK_QUEUE: usize = 16;
/// Odometry messages waiting for the analysis stage at most (the stage keeps only
/// the latest: more would be lost time, not lost travel).
const ODOMETRY_QUEUE: usize = 64;

/// An odometry message from the controller and when the link thread read it.
pub(super) type OdometryIn = (proto::Odometry, Instant);

/// What analysis hands to the link thread.
pub(super) enum LinkMsg {
    /// A verdict to send, with when its frame arrived and how long it waited and
    /// took (for the metrics); `fresh` is false for the fail-safe unknowns.
    Verdict {
        verdict: proto::Verdict,
        arrived: Instant,
        fresh: bool,
        queued: Duration,
        process: Duration,
    },
    /// The last verdict: send it, a stopping heartbeat, and end.
    Stop(proto::Verdict),
}

/// The link thread's ends: verdicts in, the controller's odometry out, its handle.
pub(super) struct Started {
    pub link_tx: Sender<LinkMsg>,
    pub odometry_rx: Receiver<OdometryIn>,
    pub handle: thread::JoinHandle<LinkReport>,
}

/// Start the link thread; verdicts go in through the returned sender, odometry the
/// controller sends on the link comes out of the returned receiver.
pub(super) fn start(
    target: &LinkTarget,
    baud: u32,
    config: &Config,
    notifier: Notifier,
    counters: &Arc<Counters>,
) -> Result<Started, Error> {
    let (link_tx, link_rx) = bounded::<LinkMsg>(LINK_QUEUE);
    let (odometry_tx, odometry_rx) = bounded::<OdometryIn>(ODOMETRY_QUEUE);
    let link = LinkThread {
        link: Resilient::new(target.clone(), baud),
        rx: link_rx,
        odometry_tx,
        notifier,
        counters: Arc::clone(counters),
        heartbeat: Duration::from_millis(config.service.heartbeat_ms),
        stats_every: Duration::from_secs(config.service.stats_interval_s),
        total: Histogram::new(),
        window: Windows::default(),
    };
    let handle = thread::Builder::new()
        .name("link".into())
        .spawn(move || link.run())
        .map_err(|e| Error::Setup(format!("cannot start the link thread: {e}")))?;
    Ok(Started {
        link_tx,
        odometry_rx,
        handle,
    })
}

/// Per-stage latencies over one metrics interval.
#[derive(Debug, Default)]
struct Windows {
    queued: Histogram,
    process: Histogram,
    link: Histogram,
    total: Histogram,
    since: Option<Instant>,
}

/// What the link thread did, when it ends.
pub(super) struct LinkReport {
    /// Messages sent.
    pub sent: u64,
    /// Link failures.
    pub failures: u64,
    /// Verdicts the link could not take.
    pub dropped: u64,
    /// Arrival to bytes on the link.
    pub latency: Percentiles,
}

/// The link thread: sends verdicts and heartbeats, talks to systemd, logs metrics.
struct LinkThread {
    link: Resilient,
    rx: Receiver<LinkMsg>,
    odometry_tx: Sender<OdometryIn>,
    notifier: Notifier,
    counters: Arc<Counters>,
    heartbeat: Duration,
    stats_every: Duration,
    total: Histogram,
    window: Windows,
}

/// The link thread's running state between messages.
struct Tick {
    sent: u64,
    ready: bool,
    ping_every: Option<Duration>,
    last_ping: Option<Instant>,
    next_heartbeat: Instant,
    next_stats: Instant,
    heartbeat_seq: u8,
    fresh_in_window: u64,
}

impl LinkThread {
    /// Send what comes until the stop verdict (or the queue closes), heartbeats and
    /// metrics in between.
    fn run(mut self) -> LinkReport {
        let start = Instant::now();
        let mut t = Tick {
            sent: 0,
            ready: false,
            ping_every: self.notifier.watchdog().map(|w| w / 4),
            last_ping: None,
            next_heartbeat: start + self.heartbeat,
            next_stats: start + self.stats_every,
            heartbeat_seq: 0,
            fresh_in_window: 0,
        };
        self.window.since = Some(start);
        loop {
            let deadline = t.next_heartbeat.min(t.next_stats);
            match self.rx.recv_deadline(deadline) {
                Ok(LinkMsg::Verdict {
                    verdict,
                    arrived,
                    fresh,
                    queued,
                    process,
                }) => self.send_verdict(&mut t, verdict, arrived, fresh, queued, process),
                Ok(LinkMsg::Stop(verdict)) => {
                    self.send_last(&mut t, &verdict);
                    break;
                }
                Err(crossbeam_channel::RecvTimeoutError::Timeout) => {}
                Err(crossbeam_channel::RecvTimeoutError::Disconnected) => {
                    self.notifier.notify(b"STOPPING=1");
                    break;
                }
            }
            self.receive_odometry();
            let now = Instant::now();
            if now >= t.next_stats {
                self.stats(&mut t, now);
            }
            if now >= t.next_heartbeat {
                self.heartbeat(&mut t, now);
            }
        }
        LinkReport {
            sent: t.sent,
            failures: self.link.failures(),
            dropped: self.link.dropped(),
            latency: self.total.percentiles(),
        }
    }

    /// Send one verdict; a fresh one sent counts in the metrics, makes the service
    /// ready (systemd READY=1) and pings the watchdog.
    fn send_verdict(
        &mut self,
        t: &mut Tick,
        mut verdict: proto::Verdict,
        arrived: Instant,
        fresh: bool,
        queued: Duration,
        process: Duration,
    ) {
        let t0 = Instant::now();
        verdict.age_10ms = ((t0 - arrived).as_millis() / 10).min(255) as u8;
        let ok = self.link.send_verdict(&verdict) && self.link.flush();
        let done = Instant::now();
        if ok {
            t.sent += 1;
        }
        if !(ok && fresh) {
            return;
        }
        t.fresh_in_window += 1;
        let total = done - arrived;
        self.total.record(total);
        self.window.total.record(total);
        self.window.queued.record(queued);
        self.window.process.record(process);
        self.window.link.record(done - t0);
        if !t.ready {
            t.ready = true;
            self.notifier.notify(b"READY=1\nSTATUS=running");
            log::info!("first verdict sent: ready");
        }
        if let Some(every) = t.ping_every {
            if t.last_ping.is_none_or(|p| done - p >= every) {
                self.notifier.notify(b"WATCHDOG=1");
                t.last_ping = Some(done);
            }
        }
    }

    /// Pass on the odometry that arrived on the link (the oldest is dropped when the
    /// analysis stage is behind: it only needs the latest).
    fn receive_odometry(&mut self) {
        let (tx, counters) = (&self.odometry_tx, &self.counters);
        self.link.receive_odometry(&mut |o| {
            super::bump(&counters.odometry_in);
            let _ = tx.try_send((o, Instant::now()));
        });
    }

    /// The last verdict and a stopping heartbeat, flushed.
    fn send_last(&mut self, t: &mut Tick, verdict: &proto::Verdict) {
        self.notifier.notify(b"STOPPING=1\nSTATUS=stopping");
        let hb = self.heartbeat_msg(proto::ServiceState::Stopping, t.heartbeat_seq, 0);
        if self.link.send_verdict(verdict) {
            t.sent += 1;
        }
        if self.link.send_heartbeat(&hb) {
            t.sent += 1;
        }
        self.link.flush();
    }

    /// Fresh verdicts per second in the current metrics window.
    fn window_rate(&self, t: &Tick, now: Instant) -> f64 {
        let secs = self
            .window
            .since
            .map_or(1.0, |s| (now - s).as_secs_f64().max(1e-3));
        t.fresh_in_window as f64 / secs
    }

    /// The metrics line, then a new window.
    fn stats(&mut self, t: &mut Tick, now: Instant) {
        self.report(self.window_rate(t, now));
        t.fresh_in_window = 0;
        self.window.since = Some(now);
        t.next_stats = now + self.stats_every;
    }

    /// A heartbeat: running while frames flow, degraded while they do not.
    fn heartbeat(&mut self, t: &mut Tick, now: Instant) {
        let state = if self.counters.flowing.load(Ordering::Relaxed) {
            proto::ServiceState::Running
        } else {
            proto::ServiceState::Degraded
        };
        let rate_chz = (self.window_rate(t, now) * 100.0).round() as u16;
        let hb = self.heartbeat_msg(state, t.heartbeat_seq, rate_chz);
        if self.link.send_heartbeat(&hb) && self.link.flush() {
            t.sent += 1;
        }
        t.heartbeat_seq = t.heartbeat_seq.wrapping_add(1);
        t.next_heartbeat = now + self.heartbeat;
    }

    fn heartbeat_msg(
        &self,
        state: proto::ServiceState,
        seq: u8,
        rate_chz: u16,
    ) -> proto::Heartbeat {
        proto::Heartbeat {
            state,
            camera_ok: self.counters.flowing.load(Ordering::Relaxed),
            memory_fused: self.counters.memory_fused.load(Ordering::Relaxed),
            frame_rate_chz: rate_chz,
            dropped: get(&self.counters.dropped).min(u64::from(u16::MAX)) as u16,
            seq,
        }
    }

    /// The metrics line and the systemd STATUS.
    fn report(&mut self, fps: f64) {
        let w = &mut self.window;
        let (q, p, l, t) = (
            w.queued.percentiles(),
            w.process.percentiles(),
            w.link.percentiles(),
            w.total.percentiles(),
        );
        let c = &self.counters;
        log::info!(
            "{fps:.1} fps; queue {q}; analysis {p}; link {l}; arrival→link {t}; \
             dropped {} rejected {} camera timeouts {} reopens {}; link failures {} unsent {}; \
             viewer pictures dropped {}",
            get(&c.dropped),
            get(&c.rejected),
            get(&c.camera_timeouts),
            get(&c.camera_reopens),
            self.link.failures(),
            self.link.dropped(),
            get(&c.viewer_dropped)
        );
        self.notifier.status(format_args!(
            "{fps:.1} fps, latency p50 {:.1} ms p99 {:.1} ms, dropped {}, rejected {}, link failures {}",
            t.p50_us as f64 / 1e3,
            t.p99_us as f64 / 1e3,
            get(&c.dropped),
            get(&c.rejected),
            self.link.failures()
        ));
        w.queued.clear();
        w.process.clear();
        w.link.clear();
        w.total.clear();
    }
}
