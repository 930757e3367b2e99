//! Families of random scenes beyond the catalogue, each drawn with random geometry
//! and, optionally, a random camera and mount: one-track ramps with vertical side
//! faces, ramps that rise out of the image, ground falling away beside a track, toes
//! in the blind zone, rough ground with rock fields, combinations. Each draw carries
//! the config to render and analyse it with and the verdict it must give.
//!
//! Expectations are stated from the geometry alone (the rover's limits and the
//! drawn terrain), never from what the analysis happens to output. Where the camera
//! cannot see a feature at all (the toe of a ramp below the image), the draw is kept
//! inside what the rig sees, so that the expectation stays decidable.

use nalgebra::Vector3;
use rand::Rng;

use super::catalogue::Expectation;
use super::terrain::{Element, Extent, StoneShape, Terrain};
use super::{Tolerance, CLEAN, NOISY};
use crate::config::Config;
use crate::projection::Projector;
use crate::verdict::{Decision, HazardKind};

/// A family of random scenes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// A climbable ramp (15-25°) under one wheel track only, straight or diagonal,
    /// with vertical side faces along the track's edges; unbounded or capped.
    OneTrackRamp,
    /// A climbable ramp across the full width that rises out of the top of the image
    /// before the corridor ends.
    RampOutOfView,
    /// The ground beyond one track's inner edge (a half-plane) falls away at 10-15°.
    HalfPlaneDescent,
    /// A descent (8-15°, 0.12-0.25 m deep) under one wheel track only: a trench
    /// with side faces.
    OneTrackDescent,
    /// Rough ground (±2.5 cm, correlation 10-20 cm), otherwise flat.
    RoughFlat,
    /// Rough ground under a full-width ramp or descent: the workcase and measures
    /// within the rough-ground tolerance.
    RoughRamp,
    /// Pebbles and rocks of 4-9 cm in the tracks, on rough ground: go.
    RockField,
    /// The same, with one rock of 15-20 cm in a track among them: stop.
    RockFieldWithBoulder,
    /// A rock under the belly: 0.22-0.27 m go, 0.37-0.45 m stop.
    BellyRock,
    /// A different climbable ramp under each track: go, the nearer one reported.
    TwoRamps,
    /// A rock on a full-width ramp: a 4-8 cm pebble is go, a 15-20 cm rock stop.
    RockOnRamp,
    /// A rock on a full-width descent (10-18° down): a 3-6 cm pebble is go, a 15-20 cm
    /// rock stop. The pebble's back and the descent fall together.
    RockOnDescent,
    /// A rock under the belly while one track climbs a straight ramp beside it: the
    /// body rolls, and its belly rests on the line between the tracks. Go or stop by
    /// a hand calculation of the belly's clearance over the rock
    /// (`belly_margin`), at least 5 cm either way.
    BellyRockBesideRamp,
}

impl Family {
    /// Every family, in report order.
    pub const ALL: [Family; 11] = [
        Family::OneTrackRamp,
        Family::RampOutOfView,
        Family::HalfPlaneDescent,
        Family::OneTrackDescent,
        Family::RoughFlat,
        Family::RoughRamp,
        Family::RockField,
        Family::RockFieldWithBoulder,
        Family::BellyRock,
        Family::TwoRamps,
        Family::RockOnRamp,
    ];

    /// Families added after [`Family::ALL`]'s sweeps were measured, drawn when asked
    /// for by index (after ALL's: [`Family::by_index`]) and in the validation report
    /// after ALL's, so that a sweep over ALL draws what it drew before.
    pub const LATER: [Family; 2] = [Family::BellyRockBesideRamp, Family::RockOnDescent];

    /// Family `k`: [`Family::ALL`]'s, then [`Family::LATER`]'s; `None` past them.
    pub fn by_index(k: usize) -> Option<Family> {
        Family::ALL
            .get(k)
            .or_else(|| Family::LATER.get(k.checked_sub(Family::ALL.len())?))
            .copied()
    }

    /// The families of natural ground: rough ground and rocks, the ones
    /// [`restyled`] draws another way.
    pub const NATURAL: [Family; 6] = [
        Family::RoughFlat,
        Family::RoughRamp,
        Family::RockField,
        Family::RockFieldWithBoulder,
        Family::BellyRock,
        Family::RockOnRamp,
    ];

    /// The families whose terrain has bands with vertical sides (a one-track ramp or
    /// descent, ground falling away beside a track, a ramp under each track): the ones
    /// [`bevelled`] draws another way.
    pub const BANDED: [Family; 4] = [
        Family::OneTrackRamp,
        Family::HalfPlaneDescent,
        Family::OneTrackDescent,
        Family::TwoRamps,
    ];

    /// The families with a ramp or a descent (its toe a straight line): the ones
    /// [`rounded`] draws another way.
    pub const RAMPED: [Family; 7] = [
        Family::OneTrackRamp,
        Family::RampOutOfView,
        Family::HalfPlaneDescent,
        Family::OneTrackDescent,
        Family::RoughRamp,
        Family::TwoRamps,
        Family::RockOnRamp,
    ];

    /// A short name for reports.
    pub fn name(self) -> &'static str {
        match self {
            Family::OneTrackRamp => "one-track ramp",
            Family::RampOutOfView => "ramp out of view",
            Family::HalfPlaneDescent => "half-plane descent",
            Family::OneTrackDescent => "one-track descent",
            Family::RoughFlat => "rough ground",
            Family::RoughRamp => "rough ramp",
            Family::RockField => "rock field",
            Family::RockFieldWithBoulder => "rock field + boulder",
            Family::BellyRock => "belly rock",
            Family::TwoRamps => "two ramps",
            Family::RockOnRamp => "rock on ramp",
            Family::BellyRockBesideRamp => "belly rock beside a ramp",
            Family::RockOnDescent => "rock on descent",
        }
    }
}

/// The camera models the random rigs draw from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CameraModel {
    /// Kinect v1: 640×480, 57°×43° (the paper's).
    KinectV1,
    /// Kinect v2: 512×424, 70.6°×60°.
    KinectV2,
    /// A RealSense D435-like pinhole: 848×480, fx ≈ fy ≈ 425, principal point off
    /// centre.
    D435,
    /// A 320×240 camera with the Kinect v1's field of view.
    Qvga,
}

/// Where the camera sits and what it is: a [`Config`] with the rover's defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct Rig {
    /// The camera model.
    pub camera: CameraModel,
    /// The config to render and analyse with.
    pub config: Config,
}

