//! The on-board service: a camera thread, the analysis stage and a link thread,
//! joined by bounded channels over a frame pool allocated at start.
//!
//! ```text
//!  camera thread ──ready (1)──▶ analysis (caller's thread) ──verdicts (16)──▶ link thread
//!        ▲                              │                                        │
//!        └────────── free frames (pool) ◀┘                      serial/SLCAN/CAN/stdout,
//!                                                               heartbeats, sd_notify
//! ```
//!
//! - **Newest wins**: the ready queue holds one frame. When the camera delivers while
//!   one is still waiting, the waiting (older) frame goes back to the pool and is
//!   counted as dropped.
//! - **No allocation per frame**: frames move between threads by value (their pixel
//!   buffers were allocated at start); the channels are bounded arrays; the verdict
//!   and its wire form live in preallocated state. The `no_alloc` test runs the whole
//!   service with a counting allocator.
//! - **Fail-safe**: no frame for `service.frame_timeout_ms` and an "unknown" verdict
//!   goes out every `service.heartbeat_ms` until frames return; the watchdog pings
//!   stop with the fresh verdicts. A camera that vanishes is reopened with backoff;
//!   a link that fails is reopened with backoff ([`Resilient`]) while frames keep
//!   being analysed. On shutdown a final stop verdict is sent and flushed.

mod histogram;
pub mod notify;

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::thread;
use std::time::{Duration, Instant};

use crossbeam_channel::{bounded, select, Receiver, Sender, TryRecvError};
use rover_terrain_drivers::{
    CameraOptions, CameraSpec, DepthCamera, DepthFrame, DriverError, FakeCamera, Faults,
    FrameStatus, Pace,
};

pub use histogram::{Histogram, Percentiles};
pub use notify::Notifier;

use crate::link::{proto, wire, LinkTarget, Resilient};
use crate::{Config, Error, Pipeline};

/// A replayed recording is decoded into memory when one pass fits in this, bytes.
pub const PRELOAD_BUDGET: usize = 48 << 20;
/// First wait before reopening a camera that vanished.
pub const CAMERA_BACKOFF_MIN: Duration = Duration::from_millis(100);
/// Longest wait between camera reopen attempts.
pub const CAMERA_BACKOFF_MAX: Duration = Duration::from_secs(5);
/// Verdicts waiting for the link thread at most.
const LINK_QUEUE: usize = 16;

/// What to run.
#[derive(Debug, Clone)]
pub struct Options {
    /// The validated configuration.
    pub config: Config,
    /// The camera to read.
    pub camera: CameraSpec,
    /// Where verdicts go.
    pub link: LinkTarget,
    /// Serial speed for serial links, baud.
    pub baud: u32,
    /// Faults the fake camera injects (tests); ignored by live cameras.
    pub faults: Faults,
    /// Stop after this many frames analysed.
    pub frames: Option<u64>,
}

impl Options {
    /// The options the configuration gives: its camera (or `default_camera`) and link.
    pub fn from_config(config: Config, default_camera: CameraSpec) -> Result<Self, Error> {
        let camera = match &config.camera.source {
            Some(s) => s.parse()?,
            None => default_camera,
        };
        let link = config.link.target.parse()?;
        let baud = config.link.baud;
        Ok(Options {
            config,
            camera,
            link,
            baud,
            faults: Faults::default(),
            frames: None,
        })
    }
}

/// Why the service stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// SIGTERM/SIGINT (or the caller's shutdown channel).
    Signal,
    /// A recording played to its end (not looping).
    EndOfStream,
    /// `frames` frames were analysed.
    FrameLimit,
}

/// What a run did.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Summary {
    /// Why it stopped.
    pub reason: StopReason,
    /// Frames the camera delivered.
    pub frames_in: u64,
    /// Frames analysed.
    pub analysed: u64,
    /// Frames dropped because a newer one arrived before analysis took them.
    pub dropped: u64,
    /// Frames rejected (corrupt, wrong size), never analysed.
    pub rejected: u64,
    /// Camera timeouts.
    pub camera_timeouts: u64,
    /// Times the camera was reopened after vanishing.
    pub camera_reopens: u64,
    /// "Unknown" verdicts sent because no frame came in time.
    pub unknown_sent: u64,
    /// Verdicts and heartbeats sent.
    pub messages_sent: u64,
    /// Link failures (open or write).
    pub link_failures: u64,
    /// Verdicts not sent (link down, or the link queue full).
    pub link_dropped: u64,
    /// Frame arrival to verdict bytes written on the link, over the whole run.
    pub latency: Percentiles,
}

