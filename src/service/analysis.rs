//! The analysis stage, on the service's own thread: analyse each frame as it comes,
//! pass its verdict to the link thread, and when frames stop coming send "unknown"
//! verdicts (the fail-safe timer) until they return.

use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crossbeam_channel::{select, Receiver, Sender};

use super::camera::{CameraMsg, Slot};
use super::link::{LinkMsg, OdometryIn};
use super::{bump, Counters, StopReason};
use crate::level::Leveler;
use crate::link::{proto, wire};
use crate::memory::odometry::{Tracker, Untrusted};
use crate::{Config, Pipeline};

/// The analysis stage and what it counts.
pub(super) struct Stage {
    pipeline: Pipeline,
    leveler: Option<Leveler>,
    seq: SeqCounter,
    counters: Arc<Counters>,
    link_tx: Sender<LinkMsg>,
    free_tx: Sender<Slot>,
    /// The controller's odometry, as the link thread reads it, and what it tells of
    /// the motion between frames (`None`: the terrain memory is off).
    odometry_rx: Receiver<OdometryIn>,
    tracker: Option<Tracker>,
    /// Why the last frame stood alone (`None`: it was fused), for logging changes.
    alone: Option<Untrusted>,
    start: Instant,
    /// No frame for this long and the fail-safe starts.
    timeout: Duration,
    /// Then an unknown verdict this often.
    heartbeat: Duration,
    frame_limit: Option<u64>,
    next_unknown: Instant,
    stalled: bool,
    analysed: u64,
    unknown_sent: u64,
    link_dropped: u64,
    /// Where pictures of the analysis go (`run --mcap`), off the hot path.
    viewer: Option<super::viewer::Viewer>,
}

/// What the stage counted over a run.
pub(super) struct Counts {
    /// Frames analysed.
    pub analysed: u64,
    /// Fail-safe unknown verdicts sent.
    pub unknown_sent: u64,
    /// Verdicts the link queue could not take.
    pub link_dropped: u64,
    /// The viewer's outcome: frames it wrote, or why it stopped.
    pub viewer: Option<Result<u64, crate::Error>>,
}

impl Stage {
    /// A stage analysing with `pipeline`, sending to `link_tx`, returning frame
    /// buffers to `free_tx`; the fail-safe timer starts now.
    pub fn new(
        pipeline: Pipeline,
        config: &Config,
        frame_limit: Option<u64>,
        counters: Arc<Counters>,
        (link_tx, odometry_rx): (Sender<LinkMsg>, Receiver<OdometryIn>),
        free_tx: Sender<Slot>,
    ) -> Self {
        let timeout = Duration::from_millis(config.service.frame_timeout_ms);
        Stage {
            pipeline,
            leveler: config.mount.auto_level.then(Leveler::new),
            seq: SeqCounter::default(),
            counters,
            link_tx,
            free_tx,
            odometry_rx,
            tracker: config.memory.enabled.then(|| Tracker::new(&config.memory)),
            alone: Some(Untrusted::NoOdometry),
            start: Instant::now(),
            timeout,
            heartbeat: Duration::from_millis(config.service.heartbeat_ms),
            frame_limit,
            next_unknown: Instant::now() + timeout,
            stalled: false,
            analysed: 0,
            unknown_sent: 0,
            link_dropped: 0,
            viewer: None,
        }
    }

    /// Also hand every analysed frame to `viewer`.
    pub fn with_viewer(mut self, viewer: Option<super::viewer::Viewer>) -> Self {
        self.viewer = viewer;
        self
    }

    /// Analyse frames from `ready` until the recording ends, the frame limit is
    /// reached or `shutdown` receives (or is dropped).
    pub fn run(&mut self, ready: &Receiver<CameraMsg>, shutdown: &Receiver<()>) -> StopReason {
        loop {
            let wait = self.next_unknown.saturating_duration_since(Instant::now());
            select! {
                recv(ready) -> msg => match msg {
                    Ok(CameraMsg::Frame(slot)) => {
                        if self.analyse(slot) {
                            break StopReason::FrameLimit;
                        }
                    }
                    Ok(CameraMsg::Ended) | Err(_) => break StopReason::EndOfStream,
                },
                recv(shutdown) -> _ => break StopReason::Signal,
                default(wait) => {}
            }
            self.fail_safe(Instant::now());
        }
    }

