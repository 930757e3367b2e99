//! `record`: a camera into a libfreenect fakenect session.

use std::path::PathBuf;

use anyhow::Context;
use std::process::ExitCode;

use rover_terrain_drivers::fakenect::{Registration, Session, SessionWriter};
use rover_terrain_drivers::{CameraSpec, DepthFrame, FrameStatus};

/// `record`'s arguments.
#[derive(clap::Args, Debug)]
pub struct Args {
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
    /// Listen on this link (serial:PATH, slcan:PATH, can:IFACE) for the controller's
    /// odometry and record the latest message with each frame (odometry.txt). A
    /// replayed drive's own odometry is kept without it.
    #[arg(long)]
    odometry_link: Option<rover_terrain::link::LinkTarget>,
    /// Serial speed for --odometry-link.
    #[arg(long, default_value_t = rover_terrain::link::DEFAULT_BAUD)]
    baud: u32,
}

/// Record the camera into a fakenect session.
pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let Args {
        camera,
        out,
        frames,
        seconds,
        odometry_link,
        baud,
    } = args;
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
    let mut writer = SessionWriter::create(out, Some(registration))?;
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
            CameraSpec::Fake(_) => frame.timestamp_s,
            _ => wall0 + start.elapsed().as_secs_f64(),
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
    eprintln!("recorded {n} frames into {}", out.display());
    Ok(ExitCode::SUCCESS)
}
