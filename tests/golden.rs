//! The committed fixture suite against the expected verdicts stored beside each frame,
//! with the tolerances stored there (the bars: clean 1 cm / 0.5° / 1°, Kinect
//! noise 3 cm / 1.5° / 3°).

use std::collections::BTreeSet;
use std::path::Path;

use rover_terrain::validate::{self, CLEAN, NOISY};
use rover_terrain::{Decision, HazardKind};

fn suite() -> Vec<validate::CaseResult> {
    validate::run_suite(&Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures")).unwrap()
}

#[test]
fn every_fixture_meets_its_expected_verdict() {
    let results = suite();
    let failed: Vec<String> = results
        .iter()
        .filter(|r| !r.passed())
        .map(|r| format!("{}: {}", r.name, r.failures.join("; ")))
        .collect();
    assert!(failed.is_empty(), "{failed:#?}");
}

#[test]
fn the_suite_covers_every_workcase_and_hazard_clean_and_noisy() {
    let results = suite();
    for noisy in [false, true] {
        let workcases: BTreeSet<u8> = results
            .iter()
            .filter(|r| r.fixture.noise.is_some() == noisy)
            .filter_map(|r| r.fixture.expected.workcase)
            .collect();
        assert_eq!(workcases, (1..=10).collect(), "noisy = {noisy}");
    }
    let hazards: BTreeSet<String> = results
        .iter()
        .filter_map(|r| r.fixture.expected.hazard)
        .map(|h| format!("{h:?}"))
        .collect();
    for k in [
        HazardKind::Slope,
        HazardKind::Step,
        HazardKind::Belly,
        HazardKind::DropOff,
        HazardKind::Unknown,
    ] {
        assert!(hazards.contains(&format!("{k:?}")), "no fixture for {k:?}");
    }
    // Tolerances are the bars, not looser.
    for r in &results {
        let bar = if r.fixture.noise.is_some() {
            NOISY
        } else {
            CLEAN
        };
        assert!(
            r.fixture.tolerance.distance_m <= bar.distance_m,
            "{}",
            r.name
        );
        assert!(
            r.fixture.tolerance.gradient_deg <= bar.gradient_deg,
            "{}",
            r.name
        );
        assert!(r.fixture.tolerance.alpha_deg <= bar.alpha_deg, "{}", r.name);
    }
}

#[test]
fn clean_paper_cases_beat_the_papers_table_2() {
    let results = suite();
    for (case, name, actual, _paper, paper_err) in validate::PAPER_TABLE_2 {
        let r = results
            .iter()
            .find(|r| r.fixture.paper_case == Some(case) && r.fixture.noise.is_none())
            .unwrap_or_else(|| panic!("no clean fixture for paper case {case}"));
        let f = r.got.feature.expect("paper cases are passable");
        let got = match name {
            "distance_m" => f.distance_m,
            "gradient_deg" => f.gradient_deg,
            _ => f.alpha_deg,
        }
        .expect("measure present");
        let err = (f64::from(got) - actual).abs() / actual.abs() * 100.0;
        assert!(
            err < paper_err,
            "case {case} {name}: {err:.4} % vs paper {paper_err} %"
        );
    }
}

#[test]
fn frames_with_no_usable_data_are_never_go() {
    for r in suite() {
        if r.got.points_binned == 0 {
            assert_eq!(r.got.decision, Decision::Unknown, "{}", r.name);
        }
    }
}

#[test]
fn committed_frames_are_what_the_renderer_makes() {
    // The fixtures are reproducible from the scene catalogue (spot-check two).
    let dir = tempfile::tempdir().unwrap();
    validate::write_fixtures(dir.path()).unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    for f in [
        "scenes/diagonal_left.png",
        "pitch40/uphill_left.png",
        "scenes/drop_off.fixture.toml",
    ] {
        let a = std::fs::read(root.join(f)).unwrap();
        let b = std::fs::read(dir.path().join(f)).unwrap();
        assert!(
            a == b,
            "{f} differs from a fresh render: run `rover-terrain render-fixtures`"
        );
    }
}