impl Rig {
    /// The default rig: Kinect v1, 0.8 m high, pitched 30° down.
    pub fn default_rig() -> Rig {
        Rig {
            camera: CameraModel::KinectV1,
            config: Config::default(),
        }
    }

    /// A random rig: mount 0.5-1.2 m high, pitched 15-45° down, rolled and yawed
    /// within ±10°, offset up to 0.3 m forward and ±0.1 m sideways; one of the four
    /// camera models; minimum range 0.3-0.5 m. Redrawn until the camera sees the
    /// tracks on flat ground from at most 1.3 m to at least 2.0 m ahead, so that
    /// features drawn in that span are in view.
    pub fn random<R: Rng>(rng: &mut R) -> Rig {
        loop {
            let mut c = Config::default();
            let camera = match rng.gen_range(0..4) {
                0 => CameraModel::KinectV1,
                1 => CameraModel::KinectV2,
                2 => CameraModel::D435,
                _ => CameraModel::Qvga,
            };
            match camera {
                CameraModel::KinectV1 => {}
                CameraModel::KinectV2 => {
                    c.camera.width = 512;
                    c.camera.height = 424;
                    c.camera.hfov_deg = 70.6;
                    c.camera.vfov_deg = 60.0;
                }
                CameraModel::D435 => {
                    c.camera.width = 848;
                    c.camera.height = 480;
                    let f = rng.gen_range(415.0..435.0);
                    c.camera.fx = Some(f);
                    c.camera.fy = Some(f + rng.gen_range(-2.0..2.0));
                    c.camera.cx = Some(424.0 + rng.gen_range(-20.0..20.0));
                    c.camera.cy = Some(240.0 + rng.gen_range(-15.0..15.0));
                    // hfov/vfov are unused with intrinsics; keep them consistent.
                    c.camera.hfov_deg = 2.0 * (424.0 / f).atan().to_degrees();
                    c.camera.vfov_deg = 2.0 * (240.0 / f).atan().to_degrees();
                }
                CameraModel::Qvga => {
                    c.camera.width = 320;
                    c.camera.height = 240;
                }
            }
            c.camera.min_range_m = rng.gen_range(0.3..0.5);
            c.mount.z_m = rng.gen_range(0.5..1.2);
            c.mount.pitch_deg = rng.gen_range(15.0..45.0);
            c.mount.roll_deg = rng.gen_range(-10.0..10.0);
            c.mount.yaw_deg = rng.gen_range(-10.0..10.0);
            c.mount.x_m = rng.gen_range(0.0..0.3);
            c.mount.y_m = rng.gen_range(-0.1..0.1);
            let (near, far) = footprint(&c);
            if near <= 1.3 && far >= 2.0 {
                return Rig { camera, config: c };
            }
        }
    }
}

/// The forward span in which the camera sees flat ground under both wheel tracks'
/// centres (the nearest and farthest x seen at y = ±0.45 m), metres. Computed by
/// projecting ground points: the span where both points are inside the image and
/// the range limits.
pub fn footprint(config: &Config) -> (f64, f64) {
    let p = Projector::new(
        config,
        config.camera.width as usize,
        config.camera.height as usize,
    );
    let tc = config.rover.track_centre_m();
    let visible = |x: f64| {
        [tc, -tc]
            .iter()
            .all(|&y| in_view(&p, config, Vector3::new(x, y, 0.0), 0.05))
    };
    let xs: Vec<f64> = (0..=600)
        .map(|i| i as f64 * 0.01)
        .filter(|&x| visible(x))
        .collect();
    match (xs.first(), xs.last()) {
        (Some(&a), Some(&b)) => (a, b),
        _ => (f64::INFINITY, f64::NEG_INFINITY),
    }
}

/// Whether `p`, `config`'s camera, sees point `at` (rover frame, metres): it projects
/// inside the image, and its depth lies within the range limits, `margin_m` clear of
/// both.
pub(crate) fn in_view(p: &Projector, config: &Config, at: Vector3<f64>, margin_m: f64) -> bool {
    p.project(at).is_some_and(|(u, v, d)| {
        p.in_image(u, v)
            && d >= config.camera.min_range_m + margin_m
            && d <= config.camera.max_range_m - margin_m
    })
}

/// Whether a rig that sees flat ground up to `end` metres (`footprint`) stops seeing
/// it at least 0.1 m before the corridor's end: a ramp placed there rises out of the
/// image, not out of the corridor.
pub fn view_ends_in_corridor(end: f64, config: &Config) -> bool {
    end <= config.analysis.corridor_length_m - 0.1
}

/// A ramp on rough ground whose toe lies 0.3-0.7 m before the far end of what
/// `config`'s rig sees of flat ground (`footprint`), so that the view ends on its
/// first decimetres: half the time climbable (12-25°), half steeper than the default
/// rover climbs (31.5-40°); under the left track, the right one or both; on plane-wave
/// or value-noise ground (±2.5 cm, correlation 10-20 cm). Returns the terrain and
/// whether the ramp is the steep kind; `None` (drawing nothing) when the rig sees
/// flat ground to within 0.1 m of the corridor's end, where the ramp would leave the
/// corridor before the image.
pub fn rough_ramp_at_view_end<R: Rng>(rng: &mut R, config: &Config) -> Option<(Terrain, bool)> {
    let (_, end) = footprint(config);
    if !view_ends_in_corridor(end, config) {
        return None;
    }
    let steep = rng.gen_bool(0.5);
    let toe = rng.gen_range(end - 0.7..end - 0.3);
    let gradient = if steep {
        rng.gen_range(31.5..40.0)
    } else {
        rng.gen_range(12.0..25.0)
    };
    let (correlation_m, seed) = (rng.gen_range(0.1..0.2), rng.gen());
    let ground = if rng.gen_bool(0.5) {
        Element::Rough {
            amplitude_m: 0.025,
            correlation_m,
            seed,
        }
    } else {
        Element::Lumpy {
            amplitude_m: 0.025,
            spacing_m: correlation_m,
            seed,
        }
    };
    let extent = [Extent::Left, Extent::Right, Extent::Full][rng.gen_range(0..3)];
    let ramp = Element::ramp(toe, 0.0, gradient, 0.0, extent);
    Some((Terrain::new(vec![ground, ramp]), steep))
}

