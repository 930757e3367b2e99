//! `bench`: time the pipeline on one frame, or soak the whole service.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rover_terrain::Pipeline;
use rover_terrain_drivers::{CameraSpec, DepthCamera, DepthFrame, FakeCamera, FrameStatus};

use super::{bundled, load_config, soak};

/// `bench`'s arguments.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Config file (TOML).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Timed iterations after the warm-up.
    #[arg(long, default_value_t = 1000)]
    iterations: usize,
    /// Instead: run the whole service this many seconds at the recording's pace
    /// (30 Hz) over a pseudo-terminal and report latency, drops and memory.
    #[arg(long, value_name = "SECONDS")]
    pub soak: Option<f64>,
    /// A depth image, directory or session (its first frame is used; with --soak
    /// all of it, looping; default the bundled fixtures).
    #[arg(required_unless_present = "soak")]
    input: Option<PathBuf>,
}

/// One JSON line of timings (or the soak report) on stdout.
pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let config = load_config(args.config.as_deref())?;
    let line = match args.soak {
        Some(seconds) => {
            let input = args.input.unwrap_or_else(|| bundled("fixtures/scenes"));
            soak::run(config, CameraSpec::Fake(input), seconds)?.to_string()
        }
        None => {
            let input = args.input.context("bench needs an INPUT")?;
            anyhow::ensure!(args.iterations > 0, "--iterations must be at least 1");
            let mut pipeline = Pipeline::new(config)?;
            let mut camera = FakeCamera::open(&input)?;
            let mut frame = DepthFrame::default();
            match camera.next_frame(&mut frame)? {
                FrameStatus::Frame => {}
                FrameStatus::EndOfStream => anyhow::bail!("{}: no frame", input.display()),
            }
            rover_terrain::bench::run(&mut pipeline, &frame, args.iterations)?.to_string()
        }
    };
    super::print_stdout(&format!("{line}\n"))?;
    Ok(ExitCode::SUCCESS)
}
