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
//!   a link that fails is reopened with backoff
//!   ([`Resilient`](crate::link::Resilient)) while frames keep being analysed. On
//!   shutdown a final stop verdict is sent and flushed.

mod analysis;
mod camera;
mod histogram;
mod link;
pub mod notify;
mod viewer;

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;

use crossbeam_channel::Receiver;
use rover_terrain_drivers::{CameraSpec, Faults};

pub use histogram::{Histogram, Percentiles};
pub use notify::Notifier;

use crate::coverage::Coverage;
use crate::link::LinkTarget;
use crate::{Config, Error, Pipeline};

/// A replayed recording is decoded into memory when one pass fits in this, bytes.
pub const PRELOAD_BUDGET: usize = 48 << 20;
/// First wait before reopening a camera that vanished.
pub const CAMERA_BACKOFF_MIN: Duration = Duration::from_millis(100);
/// Longest wait between camera reopen attempts.
pub const CAMERA_BACKOFF_MAX: Duration = Duration::from_secs(5);

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
    /// Also write what the analysis saw into this MCAP file (a viewer thread, off
    /// the hot path; pictures it cannot keep up with are dropped, never verdicts).
    pub mcap: Option<std::path::PathBuf>,
    /// Also serve it live over the Foxglove WebSocket protocol on `HOST:PORT`
    /// (feature `foxglove-live`; the same viewer thread).
    pub foxglove: Option<String>,
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
            mcap: None,
            foxglove: None,
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
    /// Frames the viewer wrote (`run --mcap`), `None` without one.
    pub viewer_written: Option<u64>,
    /// Pictures the viewer was too slow for.
    pub viewer_dropped: u64,
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
    /// Whether the last verdict was fused with the terrain memory.
    memory_fused: AtomicBool,
    /// Odometry messages received from the controller.
    odometry_in: AtomicU64,
    /// Pictures the viewer was too slow for (`run --mcap`).
    viewer_dropped: AtomicU64,
}

fn bump(c: &AtomicU64) -> u64 {
    c.fetch_add(1, Ordering::Relaxed) + 1
}

fn get(c: &AtomicU64) -> u64 {
    c.load(Ordering::Relaxed)
}

/// Logs a warning naming the corridor's strips this mount never sees an obstacle a
/// wheel radius high whole in ([`Coverage`]): the rover drives over ground there whose
/// obstacles no frame can measure. With `mount.auto_level`, for the configured pose.
fn warn_uncovered(config: &Config) {
    let coverage = Coverage::for_rover(config);
    let never = coverage.never_whole_at();
    if !never.is_empty() {
        log::warn!(
            "this mount never sees an obstacle {:.2} m high whole in the corridor's strips \
             at y = {} m: how high anything there stands is never measured \
             (`rover-terrain check-config` shows the coverage)",
            coverage.height_m,
            never
        );
    }
}

/// Run the service until `shutdown` receives (or is dropped), the recording ends, or
/// `options.frames` frames are analysed. Errors only if it cannot start (the camera
/// cannot be opened, the configuration cannot work); once running, failures are
/// logged, counted and survived.
pub fn run(options: Options, notifier: Notifier, shutdown: Receiver<()>) -> Result<Summary, Error> {
    // A source that knows its own optics (a ROS 2 bag) sizes the frames and analysis.
    let mut sized = options.config.clone();
    if let Some(k) = rover_terrain_drivers::probe_intrinsics(&options.camera)? {
        if let Some(what) = sized.apply_intrinsics(&k) {
            log::info!("{what}");
        }
    }
    let config = &sized;
    let pipeline = Pipeline::new(config.clone())?;
    warn_uncovered(config);
    let counters = Arc::new(Counters::default());
    let camera = camera::start(&options.camera, &options.faults, config, &counters)?;
    log::info!(
        "camera {} open; link {}; {}x{} frames, pool of {}",
        camera.described,
        options.link,
        config.camera.width,
        config.camera.height,
        config.service.pool_frames
    );
    let link::Started {
        link_tx,
        odometry_rx,
        handle: link_handle,
    } = link::start(&options.link, options.baud, config, notifier, &counters)?;
    let viewer = match (&options.mcap, &options.foxglove) {
        (None, None) => None,
        (path, live) => Some(viewer::Viewer::start(
            path.as_deref(),
            live.as_deref(),
            &pipeline,
            &counters,
        )?),
    };
    let mut stage = analysis::Stage::new(
        pipeline,
        config,
        options.frames,
        Arc::clone(&counters),
        (link_tx, odometry_rx),
        camera.free_tx.clone(),
    )
    .with_viewer(viewer);
    let reason = stage.run(&camera.ready_rx, &shutdown);

    log::info!("stopping: {reason:?}");
    drop(camera.stop_tx);
    let stage = stage.finish();
    let link_report = link_handle
        .join()
        .map_err(|_| Error::Setup("the link thread panicked".into()))?;
    // Unblock a camera thread waiting to hand over a frame, then wait for it.
    drop(camera.ready_rx);
    camera
        .handle
        .join()
        .map_err(|_| Error::Setup("the camera thread panicked".into()))?;
    let viewer_written = match stage.viewer {
        Some(Ok(n)) => Some(n),
        Some(Err(e)) => {
            log::error!("the viewer stopped: {e}");
            Some(0)
        }
        None => None,
    };
    Ok(Summary {
        reason,
        frames_in: get(&counters.frames_in),
        analysed: stage.analysed,
        dropped: get(&counters.dropped),
        rejected: get(&counters.rejected),
        camera_timeouts: get(&counters.camera_timeouts),
        camera_reopens: get(&counters.camera_reopens),
        unknown_sent: stage.unknown_sent,
        messages_sent: link_report.sent,
        link_failures: link_report.failures,
        link_dropped: stage.link_dropped + link_report.dropped,
        latency: link_report.latency,
        viewer_written,
        viewer_dropped: get(&counters.viewer_dropped),
    })
}
