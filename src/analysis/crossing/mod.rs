//! Crossing possibility (paper §3.1, with the fixes docs/design.md lists): slopes and steps
//! in the wheel tracks, anything too tall under the belly, and ground that should be
//! seen but is not (gaps, drop-offs).

mod belly;
mod climb;
mod faces;
mod gaps;
mod hidden;
mod posts;
mod side;

use super::plane::{Plane, PlaneFit};
use super::{Frame, Region, StripCell};
use crate::grid::Cell;
use crate::verdict::{Side, Verdict};
pub use belly::belly;
pub(crate) use belly::{median, track_medians};
use climb::{on_rim, strip_hazards, wheel_heights, STEP_REACH_VOXELS};
use faces::{
    beside_slope, clear_of_wall, cross_slope, floor_beside_fringe, fringe_of_wall,
    ground_unseen_beside_face, lip_over_shadow, slopes_across, two_levels, unresolved_ground,
    wall_goes_on,
};
pub(crate) use faces::{ground_beside_face, unresolved_face_along};
pub use gaps::{gaps, GRAZING_DEG};
pub use hidden::{blind_rise, hidden_tops, steep_exit};
pub(crate) use hidden::{cut_cells, first_cut, FRONT_RISING_M, STEEP_EXIT_RISE_M};
use posts::post_top;
pub use side::side_exit;