/// The least angle, degrees, at which the camera's lines of sight meet `terrain`'s
/// surface under the wheel tracks (|y| from the belly's edge to the track's outer
/// edge, 1 cm clear of both) from the rover's front to the corridor's end, over the
/// points that fall inside the image and the range limits. Negative where the surface
/// faces away from the camera: a descent steeper than the line of sight to it, which
/// no camera sees however fine its pixels. A hand calculation on the drawn terrain
/// (the surface's normal from its height, the camera's place from the mount), so a
/// sweep can tell a descent its camera could not see from one the analysis missed;
/// it ignores what else stands in the way (a track's side walls), so it never
/// excuses more than the surface's own slope hides.
pub fn least_incidence_deg(terrain: &Terrain, config: &Config) -> f64 {
    let p = Projector::new(
        config,
        config.camera.width as usize,
        config.camera.height as usize,
    );
    let o = p.origin();
    let cam = Vector3::new(f64::from(o[0]), f64::from(o[1]), f64::from(o[2]));
    let (inner, outer) = (
        config.rover.belly_half_width_m + 0.01,
        config.rover.track_outer_m - 0.01,
    );
    let field = terrain.field();
    let eps = 1e-3;
    let mut least = f64::INFINITY;
    let steps_y = ((outer - inner) / 0.025).ceil() as usize;
    let steps_x = (config.analysis.corridor_length_m / 0.025).ceil() as usize;
    for side in [1.0, -1.0] {
        for j in 0..=steps_y {
            let y = side * (inner + (outer - inner) * j as f64 / steps_y as f64);
            for i in 0..=steps_x {
                let x = i as f64 * 0.025;
                let z = field.height(x, y);
                let at = Vector3::new(x, y, z);
                if !in_view(&p, config, at, 0.0) {
                    continue;
                }
                let zx = (field.height(x + eps, y) - field.height(x - eps, y)) / (2.0 * eps);
                let zy = (field.height(x, y + eps) - field.height(x, y - eps)) / (2.0 * eps);
                let normal = Vector3::new(-zx, -zy, 1.0).normalize();
                let to_cam = (cam - at).normalize();
                least = least.min(normal.dot(&to_cam).asin().to_degrees());
            }
        }
    }
    least
}

/// The plane of the rendered surface itself under a straight full-width ramp or
/// descent: the least-squares line `z = a·x + c` through `terrain`'s heights on a
/// 1 cm lattice over both wheel tracks (|y| from the belly's edge to the track's outer
/// edge), from `near` to `far` metres out. Returns where it meets the ground (z = 0,
/// metres out) and its gradient (degrees, negative downhill); `None` when the span
/// holds no lattice point or the line is level.
///
/// A hand calculation on the drawn terrain, no sensor: on rough ground the surface is
/// not the drawn ramp (bumps 10-20 cm long move the plane of a metre of face by
/// centimetres), and no fit to what the camera sees can come nearer the drawn ramp
/// than the surface it sees. Tests and `examples/surface_fit.rs` measure the analysis
/// against this plane as well as against the drawn one.
pub fn surface_toe(terrain: &Terrain, config: &Config, near: f64, far: f64) -> Option<(f64, f64)> {
    let (inner, outer) = (config.rover.belly_half_width_m, config.rover.track_outer_m);
    let field = terrain.field();
    let (mut sx, mut sz, mut sxx, mut sxz, mut m) = (0.0, 0.0, 0.0, 0.0, 0.0);
    // `max(-1.0)`: a NaN span (a NaN `far`) gives −1 columns, none, where `as i64`
    // alone would make it 0 and fit one column of NaN heights.
    let steps_x = ((far - near) / 0.01).floor().max(-1.0) as i64;
    let steps_y = ((outer - inner) / 0.01).ceil() as i64;
    for i in 0..=steps_x {
        let x = near + i as f64 * 0.01;
        for j in 0..steps_y {
            let y = inner + j as f64 * 0.01;
            for y in [y, -y] {
                let z = field.height(x, y);
                (sx, sz, sxx, sxz, m) = (sx + x, sz + z, sxx + x * x, sxz + x * z, m + 1.0);
            }
        }
    }
    let det = m * sxx - sx * sx;
    if m < 3.0 || det.abs() < 1e-12 {
        return None;
    }
    let a = (m * sxz - sx * sz) / det;
    let c = (sz - a * sx) / m;
    (a.abs() > 1e-9).then(|| (-c / a, a.atan().to_degrees()))
}

/// Where a random rig's one frame can judge an edge on both tracks, metres: from the
/// [`footprint`]'s near end (not nearer than 0.9 m) to 0.15 m before its far end (not
/// past 2.4 m). A hazard past the view is not one frame's to judge; one below the
/// image is the terrain memory's.
pub fn judged_span(config: &Config) -> std::ops::Range<f64> {
    let (near, far) = footprint(config);
    let lo = near.max(0.9);
    lo..(far - 0.15).min(2.4).max(lo + 0.05)
}

/// One drawn scene.
#[derive(Debug, Clone)]
pub struct Draw {
    /// The family it was drawn from.
    pub family: Family,
    /// The terrain.
    pub terrain: Terrain,
    /// The rig.
    pub rig: Rig,
    /// The verdict it must give.
    pub expect: Expectation,
    /// How far its measures may be off, clean and with Kinect v1 noise.
    pub tolerance: (Tolerance, Tolerance),
}

/// The bar on rough ground (the issue's: 4 cm and 2°), clean or noisy.
pub const ROUGH: Tolerance = Tolerance {
    distance_m: 0.04,
    gradient_deg: 2.0,
    alpha_deg: 3.0,
};

fn go(wc: u8, d: Option<f64>, g: Option<f64>, a: Option<f64>) -> Expectation {
    Expectation {
        verdict: Decision::Go,
        workcase: Some(wc),
        distance_m: d,
        gradient_deg: g,
        alpha_deg: a,
        hazard: None,
    }
}

fn stop(hazard: HazardKind) -> Expectation {
    Expectation {
        hazard: Some(hazard),
        ..Expectation::decision(Decision::Stop)
    }
}

fn stop_any() -> Expectation {
    Expectation::decision(Decision::Stop)
}

fn go_any() -> Expectation {
    Expectation::decision(Decision::Go)
}

fn rough<R: Rng>(rng: &mut R) -> Element {
    Element::Rough {
        amplitude_m: 0.025,
        correlation_m: rng.gen_range(0.1..0.2),
        seed: rng.gen(),
    }
}