    /// Analyse one frame, queue its verdict, give its buffer back; restart the
    /// fail-safe timer. Returns whether the frame limit is reached.
    fn analyse(&mut self, slot: Slot) -> bool {
        if let Some((t, l)) = slot.tilt.zip(self.leveler.as_mut()) {
            // Rebuilds tables only when the attitude moved by over 0.5°.
            crate::level::apply(l, &t, &mut self.pipeline);
        }
        let t0 = Instant::now();
        let queued = t0 - slot.arrived;
        // A replayed drive carries the odometry recorded with each frame.
        if let Some(tracker) = self.tracker.as_mut() {
            let at = slot
                .arrived
                .saturating_duration_since(self.start)
                .as_secs_f64();
            tracker.on_recorded(slot.frame.odometry, at);
        }
        let motion = self.motion(t0);
        let outcome = self
            .pipeline
            .process_moved(&slot.frame, motion)
            .map(|v| wire::to_wire(v, 0.0));
        let process = t0.elapsed();
        if let (Some(v), true) = (&self.viewer, outcome.is_ok()) {
            v.offer(&slot.frame, &self.pipeline);
        }
        let arrived = slot.arrived;
        let frame_seq = slot.frame.seq;
        let _ = self.free_tx.send(slot);
        match outcome {
            Ok(mut verdict) => {
                verdict.seq = self.seq.fresh(frame_seq);
                self.send(LinkMsg::Verdict {
                    verdict,
                    arrived,
                    fresh: true,
                    queued,
                    process,
                });
            }
            Err(e) => {
                let n = bump(&self.counters.rejected);
                if n.is_power_of_two() {
                    log::warn!("frame rejected ({n} so far): {e}");
                }
            }
        }
        self.analysed += 1;
        self.next_unknown = Instant::now() + self.timeout;
        if self.stalled {
            self.stalled = false;
            self.counters.flowing.store(true, Ordering::Relaxed);
            log::warn!("frames flowing again");
        }
        self.frame_limit.is_some_and(|n| self.analysed >= n)
    }

    /// The rover's motion since the previous frame from the odometry received, for a
    /// frame analysed at `now`; says in the log and the heartbeat when the terrain
    /// memory falls back to single frames and when it is back.
    fn motion(&mut self, now: Instant) -> Result<crate::memory::Motion, Untrusted> {
        let secs = |t: Instant| t.saturating_duration_since(self.start).as_secs_f64();
        let Some(tracker) = self.tracker.as_mut() else {
            return Err(Untrusted::NoOdometry);
        };
        while let Ok((o, at)) = self.odometry_rx.try_recv() {
            tracker.on_odometry(o, secs(at));
        }
        let motion = tracker.motion(secs(now));
        let alone = motion.err();
        if alone != self.alone {
            match alone {
                None => log::info!("terrain memory: fusing frames over odometry"),
                Some(why) => log::warn!(
                    "terrain memory: single frames ({}), the map starts again",
                    why.as_str()
                ),
            }
            self.alone = alone;
        }
        self.counters
            .memory_fused
            .store(alone.is_none(), Ordering::Relaxed);
        motion
    }

    /// The fail-safe timer: no frame since the timeout and an unknown verdict goes
    /// out now, then every heartbeat period until frames return.
    fn fail_safe(&mut self, now: Instant) {
        if now < self.next_unknown {
            return;
        }
        if !self.stalled {
            self.stalled = true;
            self.counters.flowing.store(false, Ordering::Relaxed);
            log::warn!(
                "no frame for {} ms: sending unknown verdicts",
                self.timeout.as_millis()
            );
        }
        let verdict = unknown_verdict(self.seq.next());
        self.send(LinkMsg::Verdict {
            verdict,
            arrived: now,
            fresh: false,
            queued: Duration::ZERO,
            process: Duration::ZERO,
        });
        self.unknown_sent += 1;
        self.next_unknown = now + self.heartbeat;
    }

    fn send(&mut self, msg: LinkMsg) {
        if self.link_tx.try_send(msg).is_err() {
            self.link_dropped += 1;
        }
    }

    /// Queue the final stop verdict (waiting for room), close the link queue, and
    /// return what the stage counted.
    pub fn finish(mut self) -> Counts {
        let mut last = unknown_verdict(self.seq.next());
        last.decision = proto::Decision::Stop;
        last.hazard = None;
        let _ = self.link_tx.send(LinkMsg::Stop(last));
        Counts {
            analysed: self.analysed,
            unknown_sent: self.unknown_sent,
            link_dropped: self.link_dropped,
            viewer: self.viewer.take().map(super::viewer::Viewer::finish),
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn silence_sends_unknown_verdicts_at_the_timeout_then_every_heartbeat() {
        let config = Config::default();
        let (link_tx, link_rx) = crossbeam_channel::bounded(16);
        let (free_tx, _free_rx) = crossbeam_channel::bounded(1);
        let counters = Arc::new(Counters::default());
        counters.flowing.store(true, Ordering::Relaxed);
        let pipeline = Pipeline::new(config.clone()).unwrap();
        let mut stage = Stage::new(
            pipeline,
            &config,
            None,
            Arc::clone(&counters),
            (link_tx, crossbeam_channel::never()),
            free_tx,
        );
        let start = stage.next_unknown - stage.timeout;
        let (timeout, heartbeat) = (stage.timeout, stage.heartbeat);
        stage.fail_safe(start + timeout / 2);
        assert!(link_rx.try_recv().is_err(), "nothing before the timeout");
        stage.fail_safe(start + timeout);
        match link_rx.try_recv() {
            Ok(LinkMsg::Verdict { verdict, fresh, .. }) => {
                assert_eq!(verdict.decision, proto::Decision::Unknown);
                assert!(!fresh);
            }
            _ => panic!("an unknown verdict at the timeout"),
        }
        assert!(
            !counters.flowing.load(Ordering::Relaxed),
            "the heartbeat says degraded"
        );
        stage.fail_safe(start + timeout + heartbeat / 2);
        assert!(link_rx.try_recv().is_err(), "not before the next heartbeat");
        stage.fail_safe(start + timeout + heartbeat);
        assert!(link_rx.try_recv().is_ok());
        assert_eq!(stage.unknown_sent, 2);
    }

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