/// Steps and slopes in the wheel tracks.
///
/// Along each track strip, from every seen cell, find the first cell ahead whose mean
/// height differs by more than the wheel radius. If the slope between the two is at
/// or above the maximum, the terrain is impassable there: a *step* when the change
/// happens within two cells (≤ 0.1 m at the default voxel), a *slope* otherwise. A
/// change smaller than the wheel radius is climbable however steep (a low step); a
/// long climb is impassable only if it is steep.
///
/// A cell holding a vertical face (a band edge, a step's front) has two surfaces, the
/// face's crest and its foot ([`crate::grid::Cell::crest`], [`crate::grid::Cell::foot`];
/// both the mean for a cell with one surface); its mean belongs to neither. The strip
/// follows, in each such cell, the surface that continues it (the one nearer the last
/// cell's height), so a face along the strip (a ramp under the track beside a flat
/// belly band, a trench) makes no step, while a face across it still does: past the
/// face the cells have one surface, the other side's.
///
/// A cell the image's top edge cuts through holds only the lower part of what stands
/// there: its top is a lower bound on its height (beside a face along the strip, a
/// trench's wall on the corridor's edge, the top is the face's: the bound is then
/// the ground's own surface, [`ground_beside_face`]). So a rise *into* such a cell, or a
/// fall *out of* it, is measured (the bound proves it), while a fall into it or a
/// rise out of it proves nothing and is not a hazard: the surface simply left the
/// view (a ramp rising out of the image, seen past its horizon only by its side face).
///
/// A strip where this finds nothing is tested once more, for rises only (steps and
/// slopes), with its sharp tops ([`sharp_tops`]) at their highest points: a 16.5 cm
/// cone with 47° flanks, seen whole 1 m out, read 10.3 cm over the ground before it
/// (its apex cell's mean 2.5 cm under its highest point) and was a go (`sweep --
/// natural 200 6822 random 7` #52). An 8.7 cm mound on a 2 cm bump whose apex stands
/// 11.4-11.9 cm over the flat ground before it stops too (`sweep -- natural 200 6824
/// random 6` #124): the wheel meets both as a rise of more than its radius. A rise to
/// a sharp top longer than a step's reach is judged as any slope: a 15.6 cm cone
/// with 38° flanks, read by a strip 2.9 cm beside its apex, climbs 12.7 cm to its
/// apex cell's highest point at 32° over 0.2 m, and was a go while this pass
/// measured steps alone (`sweep -- natural 200 7508 random 7` #45, #77).
///
/// `surface` receives, per track cell, the height the strip followed there (NaN for
/// cells it did not follow: unseen, past the horizon, or not in a track).
pub fn steps_and_slopes(
    f: &Frame,
    strip: &mut Vec<StripCell>,
    surface: &mut [f32],
    verdict: &mut Verdict,
) {
    surface.fill(f32::NAN);
    let r = f.cfg.rover.wheel_radius_m as f32;
    let tan_max = (f.cfg.rover.max_slope_deg as f32).to_radians().tan();
    let wheelbase = f.cfg.rover.wheelbase_m as f32;
    let vs = f.spec.voxel_m;
    for region in [Region::Left, Region::Right] {
        for iy in f.strips(region) {
            strip.clear();
            // The last two chosen (x, z): the strip's height and slope so far.
            let mut last: [Option<(f32, f32)>; 2] = [None, None];
            // The face along the strip the last seen cell showed, [x, top, top's y]
            // (a trench's wall); x moves on through cut cells that hold only its
            // fringe. However high it stood over that cell's ground: a 15 cm wall
            // read 10.8 cm over its cell's ground, its top voxel's mean under the
            // wall's top and the ground's mean over the floor with a few of the
            // face's points, and its fringe in the next cut cell then stood 11.3 cm
            // over the strip, a `step` (noisy, `sweep -- families 100 6306 random`
            // #25). A face's fringe can fake a rise only up to its own top.
            // Its top is the highest the run of cells showing it showed: a cell's top
            // is the highest voxel layer with enough points, so along one face it
            // moves by half a voxel from cell to cell (noisy, `sweep -- natural 100
            // 6202 random` #3: 0 and −2.7 cm on a wall whose top is at 0, and the
            // next cut cell's 0 no longer on it made a 20 cm `step`).
            let mut wall: Option<[f32; 3]> = None;
            // Whether the strip read the last seen cell's mean height: its one
            // surface sloped across the strip ([`slopes_across`]).
            let mut sloped = false;
            // How steeply the last cells read so sloped across the strip: `None`
            // unless `sloped`.
            let mut cross: Option<f32> = None;
            let y_mid = f.spec.y_centre(iy);
            for ix in 0..f.spec.nx {
                let c = f.spec.cell(ix, iy);
                if !f.seen[c] {
                    continue;
                }
                let cell = &f.cells[c];
                let past = f.past[c];
                let carried = continued(last, cell.x, tan_max);
                let along = ground_along(f, ix, iy, past);
                // Past the horizon, only the fringe of the wall seen before.
                let fringe = past && along.is_none() && wall_goes_on(cell, wall, y_mid, vs);
                // A surface sloping across the strip (a ramp's side drawn sloping, in
                // the track's edge strip) has no upper and lower surface to choose
                // from: its bands are parts of one slope, and which of them continues
                // the strip changes with the share of points each holds. Its mean is
                // the ground on the strip's centre line. Read from its bands, the
                // strip jumped 13 cm where the lower band ran short (`sweep --
                // bevelled 60 904 default 0` #24, a `step`).
                let mut across =
                    !past && slopes_across(cell, y_mid, vs) && !lip_over_shadow(cell, f.camera);
                let z = if across {
                    cell.z
                } else if past && (along.is_none() || sloped) {
                    beyond_horizon(cell, fringe, sloped)
                } else {
                    // Beside a face along the strip, its ground ([`ground_along`]);
                    // past the horizon a lower bound: beside such a face the top is
                    // the face's, and the bound the ground's.
                    let beside = cross.and_then(|k| slope_goes_on(f, ix, iy, k));
                    let (z, mean) = continuing(cell, along, (carried, sloped), beside);
                    across = mean;
                    z
                };
                // A post beside the ground in the cell: the wheel meets its top.
                let post = (!past).then(|| post_top(f, ix, iy, z, r)).flatten();
                if !past && post.is_none() && spilled(f, ix, iy, z, carried, r) {
                    // The belly band's ground, not this strip's: leave the cell out.
                    continue;
                }
                if !past && post.is_none() && over_unseen_ground(f, ix, iy, z, carried) {
                    // A bound over the strip's course, not its ground: leave it out.
                    continue;
                }
                if !past {
                    surface[c] = z;
                }
                let highest = wall.map_or(cell.top, |[_, top, _]| top.max(cell.top));
                wall = match (along, wall) {
                    (Some(_), _) => Some([cell.x, highest, cell.top_xy[1]]),
                    (None, Some([_, top, top_y])) if fringe => Some([cell.x, top, top_y]),
                    (None, Some(w)) if past && clear_of_wall(cell, w, y_mid, vs) => Some(w),
                    (None, _) if !past && fringe_of_wall(cell, z, y_mid, r, vs) => {
                        Some([cell.x, highest, cell.top_xy[1]])
                    }
                    _ => None,
                };
                if !past {
                    sloped = across;
                    cross = across.then(|| cross_slope(cell, vs).or(cross)).flatten();
                }
                last = [last[1], Some((cell.x, z))];
                let z = post.unwrap_or(z);
                strip.push(StripCell {
                    x: cell.x,
                    z,
                    ix,
                    past,
                    peak: z,
                    high: cell.peak.max(z),
                    wheel: z,
                });
            }
            wheel_heights(strip, r);
            let min_gap = f.cfg.analysis.gap_min_cells as usize;
            let limits = (r, tan_max, wheelbase, min_gap);
            let face_along =
                |a: &StripCell, b: &StripCell| face_under_track(f, iy, [a, b], (r, tan_max));
            if !strip_hazards(strip, region, limits, (vs, false), &face_along, verdict) {
                sharp_top_steps(f, (iy, region), strip, limits, &face_along, verdict);
            }
        }
    }
}

