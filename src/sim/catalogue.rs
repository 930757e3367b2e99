use serde::{Deserialize, Serialize};

use super::terrain::{Element, Extent, Terrain};
use crate::verdict::{Decision, HazardKind};

/// How far a measure may be off and still pass.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tolerance {
    /// Distance, metres.
    pub distance_m: f64,
    /// Gradient, degrees.
    pub gradient_deg: f64,
    /// Alpha, degrees.
    pub alpha_deg: f64,
}

/// The bar on clean frames.
pub const CLEAN: Tolerance = Tolerance {
    distance_m: 0.01,
    gradient_deg: 0.5,
    alpha_deg: 1.0,
};
/// The bar with Kinect v1 noise.
pub const NOISY: Tolerance = Tolerance {
    distance_m: 0.03,
    gradient_deg: 1.5,
    alpha_deg: 3.0,
};

/// What a scene must give.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Expectation {
    /// The decision.
    pub verdict: Decision,
    /// The workcase (go only).
    #[serde(default)]
    pub workcase: Option<u8>,
    /// Distance to the toe line, metres.
    #[serde(default)]
    pub distance_m: Option<f64>,
    /// Gradient, degrees, negative downhill.
    #[serde(default)]
    pub gradient_deg: Option<f64>,
    /// Toe-line angle, degrees.
    #[serde(default)]
    pub alpha_deg: Option<f64>,
    /// The hazard that must decide a stop or unknown.
    #[serde(default)]
    pub hazard: Option<HazardKind>,
}

impl Expectation {
    /// Only the decision: no workcase, measure or deciding hazard named.
    pub fn decision(verdict: Decision) -> Self {
        Expectation {
            verdict,
            workcase: None,
            distance_m: None,
            gradient_deg: None,
            alpha_deg: None,
            hazard: None,
        }
    }
}

/// How a scene's frame is made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SceneConfig {
    /// The default config (the bar's camera: 640×480, 57°×43°, 0.8 m, pitched 30°).
    Default,
    /// The default config with the camera pitched 40° down, to see near toes.
    Pitch40,
}

/// One scene of the fixture suite.
#[derive(Debug, Clone)]
pub struct Scene {
    /// File stem.
    pub name: &'static str,
    /// What it shows.
    pub description: &'static str,
    /// Camera configuration.
    pub config: SceneConfig,
    /// The terrain; `None` for a synthetic frame (see `fill_mm`).
    pub terrain: Option<Terrain>,
    /// For frames that are not rendered: every pixel this depth (mm).
    pub fill_mm: u16,
    /// The expected verdict.
    pub expect: Expectation,
    /// Which row of the paper's Table 2 this scene reproduces.
    pub paper_case: Option<u8>,
    /// Also run with Kinect v1 noise, with this seed.
    pub noisy_seed: Option<u64>,
}

fn go(workcase: u8, d: Option<f64>, g: Option<f64>, a: Option<f64>) -> Expectation {
    Expectation {
        verdict: Decision::Go,
        workcase: Some(workcase),
        distance_m: d,
        gradient_deg: g,
        alpha_deg: a,
        hazard: None,
    }
}

fn halt(verdict: Decision, hazard: HazardKind) -> Expectation {
    Expectation {
        hazard: Some(hazard),
        ..Expectation::decision(verdict)
    }
}

/// The fixture suite: the ten workcases (the paper's four Table 2 cases among them),
/// the impassable cases, passable edge cases, a drop-off, and frames with no data,
/// sorted by name.
pub fn catalogue() -> Vec<Scene> {
    let mut v = [workcases(), passable_edges(), impassable(), no_data()].concat();
    v.sort_by_key(|s| s.name);
    v
}

/// Centre of a wheel track, metres.
const TRACK_CENTRE_M: f64 = 0.45;

/// A scene with the default rig, drawn without fill.
fn scene(
    name: &'static str,
    description: &'static str,
    terrain: Vec<Element>,
    expect: Expectation,
    noisy_seed: Option<u64>,
) -> Scene {
    Scene {
        name,
        description,
        config: SceneConfig::Default,
        terrain: Some(Terrain::new(terrain)),
        fill_mm: 0,
        expect,
        paper_case: None,
        noisy_seed,
    }
}