/// Counters shared by the three threads.
#[derive(Debug, Default)]
struct Counters {
    frames_in: AtomicU64,
    dropped: AtomicU64,
    rejected: AtomicU64,
    camera_timeouts: AtomicU64,
    camera_reopens: AtomicU64,
    /// Whether frames are arriving (cleared by the analysis stage on a timeout).
    flowing: AtomicBool,
}

fn bump(c: &AtomicU64) -> u64 {
    c.fetch_add(1, Ordering::Relaxed) + 1
}

fn get(c: &AtomicU64) -> u64 {
    c.load(Ordering::Relaxed)
}

/// A frame buffer from the pool and the moment its frame arrived.
struct Slot {
    frame: DepthFrame,
    arrived: Instant,
    /// The camera's tilt state, read with this frame (auto-level only, when
    /// [`crate::level::read_due`]).
    tilt: Option<rover_terrain_drivers::fakenect::TiltState>,
}

enum CameraMsg {
    Frame(Slot),
    Ended,
}

enum LinkMsg {
    Verdict {
        verdict: proto::Verdict,
        arrived: Instant,
        fresh: bool,
        queued: Duration,
        process: Duration,
    },
    Stop(proto::Verdict),
}

/// Run the service until `shutdown` receives (or is dropped), the recording ends, or
/// `options.frames` frames are analysed. Errors only if it cannot start (the camera
/// cannot be opened, the configuration cannot work); once running, failures are
/// logged, counted and survived.
pub fn run(options: Options, notifier: Notifier, shutdown: Receiver<()>) -> Result<Summary, Error> {
    let config = options.config.clone();
    let (w, h) = (config.camera.width as usize, config.camera.height as usize);
    let mut pipeline = Pipeline::new(config.clone())?;
    let counters = Arc::new(Counters::default());

    // The pool: every frame buffer the service will ever use.
    let pool_size = config.service.pool_frames as usize;
    let (free_tx, free_rx) = bounded::<Slot>(pool_size);
    for _ in 0..pool_size {
        let _ = free_tx.send(Slot {
            frame: DepthFrame::with_capacity(w, h),
            arrived: Instant::now(),
            tilt: None,
        });
    }
    let (ready_tx, ready_rx) = bounded::<CameraMsg>(1);
    let (stop_tx, stop_rx) = bounded::<()>(0);
    let (opened_tx, opened_rx) = bounded::<Result<String, DriverError>>(1);

    let camera = CameraThread {
        spec: options.camera.clone(),
        camera_options: config.camera_options(),
        faults: options.faults.clone(),
        looping: config.service.loop_replay,
        auto_level: config.mount.auto_level,
        size: (w, h),
        counters: Arc::clone(&counters),
        free_tx: free_tx.clone(),
        free_rx,
        ready_tx,
        ready_rx: ready_rx.clone(),
        stop_rx,
    };
    let camera_handle = thread::Builder::new()
        .name("camera".into())
        .spawn(move || camera.run(opened_tx))
        .map_err(|e| Error::Setup(format!("cannot start the camera thread: {e}")))?;
    let described = match opened_rx.recv() {
        Ok(Ok(d)) => d,
        Ok(Err(e)) => {
            let _ = camera_handle.join();
            return Err(Error::Driver(e));
        }
        Err(_) => {
            let _ = camera_handle.join();
            return Err(Error::Setup("the camera thread ended while opening".into()));
        }
    };
    log::info!(
        "camera {described} open; link {}; {}x{} frames, pool of {pool_size}",
        options.link,
        w,
        h
    );

    let (link_tx, link_rx) = bounded::<LinkMsg>(LINK_QUEUE);
    let link = LinkThread {
        link: Resilient::new(options.link.clone(), options.baud),
        rx: link_rx,
        notifier,
        counters: Arc::clone(&counters),
        heartbeat: Duration::from_millis(config.service.heartbeat_ms),
        stats_every: Duration::from_secs(config.service.stats_interval_s),
        total: Histogram::new(),
        window: Windows::default(),
    };
    let link_handle = thread::Builder::new()
        .name("link".into())
        .spawn(move || link.run())
        .map_err(|e| Error::Setup(format!("cannot start the link thread: {e}")))?;

    // The analysis stage, on this thread.
    let timeout = Duration::from_millis(config.service.frame_timeout_ms);
    let heartbeat = Duration::from_millis(config.service.heartbeat_ms);
    let mut seq = SeqCounter::default();
    let mut analysed = 0u64;
    let mut unknown_sent = 0u64;
    let mut link_dropped = 0u64;
    let mut last_frame = Instant::now();
    let mut next_unknown = last_frame + timeout;
    let mut stalled = false;
    let mut leveler = config.mount.auto_level.then(crate::level::Leveler::new);
    let reason = loop {
        let wait = next_unknown.saturating_duration_since(Instant::now());
        select! {
            recv(ready_rx) -> msg => match msg {
                Ok(CameraMsg::Frame(slot)) => {
                    if let Some((t, l)) = slot.tilt.zip(leveler.as_mut()) {
                        // Rebuilds tables only when the attitude moved by over 0.5°.
                        crate::level::apply(l, &t, &mut pipeline);
                    }
                    let t0 = Instant::now();
                    let queued = t0 - slot.arrived;
                    let outcome = pipeline.process(&slot.frame).map(|v| wire::to_wire(v, 0.0));
                    let process = t0.elapsed();
                    let arrived = slot.arrived;
                    let frame_seq = slot.frame.seq;
                    let _ = free_tx.send(slot);
                    match outcome {
                        Ok(mut verdict) => {
                            verdict.seq = seq.fresh(frame_seq);
                            let msg = LinkMsg::Verdict { verdict, arrived, fresh: true, queued, process };
                            if link_tx.try_send(msg).is_err() {
                                link_dropped += 1;
                            }
                        }
                        Err(e) => {
                            let n = bump(&counters.rejected);
                            if n.is_power_of_two() {
                                log::warn!("frame rejected ({n} so far): {e}");
                            }
                        }
                    }
                    analysed += 1;
                    last_frame = Instant::now();
                    next_unknown = last_frame + timeout;
                    if stalled {
                        stalled = false;
                        counters.flowing.store(true, Ordering::Relaxed);
                        log::warn!("frames flowing again");
                    }
                    if options.frames.is_some_and(|n| analysed >= n) {
                        break StopReason::FrameLimit;
                    }
                }
                Ok(CameraMsg::Ended) | Err(_) => break StopReason::EndOfStream,
            },
            recv(shutdown) -> _ => break StopReason::Signal,
            default(wait) => {}
        }
        let now = Instant::now();
        if now >= next_unknown {
            if !stalled {
                stalled = true;
                counters.flowing.store(false, Ordering::Relaxed);
                log::warn!(
                    "no frame for {} ms: sending unknown verdicts",
                    timeout.as_millis()
                );
            }
            let verdict = unknown_verdict(seq.next());
            let msg = LinkMsg::Verdict {
                verdict,
                arrived: now,
                fresh: false,
                queued: Duration::ZERO,
                process: Duration::ZERO,
            };
            if link_tx.try_send(msg).is_err() {
                link_dropped += 1;
            }
            unknown_sent += 1;
            next_unknown = now + heartbeat;
        }
    };

    log::info!("stopping: {reason:?}");
    drop(stop_tx);
    let mut last = unknown_verdict(seq.next());
    last.decision = proto::Decision::Stop;
    last.hazard = None;
    let _ = link_tx.send(LinkMsg::Stop(last));
    drop(link_tx);
    let link_report = link_handle
        .join()
        .map_err(|_| Error::Setup("the link thread panicked".into()))?;
    // Unblock a camera thread waiting to hand over a frame, then wait for it.
    drop(ready_rx);
    camera_handle
        .join()
        .map_err(|_| Error::Setup("the camera thread panicked".into()))?;
    Ok(Summary {
        reason,
        frames_in: get(&counters.frames_in),
        analysed,
        dropped: get(&counters.dropped),
        rejected: get(&counters.rejected),
        camera_timeouts: get(&counters.camera_timeouts),
        camera_reopens: get(&counters.camera_reopens),
        unknown_sent,
        messages_sent: link_report.sent,
        link_failures: link_report.failures,
        link_dropped: link_dropped + link_report.dropped,
        latency: link_report.latency,
    })
}

