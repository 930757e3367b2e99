//! Rises the image's side edge cuts: a stone in a track whose flank the camera sees
//! climbing toward the left or right edge of its image, its top beside the view.

use super::{followed, step_floor_reach_m, unknown_judged, Frame, Region, ROUGH_SPREAD_M};
use crate::verdict::{Hazard, HazardKind, Verdict};

/// Fewest strips across that a rise into the image's side edge must climb over, each
/// of them rising, for [`side_exit`]: 10 cm at the default voxel, a stone's flank,
/// not one cell's noise.
const SIDE_EXIT_MIN_STRIPS: usize = 2;

/// Most strips across [`side_exit`] follows a rise back from the image's side edge
/// to its foot: 20 cm at the default voxel, a large stone's flank.
const SIDE_EXIT_MAX_STRIPS: usize = 4;

/// Fewest strips, from a flank's foot away from the image's edge, whose rise along the
/// track [`side_exit`] takes as the ramp the flank stands on: one could lie on the
/// stone's skirt.
const RAMP_MIN_STRIPS: usize = 2;

/// A stone whose top lies beside the image: `unknown` ground at the rise.
///
/// A yawed or rolled camera's image does not span the corridor near the rover: its
/// left or right edge crosses a track. What lies beside the image is not a gap (as
/// below its bottom edge, the camera cannot see it), but a surface seen climbing
/// toward that edge goes on beyond it, and how high is not seen. Along each strip
/// the climb begins at the image's edge, its foot unseen, so the step test cannot
/// judge it; across the track its foot is seen. So where, in a row of a track, the
/// ground the strips follow rises toward a cell outside the image (neither expected
/// on flat ground nor seen), rising across each of the [`SIDE_EXIT_MIN_STRIPS`] to
/// [`SIDE_EXIT_MAX_STRIPS`] strips before it, steeper than the slope limit (what the
/// step test stops along a strip), the track is unknown at the nearest such row
/// where the rise would pass a wheel radius one strip beside the image: an 18.8 cm
/// cone 1.24 m out, a camera yawed 6.4° seeing its flank rise 12.1 cm over 0.2 m
/// toward the image's right edge, was a go (`sweep -- natural 200 7334 random 7`
/// #130). What is seen of it is a lower bound, as at the image's top edge.
///
/// One strip beside the image, the flank is taken to climb on as much as its last strip
/// did, into the edge strip: a 16.8 cm cone seen climbing 9.7 cm over three strips (2.7
/// cm the last; 10.1 cm over four, gentler than the limit) went (`sweep -- natural 200
/// 10208 random 7` #153). Each foot from the second strip on is tried. The rise is
/// measured from the foot across the track or, if it climbs more, from the ground along
/// the edge strip within a step's reach before it (steeper than the limit there too): a
/// 19.5 cm cone behind a 7 cm boulder, its flank seen only 3.4 cm over the boulder's
/// top across the track but 10.6 cm over the ground 0.15 m before it along the strip,
/// went (`natural 200 10708 random 7` #164). Cones beside the image in those two scenes
/// now stop from 15 cm up (from 20 and 22 cm before). What is seen cannot tell such a
/// cone from a pebble whose top the edge cuts: of 30,400 sweep frames, this turned 8
/// that went where a stop was due `unknown`, 34 whose stone's top lies beside the
/// image, and 6 that were due go (stones of 8.3-8.7 cm whose top the image just
/// holds, their flank cut near it).
///
/// Along the strip, what the track's ground off the flank rises itself over the same
/// rows is a ramp's, which the wheel climbs as it comes to the top: a 4.7 cm boulder on
/// a 17.6° ramp, the image's edge cutting it, stood 9.5 cm over the ramp 0.15 m before
/// it, 4.8 cm of that the ramp's rise, and was `unknown` (`natural 100 11502 random 10`
/// #26, clean and noisy).
///
/// A ramp, straight or diagonal, rises along the track: across it the ground climbs
/// gently (a 25° ramp at 26° to the rover, 11°), and along it under the limit. The
/// track's edge strips take no part: a one-track ramp's side face, drawn vertical or
/// sloping, lies in them. A rise of 5 cm, as the top edge's test asks
/// (`steep_exit`), is what a pebble's flank cut by the edge shows: 31 of 1,800
/// frames of pebble fields due go turned `unknown` with it (`natural 200 9303 random
/// 6`, `natural 200 9702 random 6`, ...), stones of 6.5-9 cm. A hazard already found
/// on that side, or nearer, stands.
pub fn side_exit(f: &Frame, surface: &[f32], verdict: &mut Verdict) {
    let s = f.spec;
    let tan_max = (f.cfg.rover.max_slope_deg as f32).to_radians().tan();
    let r = f.cfg.rover.wheel_radius_m as f32;
    let ground = |ix: usize, iy: usize| followed(f, surface, s.cell(ix, iy));
    let outside = |ix: usize, iy: usize| {
        let c = s.cell(ix, iy);
        !f.expected[c] && !f.seen[c]
    };
    for region in [Region::Left, Region::Right] {
        let Some((first, last)) = f.strips(region).next().zip(f.strips(region).last()) else {
            continue;
        };
        // Inner strips only: a band's edge strips hold its side faces.
        let inner = |iy: usize| iy > first && iy < last;
        // Whether strip `iy` of row `ix` tops a rise toward its neighbour `toward`
        // (±1), outside the image.
        let cut = |ix: usize, iy: usize, toward: isize| -> bool {
            let Some(out) = iy.checked_add_signed(toward).filter(|&o| o < s.ny) else {
                return false;
            };
            // The neighbour outside the image first: most cells have none.
            if !outside(ix, out) {
                return false;
            }
            let Some(top) = ground(ix, iy) else {
                return false;
            };
            // Down the flank, away from the edge, while each strip lies lower. The
            // flank's last step, into the edge strip, is how much more it climbs over
            // the first strip beside the image.
            let (mut foot, mut at, mut strips, mut climb_on) = (top, iy, 0, 0.0);
            while strips < SIDE_EXIT_MAX_STRIPS {
                let Some(next) = at.checked_add_signed(-toward).filter(|&n| inner(n)) else {
                    break;
                };
                match ground(ix, next) {
                    Some(z) if z < foot => (foot, at, strips) = (z, next, strips + 1),
                    _ => break,
                }
                if strips == 1 {
                    climb_on = top - foot;
                }
                let run = (s.y_centre(iy) - s.y_centre(at)).abs();
                if strips >= SIDE_EXIT_MIN_STRIPS
                    && top - foot + climb_on > r
                    && top - foot >= tan_max * run
                {
                    return true;
                }
            }
            if strips < SIDE_EXIT_MIN_STRIPS {
                return false;
            }
            // Along the strip: the ground a step to the top rises from, over what the
            // track's ground off the flank rises itself: the least any of its strips
            // from the flank's foot away from the edge rises from row `k` to this one
            // (two at least), less rough ground's spread. A ramp under the track, which
            // the wheel climbs as it comes to the top; not the flank, which they do not
            // hold (the foot is the lowest of the strips down it). The edge strips count
            // too: only the least counts, and a side face there can only lower it. Asked
            // only of a rise steeper than the limit.
            let x = s.x_centre(ix);
            let ramp_rise = |k: usize| {
                let off = (first..=last).filter(|&j| (j as isize - at as isize) * toward <= 0);
                let rises = off.filter_map(|j| Some(ground(ix, j)? - ground(k, j)?));
                let (least, n) = rises.fold((f32::INFINITY, 0), |(m, n), d| (m.min(d), n + 1));
                if n < RAMP_MIN_STRIPS {
                    0.0
                } else {
                    (least - ROUGH_SPREAD_M).max(0.0)
                }
            };
            (0..ix)
                .rev()
                .take_while(|&k| x - s.x_centre(k) <= step_floor_reach_m(s.voxel_m, r))
                .filter_map(|k| ground(k, iy).map(|z| (k, x - s.x_centre(k), z)))
                .any(|(k, run, z)| {
                    top - z >= tan_max * run && top - z - ramp_rise(k) + climb_on > r
                })
        };
        let Some(ix) = (0..s.nx).find(|&ix| {
            (first..=last)
                .filter(|&iy| inner(iy))
                .any(|iy| cut(ix, iy, 1) || cut(ix, iy, -1))
        }) else {
            continue;
        };
        let nearest = s.x_centre(ix);
        if !unknown_judged(verdict, region.side(), nearest) {
            verdict.add_hazard(Hazard {
                kind: HazardKind::Unknown,
                side: region.side(),
                distance_m: nearest.max(0.0),
            });
        }
    }
}
