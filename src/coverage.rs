//! What a camera mount can see of the corridor, from the config alone: for each strip
//! along it, how near its ground comes into view, and over which distances an
//! obstacle standing in it is seen whole, its foot and its top both in the image and
//! within range.
//!
//! The analysis judges a rise by what it sees of it. An obstacle whose top no frame
//! shows cannot be told from a pebble: a yawed camera's image leans away from the
//! corridor's outer edge as it rises (the image's side edge is a plane through the
//! camera, tilted inward by about `atan(tan(hfov/2)·sin(pitch))`, 17° for a Kinect v1
//! pitched 34°), and its top edge comes nearer for what stands higher. Where those two
//! meet before the obstacle's foot is seen, a strip is never seen whole: a 24 cm post
//! 0.57 m left, under a Kinect v1 0.52 m high yawed −8.3°, is cut by the top edge
//! from 2.1 m out and by the side edge from 1.7 m in, and went in every frame of a
//! drive past it (`sweep -- posts 100 10530 random` #96). This is a necessary
//! condition, not a sufficient one: a strip seen whole still needs the ground before
//! an obstacle for the step test.
//!
//! A point is in view as the analysis's expected cells ask of their corners
//! (`analysis::point_in_view`): half a pixel clear of the image's edges,
//! within the range limits kept 0.1 m clear.

use nalgebra::Vector3;

use crate::analysis::{point_in_view, region_of, view_depths};
use crate::config::Config;
use crate::grid::GridSpec;
use crate::projection::Projector;
use crate::verdict::Side;

/// How far apart along a strip [`Coverage::of`] tries distances, metres.
const STEP_M: f64 = 0.01;

/// What the mount sees of one strip of the corridor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StripCoverage {
    /// The strip's centre line across the corridor, metres (rover frame, left +).
    pub y_m: f64,
    /// The band it lies in: a wheel track, or under the belly (`Centre`).
    pub band: Side,
    /// The nearest distance ahead at which its ground is in view, metres; `None` when
    /// it is nowhere in view within the corridor.
    pub ground_from_m: Option<f64>,
    /// The nearest and farthest distances ahead at which a post of the coverage's
    /// height standing on flat ground there is seen whole (foot and top in view),
    /// metres; `None` when nowhere within the corridor. The points of a line along x
    /// in view of a camera form one interval, so the distances between are seen too.
    pub whole_m: Option<(f64, f64)>,
}

/// What the mount sees of the corridor, strip by strip (the analysis grid's strips,
/// right to left).
#[derive(Debug, Clone, PartialEq)]
pub struct Coverage {
    /// The height of the post [`StripCoverage::whole_m`] is for, metres.
    pub height_m: f64,
    /// The corridor's length, metres: the farthest distance tried.
    pub length_m: f64,
    /// One per strip, right to left.
    pub strips: Vec<StripCoverage>,
}

impl Coverage {
    /// The coverage of `config`'s mount and camera for a post `height_m` metres high.
    pub fn of(config: &Config, height_m: f64) -> Self {
        let spec = GridSpec::from_config(config);
        let cam = &config.camera;
        let projector = Projector::new(config, cam.width as usize, cam.height as usize);
        let depths = view_depths(config);
        let in_view =
            |x: f64, y: f64, z: f64| point_in_view(&projector, depths, Vector3::new(x, y, z));
        let length_m = config.analysis.corridor_length_m;
        let steps = (length_m / STEP_M).round() as usize;
        let bhw = config.rover.belly_half_width_m as f32;
        let strips = (0..spec.ny)
            .map(|iy| {
                let y = f64::from(spec.y_centre(iy));
                let xs = (0..=steps).map(|k| k as f64 * STEP_M);
                let ground_from_m = xs.clone().find(|&x| in_view(x, y, 0.0));
                let mut whole = xs.filter(|&x| in_view(x, y, 0.0) && in_view(x, y, height_m));
                let whole_m = whole
                    .next()
                    .map(|first| (first, whole.next_back().unwrap_or(first)));
                StripCoverage {
                    y_m: y,
                    band: region_of(spec.y_centre(iy), bhw).side(),
                    ground_from_m,
                    whole_m,
                }
            })
            .collect();
        Coverage {
            height_m,
            length_m,
            strips,
        }
    }