/// The verdict sent when no frame came in time: unknown, nothing seen.
fn unknown_verdict(seq: u32) -> proto::Verdict {
    proto::Verdict {
        decision: proto::Decision::Unknown,
        hazard: Some((proto::HazardKind::Unknown, proto::Side::Centre)),
        workcase: 0,
        seq,
        age_10ms: 0,
        distance_cm: None,
        gradient_ddeg: None,
        alpha_ddeg: None,
        seen_permille: 0,
    }
}

/// Verdict sequence numbers: a fresh verdict carries its frame's number (so the
/// controller sees dropped frames as gaps), shifted when needed to stay strictly
/// increasing across camera reopens and the unknown verdicts in between.
#[derive(Debug, Default)]
struct SeqCounter {
    base: u64,
    last: Option<u64>,
}

impl SeqCounter {
    fn fresh(&mut self, frame_seq: u64) -> u32 {
        let mut s = frame_seq + self.base;
        if let Some(last) = self.last.filter(|&l| s <= l) {
            self.base += last + 1 - s;
            s = last + 1;
        }
        self.last = Some(s);
        s as u32
    }

    fn next(&mut self) -> u32 {
        let s = self.last.map_or(0, |l| l + 1);
        self.last = Some(s);
        s as u32
    }
}

/// The camera thread: opens the camera (reporting the outcome), then fills pool
/// buffers and hands them to analysis, newest first.
struct CameraThread {
    spec: CameraSpec,
    camera_options: CameraOptions,
    faults: Faults,
    looping: bool,
    auto_level: bool,
    size: (usize, usize),
    counters: Arc<Counters>,
    free_tx: Sender<Slot>,
    free_rx: Receiver<Slot>,
    ready_tx: Sender<CameraMsg>,
    ready_rx: Receiver<CameraMsg>,
    stop_rx: Receiver<()>,
}

