//! The fixture suite: writing it from the scene catalogue, running it against the
//! expected verdicts stored beside each frame, and the validation report.
//!
//! A fixture is `NAME.fixture.toml` beside its depth image: what it shows, which
//! frame and config to use, optional Kinect noise (applied on load, deterministic,
//! so noisy variants cost no extra files), the expected verdict with tolerances, and
//! the terrain it was rendered from.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use rover_terrain_drivers::image::{encode_png_depth, read_depth_image};
use rover_terrain_drivers::DepthFrame;
use serde::{Deserialize, Serialize};

use crate::config::Config;
use crate::inspect::plots;
use crate::sim::{self, catalogue, Expectation, KinectNoise, SceneConfig, Terrain};
use crate::verdict::Verdict;
use crate::{Error, Pipeline};

pub use crate::sim::{Tolerance, CLEAN, NOISY};

/// The config of the fixtures that need the camera pitched 40° down.
const PITCH40_CONFIG: &str = "# The default rover and Kinect, with the camera pitched 40° down so that\n# it sees ground from 0.43 m (the paper's left-side toe is at 0.474 m).\n[mount]\npitch_deg = 40.0\n";

/// File name of the error-against-distance plot, beside the report.
pub const ERROR_PLOT: &str = "validation-error.png";
/// File name of the workcase confusion matrix, beside the report.
pub const CONFUSION_PLOT: &str = "validation-confusion.png";

/// Write the plots of `results` into `dir`: [`ERROR_PLOT`] and [`CONFUSION_PLOT`].
pub fn write_plots(results: &[CaseResult], dir: &Path) -> Result<(), Error> {
    let bars = plots::ErrorBars {
        clean: (CLEAN.distance_m * 1e3, CLEAN.gradient_deg),
        noisy: (NOISY.distance_m * 1e3, NOISY.gradient_deg),
    };
    for (name, canvas) in [
        (ERROR_PLOT, plots::error_plot(&error_points(results), bars)),
        (CONFUSION_PLOT, plots::confusion(&confusion_counts(results))),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, canvas.png()).map_err(|e| Error::Io { path, source: e })?;
    }
    Ok(())
}

/// The measured features of `results`, for [`plots::error_plot`].
fn error_points(results: &[CaseResult]) -> Vec<plots::ErrorPoint> {
    results
        .iter()
        .filter_map(|r| {
            let e = &r.fixture.expected;
            let d = e.distance_m?;
            let f = r.got.feature?;
            Some(plots::ErrorPoint {
                expected_distance_m: d,
                distance_error_mm: f.distance_m.map(|g| (f64::from(g) - d).abs() * 1e3),
                gradient_error_deg: e
                    .gradient_deg
                    .zip(f.gradient_deg)
                    .map(|(w, g)| (f64::from(g) - w).abs()),
                noisy: r.fixture.noise.is_some(),
            })
        })
        .collect()
}

/// Counts of expected (rows) against got (columns) classes over `results`
/// ([`plots::class`]).
pub fn confusion_counts(results: &[CaseResult]) -> [[u32; 12]; 12] {
    let mut m = [[0u32; 12]; 12];
    for r in results {
        let e = &r.fixture.expected;
        let want = plots::class(e.verdict, e.workcase);
        let got = plots::class(r.got.decision, r.got.feature.map(|f| f.workcase));
        m[want][got] += 1;
    }
    m
}

/// Suffix of fixture files.
pub const FIXTURE_SUFFIX: &str = ".fixture.toml";

/// One fixture file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixtureFile {
    /// What it shows.
    pub description: String,
    /// The depth image, relative to this file.
    pub depth: String,
    /// A config file, relative to this file; the default config if absent.
    #[serde(default)]
    pub config: Option<String>,
    /// The row of the paper's Table 2 this reproduces.
    #[serde(default)]
    pub paper_case: Option<u8>,
    /// Kinect v1 noise applied to the frame on load.
    #[serde(default)]
    pub noise: Option<KinectNoise>,
    /// The expected verdict.
    pub expected: Expectation,
    /// Tolerances on the measures.
    pub tolerance: Tolerance,
    /// The terrain the frame was rendered from (for regeneration and reading).
    #[serde(default)]
    pub terrain: Option<Terrain>,
}

/// The outcome of one fixture.
#[derive(Debug, Clone)]
pub struct CaseResult {
    /// Fixture name (file stem without the suffix).
    pub name: String,
    /// The fixture as read.
    pub fixture: FixtureFile,
    /// What the pipeline said.
    pub got: Verdict,
    /// Every way it missed; empty when it passed.
    pub failures: Vec<String>,
}