/// A toe-line angle: straight (|alpha| ≤ 3°) or clearly diagonal (11-26° either
/// way), so that the straight/diagonal split (8° by default) is never a coin toss.
fn toe_angle<R: Rng>(rng: &mut R) -> f64 {
    if rng.gen_bool(0.4) {
        rng.gen_range(-3.0..3.0)
    } else {
        rng.gen_range(11.0..26.0) * if rng.gen_bool(0.5) { 1.0 } else { -1.0 }
    }
}

/// Scatter up to `n` rocks of `h.0..h.1` metres high in the wheel tracks between
/// `x.0` and `x.1`, each with a ground radius of 1.2-2× its height, none touching
/// another (heights add up in the renderer: two touching pebbles would make a rock).
fn rocks<R: Rng>(rng: &mut R, n: usize, h: (f64, f64), x: (f64, f64)) -> Vec<Element> {
    let mut out: Vec<(f64, f64, f64)> = Vec::new();
    let mut elements = Vec::new();
    for _ in 0..n * 20 {
        if elements.len() == n {
            break;
        }
        let height_m = rng.gen_range(h.0..h.1);
        let side = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        let (x_m, y_m) = (rng.gen_range(x.0..x.1), side * rng.gen_range(0.27..0.63));
        let radius_m = height_m * rng.gen_range(1.2..2.0);
        if out
            .iter()
            .any(|&(px, py, pr)| (px - x_m).hypot(py - y_m) < pr + radius_m + 0.02)
        {
            continue;
        }
        out.push((x_m, y_m, radius_m));
        elements.push(Element::Rock {
            x_m,
            y_m,
            radius_m,
            height_m,
        });
    }
    elements
}

/// `d` drawn another way, as a renderer other than ours might: each rough field
/// becomes value noise of the same amplitude on a lattice as fine as its correlation
/// length ([`Element::Lumpy`], steeper bumps than the plane waves'), each rock a
/// stone of a random shape ([`StoneShape`]: cone, spherical cap, Gaussian mound,
/// boulder) on the same footprint and of the same height. The expectation stands:
/// it is stated from the heights and sizes, which do not change.
pub fn restyled<R: Rng>(rng: &mut R, mut d: Draw) -> Draw {
    for e in &mut d.terrain.elements {
        *e = match *e {
            Element::Rough {
                amplitude_m,
                correlation_m,
                seed,
            } => Element::Lumpy {
                amplitude_m,
                spacing_m: correlation_m,
                seed,
            },
            Element::Rock {
                x_m,
                y_m,
                radius_m,
                height_m,
            } => Element::Stone {
                x_m,
                y_m,
                radius_m,
                height_m,
                shape: StoneShape::ALL[rng.gen_range(0..StoneShape::ALL.len())],
            },
            ref other => other.clone(),
        };
    }
    d
}

/// `d` with every band's vertical sides drawn sloping, as a renderer other than ours
/// might ([`Extent::Bevelled`]): a one-track ramp's or descent's side face, the edge
/// of ground falling away beside a track, each fades over 2-15 cm centred on the
/// band's edge, as a height map sampled that far apart and interpolated draws them.
/// The expectation stands: the tracks' ground and the rover's limits do not change.
pub fn bevelled<R: Rng>(rng: &mut R, mut d: Draw) -> Draw {
    for e in &mut d.terrain.elements {
        if let Element::Ramp { extent, .. } | Element::Step { extent, .. } = e {
            if let Extent::Band { from_m, to_m } = *extent {
                *extent = Extent::Bevelled {
                    from_m,
                    to_m,
                    side_m: rng.gen_range(0.02..0.15),
                };
            }
        }
    }
    d
}

/// `d` with each band under one side drawn wider than the wheel track, as a scene
/// drawn without our band edges in mind might: its inner edge 0-15 cm into the
/// belly band (0-75 % of the belly's half width, so that two ramps never meet), a
/// one-track band's outer edge 0-40 cm past the track's. A face along the band's edge
/// then stands inside the belly band, and the belly band's strips beside it lie on
/// the ramp the track climbs (or in the trench it dips into). The expectation
/// stands: the track's ground is the band's own, and the belly band sits over the
/// same surface as the track beside it, a ramp's part of it at most a third of the
/// ramp's height above the line between the two tracks.
pub fn widened<R: Rng>(rng: &mut R, mut d: Draw) -> Draw {
    let bhw = d.rig.config.rover.belly_half_width_m;
    for e in &mut d.terrain.elements {
        if let Element::Ramp { extent, .. } | Element::Step { extent, .. } = e {
            if let Extent::Band { from_m, to_m } = extent {
                // Both drawn for every band, so the stream does not depend on the scene.
                let inward = rng.gen_range(0.0..0.75 * bhw);
                let outward = rng.gen_range(0.0..0.4);
                let far = |v: f64| v.abs() > 50.0;
                if (*from_m - bhw).abs() < 1e-9 {
                    *from_m -= inward;
                    if !far(*to_m) {
                        *to_m += outward;
                    }
                } else if (*to_m + bhw).abs() < 1e-9 {
                    *to_m += inward;
                    if !far(*from_m) {
                        *from_m -= outward;
                    }
                }
            }
        }
    }
    d
}

/// Most length over which [`rounded`] rounds a ramp's toe, metres.
pub const MAX_TOE_ROUNDING_M: f64 = 0.4;

/// `d` with every ramp's toe rounded, as terrain is and a renderer other than ours
/// might draw it: over 0.05-[`MAX_TOE_ROUNDING_M`] across the toe line, a parabola
/// tangent to the ground before and to the face after ([`super::toe_rounding`]).
/// The face and the ground still meet at the drawn toe line, so the expectation
/// stands: the paper's toe is where the two planes meet. The face rises (or falls)
/// from up to 0.2 m before it, gently.
pub fn rounded<R: Rng>(rng: &mut R, mut d: Draw) -> Draw {
    for e in &mut d.terrain.elements {
        if matches!(e, Element::Ramp { .. }) {
            *e = e
                .clone()
                .toe_rounded(Some(rng.gen_range(0.05..MAX_TOE_ROUNDING_M)));
        }
    }
    d
}

