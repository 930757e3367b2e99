//! `record`: a camera into a libfreenect fakenect session, or a ROS 2 bag (MCAP).

use std::path::PathBuf;

use anyhow::Context;
use std::process::ExitCode;

use rover_terrain_drivers::fakenect::{Registration, Session, SessionWriter};
use rover_terrain_drivers::ros2::{BagTopics, BagWriter};
use rover_terrain_drivers::{CameraSpec, DepthFrame, FrameStatus, Intrinsics};

/// `record`'s arguments.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// freenect[:INDEX], v4l:PATH, fake:PATH or mcap:PATH[#TOPIC].
    #[arg(long)]
    camera: CameraSpec,
    /// The session directory (must not hold an INDEX.txt yet), or the bag file for
    /// `--format mcap`.
    #[arg(long)]
    out: PathBuf,
    /// `fakenect`: a libfreenect session directory; `mcap`: a ROS 2 bag (depth as
    /// sensor_msgs/msg/Image 16UC1 with a CameraInfo, colour as rgb8).
    #[arg(long, value_enum, default_value_t = Format::Fakenect)]
    format: Format,
    /// Config file (TOML): `[camera]` gives the CameraInfo of a bag (a source's own
    /// calibration wins).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Stop after this many frames.
    #[arg(long, conflicts_with = "seconds")]
    frames: Option<u64>,
    /// Stop after this many seconds.
    #[arg(long)]
    seconds: Option<f64>,
    /// Listen on this link (serial:PATH, slcan:PATH, can:IFACE) for the controller's
    /// odometry and record the latest message with each frame (odometry.txt). A
    /// replayed drive's own odometry is kept without it.
    #[arg(long)]
    odometry_link: Option<rover_terrain::link::LinkTarget>,
    /// Serial speed for --odometry-link.
    #[arg(long, default_value_t = rover_terrain::link::DEFAULT_BAUD)]
    baud: u32,
}

/// What `record` writes.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// A libfreenect fakenect session directory.
    Fakenect,
    /// A ROS 2 bag in MCAP.
    Mcap,
}

/// Where frames go: a fakenect session or a ROS 2 bag.
enum Sink {
    Session(SessionWriter),
    Bag(Box<BagWriter>, Option<Intrinsics>),
}

/// Record the camera into a fakenect session or a ROS 2 bag.
pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let Args {
        camera,
        out,
        format,
        config,
        frames,
        seconds,
        odometry_link,
        baud,
    } = args;
    let config = super::load_config(config.as_deref())?;
    let (camera, out) = (&camera, out.as_path());
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
    let mut sink = match format {
        Format::Fakenect => Sink::Session(SessionWriter::create(out, Some(registration))?),
        Format::Mcap => {
            anyhow::ensure!(
                odometry_link.is_none(),
                "--odometry-link records into fakenect sessions only"
            );
            // The source's own calibration, else the configured camera (sized to each
            // frame below).
            Sink::Bag(
                Box::new(BagWriter::create(out, BagTopics::default())?),
                cam.intrinsics(),
            )
        }
    };
    let mut link = match &odometry_link {
        Some(target) => Some(
            rover_terrain::link::open(target, baud)
                .with_context(|| format!("--odometry-link {target}"))?,
        ),
        None => None,
    };
    let mut odometry: Option<[u8; 8]> = None;
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
            CameraSpec::Fake(_) | CameraSpec::Mcap { .. } => frame.timestamp_s,
            _ => wall0 + start.elapsed().as_secs_f64(),
        };
        let writer = match &mut sink {
            Sink::Session(w) => w,
            Sink::Bag(w, own) => {
                let k = own.unwrap_or_else(|| config.intrinsics_for(frame.width(), frame.height()));
                w.write_depth(&frame, t, &k)?;
                if cam.next_colour(&mut colour)? {
                    w.write_colour(&colour, t)?;
                }
                n += 1;
                continue;
            }
        };
        let name = writer.write_depth(&frame, t, n as u32)?;
        if let Some(l) = link.as_mut() {
            l.receive_odometry(&mut |o| odometry = Some(o.encode()))
                .context("reading odometry")?;
        }
        if let Some(bytes) = odometry.or(frame.odometry) {
            writer.write_odometry(&name, &bytes)?;
        }
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
    if let Sink::Bag(w, _) = sink {
        w.finish()?;
    }
    eprintln!("recorded {n} frames into {}", out.display());
    Ok(ExitCode::SUCCESS)
}