impl CaseResult {
    /// Whether every expectation held.
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |source| Error::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Write the whole suite from the catalogue under `root` (`scenes/` for the default
/// camera, `pitch40/` with its own config). Returns the fixture files written.
pub fn write_fixtures(root: &Path) -> Result<Vec<PathBuf>, Error> {
    let mut written = Vec::new();
    for scene in catalogue() {
        let (sub, config_name, config) = match scene.config {
            SceneConfig::Default => ("scenes", None, Config::default()),
            SceneConfig::Pitch40 => (
                "pitch40",
                Some("rover-terrain.toml"),
                Config::from_toml(PITCH40_CONFIG, "pitch40")?,
            ),
        };
        let dir = root.join(sub);
        std::fs::create_dir_all(&dir).map_err(io(&dir))?;
        if let Some(name) = config_name {
            let p = dir.join(name);
            std::fs::write(&p, PITCH40_CONFIG).map_err(io(&p))?;
        }
        let frame = match &scene.terrain {
            Some(t) => sim::render(t, &config),
            None => {
                let (w, h) = (config.camera.width as usize, config.camera.height as usize);
                DepthFrame::from_pixels(w, h, vec![scene.fill_mm; w * h])
            }
        };
        let png = dir.join(format!("{}.png", scene.name));
        std::fs::write(&png, encode_png_depth(&frame)).map_err(io(&png))?;
        let mut variants = vec![(scene.name.to_string(), None, CLEAN)];
        if let Some(seed) = scene.noisy_seed {
            variants.push((
                format!("{}+noise", scene.name),
                Some(KinectNoise {
                    seed,
                    ..KinectNoise::default()
                }),
                NOISY,
            ));
        }
        for (name, noise, tolerance) in variants {
            let f = FixtureFile {
                description: scene.description.to_string(),
                depth: format!("{}.png", scene.name),
                config: config_name.map(str::to_string),
                paper_case: scene.paper_case,
                noise,
                expected: scene.expect.clone(),
                tolerance,
                terrain: scene.terrain.clone(),
            };
            let p = dir.join(format!("{name}{FIXTURE_SUFFIX}"));
            let text = toml::to_string(&f).map_err(|e| Error::Fixture {
                path: p.clone(),
                message: e.to_string(),
            })?;
            std::fs::write(&p, text).map_err(io(&p))?;
            written.push(p);
        }
    }
    Ok(written)
}

/// Read a fixture: its file, its config, and its frame (noise applied).
pub fn load_fixture(path: &Path) -> Result<(FixtureFile, Config, DepthFrame), Error> {
    let text = std::fs::read_to_string(path).map_err(io(path))?;
    let fixture: FixtureFile = toml::from_str(&text).map_err(|e| Error::Fixture {
        path: path.to_path_buf(),
        message: e.to_string().trim_end().to_string(),
    })?;
    let dir = path.parent().unwrap_or(Path::new("."));
    let config = match &fixture.config {
        Some(c) => Config::load(&dir.join(c))?,
        None => Config::default(),
    };
    let mut frame = DepthFrame::default();
    read_depth_image(&dir.join(&fixture.depth), &mut Vec::new(), &mut frame)?;
    if let Some(noise) = &fixture.noise {
        noise.apply(&mut frame, config.camera.hfov_deg);
    }
    Ok((fixture, config, frame))
}

/// Run one fixture and compare.
pub fn run_case(path: &Path) -> Result<CaseResult, Error> {
    let (fixture, config, frame) = load_fixture(path)?;
    let mut pipeline = Pipeline::new(config)?;
    let got = pipeline.process(&frame)?.clone();
    let failures = compare(&fixture.expected, &fixture.tolerance, &got);
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .map(|n| n.trim_end_matches(FIXTURE_SUFFIX).to_string())
        .unwrap_or_default();
    Ok(CaseResult {
        name,
        fixture,
        got,
        failures,
    })
}

/// Every way `got` misses `want`.
pub fn compare(want: &Expectation, tol: &Tolerance, got: &Verdict) -> Vec<String> {
    let mut out = Vec::new();
    if got.decision != want.verdict {
        out.push(format!(
            "verdict {:?}, expected {:?}",
            got.decision, want.verdict
        ));
    }
    if let Some(k) = want.hazard {
        match got.hazards.first() {
            Some(h) if h.kind == k => {}
            other => out.push(format!(
                "deciding hazard {:?}, expected {k:?}",
                other.map(|h| h.kind)
            )),
        }
    }
    let f = got.feature;
    if let Some(wc) = want.workcase {
        let g = f.map(|f| f.workcase);
        if g != Some(wc) {
            out.push(format!("workcase {g:?}, expected {wc}"));
        }
    }
    let mut measure = |name: &str, want: Option<f64>, got: Option<f32>, tol: f64| {
        if let Some(w) = want {
            match got {
                Some(g) if (f64::from(g) - w).abs() <= tol => {}
                Some(g) => out.push(format!("{name} {g:.4}, expected {w} ± {tol}")),
                None => out.push(format!("{name} missing, expected {w}")),
            }
        }
    };
    measure(
        "distance_m",
        want.distance_m,
        f.and_then(|f| f.distance_m),
        tol.distance_m,
    );
    measure(
        "gradient_deg",
        want.gradient_deg,
        f.and_then(|f| f.gradient_deg),
        tol.gradient_deg,
    );
    measure(
        "alpha_deg",
        want.alpha_deg,
        f.and_then(|f| f.alpha_deg),
        tol.alpha_deg,
    );
    out
}

/// Every fixture file under `root`, sorted.
pub fn fixture_files(root: &Path) -> Result<Vec<PathBuf>, Error> {
    let mut out = Vec::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).map_err(io(&dir))? {
            let p = entry.map_err(io(&dir))?.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.to_str().is_some_and(|s| s.ends_with(FIXTURE_SUFFIX)) {
                out.push(p);
            }
        }
    }
    out.sort();
    Ok(out)
}