/// Draw a scene of `family` on `rig`.
pub fn draw<R: Rng>(rng: &mut R, family: Family, rig: Rig) -> Draw {
    let at = Setting::new(rng, &rig.config);
    let (elements, expect) = match family {
        Family::OneTrackRamp => one_track_ramp(rng, &at),
        Family::RampOutOfView => ramp_out_of_view(rng, &at),
        Family::HalfPlaneDescent => half_plane_descent(rng, &at),
        Family::OneTrackDescent => one_track_descent(rng, &at),
        Family::RoughFlat => rough_flat(rng, &at),
        Family::RoughRamp => rough_ramp(rng, &at),
        Family::RockField => rock_field(rng, &at),
        Family::RockFieldWithBoulder => rock_field_with_boulder(rng, &at),
        Family::BellyRock => belly_rock(rng, &at),
        Family::TwoRamps => two_ramps(rng, &at),
        Family::RockOnRamp => rock_on_slope(rng, &at, 1.0),
        Family::RockOnDescent => rock_on_slope(rng, &at, -1.0),
        Family::BellyRockBesideRamp => belly_rock_beside_ramp(rng, &at),
    };
    let rough_ground = elements
        .iter()
        .any(|e| matches!(e, Element::Rough { amplitude_m, .. } if *amplitude_m > 0.015))
        || matches!(family, Family::RockOnRamp | Family::RockOnDescent);
    Draw {
        family,
        terrain: Terrain::new(elements),
        rig,
        expect,
        tolerance: if rough_ground {
            (ROUGH, ROUGH)
        } else {
            (CLEAN, NOISY)
        },
    }
}

/// A family's scene: its terrain and what the analysis must make of it.
type Scene = (Vec<Element>, Expectation);

/// What every family draws in: the rig's corridor and footprint, and the side
/// (left or right) drawn for one-sided scenes.
struct Setting {
    /// Centre line of the left track, metres (the right one's is its mirror).
    tc: f64,
    belly_half_width: f64,
    track_outer: f64,
    /// Nearest and farthest ground the rig sees, metres.
    near: f64,
    far: f64,
    /// Toes where the rig sees the ground, or just below the image's bottom edge.
    toe_span: (f64, f64),
    /// Whether one-sided scenes go on the left, and its sign (+1 left, −1 right).
    left: bool,
    s: f64,
    diagonal_min_deg: f64,
    /// The rover's belly clearance, metres.
    clearance: f64,
}

impl Setting {
    fn new<R: Rng>(rng: &mut R, config: &Config) -> Self {
        let (bhw, outer) = (config.rover.belly_half_width_m, config.rover.track_outer_m);
        let (near, far) = footprint(config);
        let left = rng.gen_bool(0.5);
        Setting {
            tc: 0.5 * (bhw + outer),
            belly_half_width: bhw,
            track_outer: outer,
            near,
            far,
            toe_span: ((near - 0.15).max(0.45), (far - 0.6).clamp(0.8, 1.8)),
            left,
            s: if left { 1.0 } else { -1.0 },
            diagonal_min_deg: config.analysis.diagonal_min_deg,
            clearance: config.rover.belly_clearance_m,
        }
    }

    /// Whether a toe line at `a` degrees counts as diagonal.
    fn diagonal(&self, a: f64) -> bool {
        a.abs() >= self.diagonal_min_deg
    }

    /// The band of the left (or right) wheel track, side faces along both its edges.
    fn track_band(&self, left: bool) -> Extent {
        let (bhw, outer) = (self.belly_half_width, self.track_outer);
        if left {
            Extent::Band {
                from_m: bhw,
                to_m: outer,
            }
        } else {
            Extent::Band {
                from_m: -outer,
                to_m: -bhw,
            }
        }
    }

    /// The drawn side's track band.
    fn band(&self) -> Extent {
        self.track_band(self.left)
    }

    /// Everything beyond the drawn side's inner track edge.
    fn half_plane(&self) -> Extent {
        let bhw = self.belly_half_width;
        if self.left {
            Extent::Band {
                from_m: bhw,
                to_m: 100.0,
            }
        } else {
            Extent::Band {
                from_m: -100.0,
                to_m: -bhw,
            }
        }
    }
}

/// A climbable ramp under one track, straight or diagonal, sometimes capped.
fn one_track_ramp<R: Rng>(rng: &mut R, at: &Setting) -> Scene {
    let g = rng.gen_range(15.0..25.0);
    let a = toe_angle(rng) * at.s;
    let d = rng.gen_range(at.toe_span.0..at.toe_span.1);
    let cap = rng.gen_bool(0.3).then(|| rng.gen_range(0.2..0.4));
    let wc = match (at.left, at.diagonal(a)) {
        (true, false) => 3,
        (true, true) => 4,
        (false, false) => 5,
        (false, true) => 6,
    };
    (
        vec![Element::ramp(d, at.s * at.tc, g, a, at.band()).capped(cap)],
        go(wc, Some(d), Some(g), at.diagonal(a).then_some(a)),
    )
}

/// A full-width ramp rising out of the image.
fn ramp_out_of_view<R: Rng>(rng: &mut R, at: &Setting) -> Scene {
    let g = rng.gen_range(15.0..26.0);
    let d = rng.gen_range(at.toe_span.0..at.toe_span.1);
    (
        vec![Element::ramp(d, 0.0, g, 0.0, Extent::Full)],
        go(2, Some(d), Some(g), None),
    )
}

/// Ground falling away beyond one track's inner edge.
fn half_plane_descent<R: Rng>(rng: &mut R, at: &Setting) -> Scene {
    let g = -rng.gen_range(10.0..15.0);
    let d = rng.gen_range(at.toe_span.0.max(0.9)..at.toe_span.1.max(1.0));
    (
        vec![Element::ramp(d, at.s * at.tc, g, 0.0, at.half_plane())],
        go(if at.left { 9 } else { 10 }, Some(d), Some(g), None),
    )
}

/// A trench under one track: a descent capped at 12-25 cm.
fn one_track_descent<R: Rng>(rng: &mut R, at: &Setting) -> Scene {
    let g = -rng.gen_range(8.0..15.0);
    let d = rng.gen_range(at.toe_span.0.max(0.9)..at.toe_span.1.max(1.0));
    let cap = Some(rng.gen_range(0.12..0.25));
    (
        vec![Element::ramp(d, at.s * at.tc, g, 0.0, at.band()).capped(cap)],
        go(if at.left { 9 } else { 10 }, Some(d), Some(g), None),
    )
}

/// Rough ground, otherwise flat.
fn rough_flat<R: Rng>(rng: &mut R, _at: &Setting) -> Scene {
    (vec![rough(rng)], go(1, None, None, None))
}

