//! What the camera can see of a drawn scene, by hand: from the terrain's elements and
//! the camera model alone, never from a rendered frame or the analysis. The sweeps
//! use it to tell an obstacle whose height the camera cannot measure from one it
//! misjudged.

use nalgebra::Vector3;

use super::terrain::{Element, Terrain};
use crate::config::{Config, RoverConfig};
use crate::grid::CUT_ROWS;
use crate::projection::Projector;
use crate::verdict::{Decision, Hazard, Side, Verdict};

/// How far along x from an obstacle whose top is out of view a hazard may lie and be
/// its ([`not_go_for_unseen_tops`]), metres: the cells before its foot that its
/// front's first centimetres rise in, and a cell's rounding.
pub const TOP_REACH_M: f64 = 0.3;

/// A stone, rock, block or step up (in one band) whose top the camera cannot see
/// ([`unseen_tops`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnseenTop {
    /// Its top, rover frame, metres.
    pub top: Vector3<f64>,
    /// Its footprint along x, `[near, far]`, metres.
    pub x_m: [f64; 2],
    /// Its footprint across, `[right, left]` (y), metres.
    pub y_m: [f64; 2],
}

impl UnseenTop {
    /// Whether `hazard` may be this obstacle's: within `reach_m` (metres) of its
    /// footprint along x, on a side ([`Side`]'s band of `rover`) its footprint
    /// reaches into.
    pub fn explains(&self, hazard: &Hazard, rover: &RoverConfig, reach_m: f64) -> bool {
        let d = f64::from(hazard.distance_m);
        let (b, o) = (rover.belly_half_width_m, rover.track_outer_m);
        let [lo, hi] = match hazard.side {
            Side::Left => [b, o],
            Side::Centre => [-b, b],
            Side::Right => [-o, -b],
        };
        (self.x_m[0] - reach_m..=self.x_m[1] + reach_m).contains(&d)
            && self.y_m[0] < hi
            && self.y_m[1] > lo
    }
}

/// The stones, rocks, blocks and rising steps of `terrain` within `config`'s corridor
/// (their footprint reaching into `x < corridor_length_m`, `|y| < track_outer_m`)
/// whose top the camera cannot see. A stone's or rock's top is its apex (the
/// terrain's height at its centre, with whatever lies under it); a block's is the
/// near edge of its top face. A step up is taken band by band (each wheel track and
/// the belly band, `step_tops`): its top there is its upper ground a voxel past
/// `x_m`, in the middle of the part of the band it covers. It is out of view when it lies behind
/// the camera, outside the image, in the image's top [`CUT_ROWS`] rows (where the
/// analysis takes the view as cut), or outside the sensor's range `[min_range_m,
/// max_range_m]` (optical depth). How high such an obstacle stands is then not seen,
/// only that it reaches the view's end. Occlusion by nearer terrain is not
/// considered.
pub fn unseen_tops(terrain: &Terrain, config: &Config) -> Vec<UnseenTop> {
    let cam = &config.camera;
    let p = Projector::new(config, cam.width as usize, cam.height as usize);
    let (w, h) = (f64::from(cam.width), f64::from(cam.height));
    let in_view = |top: Vector3<f64>| {
        p.project(top).is_some_and(|(u, v, z)| {
            (0.0..=w - 1.0).contains(&u)
                && (CUT_ROWS as f64..=h - 1.0).contains(&v)
                && (cam.min_range_m..=cam.max_range_m).contains(&z)
        })
    };
    let in_corridor = |o: &UnseenTop| {
        o.x_m[0] < config.analysis.corridor_length_m
            && o.y_m[0] < config.rover.track_outer_m
            && o.y_m[1] > -config.rover.track_outer_m
    };
    terrain
        .elements
        .iter()
        .filter_map(|e| match *e {
            Element::Stone {
                x_m, y_m, radius_m, ..
            }
            | Element::Rock {
                x_m, y_m, radius_m, ..
            } => Some(UnseenTop {
                top: Vector3::new(x_m, y_m, terrain.height(x_m, y_m)),
                x_m: [x_m - radius_m, x_m + radius_m],
                y_m: [y_m - radius_m, y_m + radius_m],
            }),
            Element::Block {
                x_m,
                y_m,
                length_m,
                width_m,
                ..
            } => {
                // Just inside the near edge, so that the height includes the block.
                let x = x_m + 1e-3;
                Some(UnseenTop {
                    top: Vector3::new(x, y_m, terrain.height(x, y_m)),
                    x_m: [x_m, x_m + length_m],
                    y_m: [y_m - width_m / 2.0, y_m + width_m / 2.0],
                })
            }
            _ => None,
        })
        .chain(
            terrain
                .elements
                .iter()
                .flat_map(|e| step_tops(terrain, e, config)),
        )
        .filter(|o| in_corridor(o) && !in_view(o.top))
        .collect()
}