/// Run every fixture under `root`.
pub fn run_suite(root: &Path) -> Result<Vec<CaseResult>, Error> {
    let files = fixture_files(root)?;
    if files.is_empty() {
        return Err(Error::Fixture {
            path: root.to_path_buf(),
            message: format!("no *{FIXTURE_SUFFIX} files"),
        });
    }
    files.iter().map(|p| run_case(p)).collect()
}

/// The paper's Table 2: (case, measure, actual, paper's analysed value, paper's error %).
pub const PAPER_TABLE_2: [(u8, &str, f64, f64, f64); 7] = [
    (2, "distance_m", 0.675, 0.6763, 0.1926),
    (2, "gradient_deg", 20.0, 20.0021, 0.0105),
    (3, "distance_m", 0.474, 0.4750, 0.2110),
    (3, "gradient_deg", 20.0, 20.0014, 0.0070),
    (4, "alpha_deg", -26.0, -26.6887, 2.6488),
    (8, "distance_m", 1.295, 1.3007, 0.4402),
    (8, "gradient_deg", -11.5, -11.4787, 0.1852),
];

fn measure_of(v: &Verdict, name: &str) -> Option<f64> {
    let f = v.feature?;
    match name {
        "distance_m" => f.distance_m,
        "gradient_deg" => f.gradient_deg,
        "alpha_deg" => f.alpha_deg,
        _ => None,
    }
    .map(f64::from)
}

fn pct(got: Option<f64>, actual: f64) -> String {
    match got {
        Some(g) => format!("{:.4}", (g - actual).abs() / actual.abs() * 100.0),
        None => "—".into(),
    }
}

fn val(got: Option<f64>) -> String {
    got.map_or("—".into(), |g| format!("{g:.4}"))
}