/// The step test again on strip `iy` of `region` (its seen cells, `strip`, wheel
/// heights set; `limits` and `face_along` as [`strip_hazards`] takes them), for rising
/// steps only, with its sharp tops ([`sharp_tops`]) at their highest points, when it
/// has any: a rise to a sharp top's highest point, which the mean read low.
fn sharp_top_steps(
    f: &Frame,
    (iy, region): (usize, Region),
    strip: &mut [StripCell],
    limits: (f32, f32, f32, usize),
    face_along: &dyn Fn(&StripCell, &StripCell) -> bool,
    verdict: &mut Verdict,
) {
    if !sharp_tops(f, iy, strip) {
        return;
    }
    for c in strip.iter_mut() {
        std::mem::swap(&mut c.z, &mut c.peak);
    }
    wheel_heights(strip, limits.0);
    strip_hazards(
        strip,
        region,
        limits,
        (f.spec.voxel_m, true),
        face_along,
        verdict,
    );
}

/// Mark the sharp tops of strip `iy` (its seen cells, `strip`): where the strip reads
/// a cell's one surface (crest and foot alike), higher than the cell just before it
/// and than the cell just after it (or with that cell in its shadow: a 15.4 cm cone
/// whose far side was hidden went, `sweep -- natural 200 7334 random 7` #11), than
/// anything within a wheel radius past it, and at least as high as the
/// seen cells beside it across (or with such a cell in a shadow: a 16.9 cm cone whose
/// apex cell had its far flank beside it hidden went, `sweep -- natural 200 2921
/// random 7` #190), and whose mean lies more than rough ground's spread
/// ([`ROUGH_SPREAD_M`]) under its top voxel's highest point ([`Cell::peak`]), that
/// cell's `peak` becomes that point. Over a sharp apex (a cone, a narrow mound) the
/// surface's mean lies 2-4 cm under it; a rounded or flat top (a rock, a boulder) it
/// reads within a centimetre, and the highest point adds only depth noise (an 8.8 cm
/// rock on rough ground, 0.4 cm under it, then stood over a wheel radius above the
/// ground before it and stopped the rover: `sweep -- families 100 7001 random` #6).
/// Only a top more than a wheel radius over a cell within a step's reach before it
/// counts (the rest cannot make a step). Returns whether the strip has any.
///
/// The cell just after may also be a *glimpse* of the far side: over the cell's mean
/// but with a highest point under the cell's, and the cell after it in the shadow. A
/// cone whose apex lies at a cell's far edge shows a few points of its far side in
/// the next cell, which read over the apex cell's mean (a 15.4 cm cone whose apex
/// stood 13.1 cm over the ground before it went: `sweep -- natural 200 2608 random
/// 7` #96). Such a top's far side is hidden, and it counts over a wheel radius and
/// [`UNSEEN_FOOT_MARGIN_M`], the margin of the other tops not seen whole (a 7 cm cone
/// 2.5 m out, its noisy highest point 11.7 cm over a dip before it, stopped the
/// rover: `sweep -- natural 100 2913 random 6` #86).
///
/// The other cells keep their means: rough ground's highest points stand 1-2 cm over
/// them (more with depth noise), and a face along the strip (a ramp's side, a
/// descent's wall) lifts a cell's highest point but leaves the cells beside it across
/// as high. With every cell at its highest point, 55 of the regression sweeps' 1,780
/// frames turned from go to stop (half-plane descents, ramps past their view's end).
fn sharp_tops(f: &Frame, iy: usize, strip: &mut [StripCell]) -> bool {
    let s = f.spec;
    let r = f.cfg.rover.wheel_radius_m as f32;
    if iy == 0 || iy + 1 >= s.ny {
        return false;
    }
    let mut any = false;
    for k in 1..strip.len().saturating_sub(1) {
        let (before, here, after) = (strip[k - 1], strip[k], strip[k + 1]);
        let rises = before.z < here.z
            && before.ix + 1 == here.ix
            && !(before.past || here.past || after.past);
        if !rises {
            continue;
        }
        let cell = &f.cells[s.cell(here.ix, iy)];
        let Some(peak) = sharp_apex(cell, here.z) else {
            continue;
        };
        // The row just past the strip's `j`th cell in a shadow (`Frame::shadow_past`).
        let shadow_past = |j: usize| f.shadow_past(strip[j].ix, iy);
        // The cell just past it in its shadow, or the cell past that one, and the one
        // between a glimpse of the far side.
        let shadow = shadow_past(k);
        let glimpse = after.ix == here.ix + 1
            && after.z > here.z
            && f.cells[s.cell(after.ix, iy)].peak <= peak
            && shadow_past(k + 1);
        let under = |c: &StripCell| c.z <= here.z || (glimpse && c.ix == after.ix);
        if !((after.ix == here.ix + 1 && under(&after)) || shadow) {
            continue;
        }
        // A cell beside it in a shadow hides ground under the line of sight over what
        // casts it, no higher than a seen top: the cone's own far flank.
        let not_under = |j: usize| {
            let c = s.cell(here.ix, j);
            (f.seen[c] && f.cells[c].crest <= cell.crest) || (!f.seen[c] && f.shadowed[c])
        };
        // The lowest cell a step to it can rise from: what rises no more than a
        // wheel radius over it cannot make one (the rises-only pass's reach).
        let floor = strip[..k]
            .iter()
            .rev()
            .take_while(|c| here.x - c.x <= step_floor_reach_m(s.voxel_m, r))
            .fold(f32::INFINITY, |m, c| m.min(c.z));
        // A top: nothing within a wheel radius past it stands higher (a ramp rising
        // under the limit makes a cell a local maximum every few cells with noise).
        let top = strip[k + 1..]
            .iter()
            .take_while(|c| c.x - here.x <= r)
            .all(under);
        // A glimpse's apex has its far side hidden past it: it counts, as the other
        // tops the view does not show whole, over a wheel radius and a margin.
        let least = if glimpse { r + UNSEEN_FOOT_MARGIN_M } else { r };
        if top && peak - floor > least && not_under(iy - 1) && not_under(iy + 1) {
            strip[k].peak = peak;
            any = true;
        }
    }
    any
}