/// A full-width ramp or descent on rough ground.
fn rough_ramp<R: Rng>(rng: &mut R, at: &Setting) -> Scene {
    let d = rng.gen_range(at.toe_span.0.max(0.8)..at.toe_span.1.max(0.9));
    let (g, wc) = if rng.gen_bool(0.6) {
        (rng.gen_range(12.0..25.0), 2)
    } else {
        (-rng.gen_range(10.0..15.0), 8)
    };
    (
        vec![rough(rng), Element::ramp(d, 0.0, g, 0.0, Extent::Full)],
        go(wc, Some(d), Some(g), None),
    )
}

/// Pebbles and rocks of 4-9 cm in the tracks on rough ground.
fn rock_field<R: Rng>(rng: &mut R, at: &Setting) -> Scene {
    let n = rng.gen_range(3..8);
    // On ±2.5 cm ground a 9 cm pebble on a bump beside a dip stands more than a
    // wheel radius above the dip's bottom: the wheel bridges the dip.
    (pebbles_on_rough_ground(rng, at, n), go_any())
}

/// Rough ground with `n` pebbles and rocks of 4-9 cm where the rig sees the tracks.
fn pebbles_on_rough_ground<R: Rng>(rng: &mut R, at: &Setting, n: usize) -> Vec<Element> {
    let mut e = vec![rough(rng)];
    e.extend(rocks(
        rng,
        n,
        (0.04, 0.09),
        (at.near.max(0.6), at.far.min(2.8)),
    ));
    e
}

/// A rock field with one 15-20 cm rock in a track.
fn rock_field_with_boulder<R: Rng>(rng: &mut R, at: &Setting) -> Scene {
    let n = rng.gen_range(2..6);
    let mut e = pebbles_on_rough_ground(rng, at, n);
    let height_m = rng.gen_range(0.15..0.2);
    e.push(Element::Rock {
        x_m: rng.gen_range(at.near.max(0.8)..(at.far - 0.3).clamp(1.0, 2.2)),
        y_m: at.s * rng.gen_range(0.35..0.55),
        radius_m: rng.gen_range(0.15..0.2),
        height_m,
    });
    // A rock is a step or a slope, depending on its shape: either stops.
    (e, stop_any())
}

/// A rock under the belly, low enough to straddle or too tall.
///
/// Its centre lies within 4 cm of the centre line and its radius is 12-17 cm, so its
/// rim can reach up to 1 cm into a track. A tall rock whose rim does stands in that
/// track too, where a restyled cap taller than its radius (on a vertical rim) or a
/// boulder is a `step` as rightly as it is a `belly` hazard: the stop may name
/// either (`sweep -- natural 100 11813 random 8` #44, a 41 cm cap on a 34 cm rim 6 mm
/// into the left track, named `step` there first).
fn belly_rock<R: Rng>(rng: &mut R, at: &Setting) -> Scene {
    let tall = rng.gen_bool(0.5);
    let height_m = if tall {
        rng.gen_range(0.37..0.45)
    } else {
        rng.gen_range(0.22..0.27)
    };
    let x_m = rng.gen_range(at.near.max(0.9)..(at.far - 0.3).clamp(1.0, 2.2));
    let y_m = rng.gen_range(-0.04..0.04);
    let radius_m = rng.gen_range(0.12..0.17);
    let rock = Element::Rock {
        x_m,
        y_m,
        radius_m,
        height_m,
    };
    let want = if !tall {
        go(1, None, None, None)
    } else if y_m.abs() + radius_m > at.belly_half_width {
        stop_any()
    } else {
        stop(HazardKind::Belly)
    };
    (vec![rock], want)
}

/// A different climbable ramp under each track.
fn two_ramps<R: Rng>(rng: &mut R, at: &Setting) -> Scene {
    let d1 = rng.gen_range(at.toe_span.0..at.toe_span.1);
    let d2 = d1 + rng.gen_range(0.3..0.6);
    let (g1, g2) = (rng.gen_range(15.0..25.0), rng.gen_range(10.0..25.0));
    (
        vec![
            Element::ramp(d1, at.s * at.tc, g1, 0.0, at.band()),
            Element::ramp(d2, -at.s * at.tc, g2, 0.0, at.track_band(!at.left)),
        ],
        go(if at.left { 3 } else { 5 }, Some(d1), Some(g1), None),
    )
}

/// A rock under the belly beside a straight one-track ramp (15-25°): 12-17 cm in
/// radius, within 3 cm of the centre line (so within the belly band), 0.1-0.9 m past
/// the toe; 0.15-0.65 m high, drawn so that the belly clears it by 5 cm or more (go,
/// the ramp's workcase) or meets it by as much (stop, `belly`).
fn belly_rock_beside_ramp<R: Rng>(rng: &mut R, at: &Setting) -> Scene {
    let g = rng.gen_range(15.0..25.0);
    let d = rng.gen_range(at.toe_span.0..at.toe_span.1);
    let ramp = Element::ramp(d, at.s * at.tc, g, 0.0, at.band());
    let near = d + 0.1;
    let x_m = rng.gen_range(near..(d + 0.9).min(at.far - 0.2).max(near + 0.1));
    let (y_m, radius_m) = (rng.gen_range(-0.03..0.03), rng.gen_range(0.12..0.17));
    let tall = rng.gen_bool(0.5);
    let fits = |height_m: f64| {
        let m = belly_margin(at, (d, g), (x_m, y_m, radius_m, height_m));
        if tall {
            m <= -BELLY_MARGIN_M
        } else {
            m >= BELLY_MARGIN_M
        }
    };
    // A bounded draw: a height either way exists for every ramp drawn (0.15 m
    // clears 0.32 m by more; 0.65 m meets a belly at most 0.5 m up over the rock).
    let height_m = (0..1000)
        .map(|_| rng.gen_range(0.15..0.65))
        .find(|&h| fits(h))
        .unwrap_or(if tall { 0.65 } else { 0.15 });
    let rock = Element::Rock {
        x_m,
        y_m,
        radius_m,
        height_m,
    };
    let want = if tall {
        stop(HazardKind::Belly)
    } else {
        go(if at.left { 3 } else { 5 }, Some(d), Some(g), None)
    };
    (vec![ramp, rock], want)
}

