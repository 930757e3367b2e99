//! `analyze`: one JSON verdict per frame on stdout.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rover_terrain::foxglove::{Frames, McapOut};
use rover_terrain::inspect::Scene;
use rover_terrain::link::wire;
use rover_terrain_drivers::CameraSpec;

use super::frames::{for_each_verdict, sources};
use super::{bundled, exit_code, load_config};

/// What `analyze` prints per frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Every field, with timings.
    Full,
    /// The wire form, as `monitor` prints it.
    Wire,
}

/// `analyze`'s arguments.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Config file (TOML); defaults for every key not set.
    #[arg(long)]
    config: Option<PathBuf>,
    /// `full`: every field with timings; `wire`: what the link carries, exactly as
    /// `monitor` prints it.
    #[arg(long, value_enum, default_value_t = Format::Full)]
    format: Format,
    /// A camera instead of files: freenect[:INDEX], v4l:PATH, fake:PATH or mcap:PATH[#TOPIC].
    #[arg(long)]
    camera: Option<CameraSpec>,
    /// Stop after this many frames.
    #[arg(long)]
    frames: Option<u64>,
    /// Also write every frame's depth image, verdict, voxel cloud, ground grid,
    /// drawing and camera transform into this MCAP file, for Foxglove and ROS 2
    /// tooling (topics in the README).
    #[arg(long)]
    mcap: Option<PathBuf>,
    /// Depth images, directories or fakenect sessions.
    input: Vec<PathBuf>,
}

/// Analyse the inputs (default: the bundled fixtures) and print each verdict.
pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let config = load_config(args.config.as_deref())?;
    let inputs = sources(args.camera, args.input, Some(bundled("fixtures/scenes")))?;
    let mut mcap = args
        .mcap
        .as_deref()
        .map(|p| McapOut::create(p, Frames::of(&config)))
        .transpose()?;
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let failed = for_each_verdict(config, &inputs, args.frames, |a| {
        let v = a.verdict;
        let json = match args.format {
            Format::Full => a.json(),
            Format::Wire => wire::verdict_json(&wire::to_wire(v, 0.0)),
        };
        if let Some(m) = mcap.as_mut() {
            m.write(a.frame, &Scene::of(a.pipeline, v), &json)?;
        }
        writeln!(out, "{json}").context("writing to stdout")
    })?;
    out.flush().context("writing to stdout")?;
    if let Some(m) = mcap {
        m.finish()?;
    }
    Ok(exit_code(failed))
}
