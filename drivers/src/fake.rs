use std::path::{Path, PathBuf};

use crate::fakenect::Session;
use crate::image::{read_depth_image, ImageKind};
use crate::{DepthCamera, DepthFrame, DriverError, FrameStatus};

/// Frame period assumed for plain image sequences, seconds (a Kinect's 30 Hz).
pub const IMAGE_SEQUENCE_PERIOD_S: f64 = 1.0 / 30.0;

/// How fast the fake camera delivers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Pace {
    /// Each frame as soon as it is asked for (tests, analysis, bench).
    #[default]
    AsFastAsPossible,
    /// At the recorded timing: a session's arrival times, 30 Hz for images.
    Recorded,
}

/// Faults the fake camera injects, by frame number (0-based, counting every call that
/// would deliver a frame), for testing what sits behind the camera.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Faults {
    /// From this frame on, `count` calls in a row time out (a stalled camera), then
    /// frames flow again.
    pub stall: Option<(u64, u64)>,
    /// From this frame on, the camera is gone: every call is `Disconnected`.
    pub disconnect_at: Option<u64>,
    /// This frame arrives corrupt: the call returns a `Malformed` error and the
    /// stream goes on.
    pub corrupt_at: Option<u64>,
}

#[derive(Debug)]
enum Source {
    Images(Vec<PathBuf>),
    Session(Session),
    Bag(Box<crate::ros2::Bag>),
}

/// The file-backed camera: replays one depth image, a directory of images (in name
/// order), or a libfreenect `fakenect` session, as fast as it is asked.
///
/// Deterministic: the same input gives the same frames, sequence numbers and
/// timestamps every time.
#[derive(Debug)]
pub struct FakeCamera {
    source: Source,
    label: String,
    next: usize,
    seq: u64,
    looping: bool,
    scratch: Vec<u8>,
    last: Option<usize>,
    pace: Pace,
    faults: Faults,
    calls: u64,
    stalled: u64,
    started: Option<(std::time::Instant, f64)>,
    cache: Option<Vec<Cached>>,
    /// Each frame's recorded odometry (`odometry.txt` beside the frames).
    odometry: Vec<Option<[u8; 8]>>,
}

/// A frame decoded ahead of time by [`FakeCamera::preload`]: its pixels, or what was
/// wrong with its file.
#[derive(Debug)]
enum Cached {
    Frame(DepthFrame),
    Bad(String),
}

impl FakeCamera {
    /// Open `path`: a `.pgm`/`.png` file, a directory of them, or a fakenect session
    /// directory (one with `INDEX.txt`). Every frame file is checked to exist now;
    /// frame contents are checked as each frame is read.
    pub fn open(path: &Path) -> Result<Self, DriverError> {
        let source = if path.is_file() {
            if ImageKind::of(path).is_none() {
                return Err(DriverError::Malformed {
                    path: path.to_path_buf(),
                    what: "unknown image type (expected .pgm or .png)".into(),
                });
            }
            Source::Images(vec![path.to_path_buf()])
        } else if path.is_dir() {
            if Session::is_session(path) {
                Source::Session(Session::open(path)?)
            } else {
                let entries = std::fs::read_dir(path).map_err(|e| DriverError::Io {
                    path: path.to_path_buf(),
                    source: e,
                })?;
                let mut images = Vec::new();
                for entry in entries {
                    let entry = entry.map_err(|e| DriverError::Io {
                        path: path.to_path_buf(),
                        source: e,
                    })?;
                    let p = entry.path();
                    if p.is_file() && ImageKind::of(&p).is_some() {
                        images.push(p);
                    }
                }
                if images.is_empty() {
                    return Err(DriverError::Empty {
                        path: path.to_path_buf(),
                    });
                }
                images.sort();
                Source::Images(images)
            }
        } else {
            return Err(DriverError::NotFound {
                path: path.to_path_buf(),
            });
        };
        let odometry = if path.is_dir() {
            let recorded = crate::odometry_file::read(path)?;
            let name = |p: &Path| p.file_name().map(|n| n.to_string_lossy().into_owned());
            let files: Vec<Option<String>> = match &source {
                Source::Images(v) => v.iter().map(|p| name(p)).collect(),
                Source::Session(s) => s.depth_entries().iter().map(|e| name(&e.path)).collect(),
                Source::Bag(_) => Vec::new(),
            };
            files
                .iter()
                .map(|f| f.as_ref().and_then(|f| recorded.get(f).copied()))
                .collect()
        } else {
            Vec::new()
        };
        Ok(Self::replaying(
            source,
            format!("fake:{}", path.display()),
            odometry,
        ))
    }

