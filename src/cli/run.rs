//! `run`: the on-board service until a signal or the end of a recording.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rover_terrain::link::LinkTarget;
use rover_terrain::service;
use rover_terrain::Config;
use rover_terrain_drivers::{CameraSpec, Faults};

use super::bundled;

/// `run`'s arguments.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Config file (TOML); `[camera] source`, `[link]` and `[service]` apply.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// The camera (overrides `[camera] source`): freenect[:INDEX], v4l:PATH, fake:PATH or mcap:PATH[#TOPIC].
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
    /// Also write what the analysis saw into this MCAP file for Foxglove (as
    /// `analyze --mcap`), from a viewer thread off the hot path: frames it cannot keep
    /// up with are dropped from the file (counted), never from the link.
    #[arg(long)]
    mcap: Option<PathBuf>,
    /// Serve the analysis live to Foxglove on HOST:PORT (default 127.0.0.1:8765) over
    /// its WebSocket protocol, the same channels as --mcap (feature `foxglove-live`).
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = "127.0.0.1:8765")]
    foxglove: Option<String>,
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
}

/// Run the service with `config` (already loaded, for the log level) and the
/// command line's overrides.
pub fn run(args: Args, mut config: Config) -> anyhow::Result<ExitCode> {
    config.service.loop_replay |= args.looping;
    let fixtures = bundled("fixtures/scenes");
    if args.camera.is_none() && config.camera.source.is_none() && !fixtures.exists() {
        anyhow::bail!(
            "no camera: set [camera] source in the config or give --camera \
             (the bundled fixtures, the default, are not at {})",
            fixtures.display()
        );
    }
    let mut options = service::Options::from_config(config, CameraSpec::Fake(fixtures))?;
    if let Some(c) = args.camera {
        options.camera = c;
    }
    if let Some(l) = args.link {
        options.link = l;
    }
    if let Some(b) = args.baud {
        anyhow::ensure!(b > 0, "--baud must be positive");
        options.baud = b;
    }
    options.frames = args.frames;
    options.mcap = args.mcap;
    options.foxglove = args.foxglove;
    options.faults = Faults {
        stall: args.inject_stall.as_deref().map(parse_stall).transpose()?,
        disconnect_at: args.inject_disconnect,
        corrupt_at: args.inject_corrupt,
    };
    run_service(options)
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

/// The service until a signal or the end of a recording, then its summary in the log.
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
    if let Some(n) = summary.viewer_written {
        log::info!(
            "viewer: {n} frames written, {} pictures dropped (the viewer was behind)",
            summary.viewer_dropped
        );
    }
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stall_takes_at_and_count() {
        assert_eq!(parse_stall("5:10").unwrap(), (5, 10));
        assert!(parse_stall("5").is_err());
        assert!(parse_stall("x:1").is_err());
    }
}