/// The report as Markdown (deterministic: no dates or timings, so it can be committed).
pub fn report(results: &[CaseResult]) -> String {
    let mut s = String::new();
    let passed = results.iter().filter(|r| r.passed()).count();
    let _ = writeln!(s, "# Validation report\n");
    let _ = writeln!(
        s,
        "Written by `rover-terrain validate` from the fixtures in `fixtures/` (frames rendered by the\n\
         scene ray caster in `src/sim/`, regenerated by `rover-terrain render-fixtures`). Camera\n\
         640×480, 57°×43°, 0.8 m high, pitched 30° down, unless a fixture names its own config. Noisy\n\
         variants apply the Kinect v1 noise model (Gaussian σ = 1.425e-3·Z², 1/8-pixel disparity\n\
         quantisation, 1 % dropout) with a fixed seed. Errors are absolute differences from the\n\
         rendered truth.\n"
    );
    let _ = writeln!(s, "**{passed} of {} fixtures pass.**\n", results.len());
    let _ = writeln!(s, "## The paper's Table 2, reproduced\n");
    let _ = writeln!(
        s,
        "The left-side case (3) uses a camera pitched 40° down (`fixtures/pitch40/rover-terrain.toml`), which sees\n\
         ground from 0.43 m and so sees the 0.474 m toe; the others use the default mount.\n"
    );
    let _ = writeln!(s, "| Case | Measure | Actual | Paper: analysed | Paper: error % | Ours, clean | Error % | Ours, Kinect noise | Error % |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
    for (case, name, actual, paper, paper_err) in PAPER_TABLE_2 {
        let find = |noisy: bool| {
            results
                .iter()
                .find(|r| r.fixture.paper_case == Some(case) && r.fixture.noise.is_some() == noisy)
                .and_then(|r| measure_of(&r.got, name))
        };
        let (clean, noisy) = (find(false), find(true));
        let _ = writeln!(
            s,
            "| {case} | {name} | {actual} | {paper} | {paper_err} | {} | {} | {} | {} |",
            val(clean),
            pct(clean, actual),
            val(noisy),
            pct(noisy, actual)
        );
    }
    let _ = writeln!(s, "\n## Every fixture\n");
    let _ = writeln!(s, "| Fixture | Expected | Got | Hazards | Δ distance m | Δ gradient ° | Δ alpha ° | Seen | Result |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
    for r in results {
        let e = &r.fixture.expected;
        let want = format!(
            "{:?}{}",
            e.verdict,
            e.workcase.map(|w| format!(" wc{w}")).unwrap_or_default()
        )
        .to_lowercase();
        let f = r.got.feature;
        let got = format!(
            "{:?}{}",
            r.got.decision,
            f.map(|f| format!(" wc{}", f.workcase)).unwrap_or_default()
        )
        .to_lowercase();
        let hazards: Vec<String> = r
            .got
            .hazards
            .iter()
            .map(|h| format!("{:?}/{:?}@{:.2}", h.kind, h.side, h.distance_m).to_lowercase())
            .collect();
        let d = |w: Option<f64>, g: Option<f64>| match (w, g) {
            (Some(w), Some(g)) => format!("{:.4}", (g - w).abs()),
            _ => "".into(),
        };
        let _ = writeln!(
            s,
            "| {} | {want} | {got} | {} | {} | {} | {} | {:.2} | {} |",
            r.name,
            hazards.join(" "),
            d(e.distance_m, measure_of(&r.got, "distance_m")),
            d(e.gradient_deg, measure_of(&r.got, "gradient_deg")),
            d(e.alpha_deg, measure_of(&r.got, "alpha_deg")),
            r.got.seen_fraction,
            if r.passed() {
                "pass".to_string()
            } else {
                format!("**FAIL**: {}", r.failures.join("; "))
            }
        );
    }
    let _ = writeln!(s, "\n## Plots\n");
    let _ = writeln!(
        s,
        "Written beside this report by `validate`.\n\n\
         ![Error against the feature's distance, clean and noisy fixtures]({ERROR_PLOT})\n\n\
         ![Confusion matrix of workcases, expected against analysed]({CONFUSION_PLOT})"
    );
    let _ = writeln!(s, "\n## Summary\n");
    for (label, noisy) in [("clean", false), ("Kinect noise", true)] {
        let set: Vec<&CaseResult> = results
            .iter()
            .filter(|r| r.fixture.noise.is_some() == noisy)
            .collect();
        let maxerr = |name: &str, want: fn(&Expectation) -> Option<f64>| {
            set.iter()
                .filter_map(|r| {
                    Some((measure_of(&r.got, name)? - want(&r.fixture.expected)?).abs())
                })
                .fold(0.0f64, f64::max)
        };
        let _ = writeln!(
            s,
            "- {label}: {} of {} pass; largest errors: distance {:.4} m, gradient {:.3}°, alpha {:.3}°.",
            set.iter().filter(|r| r.passed()).count(),
            set.len(),
            maxerr("distance_m", |e| e.distance_m),
            maxerr("gradient_deg", |e| e.gradient_deg),
            maxerr("alpha_deg", |e| e.alpha_deg),
        );
    }
    s
}

/// The outcome of one drawn scene of a family sweep ([`run_families`]).
#[derive(Debug, Clone)]
pub struct FamilyResult {
    /// The family.
    pub family: crate::sim::families::Family,
    /// Drawn on a random rig (mount and camera) rather than the default one.
    pub random_rig: bool,
    /// With Kinect v1 noise.
    pub noisy: bool,
    /// What it must give.
    pub expect: Expectation,
    /// What it gave.
    pub got: Verdict,
    /// Every way it missed its bar.
    pub failures: Vec<String>,
    /// Not go for a stone, rock, block or step up whose top the camera cannot see
    /// ([`crate::sim::sight::not_go_for_unseen_tops`]): how high it stands is not
    /// seen. Still counted as missed where the bar says go; the report
    /// says why.
    pub top_unseen: bool,
}

/// Draw `per_family` scenes of every family on the default rig and as many on random
/// rigs (deterministic for `seed`), render each, and analyse it clean and with
/// Kinect v1 noise.
pub fn run_families(per_family: usize, seed: u64) -> Result<Vec<FamilyResult>, Error> {
    use crate::sim::families::Family;
    sweep_families(
        &[&Family::ALL[..], &Family::LATER[..]].concat(),
        per_family,
        seed,
        Style::Ours,
    )
}

/// [`run_families`] over the families of natural ground (rough ground and rocks),
/// each scene drawn another way ([`crate::sim::families::restyled`]: value-noise
/// ground, stones of other shapes), as a renderer other than ours might.
pub fn run_families_restyled(per_family: usize, seed: u64) -> Result<Vec<FamilyResult>, Error> {
    sweep_families(
        &crate::sim::families::Family::NATURAL,
        per_family,
        seed,
        Style::Restyled,
    )
}

/// [`run_families`] over the families with bands (one-track ramps and descents,
/// ground falling away beside a track, a ramp under each track), each band's vertical
/// sides drawn sloping ([`crate::sim::families::bevelled`]), as a renderer that
/// interpolates a height map might.
pub fn run_families_bevelled(per_family: usize, seed: u64) -> Result<Vec<FamilyResult>, Error> {
    sweep_families(
        &crate::sim::families::Family::BANDED,
        per_family,
        seed,
        Style::Bevelled,
    )
}

/// [`run_families`] over the families with bands, each band under one side drawn
/// wider than the wheel track ([`crate::sim::families::widened`]: its inner edge up
/// to 15 cm into the belly band), as a scene drawn without our band edges in mind
/// might.
pub fn run_families_widened(per_family: usize, seed: u64) -> Result<Vec<FamilyResult>, Error> {
    sweep_families(
        &crate::sim::families::Family::BANDED,
        per_family,
        seed,
        Style::Widened,
    )
}

/// [`run_families`] over the families with a ramp or a descent, each toe rounded
/// ([`crate::sim::families::rounded`]: over 5-40 cm across the toe line), as real
/// terrain is and a renderer other than ours might draw it.
pub fn run_families_rounded(per_family: usize, seed: u64) -> Result<Vec<FamilyResult>, Error> {
    sweep_families(
        &crate::sim::families::Family::RAMPED,
        per_family,
        seed,
        Style::Rounded,
    )
}

/// How [`sweep_families`] draws its scenes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Style {
    /// As `sim::families` draws them.
    Ours,
    /// [`crate::sim::families::restyled`].
    Restyled,
    /// [`crate::sim::families::bevelled`].
    Bevelled,
    /// [`crate::sim::families::widened`].
    Widened,
    /// [`crate::sim::families::rounded`].
    Rounded,
}

fn sweep_families(
    families: &[crate::sim::families::Family],
    per_family: usize,
    seed: u64,
    how: Style,
) -> Result<Vec<FamilyResult>, Error> {
    use crate::sim::families::{bevelled, draw, restyled, rounded, widened, Rig};
    use rand::SeedableRng;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut style = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    style.set_stream(1);
    let mut out = Vec::new();
    for &family in families {
        for k in 0..2 * per_family {
            let random_rig = k >= per_family;
            let rig = if random_rig {
                Rig::random(&mut rng)
            } else {
                Rig::default_rig()
            };
            let mut d = draw(&mut rng, family, rig);
            d = match how {
                Style::Ours => d,
                Style::Restyled => restyled(&mut style, d),
                Style::Bevelled => bevelled(&mut style, d),
                Style::Widened => widened(&mut style, d),
                Style::Rounded => rounded(&mut style, d),
            };
            let config = d.rig.config.clone();
            let mut pipeline = Pipeline::new(config.clone())?;
            let clean = sim::render(&d.terrain, &config);
            let tops = sim::sight::unseen_tops(&d.terrain, &config);
            for noisy in [false, true] {
                let mut frame = clean.clone();
                if noisy {
                    KinectNoise {
                        seed: seed ^ (out.len() as u64 + 1),
                        ..Default::default()
                    }
                    .apply(&mut frame, config.camera.hfov_deg);
                }
                let got = pipeline.process(&frame)?.clone();
                let tol = if noisy {
                    &d.tolerance.1
                } else {
                    &d.tolerance.0
                };
                let failures = compare(&d.expect, tol, &got);
                let top_unseen = sim::sight::not_go_for_unseen_tops(&got, &tops, &config.rover);
                out.push(FamilyResult {
                    family,
                    random_rig,
                    noisy,
                    expect: d.expect.clone(),
                    got,
                    failures,
                    top_unseen,
                });
            }
        }
    }
    Ok(out)
}

/// The family sweep as a Markdown section: pass counts per family and rig, false
/// "go"s (a go where a stop was due), and the largest measure errors.
pub fn families_report(results: &[FamilyResult], per_family: usize, seed: u64) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "\n## Scene families beyond the fixtures\n");
    s + &families_table(results, per_family, seed)
}

