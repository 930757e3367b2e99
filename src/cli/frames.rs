//! The frame loop every one-shot command shares: open each source, read its frames,
//! analyse them, hand each verdict on; bad frames and sources are reported and
//! skipped, never fatal.

use std::path::{Path, PathBuf};

use rover_terrain::{Config, Pipeline, Verdict};
use rover_terrain_drivers::{CameraSpec, DepthFrame, FrameStatus};

/// The cameras to read: `--camera`, or the files given, or the default.
pub fn sources(
    camera: Option<CameraSpec>,
    input: Vec<PathBuf>,
    default: Option<PathBuf>,
) -> anyhow::Result<Vec<CameraSpec>> {
    match (camera, input.is_empty()) {
        (Some(_), false) => anyhow::bail!("give either --camera or input files, not both"),
        (Some(c), true) => Ok(vec![c]),
        (None, false) => Ok(input.into_iter().map(CameraSpec::Fake).collect()),
        (None, true) => Ok(default.into_iter().map(CameraSpec::Fake).collect()),
    }
}

/// One analysed frame, as [`for_each_verdict`] hands it over.
pub struct Analysed<'a> {
    /// The verdict.
    pub verdict: &'a Verdict,
    /// The file the frame came from, for file sources.
    pub source: Option<&'a Path>,
    /// When the frame was read.
    pub captured: std::time::Instant,
    /// The frame.
    pub frame: &'a DepthFrame,
    /// The pipeline that analysed it (its grid and analysis state).
    pub pipeline: &'a Pipeline,
}

impl Analysed<'_> {
    /// The verdict as `analyze` prints it: every field, and the frame's file.
    pub fn json(&self) -> serde_json::Value {
        let mut json = self.verdict.to_json();
        if let Some(p) = self.source {
            json["source"] = serde_json::Value::from(p.display().to_string());
        }
        json
    }
}

/// Analyse every frame of every source (up to `limit` frames) and hand each verdict
/// (with its source file and the moment its frame was read) to `on_verdict`. A bad
/// source or frame is reported on stderr and the rest still analysed; returns whether
/// anything failed.
pub fn for_each_verdict(
    config: Config,
    sources: &[CameraSpec],
    limit: Option<u64>,
    mut on_verdict: impl FnMut(&Analysed<'_>) -> anyhow::Result<()>,
) -> anyhow::Result<bool> {
    let (w, h) = (config.camera.width as usize, config.camera.height as usize);
    let camera_options = config.camera_options();
    let mut leveler = config
        .mount
        .auto_level
        .then(rover_terrain::level::Leveler::new);
    // A recorded drive's odometry (odometry.txt beside its frames) moves the terrain
    // memory between its frames, on the recording's own clock.
    let mut tracker = config
        .memory
        .enabled
        .then(|| rover_terrain::memory::odometry::Tracker::new(&config.memory));
    let mut pipeline = Pipeline::new(config)?;
    let mut frame = DepthFrame::with_capacity(w, h);
    let mut failed = false;
    let mut index: u64 = 0;
    for spec in sources {
        let mut camera = match rover_terrain_drivers::open_with(spec, &camera_options) {
            Ok(c) => c,
            Err(e) => {
                eprintln!("rover-terrain: {e}");
                failed = true;
                continue;
            }
        };
        // A source that knows its own optics (a ROS 2 bag: image size, CameraInfo)
        // sizes the analysis to them.
        if let Some(k) = camera.intrinsics() {
            let mut sized = pipeline.config().clone();
            if let Some(what) = sized.apply_intrinsics(&k) {
                log::info!("{}: {what}", camera.describe());
                pipeline = Pipeline::new(sized)
                    .map_err(|e| anyhow::anyhow!("{}: {e}", camera.describe()))?;
            }
        }
        while limit.is_none_or(|n| index < n) {
            let captured = std::time::Instant::now();
            match camera.next_frame(&mut frame) {
                Ok(FrameStatus::Frame) => {}
                Ok(FrameStatus::EndOfStream) => break,
                Err(e @ rover_terrain_drivers::DriverError::Malformed { .. }) => {
                    eprintln!("rover-terrain: {e}");
                    failed = true;
                    continue;
                }
                Err(e) => {
                    // A camera that stopped (disconnected, timed out) ends this source.
                    eprintln!("rover-terrain: {}: {e}", camera.describe());
                    failed = true;
                    break;
                }
            }
            if let Some(l) = leveler.as_mut() {
                if rover_terrain::level::read_due(index) {
                    if let Some(t) = camera.tilt_state() {
                        rover_terrain::level::apply(l, &t, &mut pipeline);
                    }
                }
            }
            frame.seq = index;
            index += 1;
            let motion = match tracker.as_mut() {
                Some(t) => {
                    t.on_recorded(frame.odometry, frame.timestamp_s);
                    t.motion(frame.timestamp_s)
                }
                None => Err(rover_terrain::memory::odometry::Untrusted::NoOdometry),
            };
            match pipeline.process_moved(&frame, motion) {
                Ok(_) => on_verdict(&Analysed {
                    verdict: pipeline.verdict(),
                    source: camera.last_source(),
                    captured,
                    frame: &frame,
                    pipeline: &pipeline,
                })?,
                Err(e) => {
                    let name = camera
                        .last_source()
                        .map(|p| p.display().to_string())
                        .unwrap_or_else(|| camera.describe());
                    eprintln!("rover-terrain: {name}: {e}");
                    failed = true;
                }
            }
        }
    }
    Ok(failed)
}