/// The ten workcases, the paper's Table 2 cases 2, 3, 4 and 8 among them.
fn workcases() -> Vec<Scene> {
    use Extent::{Full, Left, Right};
    let (ramp, tc) = (Element::ramp, TRACK_CENTRE_M);
    vec![
        scene("flat", "flat ground", vec![], go(1, None, None, None), Some(11)),
        Scene {
            paper_case: Some(2),
            ..scene(
                "uphill_straight",
                "paper Table 2 case 2: uphill straight, toe 0.675 m, 20°",
                vec![ramp(0.675, 0.0, 20.0, 0.0, Full)],
                go(2, Some(0.675), Some(20.0), None),
                Some(12),
            )
        },
        Scene {
            paper_case: Some(3),
            config: SceneConfig::Pitch40,
            ..scene(
                "uphill_left",
                "paper Table 2 case 3: uphill on the left side only, toe 0.474 m, 20° (camera pitched 40° to see the toe)",
                vec![ramp(0.474, tc, 20.0, 0.0, Left)],
                go(3, Some(0.474), Some(20.0), None),
                Some(13),
            )
        },
        Scene {
            paper_case: Some(4),
            ..scene(
                "diagonal_left",
                "paper Table 2 case 4: uphill diagonally on the left side, alpha −26°, 20°, toe 1.0 m at the left track's centre",
                vec![ramp(1.0, tc, 20.0, -26.0, Left)],
                go(4, Some(1.0), Some(20.0), Some(-26.0)),
                Some(14),
            )
        },
        scene(
            "uphill_right",
            "uphill on the right side only, toe 1.2 m, 15°",
            vec![ramp(1.2, -tc, 15.0, 0.0, Right)],
            go(5, Some(1.2), Some(15.0), None),
            Some(15),
        ),
        scene(
            "diagonal_right",
            "uphill diagonally on the right side, alpha 20°, 18°, toe 1.1 m",
            vec![ramp(1.1, -tc, 18.0, 20.0, Right)],
            go(6, Some(1.1), Some(18.0), Some(20.0)),
            Some(16),
        ),
        scene(
            "diagonal_full",
            "uphill diagonally across the full width, alpha 25°, 15°, toe 1.3 m on the centre line",
            vec![ramp(1.3, 0.0, 15.0, 25.0, Full)],
            go(7, Some(1.3), Some(15.0), Some(25.0)),
            Some(17),
        ),
        Scene {
            paper_case: Some(8),
            ..scene(
                "downhill_straight",
                "paper Table 2 case 8: downhill straight, toe 1.295 m, −11.5°",
                vec![ramp(1.295, 0.0, -11.5, 0.0, Full)],
                go(8, Some(1.295), Some(-11.5), None),
                Some(18),
            )
        },
        scene(
            "downhill_left",
            "downhill on the left side only, toe 1.4 m, −10°",
            vec![ramp(1.4, tc, -10.0, 0.0, Left)],
            go(9, Some(1.4), Some(-10.0), None),
            Some(19),
        ),
        scene(
            "downhill_right",
            "downhill on the right side only, toe 1.1 m, −14°",
            vec![ramp(1.1, -tc, -14.0, 0.0, Right)],
            go(10, Some(1.1), Some(-14.0), None),
            Some(20),
        ),
    ]
}

/// Passable edge cases: the steepest ramp, highest step and belly rock still go.
fn passable_edges() -> Vec<Scene> {
    use Extent::Full;
    let ramp = Element::ramp;
    vec![
        scene(
            "ramp_25deg",
            "passable edge: a 25° ramp across the full width, toe 1.0 m",
            vec![ramp(1.0, 0.0, 25.0, 0.0, Full)],
            go(2, Some(1.0), Some(25.0), None),
            Some(21),
        ),
        scene(
            "step_8cm",
            "passable edge: a 0.08 m step across the full width at 1.3 m",
            vec![Element::Step {
                x_m: 1.3,
                height_m: 0.08,
                extent: Full,
            }],
            go(2, Some(1.3), None, None),
            Some(22),
        ),
        scene(
            "belly_rock_20cm",
            "passable edge: a 0.20 m rock under the belly at 1.4 m",
            vec![Element::Rock {
                x_m: 1.4,
                y_m: 0.0,
                radius_m: 0.17,
                height_m: 0.20,
            }],
            go(1, None, None, None),
            Some(23),
        ),
    ]
}

/// Impassable cases: each stops with its hazard.
fn impassable() -> Vec<Scene> {
    use Extent::{Full, Left};
    let (ramp, tc) = (Element::ramp, TRACK_CENTRE_M);
    vec![
        scene(
            "slope_35deg",
            "impassable: a 35° ramp across the full width, toe 1.2 m",
            vec![ramp(1.2, 0.0, 35.0, 0.0, Full)],
            halt(Decision::Stop, HazardKind::Slope),
            Some(24),
        ),
        scene(
            "slope_32deg_left",
            "impassable: a 32° ramp in the left track only, toe 1.5 m",
            vec![ramp(1.5, tc, 32.0, 0.0, Left)],
            halt(Decision::Stop, HazardKind::Slope),
            None,
        ),
        scene(
            "step_15cm",
            "impassable: a 0.15 m step across the full width at 1.3 m",
            vec![Element::Step {
                x_m: 1.3,
                height_m: 0.15,
                extent: Full,
            }],
            halt(Decision::Stop, HazardKind::Step),
            Some(25),
        ),
        scene(
            "track_block",
            "impassable: a 0.2 m block in the right track at 1.6 m",
            vec![Element::Block {
                x_m: 1.6,
                y_m: -0.45,
                length_m: 0.3,
                width_m: 0.3,
                height_m: 0.2,
            }],
            halt(Decision::Stop, HazardKind::Step),
            None,
        ),
        scene(
            "belly_block_40cm",
            "impassable: a 0.40 m block under the belly at 1.5 m",
            vec![Element::Block {
                x_m: 1.5,
                y_m: 0.0,
                length_m: 0.3,
                width_m: 0.3,
                height_m: 0.40,
            }],
            halt(Decision::Stop, HazardKind::Belly),
            Some(26),
        ),
        scene(
            "drop_off",
            "impassable: the ground ends at 1.6 m and falls 1 m",
            vec![Element::DropOff {
                x_m: 1.6,
                depth_m: 1.0,
            }],
            halt(Decision::Stop, HazardKind::DropOff),
            Some(27),
        ),
    ]
}

/// Frames with no usable data: unknown.
fn no_data() -> Vec<Scene> {
    vec![
        Scene {
            terrain: None,
            fill_mm: 0,
            ..scene(
                "all_zero",
                "no data: every pixel 0",
                vec![],
                halt(Decision::Unknown, HazardKind::Unknown),
                None,
            )
        },
        Scene {
            terrain: None,
            fill_mm: 9000,
            ..scene(
                "all_out_of_range",
                "no usable data: every pixel beyond the maximum range",
                vec![],
                halt(Decision::Unknown, HazardKind::Unknown),
                None,
            )
        },
    ]
}
