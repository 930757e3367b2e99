//! The rover-terrain command line.

mod logging;
mod monitor;
mod soak;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::{Parser, Subcommand};
use rover_terrain::link::{self, wire, LinkTarget, Resilient};
use rover_terrain::service;
use rover_terrain::validate;
use rover_terrain::{Config, Error, Pipeline, Verdict};
use rover_terrain_drivers::{CameraSpec, DepthCamera, DepthFrame, FakeCamera, Faults, FrameStatus};

/// Terrain analysis from a depth camera for a six-wheeled rocker rover.
#[derive(Parser, Debug)]
#[command(name = "rover-terrain", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run the on-board service: read the camera, analyse every frame, send each
    /// verdict over the link, heartbeats in between; systemd notify and watchdog when
    /// run under systemd. Stops on SIGTERM/SIGINT with a final stop verdict.
    ///
    /// With no arguments: the bundled fixtures through the fake camera at 30 Hz,
    /// verdicts and heartbeats as JSON lines on stdout.
    Run {
        /// Config file (TOML); `[camera] source`, `[link]` and `[service]` apply.
        #[arg(long)]
        config: Option<PathBuf>,
        /// The camera (overrides `[camera] source`): freenect[:INDEX], v4l:PATH or fake:PATH.
        #[arg(long)]
        camera: Option<CameraSpec>,
        /// The link (overrides `[link] target`): serial:PATH, slcan:PATH, can:IFACE or stdout.
        #[arg(long)]
        link: Option<LinkTarget>,
        /// Serial speed (overrides `[link] baud`).
        #[arg(long)]
        baud: Option<u32>,
        /// Stop after this many frames analysed.
        #[arg(long)]
        frames: Option<u64>,
        /// Replay a recording in a loop (sets `[service] loop_replay`).
        #[arg(long = "loop")]
        looping: bool,
        /// Test only: the fake camera stalls at frame AT for COUNT frame periods.
        #[arg(long, hide = true, value_name = "AT:COUNT")]
        inject_stall: Option<String>,
        /// Test only: the fake camera vanishes at frame AT (and is reopened).
        #[arg(long, hide = true, value_name = "AT")]
        inject_disconnect: Option<u64>,
        /// Test only: frame AT of the fake camera arrives corrupt.
        #[arg(long, hide = true, value_name = "AT")]
        inject_corrupt: Option<u64>,
    },
    /// Validate a config file and print the effective values (every key) as TOML.
    CheckConfig {
        /// The config file.
        file: PathBuf,
    },
    /// Analyse depth frames and print one JSON verdict per frame (JSON Lines).
    ///
    /// INPUT is a .pgm/.png depth image (16-bit, millimetres), a directory of them
    /// (name order), or a libfreenect fakenect session directory. Without INPUT, the
    /// bundled fixtures in fixtures/scenes are analysed.
    Analyze {
        /// Config file (TOML); defaults for every key not set.
        #[arg(long)]
        config: Option<PathBuf>,
        /// `full`: every field with timings; `wire`: what the link carries, exactly as
        /// `monitor` prints it.
        #[arg(long, value_enum, default_value_t = Format::Full)]
        format: Format,
        /// A camera instead of files: freenect[:INDEX], v4l:PATH or fake:PATH.
        #[arg(long)]
        camera: Option<CameraSpec>,
        /// Stop after this many frames.
        #[arg(long)]
        frames: Option<u64>,
        /// Depth images, directories or fakenect sessions.
        input: Vec<PathBuf>,
    },
    /// Analyse depth frames and send each verdict over the link, then exit.
    Send {
        /// serial:PATH, slcan:PATH, can:IFACE (feature socketcan) or stdout.
        #[arg(long)]
        link: LinkTarget,
        /// Serial speed for serial: and slcan: links.
        #[arg(long, default_value_t = link::DEFAULT_BAUD)]
        baud: u32,
        /// Config file (TOML).
        #[arg(long)]
        config: Option<PathBuf>,
        /// A camera instead of files: freenect[:INDEX], v4l:PATH or fake:PATH.
        #[arg(long)]
        camera: Option<CameraSpec>,
        /// Stop after this many frames.
        #[arg(long)]
        frames: Option<u64>,
        /// Depth images, directories or fakenect sessions.
        #[arg(required_unless_present = "camera")]
        input: Vec<PathBuf>,
    },
    /// The controller's view on the bench: decode what arrives on a link, one JSON line
    /// per message, with CRC errors, sequence gaps and staleness.
    Monitor {
        /// serial:PATH, slcan:PATH or can:IFACE (feature socketcan).
        #[arg(long)]
        link: LinkTarget,
        /// Serial speed.
        #[arg(long, default_value_t = link::DEFAULT_BAUD)]
        baud: u32,
        /// Exit after this many valid messages (verdicts and heartbeats).
        #[arg(long)]
        count: Option<u64>,
        /// No valid verdict for this long and the controller would stop, ms.
        #[arg(long, default_value_t = 200)]
        deadline_ms: u64,
    },
    /// Time the whole pipeline on one frame and print one JSON line of medians and p99s.
    Bench {
        /// Config file (TOML).
        #[arg(long)]
        config: Option<PathBuf>,
        /// Timed iterations after the warm-up.
        #[arg(long, default_value_t = 1000)]
        iterations: usize,
        /// Instead: run the whole service this many seconds at the recording's pace
        /// (30 Hz) over a pseudo-terminal and report latency, drops and memory.
        #[arg(long, value_name = "SECONDS")]
        soak: Option<f64>,
        /// A depth image, directory or session (its first frame is used; with --soak
        /// all of it, looping; default the bundled fixtures).
        #[arg(required_unless_present = "soak")]
        input: Option<PathBuf>,
    },
    /// Run the fixture suite against the expected verdicts and write the report.
    Validate {
        /// The fixture directory.
        #[arg(default_value = "fixtures")]
        dir: PathBuf,
        /// Where to write the Markdown report.
        #[arg(long, default_value = "docs/validation.md")]
        out: PathBuf,
        /// Random scenes per family and rig kind in the report's family sweep
        /// (0: none, the fixtures only).
        #[arg(long, default_value_t = rover_terrain::validate::FAMILY_SCENES)]
        families: usize,
    },
    /// Record depth frames as a libfreenect fakenect session (INDEX.txt, d-*.pgm, device.json)
    /// that our fake camera and libfreenect's fakenect can replay.
    Record {
        /// freenect[:INDEX] or fake:PATH.
        #[arg(long)]
        camera: CameraSpec,
        /// The session directory (must not hold an INDEX.txt yet).
        #[arg(long)]
        out: PathBuf,
        /// Stop after this many frames.
        #[arg(long, conflicts_with = "seconds")]
        frames: Option<u64>,
        /// Stop after this many seconds.
        #[arg(long)]
        seconds: Option<f64>,
    },
    /// Write pictures of analysed frames for people: depth.png (false-coloured range),
    /// topdown.png (the corridor from above with tracks, hazards, toe line and verdict),
    /// side.png (height profiles), and the voxels as cloud.pcd (PCL) and cloud.ply.
    Inspect {
        /// Config file (TOML).
        #[arg(long)]
        config: Option<PathBuf>,
        /// Output directory; with several frames, one subdirectory per frame written
        /// (frame-000000, ...).
        #[arg(long)]
        out: PathBuf,
        /// With a sequence or session: one set every N frames.
        #[arg(long, default_value_t = 1)]
        every: u64,
        /// A camera instead of INPUT: freenect[:INDEX], v4l:PATH or fake:PATH.
        #[arg(long)]
        camera: Option<CameraSpec>,
        /// Stop after this many frames.
        #[arg(long)]
        frames: Option<u64>,
        /// A depth image, a directory of them, or a fakenect session.
        #[arg(required_unless_present = "camera")]
        input: Option<PathBuf>,
    },
    /// List the depth cameras attached.
    Cameras,
    /// Render the fixture suite's frames and expectation files from the scene catalogue.
    RenderFixtures {
        /// Where to write them.
        #[arg(long, default_value = "fixtures")]
        out: PathBuf,
    },
}

