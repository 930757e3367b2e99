//! A post standing in a track cell beside its ground: something narrower than a cell,
//! with the ground seen around it in the same cell.

use super::faces::two_levels;
use super::{Frame, UNSEEN_FOOT_MARGIN_M};
use crate::grid::Cell;

/// The height of a post standing in track cell (`ix`, `iy`), whose ground the strip
/// reads as `z` (metres), when the cell holds one: `None` otherwise.
///
/// A cell with two surfaces is read by the one that continues its strip, so a face
/// along the strip (a trench's wall, a ramp's side) makes no step. Something narrower
/// than a cell with the ground seen around it in the same cell, a post, was then read
/// as that ground in every cell it stands in: a post 5 cm square and 30 cm high on flat
/// ground under the default rig went at 15 of 24 places tried 1-2.5 m out, and so did
/// such posts on a 24° ramp.
///
/// A post's cell has its top voxel ([`crate::grid::Cell::top`], the centroid of its
/// highest layer with enough points, 1-3 cm under a post's top) more than a wheel
/// radius `r` and [`UNSEEN_FOOT_MARGIN_M`] over its ground, and:
/// - its ground is the strip's reading `z` or, where lower, the cell's lowest voxel
///   ([`crate::grid::Cell::low`]). A track's edge strip may read a cell by its mean,
///   the post's face and the ground as one surface sloping across the cell: a 17 cm
///   post just inside the edge, read 10 cm high there, went (`sweep -- posts 100
///   10523` #97).
/// - no ground beside it at that level: the cells beside it across the strip are both
///   seen, and their ground lies more than a wheel radius under that top. A cell's
///   ground is its lower band, or its lowest voxel where that band holds too few points
///   to be a surface (a 3 cm post straddling a track's edge, most of it in the belly
///   band's cell, went). Ground beside at that level is a raised band's or a stone's,
///   the face's (the belly band beside a descent under the track, a ramp's top past its
///   sloping side, a rock's flank), which the strips there judge. A neighbour in a
///   shadow may be such ground: a ramp's sloping side in the track's edge strip, in the
///   corridor's last cell, its inner neighbour hidden, made a `step` (`sweep --
///   bevelled 100 10212 random 9` #85).
/// - no surface at that level in the two cells just past it along the strip (their
///   upper band, [`crate::grid::Cell::crest`]): else the face is a riser the strip
///   climbs onto there (a step, a block), found as such, or the post goes on into
///   that cell and is found there. (Read as a post in the riser's cell, a 25 cm step
///   1.6 m out under a 320×240 camera was reported 6 cm nearer; the cell just past
///   that riser, its face and a little of its top, has no upper band, and the next
///   one has.) A few of the post's own points that depth noise carries into the cell
///   past it, too few to be a surface, are none: with that cell's top voxel asked
///   instead, a 22.7 cm post on a 20.8° ramp went (`sweep -- posts 100 10527` #5,
///   noisy).
/// - on the corridor's edge, where no strip lies beyond, its top voxel centred more
///   than a quarter of a voxel inside the edge: nearer, it is a wall's top standing
///   beyond the corridor (a trench's outer wall).
///
/// [`steps_and_slopes`](super::steps_and_slopes) then meets the post's top in the cell
/// and never leaves the cell out of its strip as ground spilled over the band edge or
/// as a bound over unseen ground (a 6 cm post on a track's edge, most of the cell's
/// points, read as the belly band's ground, went: `sweep -- posts 100 10419` #93).
pub(super) fn post_top(f: &Frame, ix: usize, iy: usize, z: f32, r: f32) -> Option<f32> {
    let s = f.spec;
    let cell = &f.cells[s.cell(ix, iy)];
    let z = z.min(cell.low);
    if cell.top - z <= r + UNSEEN_FOOT_MARGIN_M {
        return None;
    }
    let vs = s.voxel_m;
    let y_mid = s.y_centre(iy);
    // A cell's ground: its lower band, or where that band is too small to be a surface
    // of its own (`crest` stands for both) but the cell spans two levels, its lowest
    // voxel (a post straddling the strips' boundary, most of it in that cell).
    let ground = |nb: &Cell| {
        if two_levels(nb) && nb.crest == nb.foot {
            nb.low
        } else {
            nb.foot
        }
    };
    let beside = [
        (iy.checked_sub(1), -1.0),
        ((iy + 1 < s.ny).then_some(iy + 1), 1.0),
    ];
    let ground_beside = beside.iter().any(|&(jy, side)| match jy {
        Some(jy) => {
            let c = s.cell(ix, jy);
            !f.seen[c] || ground(&f.cells[c]) >= cell.top - r
        }
        None => (y_mid + side * 0.5 * vs - cell.top_xy[1]).abs() < 0.25 * vs,
    });
    let ground_past = (ix + 1..(ix + 3).min(s.nx)).any(|k| {
        let c = s.cell(k, iy);
        f.seen[c] && f.cells[c].crest >= cell.top - r
    });
    (!ground_beside && !ground_past).then_some(cell.top)
}