/// The restyled family sweep ([`run_families_restyled`]) as a Markdown section.
pub fn restyled_report(results: &[FamilyResult], per_family: usize, seed: u64) -> String {
    styled_section(
        "Natural ground drawn another way",
        "Scenes of the natural-ground families above, drawn as there but with their rough ground as \
         value noise (heights uniform within ±2.5 cm on a lattice as fine as the correlation \
         length, blended by a smoothstep: steeper bumps than the plane waves') and each rock as \
         a cone, a spherical cap, a Gaussian mound or a boulder (a superellipsoid with steep \
         flanks) of the same height and footprint (`sim::families::restyled`).\n",
        results,
        (per_family, seed),
    )
}

/// The bevelled family sweep ([`run_families_bevelled`]) as a Markdown section.
pub fn bevelled_report(results: &[FamilyResult], per_family: usize, seed: u64) -> String {
    styled_section(
        "Bands with sloping sides",
        "Scenes of the families above whose terrain has bands (a ramp or a descent under one \
         track, ground falling away beside a track, a ramp under each track), drawn as there \
         but with each band's vertical sides sloping: the band's height fades linearly over \
         2-15 cm centred on its edge, as a renderer that samples a height map that far apart \
         and interpolates draws a vertical face (`sim::families::bevelled`).\n",
        results,
        (per_family, seed),
    )
}