/// How far back along a strip, metres, the ground lies that a step to a top can rise
/// from: the rises-only pass's reach ([`STEP_REACH_VOXELS`] voxels of `voxel_m`) and
/// a wheel radius `r`. The sharp-top test ([`sharp_tops`]) and the side edge's test
/// ([`side_exit`]) ask it.
fn step_floor_reach_m(voxel_m: f32, r: f32) -> f32 {
    STEP_REACH_VOXELS * voxel_m + r
}

/// A cell's top voxel's highest point ([`Cell::peak`]), metres, where the cell reads
/// one surface (crest and foot alike, the followed height `z`) whose mean lies more
/// than rough ground's spread ([`ROUGH_SPREAD_M`]) under it: a sharp apex (a cone, a
/// narrow mound), whose cell's mean reads 2-4 cm low. A rounded or flat top (a rock,
/// a boulder, a bump) the mean reads well, and its highest point only adds depth
/// noise: `None`. The step test's sharp tops ([`sharp_tops`]) and the hidden-rise
/// test ([`blind_rise`]) ask the same.
fn sharp_apex(cell: &Cell, z: f32) -> Option<f32> {
    let one_surface = z == cell.crest && cell.crest == cell.foot;
    (one_surface && cell.peak - z > ROUGH_SPREAD_M).then_some(cell.peak)
}

/// The ground of seen cell (`ix`, `iy`) beside a face along its strip (a trench's
/// wall, [`ground_beside_face`]), metres; in a cell seen whole, not `past` the
/// horizon, also where its two surfaces do not say which ([`unresolved_ground`]).
fn ground_along(f: &Frame, ix: usize, iy: usize, past: bool) -> Option<f32> {
    let (cell, vs, y_mid) = (
        &f.cells[f.spec.cell(ix, iy)],
        f.spec.voxel_m,
        f.spec.y_centre(iy),
    );
    let beside = ground_beside_face(cell, y_mid, vs);
    if past {
        return beside;
    }
    beside.or_else(|| unresolved_ground(cell, (f.spec.x_centre(ix), y_mid), vs, f.camera[1]))
}

/// Whether seen cell (`ix`, `iy`), read as `z` (metres), holds a face along its strip
/// and none of its ground ([`ground_unseen_beside_face`]), and `z`, the face's lowest
/// voxel, stands over the strip carried on (`carried`): the ground lies somewhere
/// under `z`, so the reading says nothing of a rise or a fall there. A reading under
/// the strip carried on still bounds a fall, and is kept.
fn over_unseen_ground(f: &Frame, ix: usize, iy: usize, z: f32, carried: Option<f32>) -> bool {
    let xy = (f.spec.x_centre(ix), f.spec.y_centre(iy));
    carried.is_some_and(|k| z > k)
        && ground_unseen_beside_face(
            &f.cells[f.spec.cell(ix, iy)],
            xy,
            f.spec.voxel_m,
            f.camera[1],
        )
}

/// Cell (`ix`, `iy`)'s height on its strip's centre line when its points lie on one
/// side of a slope across the strip at `cross` ([`beside_slope`]), metres, if the
/// slope goes on there: the next strip across on the slope's other side is seen in
/// that row (not past the horizon) at least as far up (or down) as the height read.
/// A stone's flank sloping across a strip ends with the stone: past it (the next
/// strip across in its shadow) the ground beside it is read as it is. Carried along
/// the flank's slope, that ground past a 15.4 cm cap read 4 cm higher and the cap's
/// stop was lost (`sweep -- natural 200 7322 random 7` #23, noisy, a go).
fn slope_goes_on(f: &Frame, ix: usize, iy: usize, cross: f32) -> Option<f32> {
    let (cell, y_mid, vs) = (
        &f.cells[f.spec.cell(ix, iy)],
        f.spec.y_centre(iy),
        f.spec.voxel_m,
    );
    let z = beside_slope(cell, y_mid, cross, vs)?;
    let other = if cell.y > y_mid {
        iy.checked_sub(1)?
    } else {
        Some(iy + 1).filter(|&j| j < f.spec.ny)?
    };
    let c = f.spec.cell(ix, other);
    let beyond = f.seen_whole(c).then_some(f.cells[c].z)?;
    ((beyond - z) * (z - cell.z) >= 0.0).then_some(z)
}