impl CameraThread {
    fn open(&self) -> Result<Box<dyn DepthCamera>, DriverError> {
        let mut camera: Box<dyn DepthCamera> = match &self.spec {
            // A recording replays at its recorded pace, from memory when it fits.
            CameraSpec::Fake(path) => Box::new(
                FakeCamera::open(path)?
                    .pace(Pace::Recorded)
                    .looping(self.looping)
                    .faults(self.faults.clone())
                    .preload(PRELOAD_BUDGET),
            ),
            spec => rover_terrain_drivers::open_with(spec, &self.camera_options)?,
        };
        camera.start()?;
        Ok(camera)
    }

    /// Whether the service is stopping (the sender is dropped); waits up to `d`.
    fn stopping(&self, d: Duration) -> bool {
        match self.stop_rx.recv_timeout(d) {
            Ok(()) => false,
            Err(e) => e.is_disconnected(),
        }
    }

    fn run(self, opened: Sender<Result<String, DriverError>>) {
        let mut camera = match self.open() {
            Ok(c) => {
                let _ = opened.send(Ok(c.describe()));
                c
            }
            Err(e) => {
                let _ = opened.send(Err(e));
                return;
            }
        };
        self.counters.flowing.store(true, Ordering::Relaxed);
        let (w, h) = self.size;
        loop {
            if matches!(self.stop_rx.try_recv(), Err(TryRecvError::Disconnected)) {
                break;
            }
            let mut slot = select! {
                recv(self.free_rx) -> s => match s { Ok(s) => s, Err(_) => break },
                recv(self.stop_rx) -> _ => break,
            };
            let result = camera.next_frame(&mut slot.frame);
            slot.arrived = Instant::now();
            let due = crate::level::read_due(get(&self.counters.frames_in));
            slot.tilt = if self.auto_level && due && result.is_ok() {
                camera.tilt_state()
            } else {
                None
            };
            match result {
                Ok(FrameStatus::Frame) => {
                    bump(&self.counters.frames_in);
                    if slot.frame.width() != w || slot.frame.height() != h {
                        let n = bump(&self.counters.rejected);
                        if n.is_power_of_two() {
                            log::warn!(
                                "{}: frame of {}x{} rejected, expected {w}x{h} ({n} so far)",
                                camera.describe(),
                                slot.frame.width(),
                                slot.frame.height()
                            );
                        }
                        let _ = self.free_tx.send(slot);
                        continue;
                    }
                    if !self.hand_over(slot) {
                        break;
                    }
                }
                Ok(FrameStatus::EndOfStream) => {
                    let _ = self.free_tx.send(slot);
                    let _ = self.ready_tx.send(CameraMsg::Ended);
                    break;
                }
                Err(DriverError::Timeout { .. }) => {
                    bump(&self.counters.camera_timeouts);
                    let _ = self.free_tx.send(slot);
                }
                Err(e @ DriverError::Malformed { .. }) => {
                    let n = bump(&self.counters.rejected);
                    if n.is_power_of_two() {
                        log::warn!("frame rejected ({n} so far): {e}");
                    }
                    let _ = self.free_tx.send(slot);
                }
                Err(e) => {
                    let _ = self.free_tx.send(slot);
                    log::error!("{}: {e}; reopening", camera.describe());
                    let _ = camera.stop();
                    match self.reopen() {
                        Some(c) => camera = c,
                        None => break,
                    }
                }
            }
        }
        let _ = camera.stop();
    }