    /// A camera at the start of `source`, as fast as asked, no faults.
    fn replaying(source: Source, label: String, odometry: Vec<Option<[u8; 8]>>) -> Self {
        FakeCamera {
            source,
            label,
            next: 0,
            seq: 0,
            looping: false,
            scratch: Vec::new(),
            last: None,
            pace: Pace::AsFastAsPossible,
            faults: Faults::default(),
            calls: 0,
            stalled: 0,
            started: None,
            cache: None,
            odometry,
        }
    }

    /// Open a ROS 2 bag's depth topic (see [`crate::ros2::Bag::open`]): replayed like
    /// any recording, paced by its messages' log times.
    pub fn open_bag(path: &Path, topic: Option<&str>) -> Result<Self, DriverError> {
        let bag = crate::ros2::Bag::open(path, topic)?;
        let label = format!("mcap:{}#{}", path.display(), bag.topic());
        Ok(Self::replaying(
            Source::Bag(Box::new(bag)),
            label,
            Vec::new(),
        ))
    }

    /// Decode every frame now and replay from memory, so that delivering a frame is a
    /// copy (no file reads, no decoder allocations: the service's zero-allocation
    /// hot path). Only if one pass fits in `max_bytes` of pixels; otherwise the camera
    /// stays file-backed. A frame that cannot be decoded is remembered as such and
    /// delivered as a `Malformed` error each time its turn comes.
    pub fn preload(mut self, max_bytes: usize) -> Self {
        let mut cache = Vec::with_capacity(self.len());
        let mut bytes = 0usize;
        let mut scratch = Vec::new();
        for i in 0..self.len() {
            let mut frame = DepthFrame::default();
            let read = match &mut self.source {
                Source::Images(v) => read_depth_image(&v[i], &mut scratch, &mut frame),
                Source::Session(s) => s.read_depth(i, &mut scratch, &mut frame),
                Source::Bag(b) => b.read(i, &mut frame),
            };
            cache.push(match read {
                Ok(()) => {
                    bytes += frame.pixels().len() * 2;
                    Cached::Frame(frame)
                }
                Err(e) => Cached::Bad(e.to_string()),
            });
            if bytes > max_bytes {
                return self;
            }
        }
        self.cache = Some(cache);
        self
    }

    /// Whether frames are replayed from memory (see [`FakeCamera::preload`]).
    pub fn is_preloaded(&self) -> bool {
        self.cache.is_some()
    }

    /// Deliver at this pace.
    pub fn pace(mut self, pace: Pace) -> Self {
        self.pace = pace;
        self
    }

    /// Inject these faults.
    pub fn faults(mut self, faults: Faults) -> Self {
        self.faults = faults;
        self
    }

    /// The recorded time of frame `i`, seconds.
    fn recorded_time(&self, i: usize) -> f64 {
        match &self.source {
            Source::Images(_) => self.seq as f64 * IMAGE_SEQUENCE_PERIOD_S,
            Source::Session(s) => s.depth_entries()[i].time_s,
            Source::Bag(b) => b.time_s(i),
        }
    }

    /// Sleep until frame `i` is due at the recorded pace (a session's first frame, or
    /// the first after a loop, is due at once).
    fn wait_for(&mut self, i: usize) {
        if self.pace != Pace::Recorded {
            return;
        }
        let t = self.recorded_time(i);
        let (t0, r0) = match self.started {
            Some((t0, r0)) if t >= r0 => (t0, r0),
            _ => {
                self.started = Some((std::time::Instant::now(), t));
                return;
            }
        };
        let due = t0 + std::time::Duration::from_secs_f64(t - r0);
        let now = std::time::Instant::now();
        if due > now {
            std::thread::sleep(due - now);
        }
    }

    /// Start again from the first frame after the last one, instead of ending.
    pub fn looping(mut self, looping: bool) -> Self {
        self.looping = looping;
        self
    }

    /// Number of depth frames in one pass.
    pub fn len(&self) -> usize {
        match &self.source {
            Source::Images(v) => v.len(),
            Source::Session(s) => s.depth_entries().len(),
            Source::Bag(b) => b.len(),
        }
    }

    /// Whether there are no frames (never true for an opened camera).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The file of the frame last delivered (a bag's frames: none, they share one).
    pub fn last_path(&self) -> Option<&Path> {
        let i = self.last?;
        match &self.source {
            Source::Images(v) => Some(&v[i]),
            Source::Session(s) => Some(&s.depth_entries()[i].path),
            Source::Bag(_) => None,
        }
    }
}