/// The height a strip reads on a seen cell its surface does not slope across: the
/// ground beside a face along the strip (`along`, [`ground_along`]) where there is
/// one; else its height on the centre line when its points lie on one side of a slope
/// the strip reads across (`beside`, [`beside_slope`]: given only where the strip read
/// the last cell's mean); else of its two surfaces the one that continues the strip
/// (its last height carried on at its slope, up to passable, `carried`), metres. Where
/// the strip read the last cell's mean (`sloped`), it reads this one's mean instead
/// while that continues the strip within rough ground's spread ([`ROUGH_SPREAD_M`]) of
/// the surface or ground, unless the mean is that surface (the cell's points span no
/// more than one surface band: the slope across has ended). Also whether a mean was
/// read.
///
/// A sloping side's cells do not all pass [`slopes_across`] (noise and the voxel
/// layers move their bands, and far out a narrow side, 75-85° steep, shows as a face
/// along the strip): a strip switching between means and bands jumps by 4-9 cm, as the
/// mean lies farther under the ramp's top the higher the side stands (#78 of `sweep --
/// bevelled 100 901 default 9`, a `slope`; `bevelled 100 7506 random` #75, a `step`).
/// The margin keeps it on the means where the two continue it about as well: switching
/// at a 1 mm difference, it jumped 7 cm onto a ramp's top 2.8 m out (`bevelled 100 902
/// random 9` #87, a `step`).
fn continuing(
    cell: &Cell,
    along: Option<f32>,
    (carried, sloped): (Option<f32>, bool),
    beside: Option<f32>,
) -> (f32, bool) {
    if let (None, Some(z)) = (along, beside) {
        return (z, true);
    }
    let near = carried.unwrap_or(cell.foot);
    let surface = along.unwrap_or(if (cell.crest - near).abs() <= (cell.foot - near).abs() {
        cell.crest
    } else {
        cell.foot
    });
    // A cell whose points lie in one surface band ends the reading of means.
    if sloped
        && cell.z != surface
        && (cell.z - near).abs() < (surface - near).abs() + ROUGH_SPREAD_M
    {
        (cell.z, true)
    } else {
        (surface, false)
    }
}

/// The height a strip reads on a seen cell past the horizon with no face along the
/// strip, or read by its means up to the horizon, metres: the floor beside the fringe
/// of the wall seen before (`fringe`, [`floor_beside_fringe`]); where the strip read
/// the mean up to the horizon (`sloped`), the mean of what is seen of the cell (its
/// top is the slope's high side, which stood 19 cm over the strip and made a `step`:
/// `sweep -- bevelled 60 904 default 0` #23, #54), a face along the strip or not (the
/// ground beside a ramp's sloping side, its top, stood 17 cm over the mean read just
/// before the horizon, a `step`: `sweep -- bevelled 100 4412 random 9` #41, noisy);
/// else its top, or its mean if higher: a lower bound on its height.
fn beyond_horizon(cell: &Cell, fringe: bool, sloped: bool) -> f32 {
    if fringe {
        floor_beside_fringe(cell)
    } else if sloped {
        cell.z
    } else {
        cell.top.max(cell.z)
    }
}

/// A strip's height carried on to `x` from its last two chosen cells (`last`, (x, z),
/// oldest first) at their slope, up to passable; the last height with one cell;
/// `None` with none.
fn continued(last: [Option<(f32, f32)>; 2], x: f32, tan_max: f32) -> Option<f32> {
    match last {
        [Some((x0, z0)), Some((x1, z1))] if x1 > x0 => {
            let k = ((z1 - z0) / (x1 - x0)).clamp(-tan_max, tan_max);
            Some(z1 + k * (x - x1))
        }
        [_, Some((_, z1))] => Some(z1),
        _ => None,
    }
}