/// How far the belly's underside clears a rock (`x, y, radius, height`, metres;
/// negative where it meets it) while the drawn side's track climbs a straight ramp
/// (`toe` m, `gradient` °) and the other stays on flat ground: the least, over the
/// rock's footprint (sampled every 5 mm), of the underside's height less the rock's
/// surface (a half-ellipsoid). A hand calculation of the rover's rule: at each x the
/// belly rests on the line between the tracks' heights at their centre lines, its
/// clearance measured upright under the body's roll (`clearance · √(1 + slope²)`).
fn belly_margin(at: &Setting, (toe, gradient): (f64, f64), rock: (f64, f64, f64, f64)) -> f64 {
    let (x0, y0, radius, height) = rock;
    let steps = (radius / 0.005).ceil() as i32;
    let mut least = f64::INFINITY;
    for i in -steps..=steps {
        for j in -steps..=steps {
            let (dx, dy) = (f64::from(i) * 0.005, f64::from(j) * 0.005);
            let q = 1.0 - (dx * dx + dy * dy) / (radius * radius);
            if q < 0.0 {
                continue;
            }
            let (x, y) = (x0 + dx, y0 + dy);
            let up = ((x - toe) * gradient.to_radians().tan()).max(0.0);
            let (left, right) = if at.left { (up, 0.0) } else { (0.0, up) };
            let slope = (left - right) / (2.0 * at.tc);
            let underside = right + slope * (y + at.tc) + at.clearance * slope.hypot(1.0);
            least = least.min(underside - height * q.sqrt());
        }
    }
    least
}

/// The least margin, either way, by which [`belly_rock_beside_ramp`] draws a rock
/// clear of the belly or into it, metres.
const BELLY_MARGIN_M: f64 = 0.05;