/// What `analyze` prints per frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Format {
    /// Every field, with timings.
    Full,
    /// The wire form, as `monitor` prints it.
    Wire,
}

/// Exit code for an invalid configuration.
const EXIT_CONFIG: u8 = 2;
/// Exit code for bad input or a failed run.
const EXIT_FAILURE: u8 = 1;

fn main() -> ExitCode {
    let cli = Cli::parse();
    // Logs to stderr; RUST_LOG wins over the config's level; the service logs at
    // info by default, the one-shot commands only warnings and errors.
    // The service's config is read once, here, for its log level too.
    let service_config = match &cli.command {
        Command::Run { config, .. } => Some(load_config(config.as_deref())),
        _ => None,
    };
    let level = match (&cli.command, &service_config) {
        (_, Some(Ok(c))) => c.service.log_level.clone(),
        (Command::Run { .. } | Command::Bench { soak: Some(_), .. }, _) => "info".into(),
        _ => "warn".into(),
    };
    logging::init(&level);
    match run(cli, service_config) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("rover-terrain: {e:#}");
            let config_error = e
                .chain()
                .any(|c| matches!(c.downcast_ref::<Error>(), Some(Error::Config { .. })));
            ExitCode::from(if config_error {
                EXIT_CONFIG
            } else {
                EXIT_FAILURE
            })
        }
    }
}