/// Whether a rise or fall of track strip `iy` between its cells `a` and `b` is the
/// strip reading a face along the track's edge below the track's surface, not a step
/// or slope the track meets: `iy` is the track's edge strip beside the belly band,
/// with a cell at either end holding two levels ([`two_levels`]), or its outer edge
/// strip, on the corridor's edge; the next strip inward reads one surface in both
/// rows (seen whole, not two levels; short of its horizon, except at the end whose
/// wheel stands higher, where a reading past it is a bound from below and serves)
/// and changes between them by at most a wheel radius `r` and less steeply than the
/// limit `tan_max`; and the higher end stands at most rough ground's spread
/// ([`ROUGH_SPREAD_M`]) over the inner strip's surface there, its wheel
/// ([`wheel_heights`]) as much over the inner strip's wheel ([`wheel_on`]) unless it
/// lies past the horizon (there its wheel is its reading, a bound, and the inner
/// strip's reading abreast, a bound of the same kind, vouches for it). The
/// track, half a metre wide, rests on that surface; the edge strip's lower reading is
/// the face's points.
///
/// A one-track ramp's side, 4.4 cm wide and 0.5 m high 2.7 m out, seen by a 320×240
/// camera: the edge strip read it as a surface sloping across, its mean 6-13 cm under
/// the ramp's top as the share of the side's points changed from row to row, then the
/// top: an 18 cm `step` where the inner strips climbed a smooth 21° (`sweep --
/// bevelled 100 3006 random` #75, clean and noisy). A ramp's outer side, sloping over
/// 9.7 cm, fills the outer edge strip: near the toe the strip sees it whole and reads
/// its mean, 2.4 cm under the ramp's top, and higher up the ramp hides the side's
/// lower part and the strip reads the top. It climbed 31° where the ramp climbs
/// 24.3°, a `slope` (`sweep -- bevelled 100 10312 random 9` #75, clean, a Kinect v2
/// 1.19 m high); its cells span under [`FACE_MIN_M`](faces::FACE_MIN_M), so the
/// outer edge strip asks for no two levels. A block or step across the track moves
/// the inner strip with it; a post in the edge strip stands over its surface, and
/// lifts the wheels on the cells before it over the inner strip's (a 30 cm post 5 cm
/// wide, a `step` from the cell 13 cm before it, whose own reading lay under the
/// inner strip's). A ramp rising out of the image: the inner strip's cell 2.95 m out
/// lay past its horizon, and the edge strip's, three points all at the ramp's full
/// height, lifted the wheels on the cells before it 16 cm over their side's mean, a
/// `step` (`sweep -- bevelled 100 11112 random 9` #85, clean, a 320×240 camera).
/// The higher end is told by wheel, not by mean: one of those wheels, on a cell whose
/// mean is the lower, rested on the cell past it. A 15.9° ramp's side, 4.7 cm wide,
/// seen by a Kinect v2 rolled 7.8°: the edge strip's cell 2.89 m out, past the
/// horizon, read the ramp's top within a centimetre of the inner strip's reading past
/// its horizon there, 12 cm over the side's mean before it; the inner strip's wheel
/// abreast, resting only on cells seen whole, lay 2 cm lower, and the rise was a
/// `step` (`sweep -- bevelled 100 12706 random 0` #34, clean).
///
/// In the outermost strip a fall also counts for nothing when it lands on the inner
/// strip's surface or over it (within rough ground's spread under it, read past its
/// horizon too) from a cell that the cell just before it reads within `r`: a descent
/// under the track leaves a wall along the corridor's edge from its floor up to the
/// ground beyond, and the strip read the wall's points over the floor, 6-11 cm up,
/// then the floor where depth noise left fewer of them, a fall of 11.2-12.1 cm where
/// the inner strip read the floor all along: a `step` (`sweep -- oblique 100 11403
/// random` #43 and #82, noisy, 320×240 cameras). A stone's front stands over the
/// ground before it and is judged as a rise.
fn face_under_track(f: &Frame, iy: usize, ends: [&StripCell; 2], (r, tan_max): (f32, f32)) -> bool {
    let s = f.spec;
    let (inward, outer) = match edge_strip(f, iy) {
        Some((_, inward)) => (inward, false),
        None => (outer_strip_inward(f, iy), true),
    };
    let Some(inward) = inward else {
        return false;
    };
    let spans = |ix: usize| two_levels(&f.cells[s.cell(ix, iy)]);
    let inner = |ix: usize, past_ok: bool| {
        let c = s.cell(ix, inward);
        let cell = &f.cells[c];
        (f.seen[c] && (past_ok || !f.past[c]) && !two_levels(cell)).then_some(cell.z)
    };
    let [a, b] = ends;
    let b_high = b.wheel > a.wheel;
    // On the corridor's edge a fall's landing may lie past the inner strip's horizon:
    // the surface read there is what the camera saw of it.
    let (Some(za), Some(zb)) = (inner(a.ix, !b_high), inner(b.ix, b_high || outer)) else {
        return false;
    };
    let (high, z_inner) = if b.z > a.z { (b, zb) } else { (a, za) };
    let change = (zb - za).abs();
    // On the corridor's edge, a fall that lands on the inner strip's surface or over
    // it, from a reading that the cell just before it reads within a wheel radius:
    // the points of a wall rising from the track's floor along its outer edge (a
    // trench under the track), not a stone's back, whose front stands over the ground
    // before it.
    let along_wall = a.ix > 0 && {
        let c = s.cell(a.ix - 1, iy);
        f.seen[c] && f.cells[c].z >= a.z - r
    };
    let onto_surface = outer && !b_high && along_wall && b.z >= zb - ROUGH_SPREAD_M;
    (outer || spans(a.ix) || spans(b.ix))
        && change <= r
        && change < tan_max * (b.x - a.x).abs()
        && (onto_surface
            || (high.z <= z_inner + ROUGH_SPREAD_M
                && (high.past || high.wheel <= wheel_on(f, inward, high, r) + ROUGH_SPREAD_M)))
}