/// The widened family sweep ([`run_families_widened`]) as a Markdown section.
pub fn widened_report(results: &[FamilyResult], per_family: usize, seed: u64) -> String {
    styled_section(
        "Bands wider than the track",
        "Scenes of the families with bands, drawn as there but with each band under one side \
         wider than the wheel track: its inner edge 0-15 cm into the belly band (so the belly \
         band's strips beside the track lie on the ramp or in the trench, and the band's side \
         face stands inside the belly band), a one-track band's outer edge 0-40 cm past the \
         track's (`sim::families::widened`).\n",
        results,
        (per_family, seed),
    )
}

/// The rounded family sweep ([`run_families_rounded`]) as a Markdown section.
pub fn rounded_report(results: &[FamilyResult], per_family: usize, seed: u64) -> String {
    styled_section(
        "Rounded toes",
        "Scenes of the families with a ramp or a descent, drawn as there but with each toe \
         rounded: over 5-40 cm across the toe line the ground follows a parabola tangent to the \
         ground before and to the face after, so the two planes still meet at the drawn toe \
         line, which stays the expected toe (`sim::families::rounded`). The bars are those \
         above.\n",
        results,
        (per_family, seed),
    )
}

/// A family sweep drawn another way as a Markdown section: its `title`, the `intro`
/// saying how the scenes differ (ending in a newline), and the table.
fn styled_section(
    title: &str,
    intro: &str,
    results: &[FamilyResult],
    (per_family, seed): (usize, u64),
) -> String {
    format!("\n## {title}\n\n{intro}\n") + &families_table(results, per_family, seed)
}

fn families_table(results: &[FamilyResult], per_family: usize, seed: u64) -> String {
    use crate::verdict::Decision;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Drawn by `sim::families` (seed {seed}): {per_family} scenes per family on the default rig and \
         {per_family} on random rigs (mount 0.5-1.2 m high, pitched 15-45°, rolled and yawed ±10°, \
         offset; Kinect v1, Kinect v2 512×424 70.6°×60°, a D435-like 848×480 pinhole with an \
         off-centre principal point, 320×240; minimum range 0.3-0.5 m), each clean and with Kinect v1 \
         noise. Bars: clean 1 cm / 0.5° / 1°, noisy 3 cm / 1.5° / 3°, rough ground 4 cm / 2° / 3°. \
         A *false go* is a go where the geometry calls for a stop.\n"
    );
    let _ = writeln!(
        s,
        "| Family | Default rig: pass | Random rigs: pass | False go | Largest Δ distance m | Largest Δ gradient ° |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    let false_go =
        |r: &FamilyResult| r.got.decision == Decision::Go && r.expect.verdict != Decision::Go;
    let err = |r: &FamilyResult, name: &str, want: Option<f64>| -> Option<f64> {
        Some((measure_of(&r.got, name)? - want?).abs())
    };
    let mut families: Vec<_> = results.iter().map(|r| r.family).collect();
    families.dedup();
    for family in families {
        let set: Vec<&FamilyResult> = results.iter().filter(|r| r.family == family).collect();
        let count = |random: bool| {
            let sub: Vec<_> = set.iter().filter(|r| r.random_rig == random).collect();
            format!(
                "{} / {}",
                sub.iter().filter(|r| r.failures.is_empty()).count(),
                sub.len()
            )
        };
        let worst = |name: &str, want: fn(&Expectation) -> Option<f64>| {
            set.iter()
                .filter(|r| r.got.decision == Decision::Go)
                .filter_map(|r| err(r, name, want(&r.expect)))
                .fold(None, |m: Option<f64>, e| Some(m.map_or(e, |m| m.max(e))))
                .map_or(String::new(), |e| format!("{e:.4}"))
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} |",
            family.name(),
            count(false),
            count(true),
            set.iter().filter(|r| false_go(r)).count(),
            worst("distance_m", |e| e.distance_m),
            worst("gradient_deg", |e| e.gradient_deg),
        );
    }
    let total = results.len();
    let passed = results.iter().filter(|r| r.failures.is_empty()).count();
    let _ = writeln!(
        s,
        "\n{passed} of {total} pass; {} false go.\n",
        results.iter().filter(|r| false_go(r)).count()
    );
    let failed: Vec<&FamilyResult> = results.iter().filter(|r| !r.failures.is_empty()).collect();
    if !failed.is_empty() {
        let _ = writeln!(s, "What missed, and how:\n");
        for r in failed {
            let _ = writeln!(
                s,
                "- {}{}{}: {}{}",
                r.family.name(),
                if r.random_rig { ", random rig" } else { "" },
                if r.noisy { ", noisy" } else { "" },
                r.failures.join("; "),
                if r.top_unseen {
                    " (the obstacle's top is out of the camera's view: how high it stands is not seen)"
                } else {
                    ""
                }
            );
        }
    }
    s
}