impl DepthCamera for FakeCamera {
    fn start(&mut self) -> Result<(), DriverError> {
        Ok(())
    }

    fn stop(&mut self) -> Result<(), DriverError> {
        Ok(())
    }

    fn next_frame(&mut self, frame: &mut DepthFrame) -> Result<FrameStatus, DriverError> {
        let call = self.calls;
        if self.faults.disconnect_at.is_some_and(|at| call >= at) {
            return Err(DriverError::Disconnected(format!(
                "{}: injected disconnect",
                self.label
            )));
        }
        if let Some((at, count)) = self.faults.stall {
            if call >= at && self.stalled < count {
                self.stalled += 1;
                // At the recorded pace a stalled camera takes its frame period to
                // give up, as a live one would; the replay clock restarts after.
                let period_ms = if self.pace == Pace::Recorded {
                    self.started = None;
                    std::thread::sleep(std::time::Duration::from_secs_f64(IMAGE_SEQUENCE_PERIOD_S));
                    (IMAGE_SEQUENCE_PERIOD_S * 1e3).round() as u64
                } else {
                    0
                };
                return Err(DriverError::Timeout {
                    camera: self.label.clone(),
                    timeout_ms: period_ms,
                });
            }
        }
        self.calls += 1;
        if self.faults.corrupt_at == Some(call) {
            return Err(DriverError::Malformed {
                path: self.label.clone().into(),
                what: format!("injected corrupt frame {call}"),
            });
        }
        if self.next >= self.len() {
            if !self.looping {
                return Ok(FrameStatus::EndOfStream);
            }
            self.next = 0;
        }
        let i = self.next;
        self.next += 1;
        self.last = Some(i);
        self.wait_for(i);
        frame.odometry = self.odometry.get(i).copied().flatten();
        if let Some(cache) = &self.cache {
            match &cache[i] {
                Cached::Frame(f) => {
                    frame
                        .reshape(f.width(), f.height())
                        .copy_from_slice(f.pixels());
                    frame.timestamp_s = match &self.source {
                        Source::Images(_) => self.seq as f64 * IMAGE_SEQUENCE_PERIOD_S,
                        Source::Session(_) | Source::Bag(_) => f.timestamp_s,
                    };
                }
                Cached::Bad(what) => {
                    return Err(DriverError::Malformed {
                        path: self.label.clone().into(),
                        what: what.clone(),
                    })
                }
            }
            frame.seq = self.seq;
            self.seq += 1;
            return Ok(FrameStatus::Frame);
        }
        match &mut self.source {
            Source::Images(v) => {
                read_depth_image(&v[i], &mut self.scratch, frame)?;
                frame.timestamp_s = self.seq as f64 * IMAGE_SEQUENCE_PERIOD_S;
            }
            Source::Session(s) => s.read_depth(i, &mut self.scratch, frame)?,
            Source::Bag(b) => b.read(i, frame)?,
        }
        frame.seq = self.seq;
        self.seq += 1;
        Ok(FrameStatus::Frame)
    }

    fn describe(&self) -> String {
        self.label.clone()
    }

    fn last_source(&self) -> Option<&Path> {
        self.last_path()
    }

    fn next_colour(&mut self, frame: &mut crate::ColourFrame) -> Result<bool, DriverError> {
        let (Source::Session(s), Some(i)) = (&self.source, self.last) else {
            return Ok(false);
        };
        match s.colour_at(s.depth_entries()[i].time_s) {
            Some(entry) => {
                s.read_colour(entry, &mut self.scratch, frame)?;
                frame.seq = self.seq.saturating_sub(1);
                Ok(true)
            }
            None => Ok(false),
        }
    }

    fn tilt_state(&mut self) -> Option<crate::fakenect::TiltState> {
        match &self.source {
            Source::Session(s) => {
                let i = self.last?;
                s.tilt_at(s.depth_entries()[i].time_s).copied()
            }
            Source::Images(_) | Source::Bag(_) => None,
        }
    }