/// Where a wheel of radius `r` over strip `iy`, abreast of `cell` (another strip's),
/// rests ([`wheel_heights`]' rule on that strip's seen cells short of the horizon
/// within `r` of it), metres; −∞ when it has none.
fn wheel_on(f: &Frame, iy: usize, cell: &StripCell, r: f32) -> f32 {
    let s = f.spec;
    let reach = (r / s.voxel_m).ceil() as usize;
    (cell.ix.saturating_sub(reach)..(cell.ix + reach + 1).min(s.nx))
        .map(|ix| s.cell(ix, iy))
        .filter(|&c| f.seen_whole(c))
        .filter_map(|c| on_rim(f.cells[c].z, (f.cells[c].x - cell.x).abs(), r))
        .fold(f32::NEG_INFINITY, f32::max)
}

/// For a track's outer edge strip `iy` (on the corridor's edge), the next strip
/// inward (`None` when the track has no other strip); `None` for any other strip.
fn outer_strip_inward(f: &Frame, iy: usize) -> Option<usize> {
    let run = f.strips(f.region[iy]);
    match f.region[iy] {
        Region::Left if iy + 1 == run.end && iy > run.start => Some(iy - 1),
        Region::Right if iy == run.start && iy + 1 < run.end => Some(iy + 1),
        _ => None,
    }
}

/// For a track's edge strip `iy` beside the belly band, the belly strip across the
/// band edge and the next strip inward (`None` when the track has no other strip);
/// `None` for any other strip.
fn edge_strip(f: &Frame, iy: usize) -> Option<(usize, Option<usize>)> {
    let (across, inward) = match f.region[iy] {
        Region::Left if iy >= 1 && f.region[iy - 1] == Region::Belly => (iy - 1, iy + 1),
        Region::Right if iy + 1 < f.spec.ny && f.region[iy + 1] == Region::Belly => {
            (iy + 1, iy.wrapping_sub(1))
        }
        _ => return None,
    };
    let same_track = inward < f.spec.ny && f.region[inward] == f.region[iy];
    Some((across, same_track.then_some(inward)))
}

/// Whether track cell (`ix`, `iy`), its ground read as `z`, holds the belly band's
/// ground spilled over the band edge rather than the strip's: the strip is the track's
/// edge strip beside the belly band; `z` lies more than a wheel radius from the strip
/// carried on (`near`) but within [`SPILL_M`] of the belly cell across the edge; and
/// the next strip inward sees nothing at that level there (its cell, when seen, is
/// nearer the strip carried on). A track lower than the belly band (a descent under
/// one track) leaves a wall along the edge, whose top and the belly's ground beside
/// it, few points far out and scattered by depth noise, can outnumber the track's own
/// floor in the edge cell; read as its ground they make a step. A rise across the
/// track (a ditch's far wall, a step) lifts the inner strips too.
fn spilled(f: &Frame, ix: usize, iy: usize, z: f32, near: Option<f32>, r: f32) -> bool {
    let s = f.spec;
    let Some(near) = near else {
        return false;
    };
    let Some((across, inward)) = edge_strip(f, iy) else {
        return false;
    };
    let belly = s.cell(ix, across);
    if (z - near).abs() <= r || !f.seen[belly] || (z - f.cells[belly].z).abs() > SPILL_M {
        return false;
    }
    let inner_level = inward
        .map(|j| s.cell(ix, j))
        .filter(|&c| f.seen[c])
        .map(|c| f.cells[c].z);
    inner_level.is_none_or(|zi| (zi - near).abs() < (zi - z).abs())
}

/// How close an edge cell's ground must come to the belly band's beside it to be that
/// ground spilled over ([`spilled`]), metres: rough ground's peak to peak.
const SPILL_M: f32 = 0.05;

/// Rough ground's spread about its mean, metres (σ ≈ 1.25 cm for ±2.5 cm): ground
/// within it of a level counts as at that level.
const ROUGH_SPREAD_M: f32 = 0.015;
/// How much more than a wheel radius a rise whose foot or far side is not seen must
/// stand over the ground it is measured from to be an obstacle, metres
/// ([`blind_rise`], [`hidden_tops`], and the face analysis's step relief): midway
/// between the tallest pebble the rover drives over on rough ground (9 cm on a
/// 2.5 cm bump, 11.5 cm up) and the lowest rock it must stop at (15 cm in a 2.5 cm
/// dip, 12.5 cm up), over the default 11 cm wheel radius. With 1.5 cm (rough
/// ground's spread) instead, a 15.6 cm rock whose front the image's side edge cut,
/// seen 12.4 cm over the rover's ground in one inner strip and 14.3 cm in the next,
/// was a go (`sweep -- families 100 6801 random` #7).
pub(crate) const UNSEEN_FOOT_MARGIN_M: f32 = 0.01;
/// How far a cell stands over the ground under it (`on_line`, metres) as a stone the
/// wheel must climb, metres: the more of its height `z` and of its highest point `top`
/// less [`UNSEEN_FOOT_MARGIN_M`]. A cell's mean may read a stone's top several
/// centimetres low; its highest point, which rough ground's bumps and depth noise lift
/// (a 9 cm pebble's to 11-12 cm over its line), gets the margin. A wheel of radius `r`
/// climbs the stone when this is under `r` (`climb`'s stones on a line and falls onto
/// one, `gaps`' cells before a gap or a shadow).
fn stone_height(z: f32, top: f32, on_line: f32) -> f32 {
    (z - on_line).max(top - on_line - UNSEEN_FOOT_MARGIN_M)
}

