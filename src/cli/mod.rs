//! The commands. Each lives in its own module with its arguments; this module holds
//! the command list, logging set-up, exit codes and what the commands share (config
//! loading, the bundled fixtures). The frame loop they share is [`frames`].

mod analyze;
mod bench;
mod controller;
mod frames;
mod inspect;
mod logging;
mod monitor;
mod record;
mod run;
mod send;
mod soak;
mod validate;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::{Parser, Subcommand};
use rover_terrain::coverage::Coverage;
use rover_terrain::{Config, Error};

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
    Run(run::Args),
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
    Analyze(analyze::Args),
    /// Analyse depth frames and send each verdict over the link, then exit.
    Send(send::Args),
    /// The controller's view on the bench: decode what arrives on a link, one JSON line
    /// per message, with CRC errors, sequence gaps and staleness.
    Monitor(monitor::Args),
    /// A motor controller on the bench: send the wheel odometry of a steady drive
    /// over a link (PROTOCOL.md, odometry), at a fixed rate.
    Controller(controller::Args),
    /// Time the whole pipeline on one frame and print one JSON line of medians and p99s.
    Bench(bench::Args),
    /// Run the fixture suite against the expected verdicts and write the report.
    Validate(validate::Args),
    /// Record depth frames as a libfreenect fakenect session (INDEX.txt, d-*.pgm, device.json)
    /// that our fake camera and libfreenect's fakenect can replay.
    Record(record::Args),
    /// Write pictures of analysed frames for people: depth.png (false-coloured range),
    /// topdown.png (the corridor from above with tracks, hazards, toe line and verdict),
    /// side.png (height profiles), and the voxels as cloud.pcd (PCL) and cloud.ply.
    Inspect(inspect::Args),
    /// List the depth cameras attached.
    Cameras,
    /// Render the fixture suite's frames and expectation files from the scene catalogue.
    RenderFixtures {
        /// Where to write them.
        #[arg(long, default_value = "fixtures")]
        out: PathBuf,
    },
}

/// Exit code for an invalid configuration.
const EXIT_CONFIG: u8 = 2;
/// Exit code for bad input or a failed run.
const EXIT_FAILURE: u8 = 1;

/// Parse the command line, set up logging, run the command, map errors to exit codes.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    // Logs to stderr; RUST_LOG wins over the config's level; the service logs at
    // info by default, the one-shot commands only warnings and errors.
    // The service's config is read once, here, for its log level too.
    let service_config = match &cli.command {
        Command::Run(args) => Some(load_config(args.config.as_deref())),
        _ => None,
    };
    let level = match (&cli.command, &service_config) {
        (_, Some(Ok(c))) => c.service.log_level.clone(),
        (Command::Run(_), _) => "info".into(),
        (Command::Bench(b), _) if b.soak.is_some() => "info".into(),
        _ => "warn".into(),
    };
    logging::init(&level);
    match dispatch(cli.command, service_config) {
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

fn dispatch(
    command: Command,
    service_config: Option<anyhow::Result<Config>>,
) -> anyhow::Result<ExitCode> {
    match command {
        Command::Run(args) => run::run(
            args,
            service_config.context("the service config was not loaded")??,
        ),
        Command::CheckConfig { file } => {
            let config = Config::load(&file)?;
            print_stdout(&format!(
                "# {}: valid; the effective configuration\n{}\n{}",
                file.display(),
                toml::to_string(&config).context("printing the config")?,
                Coverage::for_rover(&config).report()
            ))?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Analyze(args) => analyze::run(args),
        Command::Send(args) => send::run(args),
        Command::Monitor(args) => monitor::run(args),
        Command::Controller(args) => controller::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Validate(args) => validate::run(args),
        Command::Record(args) => record::run(args),
        Command::Inspect(args) => inspect::run(args),
        Command::Cameras => {
            for line in rover_terrain_drivers::list_cameras() {
                print_stdout(&format!("{line}\n"))?;
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::RenderFixtures { out } => {
            let written = rover_terrain::validate::write_fixtures(&out)?;
            eprintln!("wrote {} fixtures under {}", written.len(), out.display());
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// The config file given, or the defaults.
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

/// Success, or the failure exit code when anything failed along the way.
fn exit_code(failed: bool) -> ExitCode {
    if failed {
        ExitCode::from(EXIT_FAILURE)
    } else {
        ExitCode::SUCCESS
    }
}

/// Write `text` to stdout and flush it: an error (a closed pipe, a full disk) is an
/// error the caller reports, not a panic as `print!` would make it.
pub(crate) fn print_stdout(text: &str) -> anyhow::Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .context("writing to stdout")
}
