//! `inspect`: pictures of analysed frames for people.

use std::path::{Path, PathBuf};

use std::process::ExitCode;

use rover_terrain::Config;
use rover_terrain_drivers::{CameraSpec, FakeCamera};

use super::frames::for_each_verdict;
use super::{exit_code, load_config};

/// `inspect`'s arguments.
#[derive(clap::Args, Debug)]
pub struct Args {
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
    /// A camera instead of INPUT: freenect[:INDEX], v4l:PATH, fake:PATH or mcap:PATH[#TOPIC].
    #[arg(long)]
    camera: Option<CameraSpec>,
    /// Stop after this many frames.
    #[arg(long)]
    frames: Option<u64>,
    /// Also write the frames inspected into this MCAP file for Foxglove (as
    /// `analyze --mcap`): the same picture as `topdown.png`, in 3D.
    #[arg(long)]
    mcap: Option<PathBuf>,
    /// A depth image, a directory of them, or a fakenect session.
    #[arg(required_unless_present = "camera")]
    input: Option<PathBuf>,
}

/// Write the picture sets; one JSON line per set on stdout.
pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(args.every > 0, "--every must be at least 1");
    let config = load_config(args.config.as_deref())?;
    let spec = match (args.camera, args.input) {
        (Some(_), Some(_)) => anyhow::bail!("give either --camera or INPUT, not both"),
        (Some(c), None) => c,
        (None, Some(p)) => CameraSpec::Fake(p),
        (None, None) => anyhow::bail!("give INPUT or --camera"),
    };
    write_sets(
        config,
        &spec,
        &args.out,
        args.every,
        args.frames,
        args.mcap.as_deref(),
    )
}

/// `inspect`: a picture set for every `every`-th frame of `spec`.
fn write_sets(
    config: Config,
    spec: &CameraSpec,
    out: &Path,
    every: u64,
    limit: Option<u64>,
    mcap: Option<&Path>,
) -> anyhow::Result<ExitCode> {
    use rover_terrain::foxglove::{Frames, McapOut};
    use rover_terrain::inspect::{write_frame_set, Scene};
    let mut mcap = mcap
        .map(|p| McapOut::create(p, Frames::of(&config)))
        .transpose()?;
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
        let scene = Scene::of(a.pipeline, a.verdict);
        let set = write_frame_set(a.frame, &scene, &dir)?;
        if let Some(m) = mcap.as_mut() {
            m.write(a.frame, &scene, &a.json())?;
        }
        let files: Vec<String> = [&set.depth, &set.topdown, &set.side, &set.pcd, &set.ply]
            .iter()
            .map(|p| p.display().to_string())
            .collect();
        // A closed stdout (`| head`) ends the run with an error, not a panic.
        let line = serde_json::json!({
            "frame": a.frame.seq,
            "verdict": a.verdict.decision,
            "dir": dir.display().to_string(),
            "files": files,
        });
        super::print_stdout(&format!("{line}\n"))?;
        written += 1;
        Ok(())
    })?;
    if let Some(m) = mcap {
        m.finish()?;
    }
    anyhow::ensure!(written > 0 || failed, "no frame to inspect");
    Ok(exit_code(failed))
}
