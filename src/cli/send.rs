//! `send`: analyse frames and send each verdict over the link, then exit.

use std::path::PathBuf;
use std::process::ExitCode;

use rover_terrain::link::{self, wire, LinkTarget, Resilient};
use rover_terrain_drivers::CameraSpec;

use super::frames::{for_each_verdict, sources};
use super::{exit_code, load_config};

/// `send`'s arguments.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// serial:PATH, slcan:PATH, can:IFACE (feature socketcan) or stdout.
    #[arg(long)]
    link: LinkTarget,
    /// Serial speed for serial: and slcan: links.
    #[arg(long, default_value_t = link::DEFAULT_BAUD)]
    baud: u32,
    /// Config file (TOML).
    #[arg(long)]
    config: Option<PathBuf>,
    /// A camera instead of files: freenect[:INDEX], v4l:PATH, fake:PATH or mcap:PATH[#TOPIC].
    #[arg(long)]
    camera: Option<CameraSpec>,
    /// Stop after this many frames.
    #[arg(long)]
    frames: Option<u64>,
    /// Depth images, directories or fakenect sessions.
    #[arg(required_unless_present = "camera")]
    input: Vec<PathBuf>,
}

/// Send every verdict; fails when any could not be sent.
pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let Args {
        link,
        baud,
        config,
        camera,
        frames,
        input,
    } = args;
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
    Ok(exit_code(failed))
}