/// A pebble or a rock on a full-width ramp (`sign` 1) or descent (`sign` −1).
fn rock_on_slope<R: Rng>(rng: &mut R, at: &Setting, sign: f64) -> Scene {
    let d = rng.gen_range(at.toe_span.0.max(0.8)..at.toe_span.1.max(0.9));
    let big = rng.gen_bool(0.5);
    // A pebble's front adds to the ramp's rise, and its back to the descent's fall:
    // keep the two within the climbable (a 6 cm pebble on an 18° ramp rises 11 cm in
    // 14 cm).
    let g = sign * rng.gen_range(10.0..18.0);
    let height_m = if big {
        rng.gen_range(0.15..0.2)
    } else {
        rng.gen_range(0.03..0.06)
    };
    let rock = Element::Rock {
        x_m: d + rng.gen_range(0.2..0.5),
        y_m: at.s * rng.gen_range(0.35..0.55),
        radius_m: if big {
            rng.gen_range(0.15..0.2)
        } else {
            height_m * 1.5
        },
        height_m,
    };
    let want = if big {
        stop_any()
    } else {
        go(if sign > 0.0 { 2 } else { 8 }, Some(d), Some(g), None)
    };
    (
        vec![Element::ramp(d, 0.0, g, 0.0, Extent::Full), rock],
        want,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A camera 1.2 m up at the origin, pitched 30°, that sees the whole corridor.
    fn overhead() -> Config {
        let mut c = Config::default();
        (c.mount.x_m, c.mount.y_m, c.mount.z_m) = (0.0, 0.0, 1.2);
        (c.mount.roll_deg, c.mount.pitch_deg, c.mount.yaw_deg) = (0.0, 30.0, 0.0);
        c
    }

    #[test]
    fn the_belly_margin_over_a_rock_is_the_rolled_belly_s_height_less_the_rock_s() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let mut at = Setting::new(&mut rng, &Config::default());
        (at.left, at.s) = (true, 1.0);
        // Flat ground under both tracks (the ramp's toe past the rock): the belly
        // stands its clearance, 0.32 m, over the rock's apex.
        let m = belly_margin(&at, (3.0, 20.0), (1.5, 0.0, 0.15, 0.25));
        assert!((m - 0.07).abs() < 1e-9, "{m}");
        // By hand: a 20° ramp from 1 m under the left track stands 0.5 · tan 20° =
        // 0.18199 m 1.5 m out; the line between the tracks (±0.45 m) slopes 0.20221 and
        // over y = 0 stands 0.09100 m; the clearance upright, 0.32 · √(1 + 0.20221²) =
        // 0.32648 m: the underside 0.41747 m over a needle-thin rock's apex, 0.4 m.
        let m = belly_margin(&at, (1.0, 20.0), (1.5, 0.0, 0.005, 0.4));
        assert!((m - 0.01747).abs() < 1e-4, "{m}");
        // Mirrored on the right: the same.
        (at.left, at.s) = (false, -1.0);
        let mirrored = belly_margin(&at, (1.0, 20.0), (1.5, 0.0, 0.005, 0.4));
        assert!((mirrored - m).abs() < 1e-12, "{mirrored}");
    }

    #[test]
    fn a_belly_rock_beside_a_ramp_is_drawn_clear_of_the_belly_or_into_it_by_its_margin() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let mut kinds = [0, 0];
        for _ in 0..40 {
            let rig = Rig::random(&mut rng);
            let at = Setting::new(&mut rng.clone(), &rig.config);
            let d = draw(&mut rng, Family::BellyRockBesideRamp, rig);
            let [Element::Ramp {
                toe_x_m,
                gradient_deg,
                ref_y_m,
                ..
            }, Element::Rock {
                x_m,
                y_m,
                radius_m,
                height_m,
            }] = d.terrain.elements[..]
            else {
                panic!("a ramp and a rock: {:?}", d.terrain.elements);
            };
            let mut at = at;
            (at.left, at.s) = (ref_y_m > 0.0, ref_y_m.signum());
            assert!(
                y_m.abs() + radius_m <= at.belly_half_width,
                "under the belly"
            );
            let m = belly_margin(&at, (toe_x_m, gradient_deg), (x_m, y_m, radius_m, height_m));
            if d.expect.verdict == Decision::Go {
                assert!(m >= BELLY_MARGIN_M, "{m}");
                kinds[0] += 1;
            } else {
                assert_eq!(d.expect.hazard, Some(HazardKind::Belly));
                assert!(m <= -BELLY_MARGIN_M, "{m}");
                kinds[1] += 1;
            }
        }
        assert!(kinds[0] >= 10 && kinds[1] >= 10, "{kinds:?}");
    }

    #[test]
    fn a_tall_belly_rock_reaching_into_a_track_names_no_hazard_and_one_within_the_band_belly() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let mut kinds = [0, 0, 0];
        // A rim reaches a track in about one tall rock in a hundred.
        for _ in 0..2000 {
            let rig = Rig::random(&mut rng);
            let bhw = rig.config.rover.belly_half_width_m;
            let d = draw(&mut rng, Family::BellyRock, rig);
            let [Element::Rock {
                y_m,
                radius_m,
                height_m,
                ..
            }] = d.terrain.elements[..]
            else {
                panic!("one rock: {:?}", d.terrain.elements);
            };
            let reaches = y_m.abs() + radius_m > bhw;
            match d.expect.verdict {
                Decision::Go => {
                    assert!(height_m < 0.3, "{height_m}");
                    kinds[0] += 1;
                }
                _ if reaches => {
                    assert_eq!(d.expect.hazard, None, "{y_m} {radius_m}");
                    kinds[1] += 1;
                }
                _ => {
                    assert_eq!(d.expect.hazard, Some(HazardKind::Belly));
                    kinds[2] += 1;
                }
            }
        }
        assert!(kinds.iter().all(|&k| k >= 5), "{kinds:?}");
    }

    #[test]
    fn a_widened_band_reaches_into_the_belly_band_and_past_the_track_only() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        let (bhw, outer) = (0.2, 0.7);
        let families = [
            Family::OneTrackRamp,
            Family::HalfPlaneDescent,
            Family::OneTrackDescent,
            Family::TwoRamps,
        ];
        let mut moved = 0;
        for k in 0..80 {
            let d = draw(&mut rng, families[k % families.len()], Rig::default_rig());
            let w = widened(&mut rng, d.clone());
            assert_eq!(w.expect, d.expect);
            for (a, b) in d.terrain.elements.iter().zip(&w.terrain.elements) {
                let band = |e: &Element| match e {
                    Element::Ramp {
                        extent: Extent::Band { from_m, to_m },
                        ..
                    } => (*from_m, *to_m),
                    other => panic!("not a band: {other:?}"),
                };
                let ((f0, t0), (f1, t1)) = (band(a), band(b));
                // The side (mirrored on the right) and the inner and outer edges.
                let s = if f0 > 0.0 { 1.0 } else { -1.0 };
                let (inner0, outer0, inner1, outer1) = if s > 0.0 {
                    (f0, t0, f1, t1)
                } else {
                    (-t0, -f0, -t1, -f1)
                };
                assert!((inner0 - bhw).abs() < 1e-12, "{a:?}");
                assert!(inner1 <= inner0 && inner1 >= 0.25 * bhw, "{b:?}");
                if outer0 > 50.0 {
                    assert_eq!(outer1, outer0, "a half plane keeps its far edge");
                } else {
                    assert!((outer0 - outer).abs() < 1e-12, "{a:?}");
                    assert!(outer1 >= outer0 && outer1 <= outer0 + 0.4, "{b:?}");
                }
                moved += usize::from(inner0 - inner1 > 0.05);
                // By hand: half-way between the old and the new inner edge, 0.5 m
                // past the toe along the band's centre line, a straight ramp stands
                // 0.5 m · tan(gradient) up (capped); the ground there was flat before.
                if let Element::Ramp {
                    toe_x_m,
                    gradient_deg,
                    alpha_deg,
                    cap_m,
                    ..
                } = *b
                {
                    if alpha_deg == 0.0 && inner0 - inner1 > 0.01 {
                        let (x, y) = (toe_x_m + 0.5, s * 0.5 * (inner0 + inner1));
                        let mut want = 0.5 * gradient_deg.to_radians().tan();
                        if let Some(cap) = cap_m {
                            want = want.clamp(-cap, cap);
                        }
                        let got = Terrain::new(vec![b.clone()]).height(x, y);
                        assert!((got - want).abs() < 1e-9, "{got} vs {want}: {b:?}");
                        assert_eq!(Terrain::new(vec![a.clone()]).height(x, y), 0.0);
                    }
                }
            }
        }
        assert!(moved > 20, "{moved} bands moved more than 5 cm");
    }

    #[test]
    fn a_restyled_scene_keeps_its_geometry_and_its_expectation() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
        let d = draw(&mut rng, Family::RockFieldWithBoulder, Rig::default_rig());
        let r = restyled(&mut rng, d.clone());
        assert_eq!(r.expect, d.expect);
        assert_eq!(r.terrain.elements.len(), d.terrain.elements.len());
        for (a, b) in d.terrain.elements.iter().zip(&r.terrain.elements) {
            match (a, b) {
                (
                    Element::Rough {
                        amplitude_m,
                        correlation_m,
                        seed,
                    },
                    Element::Lumpy {
                        amplitude_m: a2,
                        spacing_m,
                        seed: s2,
                    },
                ) => assert_eq!((amplitude_m, correlation_m, seed), (a2, spacing_m, s2)),
                (
                    Element::Rock {
                        x_m,
                        y_m,
                        radius_m,
                        height_m,
                    },
                    Element::Stone {
                        x_m: x2,
                        y_m: y2,
                        radius_m: r2,
                        height_m: h2,
                        ..
                    },
                ) => assert_eq!((x_m, y_m, radius_m, height_m), (x2, y2, r2, h2)),
                other => panic!("not restyled: {other:?}"),
            }
        }
        // Its height bounds, which the renderer marches rays within, are the same.
        let (_, top) = r.terrain.bounds();
        assert_eq!(top, d.terrain.bounds().1);
    }

    #[test]
    fn the_least_incidence_is_the_far_corners_by_hand() {
        // The lines of sight meet the ground most obliquely at the corridor's far
        // corners, (3.0, ±0.69) (1 cm inside the track's outer edge).
        let c = overhead();
        let corner = |z: f64| (3.0f64.powi(2) + 0.69f64.powi(2) + (1.2 - z).powi(2)).sqrt();
        let flat = (1.2 / corner(0.0)).asin().to_degrees();
        let got = least_incidence_deg(&Terrain::flat(), &c);
        assert!((got - flat).abs() < 0.01, "{got} vs {flat}");
        // A 10° descent from 1 m: the normal leans forward by 10°, the corner is
        // 2·tan 10° lower.
        let t = 10f64.to_radians().tan();
        let z = -2.0 * t;
        let normal_dot = (-3.0 * t + (1.2 - z)) / (1.0 + t * t).sqrt();
        let down = (normal_dot / corner(z)).asin().to_degrees();
        let descent = Terrain::new(vec![Element::ramp(1.0, 0.0, -10.0, 0.0, Extent::Full)]);
        let got = least_incidence_deg(&descent, &c);
        assert!((got - down).abs() < 0.01, "{got} vs {down}");
        // Steeper than the lines of sight: the surface faces away.
        let cliff = Terrain::new(vec![Element::ramp(1.0, 0.0, -60.0, 0.0, Extent::Full)]);
        assert!(least_incidence_deg(&cliff, &c) < 0.0);
    }
}