    fn intrinsics(&self) -> Option<crate::Intrinsics> {
        match &self.source {
            Source::Bag(b) => Some(b.intrinsics()),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fakenect::{Registration, SessionWriter};
    use crate::image::encode_png_depth;

    #[test]
    fn image_directory_in_name_order_then_end() {
        let dir = tempfile::tempdir().unwrap();
        for (name, v) in [("b.png", 2u16), ("a.png", 1), ("c.txt", 9)] {
            let f = DepthFrame::from_pixels(2, 1, vec![v, v]);
            std::fs::write(dir.path().join(name), encode_png_depth(&f)).unwrap();
        }
        let mut cam = FakeCamera::open(dir.path()).unwrap();
        assert_eq!(cam.len(), 2);
        let mut f = DepthFrame::with_capacity(2, 1);
        assert_eq!(cam.next_frame(&mut f).unwrap(), FrameStatus::Frame);
        assert_eq!((f.pixels()[0], f.seq), (1, 0));
        assert_eq!(cam.next_frame(&mut f).unwrap(), FrameStatus::Frame);
        assert_eq!((f.pixels()[0], f.seq), (2, 1));
        assert_eq!(cam.next_frame(&mut f).unwrap(), FrameStatus::EndOfStream);
    }

    #[test]
    fn looping_restarts_and_keeps_counting() {
        let dir = tempfile::tempdir().unwrap();
        let f = DepthFrame::from_pixels(1, 1, vec![5]);
        std::fs::write(dir.path().join("a.png"), encode_png_depth(&f)).unwrap();
        let mut cam = FakeCamera::open(&dir.path().join("a.png"))
            .unwrap()
            .looping(true);
        let mut f = DepthFrame::default();
        for seq in 0..3 {
            assert_eq!(cam.next_frame(&mut f).unwrap(), FrameStatus::Frame);
            assert_eq!(f.seq, seq);
        }
    }

    #[test]
    fn injected_faults_come_when_asked_and_the_stream_goes_on() {
        let dir = tempfile::tempdir().unwrap();
        let f = DepthFrame::from_pixels(1, 1, vec![5]);
        std::fs::write(dir.path().join("a.png"), encode_png_depth(&f)).unwrap();
        let faults = Faults {
            stall: Some((1, 2)),
            corrupt_at: Some(2),
            disconnect_at: Some(4),
        };
        let mut cam = FakeCamera::open(&dir.path().join("a.png"))
            .unwrap()
            .looping(true)
            .faults(faults);
        let mut f = DepthFrame::default();
        let mut outcome = Vec::new();
        for _ in 0..8 {
            outcome.push(match cam.next_frame(&mut f) {
                Ok(FrameStatus::Frame) => "frame",
                Ok(FrameStatus::EndOfStream) => "end",
                Err(DriverError::Timeout { .. }) => "timeout",
                Err(DriverError::Malformed { .. }) => "corrupt",
                Err(DriverError::Disconnected(_)) => "gone",
                Err(_) => "other",
            });
        }
        assert_eq!(
            outcome,
            ["frame", "timeout", "timeout", "frame", "corrupt", "frame", "gone", "gone"]
        );
    }

    #[test]
    fn preloaded_replay_gives_the_same_frames_and_remembers_bad_files() {
        let dir = tempfile::tempdir().unwrap();
        for (name, v) in [("a.png", 1u16), ("b.png", 2)] {
            let f = DepthFrame::from_pixels(2, 1, vec![v, v + 10]);
            std::fs::write(dir.path().join(name), encode_png_depth(&f)).unwrap();
        }
        std::fs::write(dir.path().join("c.png"), b"not a png").unwrap();
        let mut disk = FakeCamera::open(dir.path()).unwrap();
        let mut memory = FakeCamera::open(dir.path()).unwrap().preload(1 << 20);
        assert!(memory.is_preloaded() && !disk.is_preloaded());
        let (mut a, mut b) = (DepthFrame::default(), DepthFrame::default());
        for _ in 0..2 {
            assert_eq!(disk.next_frame(&mut a).unwrap(), FrameStatus::Frame);
            assert_eq!(memory.next_frame(&mut b).unwrap(), FrameStatus::Frame);
            assert_eq!(
                (a.pixels(), a.seq, a.timestamp_s),
                (b.pixels(), b.seq, b.timestamp_s)
            );
        }
        assert!(matches!(
            disk.next_frame(&mut a),
            Err(DriverError::Malformed { .. })
        ));
        let e = memory.next_frame(&mut b).unwrap_err();
        assert!(matches!(e, DriverError::Malformed { .. }), "{e}");
        assert_eq!(memory.next_frame(&mut b).unwrap(), FrameStatus::EndOfStream);
        // Too big for the budget: stays on disk.
        assert!(!FakeCamera::open(dir.path())
            .unwrap()
            .preload(2)
            .is_preloaded());
    }

    #[test]
    fn recorded_pace_follows_the_session_times() {
        let dir = tempfile::tempdir().unwrap();
        let mut w = SessionWriter::create(dir.path(), None).unwrap();
        let frame = DepthFrame::from_pixels(2, 1, vec![1000, 1000]);
        for k in 0..3 {
            w.write_depth(&frame, 50.0 + 0.05 * f64::from(k), k)
                .unwrap();
        }
        let mut cam = FakeCamera::open(dir.path()).unwrap().pace(Pace::Recorded);
        let mut f = DepthFrame::default();
        let t = std::time::Instant::now();
        for _ in 0..3 {
            cam.next_frame(&mut f).unwrap();
        }
        // Three frames 50 ms apart take at least 100 ms to replay at their pace (a
        // lower bound on what the camera did, not a timing of our code).
        assert!(t.elapsed() >= std::time::Duration::from_millis(100));
        assert_eq!(f.timestamp_s, 50.1);
    }

    #[test]
    fn empty_missing_and_unknown_inputs_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let e = FakeCamera::open(dir.path()).unwrap_err();
        assert!(matches!(e, DriverError::Empty { .. }), "{e}");
        let e = FakeCamera::open(&dir.path().join("nope")).unwrap_err();
        assert!(matches!(e, DriverError::NotFound { .. }), "{e}");
        std::fs::write(dir.path().join("x.jpg"), b"jpeg").unwrap();
        let e = FakeCamera::open(&dir.path().join("x.jpg")).unwrap_err();
        assert!(e.to_string().contains("x.jpg"), "{e}");
    }

    #[test]
    fn session_replays_in_millimetres_with_recorded_times() {
        let dir = tempfile::tempdir().unwrap();
        let reg = Registration::LIBFREENECT_DEFAULT;
        let mut w = SessionWriter::create(dir.path(), Some(reg)).unwrap();
        let mut frame =
            DepthFrame::from_pixels(4, 2, vec![0, 800, 1000, 1500, 2000, 2500, 3000, 0]);
        w.write_depth(&frame, 100.5, 7).unwrap();
        frame.pixels_mut()[0] = 900;
        w.write_depth(&frame, 100.6, 8).unwrap();

        let mut cam = FakeCamera::open(dir.path()).unwrap();
        assert_eq!(cam.len(), 2);
        let mut f = DepthFrame::default();
        cam.next_frame(&mut f).unwrap();
        assert_eq!(f.timestamp_s, 100.5);
        assert_eq!(f.pixels()[0], 0, "no data stays no data");
        for (got, want) in f.pixels().iter().zip(frame.pixels()).skip(1) {
            if *want == 0 {
                assert_eq!(*got, 0);
            } else {
                // Within one disparity step of the Kinect at that range.
                let step = 1.0e-5 * f64::from(*want).powi(2) + 3.0;
                assert!(
                    (f64::from(*got) - f64::from(*want)).abs() <= step,
                    "{got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn session_with_missing_file_names_it() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("INDEX.txt"), "d-1.000000-1.pgm\n").unwrap();
        let e = FakeCamera::open(dir.path()).unwrap_err().to_string();
        assert!(
            e.contains("d-1.000000-1.pgm") && e.contains("INDEX.txt"),
            "{e}"
        );
    }

    #[test]
    fn session_with_bad_index_line_or_truncated_frame() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("INDEX.txt"), "garbage line\n").unwrap();
        let e = FakeCamera::open(dir.path()).unwrap_err().to_string();
        assert!(e.contains("line 1"), "{e}");

        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("INDEX.txt"), "d-1.0-1.pgm\n").unwrap();
        std::fs::write(
            dir.path().join("d-1.0-1.pgm"),
            b"P5 640 480 65535\n\x01\x02",
        )
        .unwrap();
        let mut cam = FakeCamera::open(dir.path()).unwrap();
        let e = cam
            .next_frame(&mut DepthFrame::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("d-1.0-1.pgm") && e.contains("truncated"), "{e}");
    }

    #[test]
    fn session_with_only_colour_frames_is_empty() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("INDEX.txt"), "r-1.0-1.ppm\n").unwrap();
        std::fs::write(dir.path().join("r-1.0-1.ppm"), b"P6 1 1 255\n\0\0\0").unwrap();
        let e = FakeCamera::open(dir.path()).unwrap_err();
        assert!(matches!(e, DriverError::Empty { .. }), "{e}");
    }
}
