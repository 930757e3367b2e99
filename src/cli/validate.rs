//! `validate`: the fixture suite and the scene families against their expected
//! verdicts, written as the Markdown report and its plots.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use rover_terrain::validate;

use super::exit_code;

/// `validate`'s arguments.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The fixture directory.
    #[arg(default_value = "fixtures")]
    dir: PathBuf,
    /// Where to write the Markdown report.
    #[arg(long, default_value = "docs/validation.md")]
    out: PathBuf,
    /// Random scenes per family and rig kind in the report's family sweep, which
    /// also runs the terrain memory's noisy drive (0: neither, the fixtures only).
    #[arg(long, default_value_t = validate::FAMILY_SCENES)]
    families: usize,
}

/// Run the suite, write the report beside its plots, list the failures on stderr.
pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let Args { dir, out, families } = args;
    let results = validate::run_suite(&dir)?;
    let mut report = validate::report(&results);
    if families > 0 {
        let swept = validate::run_families(families, validate::FAMILY_SEED)?;
        report += &validate::families_report(&swept, families, validate::FAMILY_SEED);
        let restyled = validate::run_families_restyled(families, validate::FAMILY_SEED)?;
        report += &validate::restyled_report(&restyled, families, validate::FAMILY_SEED);
        let bevelled = validate::run_families_bevelled(families, validate::FAMILY_SEED)?;
        report += &validate::bevelled_report(&bevelled, families, validate::FAMILY_SEED);
        let widened = validate::run_families_widened(families, validate::FAMILY_SEED)?;
        report += &validate::widened_report(&widened, families, validate::FAMILY_SEED);
        let rounded = validate::run_families_rounded(families, validate::FAMILY_SEED)?;
        report += &validate::rounded_report(&rounded, families, validate::FAMILY_SEED);
        let drive = validate::run_memory_drive(validate::FAMILY_SEED)?;
        report += &validate::memory_drive_report(&drive, validate::FAMILY_SEED);
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
    Ok(exit_code(!failed.is_empty()))
}