/// Whether `verdict` already accounts for `unknown` ground `x` metres out on `side`
/// ([`steep_exit`], [`side_exit`]): a hazard on that side, or one at least as near on
/// any side, stops the rover there first.
fn unknown_judged(verdict: &Verdict, side: Side, x: f32) -> bool {
    (verdict.hazards.iter()).any(|h| h.side == side || h.distance_m <= x)
}

/// The ground the strip followed in cell `c` (`surface`, from [`steps_and_slopes`]),
/// metres, when the cell is seen whole: not past the horizon, and in a track.
fn followed(f: &Frame, surface: &[f32], c: usize) -> Option<f32> {
    f.seen_whole(c)
        .then_some(surface[c])
        .filter(|z| z.is_finite())
}

/// Largest RMS distance of wheel heights from their line for a climb's slope
/// (`climb::climb_slope`) to take them as one slope, metres: rough ground's spread (σ ≈
/// 1.25 cm for ±2.5 cm), under what a bank steeper than the limit and shorter than the
/// wheelbase leaves (≥ 1.5 cm for banks whose wheelbase fit falls under 30°).
const ROUGH_LINE_RMS_M: f32 = 0.016;

/// The least-squares line z = a·x + c through `points` (x, z), and the RMS of their
/// heights about it, metres; `None` without two distinct x.
fn line_fit(points: impl Iterator<Item = (f32, f32)> + Clone) -> Option<(Plane, f64)> {
    plane_fit(points.map(|(x, z)| (x, 0.0, z))).map(|(p, rms, _)| (p, rms))
}

/// The least-squares plane z = a·x + b·y + c through `points` (x, y, z), the RMS of
/// their heights about it (metres) and how many they are; `None` for a degenerate fit
/// (no two distinct x, or, with y varying, all on one line).
fn plane_fit(points: impl Iterator<Item = (f32, f32, f32)> + Clone) -> Option<(Plane, f64, usize)> {
    let mut fit = PlaneFit::default();
    for (x, y, z) in points.clone() {
        fit.add(f64::from(x), f64::from(y), f64::from(z), 1.0);
    }
    let p = fit.solve()?;
    let (ss, n) = points.fold((0.0, 0usize), |(ss, n), (x, y, z)| {
        let off = f64::from(z) - p.z(f64::from(x), f64::from(y));
        (ss + off.powi(2), n + 1)
    });
    Some((p, (ss / n as f64).sqrt(), n))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_strip_reading_means_keeps_to_them_beside_a_face_until_a_band_continues_it_better() {
        // The right track's edge strip on a ramp whose side slopes over 3.3 cm,
        // 2.83 m out (`sweep -- bevelled 100 902 random 9` #87, clean; its heights
        // to the millimetre, its positions, which this does not read, rounded): the
        // side shows as a face along the strip, the ramp's top beside it 0.498 m,
        // the cell's mean 0.420 m, and the strip carried on to 0.4595 m from cells
        // whose means it read.
        let cell = Cell {
            n: 40,
            x: 2.827,
            y: -0.218,
            z: 0.420,
            top: 0.512,
            peak: 0.520,
            top_xy: [2.83, -0.205],
            low: 0.28,
            crest: 0.498,
            foot: 0.300,
            crest_xy: [2.83, -0.21],
            foot_xy: [2.82, -0.245],
        };
        let beside_face = Some(0.498);
        // The top continues the strip 1 mm better, within rough ground's spread:
        // the mean, not a 7 cm jump.
        let reading = continuing(&cell, beside_face, (Some(0.4595), true), None);
        assert_eq!(reading, (0.420, true));
        // A strip that read the last cell's band takes the ground beside the face.
        let reading = continuing(&cell, beside_face, (Some(0.4595), false), None);
        assert_eq!(reading, (0.498, false));
        // Carried on to 0.48 m the top continues it better by 2.7 cm, over the
        // spread: the strip switches to it.
        let reading = continuing(&cell, beside_face, (Some(0.48), true), None);
        assert_eq!(reading, (0.498, false));
        // With no face along the strip, of the two bands the crest continues it.
        let reading = continuing(&cell, None, (Some(0.48), true), None);
        assert_eq!(reading, (0.498, false));
        let reading = continuing(&cell, None, (Some(0.32), false), None);
        assert_eq!(reading, (0.300, false));
        // A cell whose points span one surface band, its mean: the strip reads it as
        // that surface and stops reading means (kept on, it carried a stale slope
        // across on to the next cells, and a 16.3 cm cone's `slope` was lost: `sweep
        // -- natural 200 7508 random 7` #38, noisy, in a first version).
        let mut one = cell;
        (one.crest, one.foot) = (one.z, one.z);
        let reading = continuing(&one, None, (Some(0.4595), true), None);
        assert_eq!(reading, (0.420, false));
    }
}