    /// The coverage for the least obstacle the rover must stop for: one a wheel
    /// radius high (what stands higher over the ground it comes from is a step).
    pub fn for_rover(config: &Config) -> Self {
        Self::of(config, config.rover.wheel_radius_m)
    }

    /// The strips no frame sees such a post whole in.
    pub fn never_whole(&self) -> impl Iterator<Item = &StripCoverage> {
        self.strips.iter().filter(|s| s.whole_m.is_none())
    }

    /// Where the strips never seen whole lie across the corridor, for a log line:
    /// their centres, metres, signed (left +), comma-separated; empty if none.
    pub fn never_whole_at(&self) -> String {
        let at: Vec<String> = self
            .never_whole()
            .map(|s| format!("{:+.3}", s.y_m))
            .collect();
        at.join(", ")
    }

    /// A short account for people, one line per band and one per strip never seen
    /// whole: each line starts with `# ` (TOML comments, so `check-config`'s output
    /// stays a config file).
    pub fn report(&self) -> String {
        let mut out = format!(
            "# coverage: where a post {:.2} m high on flat ground is seen whole \
             (foot and top in view), per strip, within the corridor's {:.2} m\n",
            self.height_m, self.length_m
        );
        for band in [Side::Left, Side::Centre, Side::Right] {
            let strips: Vec<_> = self.strips.iter().filter(|s| s.band == band).collect();
            let seen: Vec<_> = strips.iter().filter_map(|s| s.whole_m).collect();
            let name = match band {
                Side::Left => "left track",
                Side::Centre => "belly band",
                Side::Right => "right track",
            };
            let span = if seen.is_empty() {
                "never".to_string()
            } else {
                let from = seen.iter().map(|w| w.0).fold(f64::INFINITY, f64::min);
                let to = seen.iter().map(|w| w.1).fold(f64::NEG_INFINITY, f64::max);
                format!(
                    "in {} of {} strips, from {from:.2} to {to:.2} m",
                    seen.len(),
                    strips.len()
                )
            };
            out.push_str(&format!("#   {name}: {span}\n"));
        }
        for s in self.never_whole() {
            out.push_str(&format!(
                "# warning: the strip at y = {:+.3} m is never seen whole: no frame shows how \
                 high an obstacle there stands\n",
                s.y_m
            ));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The FOV model's edges, half a pixel clear, as `tan` of the angle off the
    /// optical axis: (left, right, top, bottom), each positive.
    fn edges(c: &Config) -> (f64, f64, f64, f64) {
        let (w, h) = (f64::from(c.camera.width), f64::from(c.camera.height));
        let (th, tv) = (
            (c.camera.hfov_deg / 2.0).to_radians().tan(),
            (c.camera.vfov_deg / 2.0).to_radians().tan(),
        );
        // u ≥ 0.5 and u ≤ W − 1.5; v ≥ 0.5 and v ≤ H − 1.5 (`Projector::in_image`).
        (
            (1.0 - 1.0 / w) * th,
            (1.0 - 3.0 / w) * th,
            (1.0 - 1.0 / h) * tv,
            (1.0 - 3.0 / h) * tv,
        )
    }

    /// By hand, for a camera pitched `p` at height `hc` with no roll or yaw: a point `d`
    /// metres ahead of the camera, `y` to its left, `z` up, is at optical depth
    /// `d·cos p + (hc − z)·sin p`, `d·sin p − (hc − z)·cos p` above the axis
    /// and `y` to the left of it.
    fn seen_by_hand(c: &Config, d: f64, y: f64, z: f64) -> bool {
        let (left, right, top, bottom) = edges(c);
        let p = c.mount.pitch_deg.to_radians();
        let hc = c.mount.z_m;
        let depth = d * p.cos() + (hc - z) * p.sin();
        let up = d * p.sin() - (hc - z) * p.cos(); // how far above the axis, metres
        let dy = y - c.mount.y_m;
        // The range limits kept 0.1 m clear.
        depth >= c.camera.min_range_m + 0.1
            && depth <= c.camera.max_range_m - 0.1
            && up <= top * depth
            && -up <= bottom * depth
            && dy <= left * depth
            && -dy <= right * depth
    }

    #[test]
    fn an_upright_mount_matches_the_hand_calculation_in_every_strip() {
        let mut c = Config::default();
        (c.mount.x_m, c.mount.y_m) = (0.12, 0.03);
        for (z, pitch) in [(0.8, 30.0), (0.5, 15.0), (1.2, 45.0)] {
            (c.mount.z_m, c.mount.pitch_deg) = (z, pitch);
            let cov = Coverage::of(&c, 0.11);
            assert_eq!(cov.strips.len(), 28);
            for s in &cov.strips {
                let xs = (0..=300).map(|k| k as f64 * STEP_M);
                let ground = |x: f64| seen_by_hand(&c, x - c.mount.x_m, s.y_m, 0.0);
                let top = |x: f64| seen_by_hand(&c, x - c.mount.x_m, s.y_m, 0.11);
                let from = xs.clone().find(|&x| ground(x));
                let whole: Vec<f64> = xs.filter(|&x| ground(x) && top(x)).collect();
                let near = |a: Option<f64>, b: Option<f64>| match (a, b) {
                    (Some(a), Some(b)) => (a - b).abs() <= STEP_M + 1e-9,
                    (a, b) => a.is_none() && b.is_none(),
                };
                assert!(near(s.ground_from_m, from), "{z} {pitch} {s:?} {from:?}");
                assert!(
                    near(s.whole_m.map(|w| w.0), whole.first().copied()),
                    "{s:?}"
                );
                assert!(near(s.whole_m.map(|w| w.1), whole.last().copied()), "{s:?}");
            }
        }
    }

    #[test]
    fn the_default_mount_sees_every_strip_whole_and_its_outer_strips_from_1_04_m() {
        // Hand calculation: the left edge leans in, so the post's top binds. Its top,
        // 0.69 m under the camera, is at depth d·cos 30° + 0.69·sin 30°, and 0.675 m
        // to the left: in view from d = (0.675 / 0.5421 − 0.345) / 0.866 = 1.039 m.
        let cov = Coverage::for_rover(&Config::default());
        assert_eq!(cov.never_whole().count(), 0);
        let outer = cov.strips.last().unwrap();
        assert!((outer.y_m - 0.675).abs() < 1e-6);
        let (from, to) = outer.whole_m.unwrap();
        assert!((from - 1.04).abs() <= 0.011, "{from}");
        assert!((to - 3.0).abs() < 1e-9, "{to}");
        // Its ground from d = (0.675 / 0.5421 − 0.4) / 0.866 = 0.976 m.
        assert!(
            (outer.ground_from_m.unwrap() - 0.98).abs() <= 0.011,
            "{outer:?}"
        );
        assert!(!cov.report().contains("warning"));
    }

    #[test]
    fn a_yawed_low_mount_never_sees_its_outer_strips_whole_on_the_side_it_turns_from() {
        // `sweep -- posts 100 10530 random` #96's rig: a Kinect v1 0.52 m high, pitched
        // 34.3°, rolled −6° and yawed −8.3° (to the right).
        let mut c = Config::default();
        (c.mount.x_m, c.mount.y_m, c.mount.z_m) = (0.0386, -0.0525, 0.5221);
        (c.mount.roll_deg, c.mount.pitch_deg, c.mount.yaw_deg) = (-5.988, 34.251, -8.256);
        let cov = Coverage::for_rover(&c);
        let never: Vec<f64> = cov.never_whole().map(|s| s.y_m).collect();
        assert!(!never.is_empty());
        assert!(never.iter().all(|&y| y > 0.5), "{never:?}");
        // The same post a wheel radius high is seen whole where the ground lies
        // beside it: its foot alone is not enough.
        let low = Coverage::of(&c, 0.0);
        assert_eq!(low.never_whole().count(), 0);
        let report = cov.report();
        assert!(
            report.contains("warning: the strip at y = +0.675 m"),
            "{report}"
        );
        assert!(report.lines().all(|l| l.starts_with('#')), "{report}");
        // Mirrored, the right track's outer strips.
        (c.mount.y_m, c.mount.roll_deg, c.mount.yaw_deg) = (0.0525, 5.988, 8.256);
        let mirrored = Coverage::for_rover(&c);
        let right: Vec<f64> = mirrored.never_whole().map(|s| s.y_m).collect();
        assert_eq!(right.len(), never.len());
        assert!(right.iter().all(|&y| y < -0.5), "{right:?}");
    }
}