/// A rising step's tops, one per band it covers (the right track, the belly band,
/// the left track, as [`Side`] divides the corridor): its edge just past `x_m`, in the
/// middle of the part of the band the step covers (where its extent raises the
/// ground by half its height or more), a voxel (`analysis.voxel_m`) past its edge: the
/// rise is seen to end only where the ground past it is seen whole. Its footprint is
/// that part across, and the edge along x. Where the image's top edge cuts a step's face over one wheel track, that
/// track sees the face rise and not how high it goes, whatever the other bands see: a
/// 7.2 cm step across the left half, its top seen only in the belly band by a camera
/// pitched 38° and yawed 8°, was `unknown` in the left track (`sweep -- hazards 100
/// 4204 random` #28). Nothing for any other element, or a step down (its top is the
/// ground before it).
fn step_tops(terrain: &Terrain, e: &Element, config: &Config) -> Vec<UnseenTop> {
    let Element::Step {
        x_m,
        height_m,
        extent,
    } = *e
    else {
        return Vec::new();
    };
    if height_m <= 0.0 {
        return Vec::new();
    }
    let (b, o) = (config.rover.belly_half_width_m, config.rover.track_outer_m);
    // The band sampled every centimetre: its covered part, [lowest, highest] y (a
    // part no wider than a sample, the band's edge on the step's, is none).
    const SAMPLES: usize = 100;
    [[-o, -b], [-b, b], [b, o]]
        .into_iter()
        .filter_map(|[lo, hi]| {
            let covered = (0..=SAMPLES)
                .map(|k| lo + (hi - lo) * k as f64 / SAMPLES as f64)
                .filter(|&y| extent.share(y) >= 0.5);
            let (from, to) = covered.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, z), y| {
                (a.min(y), z.max(y))
            });
            (from < to).then(|| {
                // A cell past the edge: the rise is seen to end only where ground
                // past it is seen whole (a cell the view's end cuts holds only the
                // lower part of what is there).
                let (x, y) = (x_m + config.analysis.voxel_m, 0.5 * (from + to));
                UnseenTop {
                    top: Vector3::new(x, y, terrain.height(x, y)),
                    x_m: [x_m, x_m],
                    y_m: [from, to],
                }
            })
        })
        .collect()
}