/// Scenes per family and rig kind in the report's family sweep.
pub const FAMILY_SCENES: usize = 2;
/// Seed of the report's family sweep.
pub const FAMILY_SEED: u64 = 12;

/// Errors of one way of analysing a drive: mean and largest |error| of the distance,
/// metres, and of the gradient, degrees, over the frames that measured them.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DriveErrors {
    /// Mean |Δ distance|, metres.
    pub distance_mean: f64,
    /// Largest |Δ distance|, metres.
    pub distance_max: f64,
    /// Mean |Δ gradient|, degrees.
    pub gradient_mean: f64,
    /// Largest |Δ gradient|, degrees.
    pub gradient_max: f64,
    /// Frames with a feature measured.
    pub measured: usize,
    /// RMS of the analysed cells' mean heights about the true ground under their
    /// centroids, over the cells wholly in view in every frame, metres.
    pub cell_rms_m: f64,
}

/// The noisy drive of [`run_memory_drive`]: single frames against the terrain memory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveComparison {
    /// Frames in the drive.
    pub frames: usize,
    /// Each frame on its own.
    pub single: DriveErrors,
    /// Frames fused over the odometry.
    pub fused: DriveErrors,
}

/// Toe of the ramp of [`run_memory_drive`] at the start, metres; its gradient, °.
pub const DRIVE_RAMP: (f64, f64) = (1.6, 20.0);

/// A 20-frame drive with Kinect v1 noise toward a full-width 20° ramp (toe 1.6 m out,
/// 3 cm per frame), analysed frame by frame and with the terrain memory over exact
/// odometry; the toe distance and gradient errors of both.
pub fn run_memory_drive(seed: u64) -> Result<DriveComparison, Error> {
    use crate::memory::Motion;
    use crate::sim::drive::{render_drive, Step};
    use crate::sim::{Element, Extent, KinectNoise, Terrain};
    let config = Config::default();
    let (toe, gradient) = DRIVE_RAMP;
    let terrain = Terrain::new(vec![Element::ramp(toe, 0.0, gradient, 0.0, Extent::Full)]);
    let step = 0.03;
    let steps = [Step {
        forward_m: step,
        turn_rad: 0.0,
    }; 19];
    let drive = render_drive(&terrain, &config, &steps, 1.0, 10.0);
    let mut single = Pipeline::new(config.clone())?;
    let mut fused = Pipeline::new(config.clone())?;
    let (mut e_single, mut e_fused) = (Vec::new(), Vec::new());
    let field = terrain.field();
    let min_points = config.analysis.min_points_per_cell;
    let half = 0.5 * config.analysis.voxel_m;
    // Squared height error and count of the cells wholly in view (not cut by the
    // image's top edge) whose ground is a plane (not the fold at the ramp's toe,
    // where a cell's mean point lies above the ground however many frames see it).
    let cell_errors = |p: &Pipeline, pose: &crate::sim::Pose, acc: &mut (f64, usize)| {
        let expected = p.analyzer().expected();
        let cut = p.grid().cut();
        for ((c, &e), &cut) in p.analysed_cells().iter().zip(expected).zip(cut) {
            let (x, y) = pose.to_terrain(f64::from(c.x), f64::from(c.y));
            let h = |dx: f64| field.height(x + dx, y);
            let planar = (h(-half) + h(half) - 2.0 * h(0.0)).abs() < 1e-6;
            if e && !cut && c.n >= min_points && planar {
                acc.0 += (f64::from(c.z) - h(0.0)).powi(2);
                acc.1 += 1;
            }
        }
    };
    let (mut c_single, mut c_fused) = ((0.0, 0usize), (0.0, 0usize));
    for (k, (frame, pose, _)) in drive.iter().enumerate() {
        let mut f = frame.clone();
        KinectNoise {
            seed: seed * 1000 + k as u64,
            ..Default::default()
        }
        .apply(&mut f, config.camera.hfov_deg);
        let motion = Motion {
            forward_m: step as f32,
            dt_s: 0.1,
            ..Motion::default()
        };
        let truth = toe - pose.x;
        let err = |v: &Verdict| {
            let f = v.feature?;
            let d = f64::from(f.distance_m?) - truth;
            let g = f64::from(f.gradient_deg?) - gradient;
            Some((d.abs(), g.abs()))
        };
        e_single.extend(err(single.process(&f)?));
        cell_errors(&single, pose, &mut c_single);
        let m = if k == 0 {
            Err(crate::memory::odometry::Untrusted::NoOdometry)
        } else {
            Ok(motion)
        };
        e_fused.extend(err(fused.process_moved(&f, m)?));
        cell_errors(&fused, pose, &mut c_fused);
    }
    let summary = |e: &[(f64, f64)], cells: (f64, usize)| {
        let n = e.len().max(1) as f64;
        DriveErrors {
            cell_rms_m: (cells.0 / cells.1.max(1) as f64).sqrt(),
            distance_mean: e.iter().map(|x| x.0).sum::<f64>() / n,
            distance_max: e.iter().map(|x| x.0).fold(0.0, f64::max),
            gradient_mean: e.iter().map(|x| x.1).sum::<f64>() / n,
            gradient_max: e.iter().map(|x| x.1).fold(0.0, f64::max),
            measured: e.len(),
        }
    };
    Ok(DriveComparison {
        frames: drive.len(),
        single: summary(&e_single, c_single),
        fused: summary(&e_fused, c_fused),
    })
}