    /// Give a frame to analysis; if an older one is still waiting, it is dropped
    /// (back to the pool, counted) and the new one takes its place.
    fn hand_over(&self, slot: Slot) -> bool {
        use crossbeam_channel::TrySendError;
        match self.ready_tx.try_send(CameraMsg::Frame(slot)) {
            Ok(()) => true,
            Err(TrySendError::Full(msg)) => {
                if let Ok(CameraMsg::Frame(old)) = self.ready_rx.try_recv() {
                    bump(&self.counters.dropped);
                    let _ = self.free_tx.send(old);
                }
                // Only this thread sends: there is room now.
                self.ready_tx.send(msg).is_ok()
            }
            Err(TrySendError::Disconnected(_)) => false,
        }
    }

    /// Reopen the camera with backoff until it opens or the service stops.
    fn reopen(&self) -> Option<Box<dyn DepthCamera>> {
        let mut backoff = CAMERA_BACKOFF_MIN;
        loop {
            if self.stopping(backoff) {
                return None;
            }
            match self.open() {
                Ok(c) => {
                    bump(&self.counters.camera_reopens);
                    log::warn!("{}: reopened", c.describe());
                    return Some(c);
                }
                Err(e) => {
                    backoff = (backoff * 2).min(CAMERA_BACKOFF_MAX);
                    log::error!("camera: {e}; retrying in {backoff:?}");
                }
            }
        }
    }
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

struct LinkReport {
    sent: u64,
    failures: u64,
    dropped: u64,
    latency: Percentiles,
}

/// The link thread: sends verdicts and heartbeats, talks to systemd, logs metrics.
struct LinkThread {
    link: Resilient,
    rx: Receiver<LinkMsg>,
    notifier: Notifier,
    counters: Arc<Counters>,
    heartbeat: Duration,
    stats_every: Duration,
    total: Histogram,
    window: Windows,
}

impl LinkThread {
    fn run(mut self) -> LinkReport {
        let start = Instant::now();
        let mut sent = 0u64;
        let mut ready = false;
        let ping_every = self.notifier.watchdog().map(|w| w / 4);
        let mut last_ping: Option<Instant> = None;
        let mut next_heartbeat = start + self.heartbeat;
        let mut next_stats = start + self.stats_every;
        let mut heartbeat_seq = 0u8;
        let mut fresh_in_window = 0u64;
        self.window.since = Some(start);
        loop {
            let deadline = next_heartbeat.min(next_stats);
            match self.rx.recv_deadline(deadline) {
                Ok(LinkMsg::Verdict {
                    mut verdict,
                    arrived,
                    fresh,
                    queued,
                    process,
                }) => {
                    let t0 = Instant::now();
                    verdict.age_10ms = ((t0 - arrived).as_millis() / 10).min(255) as u8;
                    let ok = self.link.send_verdict(&verdict) && self.link.flush();
                    let done = Instant::now();
                    if ok {
                        sent += 1;
                    }
                    if ok && fresh {
                        fresh_in_window += 1;
                        let total = done - arrived;
                        self.total.record(total);
                        self.window.total.record(total);
                        self.window.queued.record(queued);
                        self.window.process.record(process);
                        self.window.link.record(done - t0);
                        if !ready {
                            ready = true;
                            self.notifier.notify(b"READY=1\nSTATUS=running");
                            log::info!("first verdict sent: ready");
                        }
                        if let Some(every) = ping_every {
                            if last_ping.is_none_or(|t| done - t >= every) {
                                self.notifier.notify(b"WATCHDOG=1");
                                last_ping = Some(done);
                            }
                        }
                    }
                }
                Ok(LinkMsg::Stop(verdict)) => {
                    self.notifier.notify(b"STOPPING=1\nSTATUS=stopping");
                    let hb = self.heartbeat_msg(proto::ServiceState::Stopping, heartbeat_seq, 0);
                    if self.link.send_verdict(&verdict) {
                        sent += 1;
                    }
                    if self.link.send_heartbeat(&hb) {
                        sent += 1;
                    }
                    self.link.flush();
                    break;
                }
                Err(crossbeam_channel::RecvTimeoutError::Timeout) => {}
                Err(crossbeam_channel::RecvTimeoutError::Disconnected) => {
                    self.notifier.notify(b"STOPPING=1");
                    break;
                }
            }
            let now = Instant::now();
            if now >= next_stats {
                let secs = self
                    .window
                    .since
                    .map_or(1.0, |s| (now - s).as_secs_f64().max(1e-3));
                self.report(fresh_in_window as f64 / secs);
                fresh_in_window = 0;
                self.window.since = Some(now);
                next_stats = now + self.stats_every;
            }
            if now >= next_heartbeat {
                let state = if self.counters.flowing.load(Ordering::Relaxed) {
                    proto::ServiceState::Running
                } else {
                    proto::ServiceState::Degraded
                };
                let secs = self
                    .window
                    .since
                    .map_or(1.0, |s| (now - s).as_secs_f64().max(1e-3));
                let rate_chz = (fresh_in_window as f64 / secs * 100.0).round() as u16;
                let hb = self.heartbeat_msg(state, heartbeat_seq, rate_chz);
                if self.link.send_heartbeat(&hb) && self.link.flush() {
                    sent += 1;
                }
                heartbeat_seq = heartbeat_seq.wrapping_add(1);
                next_heartbeat = now + self.heartbeat;
            }
        }
        LinkReport {
            sent,
            failures: self.link.failures(),
            dropped: self.link.dropped(),
            latency: self.total.percentiles(),
        }
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
             dropped {} rejected {} camera timeouts {} reopens {}; link failures {} unsent {}",
            get(&c.dropped),
            get(&c.rejected),
            get(&c.camera_timeouts),
            get(&c.camera_reopens),
            self.link.failures(),
            self.link.dropped()
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sequence_numbers_follow_frames_and_never_go_back() {
        let mut s = SeqCounter::default();
        assert_eq!(s.fresh(0), 0);
        assert_eq!(s.fresh(1), 1);
        assert_eq!(s.fresh(3), 3, "a dropped frame shows as a gap");
        assert_eq!(s.next(), 4, "unknown verdicts continue the count");
        assert_eq!(s.next(), 5);
        assert_eq!(s.fresh(4), 6, "shifted past the unknown verdicts");
        assert_eq!(s.fresh(5), 7);
        assert_eq!(s.fresh(0), 8, "a reopened camera counts from 0 again");
        assert_eq!(s.fresh(1), 9);
    }
}