/// Whether `v` is not go for obstacles whose top is out of view: it is not go, has a
/// hazard, and each of its hazards lies within [`TOP_REACH_M`] of one of `tops` along
/// x, on its side ([`UnseenTop::explains`]). Any such verdict is right: how high the
/// obstacle stands is not seen.
pub fn not_go_for_unseen_tops(v: &Verdict, tops: &[UnseenTop], rover: &RoverConfig) -> bool {
    v.decision != Decision::Go
        && !v.hazards.is_empty()
        && v.hazards
            .iter()
            .all(|h| tops.iter().any(|o| o.explains(h, rover, TOP_REACH_M)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::Extent;

    /// The top of the first obstacle [`unseen_tops`] finds.
    fn unseen_top(terrain: &Terrain, config: &Config) -> Option<Vector3<f64>> {
        unseen_tops(terrain, config).first().map(|o| o.top)
    }

    fn rock(x_m: f64, y_m: f64, height_m: f64) -> Terrain {
        Terrain::new(vec![Element::Rock {
            x_m,
            y_m,
            radius_m: 0.15,
            height_m,
        }])
    }

    /// The default camera (0.8 m up, 43° tall, 480 rows) pitched down 45°: its top
    /// edge looks 45° − 21.5° = 23.5° below the horizon, and the third row from the
    /// top 45° − atan((0.5 − 2/480) · 2 tan 21.5°) = 23.66°. A 0.25 m rock's apex is
    /// 0.55 m under the camera, so it is in view nearer than 0.55 m / tan 23.66° =
    /// 1.255 m, and out of it farther.
    /// The default config pitched 45°, and how far below the horizon its third row
    /// from the top looks, radians (the hand calculation above).
    fn pitched_45() -> (Config, f64) {
        let mut c = Config::default();
        c.mount.pitch_deg = 45.0;
        let half = 21.5f64.to_radians();
        let row2 = 45f64.to_radians() - ((0.5 - 2.0 / 480.0) * 2.0 * half.tan()).atan();
        (c, row2)
    }

    #[test]
    fn an_apex_above_the_image_s_top_edge_is_unseen() {
        let (c, row2) = pitched_45();
        let edge = 0.55 / row2.tan();
        assert!((edge - 1.255).abs() < 0.001, "{edge}");
        assert_eq!(unseen_top(&rock(edge - 0.03, 0.0, 0.25), &c), None);
        let top = unseen_top(&rock(edge + 0.03, 0.0, 0.25), &c).expect("unseen");
        assert!((top.z - 0.25).abs() < 1e-9 && (top.x - edge - 0.03).abs() < 1e-9);
        // At the default 30° pitch the top edge looks 8.5° down: the same rock is
        // seen out to 0.55 m / tan 8.5° = 3.68 m.
        let c = Config::default();
        assert_eq!(unseen_top(&rock(2.5, 0.0, 0.25), &c), None);
        assert_eq!(unseen_top(&rock(3.6, 0.0, 0.25), &c), None);
    }

    #[test]
    fn an_apex_past_the_range_or_outside_the_corridor_is_judged_as_such() {
        let mut c = Config::default();
        c.camera.max_range_m = 2.0;
        // Optical depth of the apex at x = 2.0 m: (2.0, 0.55 below) along a ray 30°
        // down: 2.0 cos 30° + 0.55 sin 30° = 2.007 m, just past 2.0 m.
        assert!(unseen_top(&rock(2.0, 0.0, 0.25), &c).is_some());
        assert_eq!(unseen_top(&rock(1.9, 0.0, 0.25), &c), None);
        // Beside the corridor (its footprint wholly past the tracks' outer edge):
        // never counted, however far out of view.
        let outer = c.rover.track_outer_m;
        assert_eq!(unseen_top(&rock(2.0, outer + 0.2, 0.25), &c), None);
        assert!(unseen_top(&rock(2.0, outer + 0.1, 0.25), &c).is_some());
        assert_eq!(unseen_top(&rock(2.0, -outer - 0.2, 0.25), &c), None);
        assert!(unseen_top(&rock(2.0, -outer - 0.1, 0.25), &c).is_some());
        // Behind the camera.
        assert!(unseen_top(&rock(-0.3, 0.0, 0.25), &c).is_some());
    }

    #[test]
    fn a_rising_step_s_tops_are_its_upper_ground_a_voxel_past_its_edge_band_by_band() {
        // The default camera pitched 45°, as above: its third row from the top looks
        // 23.66° down. A 0.1 m step's upper ground is 0.7 m under the camera, so it
        // is in view nearer than 0.7 m / tan 23.66° = 1.597 m; its top is taken a
        // voxel (0.05 m) past the edge, so the edge may lie out to 1.547 m.
        let (c, row2) = pitched_45();
        let edge = 0.7 / row2.tan() - c.analysis.voxel_m;
        assert!((edge - 1.547).abs() < 0.001, "{edge}");
        let step = |x_m: f64, height_m: f64, extent: Extent| {
            unseen_tops(
                &Terrain::new(vec![Element::Step {
                    x_m,
                    height_m,
                    extent,
                }]),
                &c,
            )
        };
        assert!(step(edge - 0.03, 0.1, Extent::Left).is_empty());
        // Across the left half: the left track's and the belly band's left half.
        let tops = step(edge + 0.03, 0.1, Extent::Left);
        assert_eq!(tops.len(), 2, "{tops:?}");
        for (o, y, y_m) in [(&tops[0], 0.1, [0.0, 0.2]), (&tops[1], 0.45, [0.2, 0.7])] {
            assert!(
                (o.top - Vector3::new(edge + 0.08, y, 0.1)).norm() < 1e-9,
                "{o:?}"
            );
            assert!((o.y_m[0] - y_m[0]).abs() < 1e-9 && (o.y_m[1] - y_m[1]).abs() < 1e-9);
            assert_eq!(o.x_m, [edge + 0.03; 2]);
        }
        // Each explains a hazard in its own band only.
        let rover = &c.rover;
        let left = Hazard {
            kind: crate::verdict::HazardKind::Unknown,
            side: Side::Left,
            distance_m: (edge + 0.03) as f32,
        };
        let centre = Hazard {
            side: Side::Centre,
            ..left
        };
        assert!(tops[1].explains(&left, rover, TOP_REACH_M));
        assert!(!tops[1].explains(&centre, rover, TOP_REACH_M));
        assert!(tops[0].explains(&centre, rover, TOP_REACH_M));
        assert!(!tops[0].explains(&left, rover, TOP_REACH_M));
        // The whole width: one per band. Under one track: that track's alone.
        assert_eq!(step(edge + 0.03, 0.1, Extent::Full).len(), 3);
        let band = step(
            edge + 0.03,
            0.1,
            Extent::Band {
                from_m: -0.7,
                to_m: -0.2,
            },
        );
        assert_eq!(band.len(), 1, "{band:?}");
        assert!((band[0].top.y + 0.45).abs() < 1e-9);
        // A step down's top is the ground before it, in view.
        assert!(step(edge + 0.03, -0.1, Extent::Full).is_empty());
    }

    #[test]
    fn a_block_s_top_is_its_near_top_edge() {
        let mut c = Config::default();
        c.mount.pitch_deg = 45.0;
        let block = |x_m: f64| {
            Terrain::new(vec![Element::Block {
                x_m,
                y_m: 0.0,
                length_m: 0.25,
                width_m: 0.25,
                height_m: 0.25,
            }])
        };
        // The near top edge is what must be seen: as the rock's apex above.
        assert_eq!(unseen_top(&block(1.22), &c), None);
        let top = unseen_top(&block(1.29), &c).expect("unseen");
        assert!((top.z - 0.25).abs() < 1e-9);
    }

    #[test]
    fn a_hazard_is_explained_by_an_unseen_top_on_its_side_and_near_it() {
        let rover = RoverConfig::default(); // belly |y| < 0.2 m, tracks to 0.7 m
        let o = UnseenTop {
            top: Vector3::new(2.0, -0.3, 0.1),
            x_m: [1.9, 2.1],
            y_m: [-0.4, -0.2],
        };
        let at = |side, distance_m| Hazard {
            kind: crate::verdict::HazardKind::Unknown,
            side,
            distance_m,
        };
        assert!(o.explains(&at(Side::Right, 1.75), &rover, 0.2));
        assert!(o.explains(&at(Side::Right, 2.3), &rover, 0.2));
        assert!(!o.explains(&at(Side::Right, 1.65), &rover, 0.2));
        assert!(!o.explains(&at(Side::Right, 2.35), &rover, 0.2));
        // Its footprint ends on the belly band's edge: not the belly's, nor the left's.
        assert!(!o.explains(&at(Side::Centre, 2.0), &rover, 0.2));
        assert!(!o.explains(&at(Side::Left, 2.0), &rover, 0.2));
        let wider = UnseenTop {
            y_m: [-0.4, -0.15],
            ..o
        };
        assert!(wider.explains(&at(Side::Centre, 2.0), &rover, 0.2));
    }

    #[test]
    fn a_verdict_is_not_go_for_unseen_tops_only_when_each_hazard_is_theirs() {
        let rover = RoverConfig::default();
        let o = UnseenTop {
            top: Vector3::new(2.0, 0.0, 0.3),
            x_m: [1.85, 2.15],
            y_m: [-0.15, 0.15],
        };
        let hazard = |kind, side, distance_m| Hazard {
            kind,
            side,
            distance_m,
        };
        let mut v = Verdict::default(); // unknown, no hazard: nothing to explain
        assert!(!not_go_for_unseen_tops(&v, &[o], &rover));
        v.add_hazard(hazard(
            crate::verdict::HazardKind::Unknown,
            Side::Centre,
            1.7,
        ));
        assert!(not_go_for_unseen_tops(&v, &[o], &rover));
        assert!(!not_go_for_unseen_tops(&v, &[], &rover));
        let mut go = v.clone();
        go.decision = Decision::Go;
        assert!(!not_go_for_unseen_tops(&go, &[o], &rover));
        // A second hazard elsewhere (a step in the left track) is not the rock's.
        v.add_hazard(hazard(crate::verdict::HazardKind::Step, Side::Left, 1.2));
        assert!(!not_go_for_unseen_tops(&v, &[o], &rover));
    }
}