/// [`run_memory_drive`] as a Markdown section.
pub fn memory_drive_report(c: &DriveComparison, seed: u64) -> String {
    let mut s = String::new();
    let (toe, gradient) = DRIVE_RAMP;
    let _ = writeln!(s, "\n## Terrain memory on a noisy drive\n");
    let _ = writeln!(
        s,
        "A {}-frame drive (`sim::drive`, Kinect v1 noise, seed {seed}) toward a full-width \
         {gradient}° ramp whose toe starts {toe} m out, 3 cm per frame with exact odometry: each \
         frame analysed on its own, and fused with the terrain memory.\n",
        c.frames
    );
    let _ = writeln!(
        s,
        "| Analysis | Frames measured | Mean Δ distance mm | Largest Δ distance mm | Mean Δ gradient ° | Largest Δ gradient ° | Cell height RMS mm |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for (name, e) in [("single frames", c.single), ("terrain memory", c.fused)] {
        let _ = writeln!(
            s,
            "| {name} | {} | {:.2} | {:.2} | {:.4} | {:.4} | {:.2} |",
            e.measured,
            1000.0 * e.distance_mean,
            1000.0 * e.distance_max,
            e.gradient_mean,
            e.gradient_max,
            1000.0 * e.cell_rms_m
        );
    }
    let better = c.fused.distance_mean < c.single.distance_mean
        && c.fused.gradient_mean < c.single.gradient_mean;
    let quieter = c.fused.cell_rms_m < c.single.cell_rms_m;
    let _ = writeln!(
        s,
        "\nCell height RMS: the analysed cells' mean heights about the true ground, over the \
         cells wholly in view (not cut by the image's top edge) on planar ground (not \
         the fold at the toe).\n"
    );
    let _ = writeln!(
        s,
        "{}",
        match (better, quieter) {
            (true, _) =>
                "The terrain memory's averaging lowers the toe's distance and gradient errors \
                 as well as every cell's noise. It averages a cell's views only where the ground \
                 under it is a plane, in this view and the last: the memory re-bins each view \
                 at the place its points' centroid moved to, so two views of one cell cover \
                 different parts of it, and over a bend (the fold at the toe) their mean points \
                 lie on different chords. Averaged there, the fold cell alone made the fused \
                 errors larger than single frames'.",
            (false, true) =>
                "The terrain memory's averaging lowers the noise of every cell's height, but not \
                 the toe's distance and gradient errors: those are already under a millimetre \
                 and a few hundredths of a degree, and what is left is a bias, not a spread. \
                 The cell the toe falls in holds the fold between ground and face, and the \
                 memory blends views in which the fold lay at different places in it (the \
                 largest fused errors are in the frames where the toe lies 3-4 cm into a \
                 cell); and depth noise along the rays flattens a face slightly, the more the \
                 farther it is seen, while the memory averages each cell's views from a little \
                 farther back. Both stay far inside the noisy bars (3 cm, 1.5°).",
            (false, false) =>
                "The terrain memory does not lower the errors here: a single frame's face fit \
                 already averages hundreds of cells, and both stay far inside the noisy bars \
                 (3 cm, 1.5°).",
        }
    );
    s
}
