//! The camera thread: opens the camera (reporting the outcome), then fills pool
//! buffers and hands them to analysis, newest first; reopens a camera that vanished.

use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::thread;
use std::time::{Duration, Instant};

use crossbeam_channel::{bounded, select, Receiver, Sender, TryRecvError};
use rover_terrain_drivers::{
    CameraOptions, CameraSpec, DepthCamera, DepthFrame, DriverError, FakeCamera, Faults,
    FrameStatus, Pace,
};

use super::{bump, get, Counters, CAMERA_BACKOFF_MAX, CAMERA_BACKOFF_MIN, PRELOAD_BUDGET};
use crate::{Config, Error};

/// A frame buffer from the pool and the moment its frame arrived.
pub(super) struct Slot {
    pub frame: DepthFrame,
    pub arrived: Instant,
    /// The camera's tilt state, read with this frame (auto-level only, when
    /// [`crate::level::read_due`]).
    pub tilt: Option<rover_terrain_drivers::fakenect::TiltState>,
}

/// What the camera thread hands to analysis.
pub(super) enum CameraMsg {
    /// A frame.
    Frame(Slot),
    /// The recording ended.
    Ended,
}

/// The running camera thread and the ends of its channels the service keeps.
pub(super) struct Camera {
    /// What the camera says it is.
    pub described: String,
    /// Frames (newest wins: capacity one).
    pub ready_rx: Receiver<CameraMsg>,
    /// Where analysed frames go back to the pool.
    pub free_tx: Sender<Slot>,
    /// Dropped to stop the thread.
    pub stop_tx: Sender<()>,
    /// The thread.
    pub handle: thread::JoinHandle<()>,
}

/// Allocate the pool (every frame buffer the service will ever use), start the
/// camera thread and wait until the camera is open. Fails if it cannot be opened.
pub(super) fn start(
    spec: &CameraSpec,
    faults: &Faults,
    config: &Config,
    counters: &Arc<Counters>,
) -> Result<Camera, Error> {
    let (w, h) = (config.camera.width as usize, config.camera.height as usize);
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
    let thread = CameraThread {
        spec: spec.clone(),
        camera_options: config.camera_options(),
        faults: faults.clone(),
        looping: config.service.loop_replay,
        auto_level: config.mount.auto_level,
        size: (w, h),
        counters: Arc::clone(counters),
        free_tx: free_tx.clone(),
        free_rx,
        ready_tx,
        ready_rx: ready_rx.clone(),
        stop_rx,
    };
    let handle = thread::Builder::new()
        .name("camera".into())
        .spawn(move || thread.run(opened_tx))
        .map_err(|e| Error::Setup(format!("cannot start the camera thread: {e}")))?;
    let described = match opened_rx.recv() {
        Ok(Ok(d)) => d,
        Ok(Err(e)) => {
            let _ = handle.join();
            return Err(Error::Driver(e));
        }
        Err(_) => {
            let _ = handle.join();
            return Err(Error::Setup("the camera thread ended while opening".into()));
        }
    };
    Ok(Camera {
        described,
        ready_rx,
        free_tx,
        stop_tx,
        handle,
    })
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
        // A recording replays at its recorded pace, from memory when it fits.
        let replay = |c: FakeCamera| -> Box<dyn DepthCamera> {
            Box::new(
                c.pace(Pace::Recorded)
                    .looping(self.looping)
                    .faults(self.faults.clone())
                    .preload(PRELOAD_BUDGET),
            )
        };
        let mut camera: Box<dyn DepthCamera> = match &self.spec {
            CameraSpec::Fake(path) => replay(FakeCamera::open(path)?),
            CameraSpec::Mcap { path, topic } => {
                replay(FakeCamera::open_bag(path, topic.as_deref())?)
            }
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