fn load_config(path: Option<&Path>) -> anyhow::Result<Config> {
    Ok(match path {
        Some(p) => Config::load(p)?,
        None => Config::default(),
    })
}

/// The bundled fixtures: in the working directory, else beside the source tree.
fn bundled(rel: &str) -> PathBuf {
    let here = PathBuf::from(rel);
    if here.exists() {
        return here;
    }
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

fn run(cli: Cli, service_config: Option<anyhow::Result<Config>>) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Run {
            config: _,
            camera,
            link,
            baud,
            frames,
            looping,
            inject_stall,
            inject_disconnect,
            inject_corrupt,
        } => {
            let mut config = service_config.context("the service config was not loaded")??;
            config.service.loop_replay |= looping;
            let fixtures = bundled("fixtures/scenes");
            if camera.is_none() && config.camera.source.is_none() && !fixtures.exists() {
                anyhow::bail!(
                    "no camera: set [camera] source in the config or give --camera \
                     (the bundled fixtures, the default, are not at {})",
                    fixtures.display()
                );
            }
            let mut options = service::Options::from_config(config, CameraSpec::Fake(fixtures))?;
            if let Some(c) = camera {
                options.camera = c;
            }
            if let Some(l) = link {
                options.link = l;
            }
            if let Some(b) = baud {
                anyhow::ensure!(b > 0, "--baud must be positive");
                options.baud = b;
            }
            options.frames = frames;
            options.faults = Faults {
                stall: inject_stall.as_deref().map(parse_stall).transpose()?,
                disconnect_at: inject_disconnect,
                corrupt_at: inject_corrupt,
            };
            run_service(options)
        }
        Command::CheckConfig { file } => {
            let config = Config::load(&file)?;
            print!(
                "# {}: valid; the effective configuration\n{}",
                file.display(),
                toml::to_string(&config).context("printing the config")?
            );
            Ok(ExitCode::SUCCESS)
        }
        Command::Analyze {
            config,
            format,
            camera,
            frames,
            input,
        } => {
            let config = load_config(config.as_deref())?;
            let inputs = sources(camera, input, Some(bundled("fixtures/scenes")))?;
            let stdout = std::io::stdout();
            let mut out = stdout.lock();
            let failed = for_each_verdict(config, &inputs, frames, |a| {
                let v = a.verdict;
                let json = match format {
                    Format::Full => {
                        let mut json = v.to_json();
                        if let Some(p) = a.source {
                            json["source"] = serde_json::Value::from(p.display().to_string());
                        }
                        json
                    }
                    Format::Wire => wire::verdict_json(&wire::to_wire(v, 0.0)),
                };
                writeln!(out, "{json}").context("writing to stdout")
            })?;
            out.flush().context("writing to stdout")?;
            Ok(if failed {
                ExitCode::from(EXIT_FAILURE)
            } else {
                ExitCode::SUCCESS
            })
        }
        Command::Send {
            link,
            baud,
            config,
            camera,
            frames,
            input,
        } => {
            let inputs = sources(camera, input, None)?;
            let config = load_config(config.as_deref())?;
            // Fail at once, clearly, if the link cannot be opened at all.
            drop(link::open(&link, baud)?);
            let mut resilient = Resilient::new(link.clone(), baud);
            let failed = for_each_verdict(config, &inputs, frames, |a| {
                let age_ms = a.captured.elapsed().as_secs_f64() * 1e3;
                resilient.send_verdict(&wire::to_wire(a.verdict, age_ms));
                Ok(())
            })?;
            resilient.flush();
            if resilient.dropped() > 0 {
                anyhow::bail!(
                    "link {link}: {} verdicts not sent ({} failures, {} reopened)",
                    resilient.dropped(),
                    resilient.failures(),
                    resilient.reopened()
                );
            }
            Ok(if failed {
                ExitCode::from(EXIT_FAILURE)
            } else {
                ExitCode::SUCCESS
            })
        }
        Command::Monitor {
            link,
            baud,
            count,
            deadline_ms,
        } => monitor::run(&link, baud, count, deadline_ms),
        Command::Bench {
            config,
            iterations: _,
            soak: Some(seconds),
            input,
        } => {
            let config = load_config(config.as_deref())?;
            let input = input.unwrap_or_else(|| bundled("fixtures/scenes"));
            let report = soak::run(config, CameraSpec::Fake(input), seconds)?;
            println!("{report}");
            Ok(ExitCode::SUCCESS)
        }
        Command::Bench {
            config,
            iterations,
            soak: None,
            input,
        } => {
            let config = load_config(config.as_deref())?;
            let input = input.context("bench needs an INPUT")?;
            anyhow::ensure!(iterations > 0, "--iterations must be at least 1");
            let mut pipeline = Pipeline::new(config)?;
            let mut camera = FakeCamera::open(&input)?;
            let mut frame = DepthFrame::default();
            match camera.next_frame(&mut frame)? {
                FrameStatus::Frame => {}
                FrameStatus::EndOfStream => anyhow::bail!("{}: no frame", input.display()),
            }
            let line = rover_terrain::bench::run(&mut pipeline, &frame, iterations)?;
            println!("{line}");
            Ok(ExitCode::SUCCESS)
        }
        Command::Validate { dir, out, families } => {
            let results = validate::run_suite(&dir)?;
            let mut report = validate::report(&results);
            if families > 0 {
                let swept = validate::run_families(families, validate::FAMILY_SEED)?;
                report += &validate::families_report(&swept, families, validate::FAMILY_SEED);
            }
            if let Some(parent) = out.parent().filter(|p| !p.as_os_str().is_empty()) {
                std::fs::create_dir_all(parent)
                    .with_context(|| format!("creating {}", parent.display()))?;
            }
            std::fs::write(&out, &report).with_context(|| format!("writing {}", out.display()))?;
            let plots_dir = out
                .parent()
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or(Path::new("."));
            validate::write_plots(&results, plots_dir)?;
            let failed: Vec<_> = results.iter().filter(|r| !r.passed()).collect();
            for r in &failed {
                eprintln!("FAIL {}: {}", r.name, r.failures.join("; "));
            }
            eprintln!(
                "{} passed, {} failed; report in {}",
                results.len() - failed.len(),
                failed.len(),
                out.display()
            );
            Ok(if failed.is_empty() {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(EXIT_FAILURE)
            })
        }
        Command::Record {
            camera,
            out,
            frames,
            seconds,
        } => record(&camera, &out, frames, seconds),
        Command::Inspect {
            config,
            out,
            every,
            camera,
            frames,
            input,
        } => {
            anyhow::ensure!(every > 0, "--every must be at least 1");
            let config = load_config(config.as_deref())?;
            let spec = match (camera, input) {
                (Some(_), Some(_)) => anyhow::bail!("give either --camera or INPUT, not both"),
                (Some(c), None) => c,
                (None, Some(p)) => CameraSpec::Fake(p),
                (None, None) => anyhow::bail!("give INPUT or --camera"),
            };
            inspect(config, &spec, &out, every, frames)
        }
        Command::Cameras => {
            for line in rover_terrain_drivers::list_cameras() {
                println!("{line}");
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::RenderFixtures { out } => {
            let written = validate::write_fixtures(&out)?;
            eprintln!("wrote {} fixtures under {}", written.len(), out.display());
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// `inspect`: a picture set for every `every`-th frame of `spec`.
fn inspect(
    config: Config,
    spec: &CameraSpec,
    out: &Path,
    every: u64,
    limit: Option<u64>,
) -> anyhow::Result<ExitCode> {
    use rover_terrain::inspect::{write_frame_set, Scene};
    let single = match spec {
        CameraSpec::Fake(p) => FakeCamera::open(p).is_ok_and(|c| c.len() == 1),
        _ => false,
    };
    let mut written = 0u64;
    let failed = for_each_verdict(config, std::slice::from_ref(spec), limit, |a| {
        if a.frame.seq % every != 0 {
            return Ok(());
        }
        let dir = if single {
            out.to_path_buf()
        } else {
            out.join(format!("frame-{:06}", a.frame.seq))
        };
        let set = write_frame_set(a.frame, &Scene::of(a.pipeline, a.verdict), &dir)?;
        let files: Vec<String> = [&set.depth, &set.topdown, &set.side, &set.pcd, &set.ply]
            .iter()
            .map(|p| p.display().to_string())
            .collect();
        println!(
            "{}",
            serde_json::json!({
                "frame": a.frame.seq,
                "verdict": a.verdict.decision,
                "dir": dir.display().to_string(),
                "files": files,
            })
        );
        written += 1;
        Ok(())
    })?;
    anyhow::ensure!(written > 0 || failed, "no frame to inspect");
    Ok(if failed {
        ExitCode::from(EXIT_FAILURE)
    } else {
        ExitCode::SUCCESS
    })
}

/// `AT:COUNT` for `--inject-stall`.
fn parse_stall(s: &str) -> anyhow::Result<(u64, u64)> {
    let (at, count) = s.split_once(':').context("--inject-stall takes AT:COUNT")?;
    Ok((
        at.parse().context("--inject-stall AT")?,
        count.parse().context("--inject-stall COUNT")?,
    ))
}

/// SIGTERM and SIGINT, as a channel the service listens to; the handle closes it.
fn shutdown_on_signals() -> anyhow::Result<(
    crossbeam_channel::Receiver<()>,
    signal_hook::iterator::Handle,
)> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let (tx, rx) = crossbeam_channel::bounded(1);
    let mut signals = signal_hook::iterator::Signals::new([SIGTERM, SIGINT])
        .context("installing signal handlers")?;
    let handle = signals.handle();
    std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(sig) = signals.forever().next() {
                log::info!("signal {sig}: shutting down");
                let _ = tx.send(());
            }
        })
        .context("starting the signal thread")?;
    Ok((rx, handle))
}

/// `run`: the service until a signal or the end of a recording.
fn run_service(options: service::Options) -> anyhow::Result<ExitCode> {
    let notifier = service::Notifier::from_env()?;
    let (shutdown, signals) = shutdown_on_signals()?;
    let result = service::run(options, notifier, shutdown);
    signals.close();
    let summary = result?;
    log::info!(
        "stopped ({:?}): {} frames in, {} analysed, {} dropped, {} rejected, {} unknown sent, \
         {} link failures, arrival→link {}",
        summary.reason,
        summary.frames_in,
        summary.analysed,
        summary.dropped,
        summary.rejected,
        summary.unknown_sent,
        summary.link_failures,
        summary.latency
    );
    Ok(ExitCode::SUCCESS)
}

/// Record a camera into a fakenect session.
fn record(
    camera: &CameraSpec,
    out: &Path,
    frames: Option<u64>,
    seconds: Option<f64>,
) -> anyhow::Result<ExitCode> {
    use rover_terrain_drivers::fakenect::{Registration, Session, SessionWriter};
    anyhow::ensure!(
        frames.is_some() || seconds.is_some(),
        "give --frames N or --seconds S"
    );
    if let Some(s) = seconds {
        anyhow::ensure!(s.is_finite() && s > 0.0, "--seconds must be positive");
    }
    // Keep a replayed session's registration; else libfreenect's default.
    let registration = match camera {
        CameraSpec::Fake(p) if Session::is_session(p) => Session::open(p)?.registration().copied(),
        _ => None,
    }
    .unwrap_or(Registration::LIBFREENECT_DEFAULT);
    let mut cam = rover_terrain_drivers::open(camera)?;
    let mut writer = SessionWriter::create(out, Some(registration))?;
    let mut frame = DepthFrame::default();
    let mut colour = rover_terrain_drivers::ColourFrame::default();
    let start = std::time::Instant::now();
    let wall0 = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64());
    let mut n = 0u64;
    while frames.is_none_or(|f| n < f) && seconds.is_none_or(|s| start.elapsed().as_secs_f64() < s)
    {
        match cam.next_frame(&mut frame)? {
            FrameStatus::Frame => {}
            FrameStatus::EndOfStream => break,
        }
        // Arrival time: the frame's own clock for replayed sessions (so a re-recording
        // keeps the original timing), else wall time now. The second number in the
        // file name is the frame counter (libfreenect writes the Kinect's timestamp).
        let t = match camera {
            CameraSpec::Fake(_) => frame.timestamp_s,
            _ => wall0 + start.elapsed().as_secs_f64(),
        };
        writer.write_depth(&frame, t, n as u32)?;
        // The colour frame that came with it, if the camera has colour.
        if cam.next_colour(&mut colour)? {
            writer.write_colour(&colour, t, n as u32)?;
        }
        // The tilt state with each frame, as libfreenect's recorder snapshots it.
        if let Some(tilt) = cam.tilt_state() {
            writer.write_tilt(&tilt, t, n as u32)?;
        }
        n += 1;
    }
    eprintln!("recorded {n} frames into {}", out.display());
    Ok(ExitCode::SUCCESS)
}

/// The cameras to read: `--camera`, or the files given, or the default.
fn sources(
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

/// Analyse every frame of every source (up to `limit` frames) and hand each verdict
/// (with its source file and the moment its frame was read) to `on_verdict`. A bad
/// source or frame is reported on stderr and the rest still analysed; returns whether
/// anything failed.
/// One analysed frame, as [`for_each_verdict`] hands it over.
struct Analysed<'a> {
    /// The verdict.
    verdict: &'a Verdict,
    /// The file the frame came from, for file sources.
    source: Option<&'a Path>,
    /// When the frame was read.
    captured: std::time::Instant,
    /// The frame.
    frame: &'a DepthFrame,
    /// The pipeline that analysed it (its grid and analysis state).
    pipeline: &'a Pipeline,
}

fn for_each_verdict(
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
            match pipeline.process(&frame) {
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
