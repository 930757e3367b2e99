//! Crossing possibility (paper §3.1, with the fixes docs/design.md lists): slopes and steps
//! in the wheel tracks, anything too tall under the belly, and ground that should be
//! seen but is not (gaps, drop-offs).

use nalgebra::Vector3;

use super::plane::{Plane, PlaneFit};
use super::{Frame, Region, StripCell};
use crate::grid::Cell;
use crate::verdict::{Hazard, HazardKind, Verdict};

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
                let fringe =
                    past && along.is_none() && wall_goes_on(cell, wall, f.spec.y_centre(iy), vs);
                // A surface sloping across the strip (a ramp's side drawn sloping, in
                // the track's edge strip) has no upper and lower surface to choose
                // from: its bands are parts of one slope, and which of them continues
                // the strip changes with the share of points each holds. Its mean is
                // the ground on the strip's centre line. Read from its bands, the
                // strip jumped 13 cm where the lower band ran short (`sweep --
                // bevelled 60 904 default 0` #24, a `step`).
                let mut across = !past && slopes_across(cell, f.spec.y_centre(iy), vs);
                let z = if across {
                    cell.z
                } else if let Some(z) = along {
                    // Past the horizon a lower bound: beside such a face the top is
                    // the face's, and the bound the ground's.
                    z
                } else if past {
                    if fringe {
                        floor_beside_fringe(cell)
                    } else if sloped {
                        // Where the strip read the mean up to the horizon, the mean
                        // of what is seen of the cell past it: its top is the slope's
                        // high side, which stood 19 cm over the strip and made a
                        // `step` (#23, #54).
                        cell.z
                    } else {
                        cell.top.max(cell.z)
                    }
                } else {
                    let (z, mean) = continuing(cell, carried, sloped);
                    across = mean;
                    z
                };
                if !past && spilled(f, ix, iy, z, carried, r) {
                    // The belly band's ground, not this strip's: leave the cell out.
                    continue;
                }
                if !past {
                    surface[c] = z;
                }
                let highest = wall.map_or(cell.top, |[_, top, _]| top.max(cell.top));
                wall = match (along, wall) {
                    (Some(_), _) => Some([cell.x, highest, cell.top_xy[1]]),
                    (None, Some([_, top, top_y])) if fringe => Some([cell.x, top, top_y]),
                    (None, _) if !past && fringe_of_wall(cell, z, f.spec.y_centre(iy), r, vs) => {
                        Some([cell.x, highest, cell.top_xy[1]])
                    }
                    _ => None,
                };
                if !past {
                    sloped = across;
                }
                last = [last[1], Some((cell.x, z))];
                strip.push(StripCell {
                    x: cell.x,
                    z,
                    ix,
                    past,
                    wheel: z,
                });
            }
            wheel_heights(strip, r);
            let min_gap = f.cfg.analysis.gap_min_cells as usize;
            strip_hazards(strip, region, (r, tan_max, wheelbase, min_gap), vs, verdict);
        }
    }
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

/// Of a seen cell's two surfaces, the one that continues the strip (its last height
/// carried on at its slope, up to passable, `carried`), metres; or, where the strip
/// read the last cell's mean (`sloped`), this one's mean when it continues the strip
/// better. Also whether the mean was read. A sloping side's cells do not all pass
/// [`slopes_across`] (noise and the voxel layers move their bands), and a strip
/// switching between means and bands jumps by 4-5 cm (#78 of `sweep -- bevelled 100
/// 901 default 9`, a `slope`).
fn continuing(cell: &Cell, carried: Option<f32>, sloped: bool) -> (f32, bool) {
    let near = carried.unwrap_or(cell.foot);
    let surface = if (cell.crest - near).abs() <= (cell.foot - near).abs() {
        cell.crest
    } else {
        cell.foot
    };
    if sloped && (cell.z - near).abs() < (surface - near).abs() {
        (cell.z, true)
    } else {
        (surface, false)
    }
}

/// Whether a cell past the horizon holds only the fringe of the face along its strip
/// that the strip's last seen cell showed (`wall`: that cell's x, top and top's y,
/// metres, the top the highest of the run of cells that showed it; x moved on to each
/// cut cell after it holding only that fringe). The cell's upper band is under
/// [`crate::grid::SURFACE_MIN_SHARE`] of its points (`crest` is `foot`), or centres
/// on the face's line too (the fringe is a surface of its own, but the floor's few
/// points, drawn toward the wall by noise, centre too close to it for
/// [`ground_beside_face`] to tell the two apart: `sweep -- families 100 5701 random`
/// #47, noisy, an 18 cm `step` 2.80 m out); it lies within [`WALL_REACH_M`] of that
/// x; its top stands no higher than the face's did (within rough ground's spread,
/// [`ROUGH_SPREAD_M`]); and its top voxel hugs the strip's side
/// ([`FACE_OFF_VOXELS`] off its centre line `y_mid`) on the face's line (within that
/// much of the face's top). Its top is then
/// the wall's, not a bound on the strip's ground: a trench's wall along the
/// corridor's edge, its top level with the ground beside the trench, ran on into the
/// cells the image's top edge cuts and made the floor "rise" to it (`sweep --
/// families 100 5401 random` #91, `oblique 100 5403` #44 noisy). Anything new there
/// still bounds the strip: a top higher than the wall's, off its line (a post
/// standing in the strip), or a surface across the cell.
fn wall_goes_on(cell: &Cell, wall: Option<[f32; 3]>, y_mid: f32, vs: f32) -> bool {
    let side = FACE_OFF_VOXELS * vs;
    (cell.top_xy[1] - y_mid).abs() >= side
        && wall.is_some_and(|[x, top, top_y]| {
            let on_line = |y: f32| (y - top_y).abs() <= side;
            (cell.crest == cell.foot || on_line(cell.crest_xy[1]))
                && cell.x - x <= WALL_REACH_M
                && cell.top <= top + ROUGH_SPREAD_M
                && on_line(cell.top_xy[1])
        })
}

/// Whether a cell seen whole holds the fringe of a face along its strip standing more
/// than a wheel radius `r` above its ground `z`: one surface (the face's points are
/// under [`crate::grid::SURFACE_MIN_SHARE`] of the cell's, `crest` is `foot`), and a
/// top over `z` by more than `r` whose voxel hugs the strip's side
/// ([`FACE_OFF_VOXELS`] off its centre line `y_mid`). Depth noise scatters a trench
/// wall's points on the corridor's edge over more voxel layers, so that in some of its
/// cells they no longer make a band of their own; the wall is still there, and the
/// cells the image's top edge cuts past it hold its fringe ([`wall_goes_on`]): without
/// it, their tops read as a rise of the floor (`sweep -- families 100 5606 random` #3,
/// noisy: a 16 cm `step` 2.35 m out).
fn fringe_of_wall(cell: &Cell, z: f32, y_mid: f32, r: f32, vs: f32) -> bool {
    cell.crest == cell.foot
        && cell.top - z > r
        && (cell.top_xy[1] - y_mid).abs() >= FACE_OFF_VOXELS * vs
}

/// The floor's height in a cell past the horizon that holds a wall's fringe
/// ([`wall_goes_on`]), metres: its lower surface, or, where `foot` is not one (it is
/// the cell's mean or its upper surface), its lowest voxel (a bound, and past the
/// horizon the lower one proves less). `foot` falls back to the mean when neither
/// band holds a surface (a tall face's points spread over so many voxel layers that
/// neither band holds a quarter of them), and to `crest` when only the upper band
/// does; either is then the face, not the floor. A one-track descent's 43 cm side
/// face on the corridor's edge, in the first cell the image's top edge cuts, read
/// 15 cm above the floor and made a `step` (`sweep -- oblique 100 5903` #57, the
/// mean); a 37 cm one, 30 cm above it (`oblique 100 6203` #66, the upper band). A
/// cell of one surface gives its mean for both too; its lowest voxel lies within a
/// voxel of it.
fn floor_beside_fringe(cell: &Cell) -> f32 {
    if cell.foot == cell.z || cell.foot == cell.crest {
        cell.low.min(cell.foot)
    } else {
        cell.foot
    }
}

/// How far past the last cell that showed a face along the strip (or its fringe)
/// [`wall_goes_on`] takes it to run on, metres: three cells.
const WALL_REACH_M: f32 = 0.15;

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
    let (across, inward) = match f.region[iy] {
        Region::Left if iy >= 1 && f.region[iy - 1] == Region::Belly => (iy - 1, iy + 1),
        Region::Right if iy + 1 < s.ny && f.region[iy + 1] == Region::Belly => {
            (iy + 1, iy.wrapping_sub(1))
        }
        _ => return false,
    };
    let belly = s.cell(ix, across);
    if (z - near).abs() <= r || !f.seen[belly] || (z - f.cells[belly].z).abs() > SPILL_M {
        return false;
    }
    let inner_level = (inward < s.ny && f.region[inward] == f.region[iy])
        .then(|| s.cell(ix, inward))
        .filter(|&c| f.seen[c])
        .map(|c| f.cells[c].z);
    inner_level.is_none_or(|zi| (zi - near).abs() < (zi - z).abs())
}

/// How close an edge cell's ground must come to the belly band's beside it to be that
/// ground spilled over ([`spilled`]), metres: rough ground's peak to peak.
const SPILL_M: f32 = 0.05;

/// Obstacles whose top the camera does not see, standing in a track.
///
/// A strip that climbs more than a wheel radius within a wheelbase and then leaves the
/// view (its next cells unseen: in the shadow of what it climbed, or past the image's
/// top edge) looks, along that strip alone, like a ramp rising out of the image: its
/// step test judges only the front it saw, and a boulder's front seen through 5 cm
/// cells can measure under the slope limit. Across the track the two differ: a ramp
/// spans the track, so the strips beside rise with it, but a boulder stands on ground
/// that continues beside it. So when a third or more of what the other strips of the track
/// within [`HIDDEN_TOP_REACH_M`] see past the exit, within [`HIDDEN_TOP_REACH_M`] of
/// it, lies more than a wheel radius and a margin for rough ground's bumps
/// ([`UNSEEN_FOOT_MARGIN_M`]) below the height the climb last reached (its exit, or
/// the mean of a cell the image's top edge cuts just past it: a lower bound), the
/// climb is an obstacle higher than a wheel radius with its far side hidden: a step
/// at its foot (the last cell of the climb at most half a wheel radius above its
/// lowest).
///
/// A diagonal ramp (26° across the rover, 25° steep) moves the strips beside by at
/// most 6 cm over that lateral distance, well under a wheel radius. The track's two
/// edge strips take no part: a face along the band's edge (a one-track ramp's side,
/// the ground beyond a one-track descent) mixes two levels there.
///
/// An obstacle as wide as the track hides the ground beside it in its own shadow (a
/// 40 cm boulder, seen from low). Then the ground the strips see again past the
/// shadow tells: a ramp goes on rising behind what hid it, but ground past a boulder
/// is back at its foot. When [`HIDDEN_TOP_BEYOND_STRIPS`] strips of a track, each
/// climbing more than a wheel radius into its shadow, see ground again past it whose
/// mean ([`ground_beyond`]) lies more than a wheel radius and rough ground's spread
/// below the climb's top, the nearest of their climbs is a step at its foot: what
/// stands there is over a wheel radius high, and its far side is not seen.
pub fn hidden_tops(f: &Frame, surface: &[f32], verdict: &mut Verdict) {
    let r = f.cfg.rover.wheel_radius_m as f32;
    let wheelbase = f.cfg.rover.wheelbase_m as f32;
    let reach = (HIDDEN_TOP_REACH_M / f.spec.voxel_m).round() as usize;
    let ground = |ix: usize, iy: usize| followed(f, surface, f.spec.cell(ix, iy));
    for region in [Region::Left, Region::Right] {
        // Strips whose climb the ground past its shadow shows to be an obstacle, and
        // the nearest such climb's foot.
        let (mut beyond_strips, mut beyond_foot) = (0usize, f32::INFINITY);
        for iy in inner_strips(f, region) {
            let mut beyond_here = false;
            for ix in 0..f.spec.nx.saturating_sub(1) {
                let Some(z_exit) = ground(ix, iy) else {
                    continue;
                };
                if ground(ix + 1, iy).is_some() {
                    continue;
                }
                let top = (ix + 1..(ix + 3).min(f.spec.nx))
                    .map(|jx| f.spec.cell(jx, iy))
                    .filter(|&c| f.seen[c] && f.past[c])
                    .map(|c| f.cells[c].z)
                    .fold(z_exit, f32::max);
                let x_exit = f.spec.x_centre(ix);
                let climb = (0..=ix)
                    .rev()
                    .take_while(|&jx| x_exit - f.spec.x_centre(jx) <= wheelbase)
                    .filter_map(|jx| ground(jx, iy).map(|z| (jx, z)));
                let Some(base) = climb.clone().map(|(_, z)| z).reduce(f32::min) else {
                    continue;
                };
                if top - base <= r {
                    continue;
                }
                let (mut below, mut all) = (0, 0);
                for jy in inner_strips(f, region).filter(|&jy| jy != iy && jy.abs_diff(iy) <= reach)
                {
                    for jx in ix + 1..(ix + 1 + reach).min(f.spec.nx) {
                        if let Some(z) = ground(jx, jy) {
                            all += 1;
                            below += usize::from(z < top - r - UNSEEN_FOOT_MARGIN_M);
                        }
                    }
                }
                let foot = climb
                    .filter(|&(_, z)| z <= base + 0.5 * r)
                    .map(|(jx, _)| jx)
                    .max()
                    .unwrap_or(ix);
                let foot_m = f.spec.x_centre(foot).max(0.0);
                if below < HIDDEN_TOP_MIN_CELLS || 3 * below < all {
                    let past = ground_beyond(f, surface, iy, ix + 1);
                    if past.is_some_and(|z| z < top - r - UNSEEN_FOOT_MARGIN_M) {
                        beyond_here = true;
                        beyond_foot = beyond_foot.min(foot_m);
                    }
                    continue;
                }
                verdict.add_hazard(Hazard {
                    kind: HazardKind::Step,
                    side: region.side(),
                    distance_m: foot_m,
                });
            }
            beyond_strips += usize::from(beyond_here);
        }
        if beyond_strips >= HIDDEN_TOP_BEYOND_STRIPS {
            verdict.add_hazard(Hazard {
                kind: HazardKind::Step,
                side: region.side(),
                distance_m: beyond_foot,
            });
        }
    }
}

/// The ground strip `iy` sees again past an unseen run that starts at row `from`
/// (the shadow of what it climbed): the mean of the followed ground
/// ([`followed`]) within [`BEYOND_MEAN_M`] of the first cell seen past the run,
/// metres, so one dip of rough ground does not stand for the level; `None` when the
/// strip sees no ground past it.
fn ground_beyond(f: &Frame, surface: &[f32], iy: usize, from: usize) -> Option<f32> {
    let ground = |ix: usize| followed(f, surface, f.spec.cell(ix, iy)).map(|z| (ix, z));
    let (first, _) = (from..f.spec.nx).find_map(ground)?;
    let x0 = f.spec.x_centre(first);
    let (sum, n) = (first..f.spec.nx)
        .take_while(|&ix| f.spec.x_centre(ix) - x0 <= BEYOND_MEAN_M)
        .filter_map(ground)
        .fold((0.0, 0u32), |(s, n), (_, z)| (s + z, n + 1));
    Some(sum / n as f32)
}

/// A rise or fall hidden below the image, or beside it. The rover stands on its
/// ground (z = 0 at the origin), so a track strip whose nearest seen ground (its
/// first [`BLIND_FIT_M`]) gets more than a wheel radius (and a margin for rough
/// ground's bumps, [`UNSEEN_FOOT_MARGIN_M`]) above or below it, or lies on one line
/// (within [`ROUGH_LINE_RMS_M`]) whose mean level is over a wheel radius from it,
/// changed height at least partly between the rover and the camera's view, where
/// nothing is seen (a boulder whose foot is below the image is seen rising from part
/// of its height; one whose front the image's side edge cuts, from its top), unless
/// the strip is seen at that ground first (a toe in view: the step and slope test
/// judges it).
///
/// When that seen ground lies on one line over its first [`BLIND_FIT_M`] (within
/// rough ground's spread, [`ROUGH_LINE_RMS_M`]) and, continued back to the origin at
/// that passable slope, stands there at most `rise_threshold_m` off z = 0 on the near
/// side (its toe ahead of the origin, or so little behind it that the rover's ground
/// there is flat by the onset's measure: a descent met at 60° whose toe line passes
/// just behind the rover under one track, `sweep -- oblique 100 5503` #98), with and
/// without its first cell (which the image's bottom edge cuts: a step's top seen with
/// the upper part of its face fits a gentle line back to the rover), it is a ramp with
/// its toe below the image (the paper's Table 2 case 3, measured by the feature
/// analysis).
/// So is a strip seen from a passable ramp's foot: its first cell within
/// `rise_threshold_m` of z = 0, and its first [`BLIND_FOOT_M`] on one line meeting
/// z = 0 ahead in the same way (with and without that cell). What stands on the ramp
/// after it is seen whole, and the step and slope test judges it (a 5 cm stone 0.37 m
/// up a 12.7° ramp, whose foot a Kinect v2 saw from 1.5 cm up, lifted the first
/// 0.3 m off one line and 14 cm high: `sweep -- natural 100 5707 random` #43).
/// Otherwise (a plateau, a step's top, ground below a fall, a boulder) the change is
/// unseen: an `unknown` hazard at the nearest such ground, when two or more strips of
/// a track show it (10 cm: narrower than a wheel; a boulder whose front is below the
/// image shows it in a few). The track's edge strips take no part
/// ([`inner_strips`]).
pub fn blind_rise(f: &Frame, surface: &[f32], verdict: &mut Verdict) {
    let r = f.cfg.rover.wheel_radius_m as f32;
    let rise = f.cfg.analysis.rise_threshold_m as f32;
    let tan_max = (f.cfg.rover.max_slope_deg as f32).to_radians().tan();
    for region in [Region::Left, Region::Right] {
        let mut hidden = 0usize;
        let mut nearest = f32::INFINITY;
        for iy in inner_strips(f, region) {
            let ground = |ix: usize| {
                let c = f.spec.cell(ix, iy);
                followed(f, surface, c).map(|z| (f.cells[c].x, z))
            };
            let Some(start) = (0..f.spec.nx).find(|&ix| ground(ix).is_some()) else {
                continue;
            };
            let x0 = f.spec.x_centre(start);
            let near = || {
                (start..f.spec.nx)
                    .map_while(ground)
                    .take_while(|(x, _)| *x <= x0 + BLIND_FIT_M)
            };
            // The line through the stretch's first `len` metres from its `skip`th
            // cell: slope, height at x0, and whether it holds within rough ground's
            // spread.
            let fit = |len: f32, skip: usize| {
                let points = near().take_while(move |(x, _)| *x <= x0 + len);
                line_fit(points.skip(skip)).map(|(p, rms)| {
                    let (k, z0) = (p.a as f32, p.z(f64::from(x0), 0.0) as f32);
                    (k, z0, rms as f32 <= ROUGH_LINE_RMS_M)
                })
            };
            // Continued back at a passable slope to the origin, it stands there at
            // most the rise threshold off the rover's ground, on the near side (its
            // toe ahead of the origin, or so little behind that the ground there is
            // flat by the onset's measure): a ramp whose toe is below the image.
            let toe_ahead = |(k, z0, straight): (f32, f32, bool)| {
                straight
                    && k * z0 > 0.0
                    && k.abs() < tan_max
                    && from_rover_ground((k, z0, x0), 0.0, rise)
            };
            // The farthest from the rover's ground the strip gets in that stretch, and
            // whether it is seen at that ground before (the change is then seen
            // whole, and the step and slope test judges it).
            let (mut reach, mut at) = (0.0f32, 0);
            for (i, (_, z)) in near().enumerate() {
                if z.abs() > reach.abs() {
                    (reach, at) = (z, i);
                }
            }
            let from_ground = near().take(at).any(|(_, z)| z.abs() <= ROUGH_SPREAD_M);
            // Or seen from a passable ramp's foot: its first cell within the rise
            // threshold of the rover's ground, and its first BLIND_FOOT_M on one line
            // whose toe is ahead (with and without that cell). What stands on the ramp
            // past them is seen whole.
            let from_foot = near().next().is_some_and(|(_, z)| z.abs() <= rise)
                && fit(BLIND_FOOT_M, 0).is_some_and(toe_ahead)
                && fit(BLIND_FOOT_M, 1).is_some_and(toe_ahead);
            // The first cell is the one the image's bottom edge cuts: it may hold
            // only part of a face (the top of a step whose foot is not seen), so the
            // ground from the next cell on must tell the same story. Ground that
            // lies on one line has no bumps to allow for: its mean level over a
            // wheel radius from the rover's ground is a change that big (a 12 cm
            // step whose foot is below the image stands level at 12 cm).
            let (sum, n) = near()
                .skip(1)
                .fold((0.0f32, 0.0f32), |(s, n), (_, z)| (s + z, n + 1.0));
            let rest = fit(BLIND_FIT_M, 1);
            let level_over = rest.is_some_and(|(_, _, straight)| straight) && (sum / n).abs() > r;
            if (reach.abs() <= r + UNSEEN_FOOT_MARGIN_M && !level_over) || from_ground || from_foot
            {
                continue;
            }
            let ramp = fit(BLIND_FIT_M, 0).is_some_and(toe_ahead) && rest.is_none_or(toe_ahead);
            if !ramp {
                hidden += 1;
                nearest = nearest.min(x0);
            }
        }
        if hidden >= 2 {
            verdict.add_hazard(Hazard {
                kind: HazardKind::Unknown,
                side: region.side(),
                distance_m: nearest.max(0.0),
            });
        }
    }
}

/// A climb the view ends in, steeper than the rover climbs: how high it goes is not
/// seen. Where a strip's view ends (its first cell the image's top edge cuts, or seen
/// past one), the ground it climbed over the last wheelbase before it (over less,
/// rough ground's bumps steepen a 24° ramp past 30°) and the part of the cut cells
/// that is seen (their upper surface, `crest`) are fitted with one line from the
/// last cell at the climb's foot (within rough ground's spread,
/// [`ROUGH_SPREAD_M`], of the lowest). When that line is steeper than the slope
/// limit and the cut cells' top stands [`STEEP_EXIT_RISE_M`] or more above the foot,
/// the strip saw the front of a wall, a step or a ramp too steep to climb, and the
/// image ended before its top: the step and slope test sees under a wheel radius of
/// it (or, on a steep ramp, the wheel's rounding at the toe), and the feature analysis
/// measures a face it cannot call climbable. Two or more inner strips of a track or
/// of the belly band showing it (10 cm) give an `unknown` hazard at the nearest foot,
/// unless the other tests already found a hazard on that side or one nearer than the
/// foot (the rover stops already, and the verdict says why). Runs last of the crossing
/// tests.
///
/// A climb of under [`STEEP_EXIT_RISE_M`] into the cut cells can be a bump of rough
/// ground in one strip, but not across the band: bumps 10-20 cm long lift two or
/// three strips at a time. So a steep line over at least [`STEEP_EXIT_SHORT_RISE_M`]
/// in most inner strips of a band ([`broad`]) is the same unseen front: a 36° ramp
/// whose toe lies a few centimetres before a low camera's view ends, seen rising
/// 4.4 cm in every inner strip of its track, was a go. Likewise a cut cell whose
/// points span [`STEEP_EXIT_RISE_M`] but whose two surfaces depth noise has merged
/// (`crest` and `foot` both its mean, so the line through it climbs gently), unless
/// its points hug one side of the cell (a face along the strip): a 12 cm step seen by
/// a rolled Kinect v1 only where its image's top edge crosses it was a noisy go.
/// Such cells rising [`STEEP_EXIT_RISE_M`] or more in [`SPREAD_TALL_STRIPS`] strips
/// count however wide the band: a 21 cm step under a track, seen rising 5-6 cm in
/// three strips where a rolled camera's view ends across it, was a noisy go.
/// On smooth ground a front the view ends on, seen from up to two cells before the
/// cut, counts from a smaller bend ([`bends_up`], in [`BENT_STRIPS`] inner strips).
/// A ramp rising out of view at a passable slope is not this: it stays go, measured.
/// Edge strips take no part ([`inner_strips`]): a one-track ramp's side face rises
/// out of view in them.
pub fn steep_exit(f: &Frame, surface: &[f32], verdict: &mut Verdict) {
    let tan_max = (f.cfg.rover.max_slope_deg as f32).to_radians().tan();
    let wheelbase = f.cfg.rover.wheelbase_m as f32;
    let s = f.spec;
    let found = [Region::Left, Region::Belly, Region::Right].map(|region| {
        let (mut tall, mut short, mut nearest) = (0usize, 0usize, f32::INFINITY);
        let (mut short_nearest, mut inner) = (f32::INFINITY, 0usize);
        let (mut any_tall, mut any_nearest) = (0usize, f32::INFINITY);
        let (mut bent, mut bent_nearest) = (0usize, f32::INFINITY);
        for iy in inner_strips(f, region) {
            inner += 1;
            let ground = |ix: usize| {
                let c = s.cell(ix, iy);
                let z = if region == Region::Belly {
                    (f.seen[c] && !f.past[c]).then_some(f.cells[c].z)
                } else {
                    followed(f, surface, c)
                };
                z.map(|z| (f.cells[c].x, z))
            };
            let Some(h) = (1..s.nx).find(|&ix| {
                let c = s.cell(ix, iy);
                f.seen[c] && f.past[c]
            }) else {
                continue;
            };
            let x_h = s.x_centre(h);
            let before = || {
                (0..h)
                    .rev()
                    .map_while(ground)
                    .take_while(|&(x, _)| x_h - x <= wheelbase)
            };
            let Some(base) = before().map(|(_, z)| z).reduce(f32::min) else {
                continue;
            };
            let Some(foot) = before().find(|&(_, z)| z <= base + ROUGH_SPREAD_M) else {
                continue;
            };
            let cut = (h..(h + 3).min(s.nx))
                .map(|ix| (ix, s.cell(ix, iy)))
                .filter(|&(_, c)| f.seen[c] && f.past[c])
                .map(|(ix, c)| (ix, &f.cells[c]));
            let top = cut
                .clone()
                .map(|(_, c)| c.top)
                .fold(f32::NEG_INFINITY, f32::max);
            let rise = top - foot.1;
            if rise < STEEP_EXIT_SHORT_RISE_M {
                continue;
            }
            // A face across the strip within one cut cell (its points span the rise
            // in 5 cm: steeper than 45°; its upper surface beyond its lower one more
            // than beside it, unlike a ramp's side face along the strip), or the climb
            // and the cut cells' upper surface on one line steeper than the limit (a
            // face the cell boundary splits, a steep ramp).
            let spans = |c: &Cell| c.top - c.low >= STEEP_EXIT_RISE_M;
            let face = cut.clone().any(|(_, c)| {
                let (dx, dy) = (c.crest_xy[0] - c.foot_xy[0], c.crest_xy[1] - c.foot_xy[1]);
                spans(c) && dx > dy.abs()
            });
            // A face whose points depth noise spreads so that neither band of the
            // cell is a surface (`crest` and `foot` both the mean) has no orientation
            // of its own; its points not hugging one side of the cell, it is not
            // along the strip. Counted only where most of the band shows a front.
            let y_mid = s.y_centre(iy);
            let spread = cut.clone().any(|(_, c)| {
                spans(c)
                    && c.crest_xy == c.foot_xy
                    && (c.y - y_mid).abs() < FACE_OFF_VOXELS * s.voxel_m
            });
            let climb = before().take_while(|&(x, _)| x > foot.0);
            let points = std::iter::once(foot)
                .chain(climb)
                .chain(cut.clone().map(|(_, c)| (c.crest_xy[0], c.crest)));
            let steep = face || line_fit(points).is_some_and(|(p, _)| p.a as f32 >= tan_max);
            if let Some(x) = bends_up(f, iy, h, before(), cut, tan_max) {
                bent += 1;
                bent_nearest = bent_nearest.min(x);
            }
            if !steep && !spread {
                continue;
            }
            short += 1;
            short_nearest = short_nearest.min(foot.0);
            if rise >= STEEP_EXIT_RISE_M {
                any_tall += 1;
                any_nearest = any_nearest.min(foot.0);
                if steep {
                    tall += 1;
                    nearest = nearest.min(foot.0);
                }
            }
        }
        let (steep, nearest) = if tall >= 2 {
            (true, nearest)
        } else if any_tall >= SPREAD_TALL_STRIPS {
            (true, any_nearest)
        } else if bent >= BENT_STRIPS {
            (true, bent_nearest)
        } else {
            (broad(short, inner), short_nearest)
        };
        // Judged against the other tests' hazards only: a band beside this one
        // showing the same wall does not hide it.
        let judged =
            (verdict.hazards.iter()).any(|h| h.side == region.side() || h.distance_m <= nearest);
        (region, steep && !judged, nearest)
    });
    for (region, _, nearest) in found.into_iter().filter(|&(_, new, _)| new) {
        verdict.add_hazard(Hazard {
            kind: HazardKind::Unknown,
            side: region.side(),
            distance_m: nearest.max(0.0),
        });
    }
}

/// Where a strip's view ends (`h`, its first cut cell) on smooth ground, whether the
/// cut cells show a rise steeper than the rover climbs: the x of the last ground cell
/// on the smooth ground's line, metres, or `None`.
///
/// `before` is the strip's ground over the wheelbase before `h`, one cell after the
/// other from `h − 1` back (its k-th item is cell `h − 1 − k`); `cut` its seen cells
/// among the first three from `h`, with their column. The front may
/// begin up to [`FRONT_CELLS`] ground cells before the cut. For each such start, when
/// the [`SMOOTH_GROUND_CELLS`] ground cells before it lie on one line within
/// [`SMOOTH_GROUND_RMS_M`] (no bumps that steepen a short stretch), a cut cell counts
/// when its top stands [`BEND_RISE_M`] or more above that line carried to the cell's
/// far edge (off the ground the strip was on), above the line where the front begins
/// by more than the slope limit `tan_max` climbs from there to the cell's far edge
/// (the gentlest the rise can be), and [`FRONT_RISING_M`] or more above the front's
/// cells before the cut (still rising where the view ends: a stone seen whole, its
/// top before the cut, is the step test's). That is the front of a rock, a wall or a
/// ramp too steep, cut by the image's top edge: a 15 cm rock on a smooth 15° ramp,
/// seen rising 3-5 cm before the view ends, and a 19 cm mound on a 10° ramp, seen
/// rising 8 cm over two cells and into the cut (10.7 cm from its foot, under a wheel
/// radius), were each a go. Its height is not seen, so a 9 cm pebble there looks the
/// same.
fn bends_up<'c>(
    f: &Frame,
    iy: usize,
    h: usize,
    before: impl Iterator<Item = (f32, f32)> + Clone,
    cut: impl Iterator<Item = (usize, &'c Cell)> + Clone,
    tan_max: f32,
) -> Option<f32> {
    let s = f.spec;
    (0..=FRONT_CELLS).find_map(|lead| {
        let window = before.clone().skip(lead).take(SMOOTH_GROUND_CELLS);
        if window.clone().count() < SMOOTH_GROUND_CELLS {
            return None;
        }
        let (line, rms) = line_fit(window.clone())?;
        if rms > f64::from(SMOOTH_GROUND_RMS_M) {
            return None;
        }
        let (last_x, _) = window.clone().next()?;
        let end = h - 1 - lead;
        let front_top = (end + 1..h)
            .map(|ix| f.cells[s.cell(ix, iy)].top)
            .fold(f32::NEG_INFINITY, f32::max);
        let on_line = |x: f32| line.z(f64::from(x), 0.0) as f32;
        let near = s.x_centre(end) + 0.5 * s.voxel_m;
        let bends = cut.clone().any(|(ix, c)| {
            let far = s.x_centre(ix) + 0.5 * s.voxel_m;
            c.top - on_line(far) >= BEND_RISE_M
                && c.top - on_line(near) >= tan_max * (far - near)
                && c.top >= front_top + FRONT_RISING_M
        });
        bends.then_some(last_x)
    })
}

/// Most RMS of a strip's last ground cells about their line for [`bends_up`] to take
/// them for smooth, metres. Cells average rough ground's bumps (±2.5 cm, 10-20 cm
/// long), and over 25 cm their means can lie within 2-3 mm of a line (a 20° rough
/// ramp's belly strips did, and a bump at the view's end was a false stop); a smooth
/// ramp's lie within 0.4 mm, depth noise included, where a D435-like camera sees them
/// at 2 m.
const SMOOTH_GROUND_RMS_M: f32 = 0.001;
/// How many ground cells before a front [`bends_up`] fits its line to: 20 cm at the
/// default voxel. The ramp's own line before a front can be that short (a mound's
/// rising 0.2 m past a 10° ramp's toe). With four cells, as with five, no verdict of
/// the rough-ground sweeps changed (`sweep -- near_edge 400 30|36 rough`, `families`
/// and `natural 88 179 random`, `families 300 2 random`, where 4 mm RMS over five
/// cells had made a false stop).
const SMOOTH_GROUND_CELLS: usize = 4;
/// Most ground cells of a front that [`bends_up`] looks for between the smooth
/// ground's line and the cut: 10 cm, a rock's or a mound's front.
const FRONT_CELLS: usize = 2;
/// Least height of a cut cell's top over the tops of the front's cells before the cut
/// for [`bends_up`], metres: the front still rises where the view ends.
const FRONT_RISING_M: f32 = 0.01;
/// Least height of a cut cell's top above the smooth ground's line for [`bends_up`],
/// metres. The ground carried on into the cell has its top at or under the line at
/// the cell's far edge; 2 cm leaves room for depth noise, and a rock's front cut
/// after its first centimetres stands 2-5 cm above it.
const BEND_RISE_M: f32 = 0.02;
/// Fewest inner strips of a band whose view ends bending up steeply on smooth ground
/// ([`bends_up`]) for [`steep_exit`] to take it for an unseen front: 15 cm, so one
/// or two strips of noise do not count.
const BENT_STRIPS: usize = 3;

/// Least rise from a climb's foot to the top of the cut cells the view ends in for
/// [`steep_exit`], metres: more than rough ground's peak to peak (±2.5 cm).
const STEEP_EXIT_RISE_M: f32 = 0.05;
/// Least rise for a climb of [`steep_exit`] to count in a band's [`broad`] test,
/// metres: beyond what depth noise (about 1 cm at 2 m) and a cell's partial view make
/// of level ground.
const STEEP_EXIT_SHORT_RISE_M: f32 = 0.03;

/// Fewest strips of a band whose climb into the cut cells rises [`STEEP_EXIT_RISE_M`]
/// or more and is steep or a face noise spread (see [`steep_exit`]) for that band to
/// count as showing an unseen front, whatever the band's width: a face along a strip
/// (a half-plane's side face) spreads the points of the two strips it lies between,
/// never of three.
const SPREAD_TALL_STRIPS: usize = 3;

/// Whether `steep` of a band's `inner` strips make most of it (two thirds, and at
/// least three): a front across the band, not a bump of rough ground (10-20 cm long,
/// two or three strips) for [`steep_exit`].
fn broad(steep: usize, inner: usize) -> bool {
    steep >= 3 && 3 * steep >= 2 * inner
}

/// How much of a track strip's nearest seen ground [`blind_rise`] fits its slope to,
/// metres.
const BLIND_FIT_M: f32 = 0.3;

/// How much of a track strip's nearest seen ground [`blind_rise`] takes for a
/// ramp's foot, metres: three or four cells.
const BLIND_FOOT_M: f32 = 0.15;

/// How far beside and beyond a climb leaving the view [`hidden_tops`] looks for the
/// ground it stands on, metres: a boulder's radius.
const HIDDEN_TOP_REACH_M: f32 = 0.25;
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
/// Fewest cells of ground beside a hidden top, more than a wheel radius below it, for
/// [`hidden_tops`] to take it for an obstacle.
const HIDDEN_TOP_MIN_CELLS: usize = 3;
/// Fewest strips of a track whose ground past a climb's shadow lies too low for
/// [`hidden_tops`] to take the climb for an obstacle: one strip may be a pebble's
/// narrow top seen beside a dip.
const HIDDEN_TOP_BEYOND_STRIPS: usize = 2;
/// Length of ground past a shadow whose mean is its level ([`ground_beyond`]),
/// metres: three cells, about a bump of rough ground.
const BEYOND_MEAN_M: f32 = 0.1;

/// The strips of a track but its two edge strips, where a face along the band's edge
/// mixes two levels ([`hidden_tops`], [`blind_rise`]).
fn inner_strips<'a>(f: &'a Frame, region: Region) -> impl Iterator<Item = usize> + 'a {
    let first = f.strips(region).next();
    let last = f.strips(region).last();
    f.strips(region)
        .filter(move |&iy| first.is_some_and(|a| iy > a) && last.is_some_and(|b| iy < b))
}

/// The ground the strip followed in cell `c` (`surface`, from [`steps_and_slopes`]),
/// metres, when the cell is seen whole: not past the horizon, and in a track.
fn followed(f: &Frame, surface: &[f32], c: usize) -> Option<f32> {
    (f.seen[c] && !f.past[c])
        .then_some(surface[c])
        .filter(|z| z.is_finite())
}

/// The least-squares line z = a·x + c through `points` (x, z), and the RMS of their
/// heights about it, metres; `None` without two distinct x.
fn line_fit(points: impl Iterator<Item = (f32, f32)> + Clone) -> Option<(Plane, f64)> {
    let mut fit = PlaneFit::default();
    for (x, z) in points.clone() {
        fit.add(f64::from(x), 0.0, f64::from(z), 1.0);
    }
    let p = fit.solve()?;
    let (ss, n) = points.fold((0.0, 0.0), |(ss, n), (x, z)| {
        (
            ss + (f64::from(z) - p.z(f64::from(x), 0.0)).powi(2),
            n + 1.0,
        )
    });
    Some((p, (ss / n).sqrt()))
}

/// In a cell with two surfaces, the ground when the face between them runs along the
/// strip: the face's points hug one side of the cell while the ground's spread across
/// it, so the surface whose points centre farther off the strip's centre line is the
/// face (the wall of a trench under the track, the side of a ramp beside the belly
/// band). `None` when the surfaces are close, or when they are offset more forward
/// than sideways (a face across the strip: a step, judged by the strip's course).
pub(crate) fn ground_beside_face(cell: &Cell, y_mid: f32, vs: f32) -> Option<f32> {
    if cell.crest - cell.foot < FACE_MIN_M {
        return None;
    }
    let dx = cell.crest_xy[0] - cell.foot_xy[0];
    let dy = cell.crest_xy[1] - cell.foot_xy[1];
    let off_crest = (cell.crest_xy[1] - y_mid).abs();
    let off_foot = (cell.foot_xy[1] - y_mid).abs();
    let (face, ground) = if off_crest > off_foot {
        (off_crest, off_foot)
    } else {
        (off_foot, off_crest)
    };
    if dy.abs() <= dx.abs() || face < FACE_OFF_VOXELS * vs || face - ground < SIDE_MIN_VOXELS * vs {
        return None;
    }
    Some(if off_crest < off_foot {
        cell.crest
    } else {
        cell.foot
    })
}

/// The ground of a cell holding a face along its strip that [`ground_beside_face`]
/// cannot resolve ([`unresolved_face_along`]): a face seen is turned to the camera,
/// so when its points hug the cell's side away from the camera the ground beyond
/// that side is higher and the cell's ground is its lowest voxel (a trench's wall on
/// the corridor's edge, whose points outnumber the floor's there so far that both of
/// the cell's bands lie on the wall); when they hug the side toward the camera, the
/// cell's ground is its highest voxel (a ramp's side beside the belly band). `None`
/// for any other cell, or when the camera is right above the strip.
///
/// For a cell [`ground_beside_face`] already gave nothing for.
fn unresolved_ground(
    cell: &Cell,
    (x_mid, y_mid): (f32, f32),
    vs: f32,
    camera_y: f32,
) -> Option<f32> {
    if !hugs_one_side(cell, x_mid, y_mid, vs) || (camera_y - y_mid).abs() <= 0.5 * vs {
        return None;
    }
    let away = (cell.y - y_mid).signum() != (camera_y - y_mid).signum();
    Some(if away { cell.low } else { cell.top })
}

/// Whether a cell holds a face along its strip whose ground its two surfaces do not
/// give: its points span more than [`FACE_MIN_M`] and hug one side of the cell
/// (their mean off the strip's centre line by [`FACE_OFF_VOXELS`], and off the row's
/// by at most half that: a face along the strip, not a corner of one across it), but
/// [`ground_beside_face`] cannot tell the bands apart. Its mean height
/// belongs to neither the ground nor the face's other side. `x_mid`, `y_mid`: the
/// cell's centre, metres.
pub(crate) fn unresolved_face_along(cell: &Cell, x_mid: f32, y_mid: f32, vs: f32) -> bool {
    hugs_one_side(cell, x_mid, y_mid, vs) && ground_beside_face(cell, y_mid, vs).is_none()
}

/// The side test of [`unresolved_face_along`], without the band test.
fn hugs_one_side(cell: &Cell, x_mid: f32, y_mid: f32, vs: f32) -> bool {
    let off_y = (cell.y - y_mid).abs();
    cell.top - cell.low >= FACE_MIN_M
        && off_y >= FACE_OFF_VOXELS * vs
        && (cell.x - x_mid).abs() <= 0.5 * FACE_OFF_VOXELS * vs
}

/// Whether a cell holds one surface sloping across its strip, not two surfaces with a
/// face between: its points span more than [`FACE_MIN_M`], spread evenly across the
/// cell (their mean within [`SPREAD_OFF_VOXELS`] of the strip's centre line `y_mid`:
/// a face's points pull it toward the cell's side) and over their span (their mean
/// height within [`SPREAD_MID_SHARE`] of its middle: a flat surface beside a face
/// pulls it toward that surface); its upper and lower bands centre on opposite sides
/// of the points' mean, apart more sideways than forward (a face across the strip
/// parts them forward) by at least [`SIDE_MIN_VOXELS`]; or, when only one band holds
/// a surface, its top voxel lies to one side by half [`FACE_OFF_VOXELS`]. The cell's
/// mean height is then the ground's on the strip's centre line (exact for a plane).
fn slopes_across(cell: &Cell, y_mid: f32, vs: f32) -> bool {
    let span = cell.top - cell.low;
    if span < FACE_MIN_M
        || (cell.y - y_mid).abs() > SPREAD_OFF_VOXELS * vs
        || (cell.z - 0.5 * (cell.top + cell.low)).abs() > SPREAD_MID_SHARE * span
    {
        return false;
    }
    if cell.crest == cell.foot {
        return (cell.top_xy[1] - cell.y).abs() >= 0.5 * FACE_OFF_VOXELS * vs;
    }
    let (dx, dy) = (
        cell.crest_xy[0] - cell.foot_xy[0],
        cell.crest_xy[1] - cell.foot_xy[1],
    );
    (cell.crest_xy[1] - cell.y) * (cell.foot_xy[1] - cell.y) < 0.0
        && dy.abs() > dx.abs()
        && dy.abs() >= SIDE_MIN_VOXELS * vs
}

/// Most sideways offset of the mean of a cell's points from the strip's centre line
/// for [`slopes_across`], voxels: a ramp's sloping side put it within 0.1 of a voxel,
/// a vertical side's points beside the ramp's top 0.13-0.3 (`sweep -- families 100
/// 5501 random` #99 and #97; where they pull it less, the height test tells).
const SPREAD_OFF_VOXELS: f32 = 0.15;
/// Most offset of a cell's mean height from the middle of its span for
/// [`slopes_across`], a share of the span: up to 0.13 on a ramp's sloping side (the
/// voxel layers move its top and low), 0.23-0.33 on a ramp's top beside its vertical
/// side (#97, #99).
const SPREAD_MID_SHARE: f32 = 0.2;

/// Least height between a cell's two surfaces for [`ground_beside_face`] to tell
/// them apart, metres: above rough ground's spread within one cell.
const FACE_MIN_M: f32 = 0.04;
/// Least sideways offset of a face's points from the strip's centre line for
/// [`ground_beside_face`], voxels: a face hugs the cell's side (0.5), a surface spread
/// across the cell centres on it (0), whatever the noise.
const FACE_OFF_VOXELS: f32 = 0.3;
/// Least difference of the two surfaces' sideways offsets for [`ground_beside_face`],
/// voxels.
const SIDE_MIN_VOXELS: f32 = 0.2;

/// Where a wheel of radius `r` rests on each cell of a strip: the lowest point of a
/// wheel centred over the cell, held up by whatever stands within `r` of it along
/// the strip (`z_j − (r − √(r² − dx²))`, the rim's height over a neighbour at dx).
/// A dip narrower than the wheel is bridged and a pebble is climbed from the ground
/// the wheel stands on, not from the bottom of the dip beside it; a step still rises
/// by its full height within a wheel radius. Neighbours across a hole or past the
/// horizon do not count (their heights are unknown or only bounds).
fn wheel_heights(strip: &mut [StripCell], r: f32) {
    for i in 0..strip.len() {
        let (xi, mut h) = (strip[i].x, strip[i].z);
        if !strip[i].past {
            let rim = |j: usize| {
                (!strip[j].past)
                    .then(|| on_rim(strip[j].z, (strip[j].x - xi).abs(), r))
                    .flatten()
            };
            for j in (0..i).rev() {
                if strip[j + 1].ix > strip[j].ix + 1 {
                    break;
                }
                let Some(z) = rim(j) else { break };
                h = h.max(z);
            }
            // The first cell of a run is where the strip's view of the ground starts:
            // the wheel comes to it over that ground carried on (what is before it is
            // not seen; the gap and hidden-rise tests judge that), so a face ahead does
            // not hold it up. Held up, a step a cell or two past the image's bottom
            // edge or a shadow is seen only from near its top.
            let run_start = i == 0 || strip[i].ix > strip[i - 1].ix + 1;
            for j in (i + 1..strip.len()).take_while(|_| !run_start) {
                if strip[j].ix > strip[j - 1].ix + 1 {
                    break;
                }
                let Some(z) = rim(j) else { break };
                h = h.max(z);
            }
        }
        strip[i].wheel = h;
    }
}

/// Where the bottom of a wheel of radius `r` stands, metres, when its rim rests on
/// ground at height `z` that lies `dx` metres (horizontally) before or behind its axle;
/// `None` when that ground is beyond the rim's reach.
fn on_rim(z: f32, dx: f32, r: f32) -> Option<f32> {
    (dx < r).then(|| z - (r - (r * r - dx * dx).sqrt()))
}

/// Steps and slopes along one strip's seen cells (see [`steps_and_slopes`]).
fn strip_hazards(
    strip: &[StripCell],
    region: Region,
    (r, tan_max, wheelbase, min_gap): (f32, f32, f32, usize),
    vs: f32,
    verdict: &mut Verdict,
) {
    // No pair differs by more than `r` from a cell within `r` of the strip's highest
    // and lowest wheels: such a cell is skipped without looking at its pairs.
    let (low, high) = strip
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), c| {
            (lo.min(c.wheel), hi.max(c.wheel))
        });
    let all_finite = strip.iter().all(|c| c.wheel.is_finite());
    for (i, a) in strip.iter().enumerate() {
        let (xi, zi) = (a.x, a.wheel);
        if all_finite && high - zi <= r && zi - low <= r {
            continue;
        }
        for (j, b) in strip.iter().enumerate().skip(i + 1) {
            let (xj, zj) = (b.x, b.wheel);
            let (dx, dz) = (xj - xi, zj - zi);
            if dz.abs() <= r {
                continue;
            }
            if holey(&strip[i..=j], min_gap) {
                break; // unseen ground in between: the gap test judges it
            }
            if (dz > 0.0 && a.past) || (dz < 0.0 && b.past) {
                break; // a bound that proves nothing: the view ends here
            }
            if dx > 0.0 && dz.abs() >= tan_max * dx {
                let kind = if dx <= 3.5 * vs {
                    // A window on one line under the limit: a rough ramp's bumps. Every
                    // window on one line over it: a ramp too steep, not a step (which
                    // leaves no window on one line).
                    let line = line_windows(strip, i, j, wheelbase.min(STEP_WINDOW_MAX_M))
                        .reduce(f32::min);
                    match line {
                        Some(k) if k < tan_max => None,
                        Some(_) => Some((HazardKind::Slope, xi)),
                        None => Some((HazardKind::Step, 0.5 * (xi + xj))),
                    }
                } else if sustained(&strip[i..=j])
                    && climb_slope(strip, i, j, (wheelbase, r, min_gap)) >= tan_max
                {
                    Some((HazardKind::Slope, xi))
                } else {
                    None // flat, then a jump: a step, found from nearer cells
                };
                let Some((kind, at)) = kind else { break };
                verdict.add_hazard(Hazard {
                    kind,
                    side: region.side(),
                    distance_m: at.max(0.0),
                });
            }
            break;
        }
    }
}

/// Whether consecutive seen cells of a run are `min_gap` or more unseen cells apart
/// somewhere (a hole the gap test judges: what lies there is unknown, so no slope or
/// step is measured across it). Across a shorter hole, which the gap test leaves
/// alone, the step test measures: a step down seen from high above hides only the
/// cell just past its edge (a 22 cm step 0.57 m out under a camera 0.93 m high),
/// and the ground beyond, seen a wheel radius lower, proves the fall.
fn holey(run: &[StripCell], min_gap: usize) -> bool {
    run.windows(2).any(|w| w[1].ix > w[0].ix + min_gap)
}

/// Whether every cell between the ends lies on the straight line between them
/// (within [`SLOPE_STRAIGHTNESS_M`]): a slope, not flat ground and a jump.
fn sustained(run: &[StripCell]) -> bool {
    let (Some(a), Some(b)) = (run.first(), run.last()) else {
        return false;
    };
    let k = (b.wheel - a.wheel) / (b.x - a.x);
    run.iter()
        .all(|c| (c.wheel - (a.wheel + k * (c.x - a.x))).abs() <= SLOPE_STRAIGHTNESS_M)
}

/// The slope |dz/dx| of the ground a run `strip[i..=j]` climbs. A run a wheel radius
/// high is only 4-5 cells, where ±2.5 cm of roughness swings the slope by 5-10°: when
/// a wheelbase of contiguous seen cells starting at the run's start, or ending at its
/// end, lies on one line within rough ground's spread (RMS residual up to
/// [`ROUGH_LINE_RMS_M`]), the ground is that line and its least-squares slope counts
/// (the gentler of the two when both are lines), and so does a window on one line
/// but for a stone under a wheel radius standing on it ([`stone_windows`]).
/// Otherwise the run's own: a short steep bank and the flat beside it are not one
/// line, and keep their steepness.
///
/// Where the view ends less than a wheelbase past the run's start, so that no such
/// window is seen, the ground from a hinge before the run to where the view ends
/// counts instead when it is long enough ([`view_end_slope`]).
fn climb_slope(
    strip: &[StripCell],
    i: usize,
    j: usize,
    (wheelbase, r, min_gap): (f32, f32, usize),
) -> f32 {
    line_windows(strip, i, j, wheelbase)
        .chain(stone_windows(strip, i, j, (wheelbase, r, min_gap)))
        .chain(view_end_slope(strip, i, j, wheelbase))
        .fold(fitted_slope(&strip[i..=j]), f32::min)
}

/// The slope |dz/dx| of a rough ramp that rises out of the view less than 0.9 of a
/// wheelbase past the run `strip[i..=j]`, so that [`line_windows`] has no window
/// ahead: over the wheelbase of contiguous cells seen whole that ends where the view
/// does (the next cell past the horizon, or none), the best two lines joined at a
/// hinge at or before the run's start (the ground before the ramp's toe, the ramp
/// after it), when they explain the cells within rough ground's spread
/// ([`ROUGH_LINE_RMS_M`]) and the ramp's line is at least [`VIEW_END_RAMP_M`] long;
/// the ramp line's slope plus twice its standard error (so a rough ramp just over
/// the limit is not let through by its bumps: over 0.45 m of ramp on ±2.5 cm
/// ground the standard error is about 1.3°). A ramp's own slope, not a dip-to-bump
/// run's: on ±2.5 cm ground 0.2 m of a 24° ramp can climb 32°. A short bank and the
/// flat above it are not one line after the hinge, and keep their steepness; so does
/// a ramp seen for less than [`VIEW_END_RAMP_M`].
fn view_end_slope(strip: &[StripCell], i: usize, j: usize, wheelbase: f32) -> Option<f32> {
    if strip[i].past {
        return None;
    }
    let mut end = if strip[j].past { j - 1 } else { j };
    while end + 1 < strip.len() && joined(strip, end, 1) {
        end += 1;
    }
    let view_ends = end + 1 == strip.len() || strip[end + 1].past;
    if !view_ends || end < i || strip[end].x - strip[i].x >= 0.9 * wheelbase {
        return None;
    }
    let mut start = i;
    while start > 0 && joined(strip, start - 1, 1) && strip[end].x - strip[start - 1].x <= wheelbase
    {
        start -= 1;
    }
    let window = &strip[start..=end];
    // Two cells at least on the line before the hinge, so that it is a line.
    (start + 2..=i)
        .filter(|&h| strip[end].x - strip[h].x >= VIEW_END_RAMP_M)
        .filter_map(|h| {
            let hinge = strip[h].x;
            let mut fit = PlaneFit::default();
            for c in window {
                let (x, after) = (f64::from(c.x), f64::from((c.x - hinge).max(0.0)));
                fit.add(x, after, f64::from(c.wheel), 1.0);
            }
            let p = fit.solve()?;
            let ss: f64 = window
                .iter()
                .map(|c| {
                    let after = f64::from((c.x - hinge).max(0.0));
                    (f64::from(c.wheel) - p.z(f64::from(c.x), after)).powi(2)
                })
                .sum();
            let n = window.len() as f64;
            // The ramp line's slope, raised by twice its standard error: the line
            // must be climbable with confidence, not by the luck of the bumps.
            let ramp = || {
                window
                    .iter()
                    .map(|c| f64::from(c.x))
                    .filter(|&x| x >= f64::from(hinge))
            };
            let (k, sum) = ramp().fold((0.0, 0.0), |(k, s), x| (k + 1.0, s + x));
            let spread: f64 = ramp().map(|x| (x - sum / k).powi(2)).sum();
            let sigma = (ss / (n - 3.0).max(1.0)).sqrt();
            let slope = (p.a + p.b).abs() + 2.0 * sigma / spread.sqrt();
            Some(((ss / n).sqrt(), slope as f32))
        })
        .filter(|&(rms, _)| rms <= f64::from(ROUGH_LINE_RMS_M))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, slope)| slope)
}

/// Whether strip cells `k` and `k + 1` are at most `step` rows apart (1: neighbouring
/// rows), both seen whole (not past the horizon): a window of [`line_windows`],
/// [`stone_windows`] or [`view_end_slope`] runs on.
fn joined(strip: &[StripCell], k: usize, step: usize) -> bool {
    strip[k + 1].ix <= strip[k].ix + step && !strip[k].past && !strip[k + 1].past
}

/// Least length of a ramp's line for [`view_end_slope`], metres: over 0.4 m, ±2.5 cm
/// ground moves a line's slope by about 2° (one σ); over 0.25 m by 5°.
const VIEW_END_RAMP_M: f32 = 0.4;

/// The slopes |dz/dx| of the windows about a run `strip[i..=j]` that lie on one line
/// (see [`climb_slope`]): a wheelbase of contiguous cells seen whole starting at the
/// run's start, and one ending at its end, each when at least 0.9 wheelbase long.
fn line_windows(
    strip: &[StripCell],
    i: usize,
    j: usize,
    wheelbase: f32,
) -> impl Iterator<Item = f32> + '_ {
    windows(strip, i, j, wheelbase, 1).filter_map(line_slope)
}

/// The slopes |dz/dx| of the windows about a run `strip[i..=j]` (as [`line_windows`],
/// but stepping over holes shorter than `min_gap` cells) that lie on one line but for
/// a stone on it ([`line_under_stones`]): a 6 cm rock 0.25 m up a 17° ramp leaves no
/// window on one line (it stands off the line, and its shadow breaks the window), and
/// the run from the toe to its top climbed 31°: a `slope` (`sweep -- families 150 6921
/// random 10` #82, clean and noisy). The stone, under a wheel radius, is a step the
/// wheel climbs.
fn stone_windows(
    strip: &[StripCell],
    i: usize,
    j: usize,
    (wheelbase, r, min_gap): (f32, f32, usize),
) -> impl Iterator<Item = f32> + '_ {
    windows(strip, i, j, wheelbase, min_gap).filter_map(move |w| line_under_stones(w, r))
}

/// The windows of [`line_windows`]: a wheelbase of cells seen whole starting at the
/// run `strip[i..=j]`'s start and one ending at its end, each at least 0.9 wheelbase
/// long, consecutive cells at most `step` rows apart.
fn windows(
    strip: &[StripCell],
    i: usize,
    j: usize,
    wheelbase: f32,
    step: usize,
) -> impl Iterator<Item = &[StripCell]> + '_ {
    let mut end = j;
    while end + 1 < strip.len()
        && joined(strip, end, step)
        && strip[end + 1].x - strip[i].x <= wheelbase
    {
        end += 1;
    }
    // A run may end on a cell past the horizon (its height only a bound): the window
    // behind it ends on the last cell seen whole. When that is the run's start, the
    // window holds none of the run's rise (flat ground before a post whose front the
    // view ends on read as a gentle line, and the post as a rough ramp's bump: a go):
    // there is no window behind.
    let last = if strip[j].past && j > i { j - 1 } else { j };
    let mut start = i;
    while start > 0
        && joined(strip, start - 1, step)
        && strip[last].x - strip[start - 1].x <= wheelbase
    {
        start -= 1;
    }
    let behind = (last > i || !strip[j].past).then(|| &strip[start..=last]);
    [Some(&strip[i..=end]), behind]
        .into_iter()
        .flatten()
        .filter(|w| w.iter().all(|c| !c.past))
        .filter(move |w| w[w.len() - 1].x - w[0].x >= 0.9 * wheelbase)
}

/// The slope |dz/dx| of a window's ground when its wheel heights lie on one line
/// within [`ROUGH_LINE_RMS_M`] once a stone on it is left out: the cell standing
/// highest above the line is left out and the line refitted until it holds, leaving
/// out at most a third of the window, never its first or last cell (ground on the
/// line before and after the stone: not a climb going on), and no cell stands a
/// wheel radius `r` above the line (a stone the wheel climbs, judged by the step
/// test). Cells below the line are never left out: a bank's flat foot and its top
/// are not one line with a stone. `None` otherwise, or for a window over 64 cells.
fn line_under_stones(run: &[StripCell], r: f32) -> Option<f32> {
    let n = run.len();
    if n > 64 {
        return None;
    }
    let off = |p: &Plane, c: &StripCell| c.wheel - p.z(f64::from(c.x), 0.0) as f32;
    let mut out = 0u64;
    loop {
        let kept = run
            .iter()
            .enumerate()
            .filter(move |(k, _)| out & (1 << k) == 0);
        let (line, rms) = line_fit(kept.clone().map(|(_, c)| (c.x, c.wheel)))?;
        if rms <= f64::from(ROUGH_LINE_RMS_M) {
            let under_r = run.iter().all(|c| off(&line, c) < r);
            return under_r.then_some(line.a.abs() as f32);
        }
        let (k, above) = kept
            .map(|(k, c)| (k, off(&line, c)))
            .max_by(|a, b| a.1.total_cmp(&b.1))?;
        let dropped = out.count_ones() as usize + 1;
        if above <= 0.0 || k == 0 || k == n - 1 || 3 * dropped > n {
            return None;
        }
        out |= 1 << k;
    }
}

/// The least-squares slope |dz/dx| of a run's wheel heights when they lie on one line
/// within [`ROUGH_LINE_RMS_M`], else `None`.
fn line_slope(run: &[StripCell]) -> Option<f32> {
    let (p, rms) = line_fit(run.iter().map(|c| (c.x, c.wheel)))?;
    (rms <= f64::from(ROUGH_LINE_RMS_M)).then_some(p.a.abs() as f32)
}

/// Largest RMS distance of wheel heights from their line for [`climb_slope`] to take
/// them as one slope, metres: rough ground's spread (σ ≈ 1.25 cm for ±2.5 cm), under
/// what a bank steeper than the limit and shorter than the wheelbase leaves (≥ 1.5 cm
/// for banks whose wheelbase fit falls under 30°).
const ROUGH_LINE_RMS_M: f32 = 0.016;

/// Longest window for the step test's line (see [`steps_and_slopes`]), metres: over a
/// window this long a step just over a wheel radius leaves an RMS of at least 2.6 cm
/// about its best line (with the step anywhere in it), well over
/// [`ROUGH_LINE_RMS_M`]; a longer window would dilute it.
const STEP_WINDOW_MAX_M: f32 = 0.6;

/// The least-squares slope |dz/dx| of a run's wheel heights: on rough ground the
/// ends of a run may sit on a dip and a bump, steeper than the ground between.
fn fitted_slope(run: &[StripCell]) -> f32 {
    wheel_line(run).map_or(0.0, |p| p.a.abs() as f32)
}

/// The least-squares line `z = a·x + c` through a run's wheel heights (as a plane with
/// b = 0); `None` with fewer than two distinct x.
fn wheel_line(run: &[StripCell]) -> Option<Plane> {
    let mut fit = PlaneFit::default();
    for c in run {
        fit.add(f64::from(c.x), 0.0, f64::from(c.wheel), 1.0);
    }
    fit.solve()
}

/// How far a cell may sit off the line for a run to count as one slope, metres.
const SLOPE_STRAIGHTNESS_M: f32 = 0.03;

/// Anything under the belly taller than the belly clearance above the higher of the
/// two wheel tracks at the same distance (the median height of each track's cells
/// seen whole in that row; a row with none borrows the nearest row within 3 cells,
/// else the ground plane z = 0, unless the track there is past the sensor's horizon:
/// then the row is beyond view and not judged). A cell the image's top edge cuts
/// holds only what lies below the edge: a ramp rising out of view left in one such
/// track cell a few centimetres of its side face, and that "track height" put the
/// ramp's side in the belly band 40 cm above it (`sweep -- families 100 5501 random`
/// #55 noisy). A belly cell beside a track is also measured against that track cell's
/// upper surface: a face along the band edge is the side of what stands in the track.
/// A belly cell off the band's edges that the image's top edge cuts, already more
/// than a wheel radius above the tracks beside it (which are seen), is an obstacle
/// whose top is not seen: unknown ground there, whatever its bound.
pub fn belly(f: &Frame, values: &mut Vec<f32>, track_ref: &mut [[f32; 2]], verdict: &mut Verdict) {
    let clearance = f.cfg.rover.belly_clearance_m as f32;
    let r = f.cfg.rover.wheel_radius_m as f32;
    let s = f.spec;
    track_medians(f, values, track_ref, |c| {
        (f.seen[c] && !f.past[c]).then(|| f.cells[c].z)
    });
    for ix in 0..s.nx {
        let mut reference = f32::NEG_INFINITY;
        let mut beyond_view = false;
        for (k, region) in [Region::Left, Region::Right].into_iter().enumerate() {
            let near = (0..=3usize)
                .flat_map(|d| [ix.checked_sub(d), Some(ix + d)])
                .flatten()
                .filter_map(|j| track_ref.get(j).map(|r| r[k]))
                .find(|v| !v.is_nan());
            match near {
                Some(v) => reference = reference.max(v),
                // No track data near this row because the track is past the horizon:
                // how high the wheels stand here is not known.
                None => beyond_view |= f.strips(region).any(|iy| f.past[s.cell(ix, iy)]),
            }
        }
        if beyond_view {
            continue;
        }
        if reference == f32::NEG_INFINITY {
            reference = 0.0;
        }
        for iy in f.strips(Region::Belly) {
            let c = s.cell(ix, iy);
            if !f.seen[c] {
                continue;
            }
            // Beside a track, the band's edge cells hold the side face of whatever
            // stands in the track: it is as high as the track there, not under the belly.
            // A track cell the image's top edge cuts (or past the horizon) is at least
            // as high as its top (a ramp rising out of view: its upper surface there is
            // only partly seen). A face on the band's edge line splits its points
            // between the two strips as they fall, so that one row's track cell may
            // hold only its foot: the track cells of the rows before and after count
            // too (a coarse camera's rows meet the face every other cell).
            let beside = [iy.checked_sub(1), Some(iy + 1)]
                .into_iter()
                .flatten()
                .filter(|&j| j < s.ny && f.region[j] != Region::Belly)
                .flat_map(|j| (ix.saturating_sub(1)..(ix + 2).min(s.nx)).map(move |i| s.cell(i, j)))
                .filter(|&j| f.seen[j])
                .map(|j| {
                    let cell = &f.cells[j];
                    if f.past[j] {
                        cell.top.max(cell.crest)
                    } else {
                        cell.crest
                    }
                })
                .fold(reference, f32::max);
            let above = f.cells[c].top - beside;
            let edge = || {
                [iy.checked_sub(1), Some(iy + 1)]
                    .into_iter()
                    .any(|j| j.is_none_or(|j| j >= s.ny || f.region[j] != Region::Belly))
            };
            let kind = if above > clearance {
                Some(HazardKind::Belly)
            } else if f.past[c] && above > r && !edge() && !on_track_surface(f, ix, iy, r) {
                // Rising out of the image more than a wheel radius above the tracks
                // beside it, which are seen: an obstacle whose top is not seen. How
                // tall it is, is not known. (An edge cell may hold the side of a
                // ramp under the track beside it, rising out of view with it.)
                Some(HazardKind::Unknown)
            } else {
                None
            };
            if let Some(kind) = kind {
                verdict.add_hazard(Hazard {
                    kind,
                    side: Region::Belly.side(),
                    distance_m: s.origin[0] + ix as f32 * s.voxel_m,
                });
            }
        }
    }
}

/// Whether belly cell (`ix`, `iy`), past the horizon, lies on the surface of the wheel
/// track on its side carried across: that track's cells seen in row `ix` (below the
/// horizon, at least [`CROSS_MIN_CELLS`]) lie on one line across the strips (within
/// rough ground's spread, [`ROUGH_LINE_RMS_M`]), and the cell's top stands no more
/// than a wheel radius `r` above that line carried to its centre. A ramp under one
/// side met diagonally rises across the corridor as well as along it: where it
/// covers the belly band's half too, the band's cells stand above the track's middle
/// by its cross slope (a 24° ramp over y ≥ 0 whose toe line runs at −35° to the axle
/// rose 11 cm from the track's middle to the corridor's centre line, and was an
/// obstacle whose top is not seen: `sweep -- workcases 60 6609` #18, #26). The
/// surface the rover climbs rising out of view is not one.
fn on_track_surface(f: &Frame, ix: usize, iy: usize, r: f32) -> bool {
    let s = f.spec;
    let y = s.y_centre(iy);
    let side = if y >= 0.0 {
        Region::Left
    } else {
        Region::Right
    };
    let across = || {
        (0..s.ny)
            .filter(move |&j| f.region[j] == side)
            .map(move |j| (j, s.cell(ix, j)))
            .filter(|&(_, c)| f.seen[c] && !f.past[c])
            .map(|(j, c)| (s.y_centre(j), f.cells[c].z))
    };
    if across().count() < CROSS_MIN_CELLS {
        return false;
    }
    line_fit(across()).is_some_and(|(p, rms)| {
        rms <= f64::from(ROUGH_LINE_RMS_M)
            && f64::from(f.cells[s.cell(ix, iy)].top) <= p.z(f64::from(y), 0.0) + f64::from(r)
    })
}

/// Fewest seen cells of a track's row for [`on_track_surface`] to carry its line.
const CROSS_MIN_CELLS: usize = 4;

/// Per cell row, each track's median height, `[left, right]`: the median over the
/// track's strips of `height(cell)` where it is `Some` (NaN where none is).
pub(crate) fn track_medians(
    f: &Frame,
    values: &mut Vec<f32>,
    out: &mut [[f32; 2]],
    height: impl Fn(usize) -> Option<f32>,
) {
    for (ix, row) in out.iter_mut().enumerate() {
        for (k, region) in [Region::Left, Region::Right].into_iter().enumerate() {
            values.clear();
            values.extend(
                f.strips(region)
                    .filter_map(|iy| height(f.spec.cell(ix, iy))),
            );
            row[k] = median(values);
        }
    }
}

/// The median of `values` (reordered in place: a selection, not a sort; it runs
/// for every row of both tracks); NaN when empty.
pub(crate) fn median(values: &mut [f32]) -> f32 {
    let n = values.len();
    if n == 0 {
        return f32::NAN;
    }
    let (below, &mut mid, _) = values.select_nth_unstable_by(n / 2, f32::total_cmp);
    if n % 2 == 1 {
        mid
    } else {
        // The other middle value is the largest below it.
        let lower = below.iter().copied().max_by(f32::total_cmp).unwrap_or(mid);
        0.5 * (lower + mid)
    }
}

/// Gaps: runs of cells the camera should see on flat ground, does not, and that are
/// not in the shadow of something seen in front of them.
///
/// - A gap with no ground seen before it in its strip is unknown ground.
/// - A gap where the surface before it, continued at its slope, would be seen at
///   grazing incidence (under [`GRAZING_DEG`]) is explained: a passable downslope
///   seen from afar gives few points per cell, not none because of a hole.
/// - A gap after seen ground with nothing seen beyond it, or with ground beyond it
///   more than a wheel radius below the ground before it (its last cell, that
///   cell's slope continued, and the line through the last cells), is a drop-off.
/// - A gap with ground beyond it at a climbable level is the shadow of a low step
///   down when that ground explains it (the line of sight to the gap at the far
///   ground's height passes below the near edge); otherwise it is unknown ground.
/// - Neither is a gap whose every cell fell between the camera's pixel rows
///   ([`between_rows`]): ground there, continued from before the gap, would be
///   crossed by under two rows per cell, and the strips on both sides see it.
///
/// A track cell's height is the surface its strip followed (`surface`, from
/// [`steps_and_slopes`]; NaN elsewhere), other cells' their mean.
pub fn gaps(f: &Frame, surface: &[f32], verdict: &mut Verdict) {
    let s = f.spec;
    // A track cell's ground is the surface its strip followed (a face along the
    // strip mixes two levels in the cell's mean); elsewhere the mean.
    let ground = |c: usize| {
        (
            f.cells[c].x,
            Some(surface[c])
                .filter(|z| z.is_finite())
                .unwrap_or(f.cells[c].z),
        )
    };
    let r = f.cfg.rover.wheel_radius_m as f32;
    let tan_max = (f.cfg.rover.max_slope_deg as f32).to_radians().tan();
    let min_run = f.cfg.analysis.gap_min_cells as usize;
    for iy in 0..s.ny {
        let side = f.region[iy].side();
        // A track cell seen whole whose ground the strip did not follow holds the
        // belly band's ground spilled over the band's edge ([`spilled`]): not the
        // strip's ground, it neither ends a gap nor stands before one.
        let track = f.region[iy] != Region::Belly;
        let spilt = |c: usize| track && !f.past[c] && !surface[c].is_finite();
        // The last seen cells (x, z): the ground before a gap and its slope.
        let mut before = Recent::default();
        let mut run: Option<(usize, usize)> = None; // (first ix, length)
        for ix in 0..=s.nx {
            let c = (ix < s.nx).then(|| s.cell(ix, iy));
            let seen_here = c.is_some_and(|c| f.seen[c] && !spilt(c));
            if seen_here || ix == s.nx {
                if let Some((start, len)) = run.take() {
                    if len >= min_run {
                        let after = c.filter(|_| seen_here).map(ground);
                        let kind = if before.last().is_none()
                            && seen_here
                            && below_view(f, iy, start, ix, ground, tan_max)
                        {
                            None
                        } else {
                            judge_gap(f, iy, start, ix, before, after, r, tan_max)
                        };
                        if let Some(kind) = kind {
                            verdict.add_hazard(Hazard {
                                kind,
                                side,
                                distance_m: s.origin[0] + start as f32 * s.voxel_m,
                            });
                        }
                    }
                }
                if let Some(c) = c.filter(|_| seen_here) {
                    let (x, z) = ground(c);
                    before.push(x, z);
                }
                continue;
            }
            let c = s.cell(ix, iy);
            if !f.expected[c] {
                continue; // outside the view: neither seen nor a gap
            }
            if f.shadowed[c] || f.beyond[c] {
                // A shadow or past the horizon: hidden by what is in front.
                run = None;
                continue;
            }
            run = Some(match run {
                Some((start, len)) => (start, len + 1),
                None => (ix, 1),
            });
        }
    }
}

/// Whether a line of slope `k` through height `z0` at `x0` (metres), continued back
/// to `origin_x`, stands there at most `rise` (metres) off the rover's ground (z = 0)
/// on the near side: below it for a rise, above it for a fall. Its toe then lies
/// ahead of `origin_x`, or so little behind that the ground there is flat by the
/// onset's own measure. [`blind_rise`] and [`below_view`] take a ramp whose toe is
/// below the image by it.
fn from_rover_ground((k, z0, x0): (f32, f32, f32), origin_x: f32, rise: f32) -> bool {
    (z0 + k * (origin_x - x0)) * k.signum() <= rise
}

/// Whether the unseen run `start..end` at the near end of strip `iy` (no ground seen
/// before it) is ground lowered out of the image: the ground seen from `end` on lies
/// on one line over [`BLIND_FIT_M`] (within rough ground's spread,
/// [`ROUGH_LINE_RMS_M`]), descending at a passable slope, which continued back to the
/// grid's near edge stands there at most `rise_threshold_m` below the rover's ground
/// (z = 0: its toe ahead, or just behind, as in [`blind_rise`]), and at that height
/// (never above z = 0) no cell of the run falls whole inside the image. The camera
/// sees flat ground there; a descent whose toe lies below the image drops that
/// ground under the image's bottom edge, so its first rows see the descent farther
/// out. [`blind_rise`] judges whether such a change below the image is a ramp.
/// Ground that stays lower than a ramp from the rover's ground would (a drop hidden
/// below the image, ground level beyond it) is not this: its run stays a gap.
fn below_view(
    f: &Frame,
    iy: usize,
    start: usize,
    end: usize,
    ground: impl Fn(usize) -> (f32, f32),
    tan_max: f32,
) -> bool {
    let s = f.spec;
    let x0 = s.x_centre(end);
    let near = || {
        (end..s.nx)
            .take_while(|&ix| f.seen[s.cell(ix, iy)] && s.x_centre(ix) <= x0 + BLIND_FIT_M)
            .map(|ix| ground(s.cell(ix, iy)))
    };
    let Some((line, rms)) = line_fit(near()) else {
        return false;
    };
    let (k, z0) = (line.a as f32, line.z(f64::from(x0), 0.0) as f32);
    let rise = f.cfg.analysis.rise_threshold_m as f32;
    let toe_ahead = rms as f32 <= ROUGH_LINE_RMS_M
        && z0 < 0.0
        && k < 0.0
        && k > -tan_max
        && from_rover_ground((k, z0, x0), s.origin[0], rise);
    toe_ahead
        && (start..end).all(|j| {
            let z = (z0 + k * (s.x_centre(j) - x0)).min(0.0);
            !super::visibility::in_view(s, f.projector, f.cfg, j, iy, z)
        })
}

/// The last few seen cells of a strip, oldest first (a fixed ring: no allocation).
#[derive(Debug, Default, Clone, Copy)]
struct Recent {
    cells: [(f32, f32); Recent::N],
    len: usize,
}

impl Recent {
    const N: usize = 16;
    /// Cells farther back than this from the last one do not count for the slope.
    const SPAN_M: f32 = 0.4;

    fn push(&mut self, x: f32, z: f32) {
        if self.len == Self::N {
            self.cells.copy_within(1.., 0);
            self.len -= 1;
        }
        self.cells[self.len] = (x, z);
        self.len += 1;
    }

    fn last(&self) -> Option<(f32, f32)> {
        self.len.checked_sub(1).map(|i| self.cells[i])
    }

    /// The least-squares line z = slope·x + c through every recent cell, as its
    /// slope, the RMS of the cells' heights about it (metres: how rough the ground
    /// before a gap is over [`Self::N`] cells) and its height at the last cell
    /// (metres: the ground there, which one odd cell does not move). `None` with
    /// fewer than [`ROUGH_MIN_CELLS`] cells or spanning under half a metre.
    fn line(&self) -> Option<(f32, f32, f32)> {
        let cells = &self.cells[..self.len];
        let (x0, xl) = (cells.first()?.0, cells.last()?.0);
        if self.len < ROUGH_MIN_CELLS || xl - x0 < 0.5 {
            return None;
        }
        let (p, rms) = line_fit(cells.iter().map(|&(x, z)| (x - xl, z)))?;
        Some((p.a as f32, rms as f32, p.z(0.0, 0.0) as f32))
    }

    /// Least-squares slope dz/dx of the recent cells within [`Self::SPAN_M`] of the
    /// last one; 0 with fewer than two.
    fn slope(&self) -> f32 {
        let Some((xl, _)) = self.last() else {
            return 0.0;
        };
        // One strip: PlaneFit fits z = a·x + c (b = 0); None with fewer than two x.
        let mut fit = PlaneFit::default();
        for &(x, z) in self.cells[..self.len]
            .iter()
            .filter(|(x, _)| xl - x <= Self::SPAN_M)
        {
            fit.add(f64::from(x - xl), 0.0, f64::from(z), 1.0);
        }
        fit.solve().map_or(0.0, |p| p.a as f32)
    }
}

/// Below this angle between the line of sight and the surface, a camera gets too
/// few points to see a cell, degrees.
pub const GRAZING_DEG: f32 = 6.0;

/// Rough ground's bumps stand up to this many RMS residuals (of the cells before a gap
/// about their line) above the dips behind them: ±2.5 cm of roughness has an RMS of
/// about 1.2 cm and 5 cm from crest to trough.
const BUMP_RMS: f32 = 8.0;

/// Fewest recent cells, over at least half a metre, to judge the ground's roughness.
const ROUGH_MIN_CELLS: usize = 8;

/// Whether the unseen cells `unseen` of strip `iy` lie on ground that falls away
/// across the strip so steeply that the camera meets it at under [`GRAZING_DEG`] (or
/// it faces away). In each cell's row the ground is taken as the line between the
/// nearest seen cells within [`ACROSS_STRIPS`] on either side ([`across_row`]), one
/// [`ACROSS_DROP_M`] or more below the other (where the row sees nothing on the low
/// side, the fall of the row before carried on: [`fall_goes_on`]), sloping `k` along
/// the strip; and the strip's own last seen ground before them, `last` (row, height
/// in metres), must lie on such a fall in its row, off its foot by
/// [`ACROSS_OFF_FOOT_SHARE`] of it: on the slope or at its top, where the ground
/// falls away beside the strip. At the foot of a wall beside the strip, the shadow
/// test judges what the wall hides.
///
/// The edge of ground falling away beside a track, drawn sloping over 8-14 cm: the
/// belly band's edge strip holds the slope's upper half, 70° across, and past 2.7 m
/// its cells get no points (`sweep -- bevelled 60 910 default 2` #0, a `drop_off`).
/// A pit in a trench's floor along the strip beside the belly band lies between the
/// belly's ground and the floor too, but the strip before it is on the floor, at the
/// foot (`belly_ground_spilled_into_a_tracks_edge_strip_ends_no_gap`).
fn grazing_across(
    f: &Frame,
    iy: usize,
    mut unseen: impl Iterator<Item = usize>,
    k: f32,
    (last_ix, last_z): (usize, f32),
) -> bool {
    let mut fall = across_row(f, last_ix, iy);
    let off_foot = fall.is_some_and(|((_, za), (_, zb))| {
        last_z - za.min(zb) >= ACROSS_OFF_FOOT_SHARE * (za - zb).abs()
    });
    let s = f.spec;
    let c = f.camera;
    off_foot
        && unseen.all(|ix| {
            fall = across_row(f, ix, iy).or_else(|| fall.and_then(|l| fall_goes_on(f, ix, iy, l)));
            let Some(((ya, za), (yb, zb))) = fall else {
                return false;
            };
            let ky = (zb - za) / (yb - ya);
            let (x, y) = (s.x_centre(ix), s.y_centre(iy));
            let z = za + ky * (y - ya);
            let normal = Vector3::new(-k, -ky, 1.0).normalize();
            let to_camera = Vector3::new(c[0] - x, c[1] - y, c[2] - z).normalize();
            normal.dot(&to_camera).asin() < GRAZING_DEG.to_radians()
        })
}

/// The fall across of an earlier row, `line` ((y, height) of its two ends, metres),
/// carried on to row `ix` of strip `iy`, which sees no ground on the fall's low side
/// within [`ACROSS_STRIPS`]: the ground past the edge lies in the edge's own shadow
/// there (`sweep -- bevelled 60 6812 random 2` #48, six rows). Only where the row
/// sees the ground at the fall's top on its high side, within [`ACROSS_STRIPS`] and
/// half of [`ACROSS_DROP_M`] of the line's top (the edge goes on); the line is moved
/// to that height.
fn fall_goes_on(f: &Frame, ix: usize, iy: usize, line: Fall) -> Option<Fall> {
    let s = f.spec;
    let ((ya, za), (yb, zb)) = line;
    let seen_z = |jy: usize| {
        let c = s.cell(ix, jy);
        f.seen[c].then_some(f.cells[c].z)
    };
    // The high side's strips lie above `iy` when `yb` (the upper end) is the top.
    let up = zb > za;
    let z = beside(iy, s.ny, up).find_map(seen_z)?;
    let shift = z - za.max(zb);
    (shift.abs() <= 0.5 * ACROSS_DROP_M && beside(iy, s.ny, !up).all(|jy| seen_z(jy).is_none()))
        .then_some(((ya, za + shift), (yb, zb + shift)))
}

/// The strips within [`ACROSS_STRIPS`] of strip `iy` on one side, nearest first:
/// above it (higher index, of `ny`) when `up`, else below.
fn beside(iy: usize, ny: usize, up: bool) -> impl Iterator<Item = usize> {
    (1..=ACROSS_STRIPS).filter_map(move |d| {
        if up {
            Some(iy + d).filter(|&jy| jy < ny)
        } else {
            iy.checked_sub(d)
        }
    })
}

/// The nearest seen cells of row `ix` within [`ACROSS_STRIPS`] of strip `iy` on
/// either side, (y, mean height) in metres, when one stands [`ACROSS_DROP_M`] or more
/// above the other.
///
/// A cell whose points lie level across its width (their heights within
/// [`ACROSS_LEVEL_SHARE`] of the fall) holds no part of the fall, which then begins or
/// ends at its edge facing the strip: its y is taken there. Between cell centres,
/// a fall 10 cm wide seen across three strips measured 60° for 70°, and the camera
/// met it at 6.2° for 2° (`sweep -- bevelled 60 6812 random 2` #9, a `drop_off`).
fn across_row(f: &Frame, ix: usize, iy: usize) -> Option<Fall> {
    let s = f.spec;
    let seen_at = |jy: usize| {
        let c = s.cell(ix, jy);
        f.seen[c].then_some((jy, f.cells[c]))
    };
    let (jb, below) = beside(iy, s.ny, false).find_map(seen_at)?;
    let (ja, above) = beside(iy, s.ny, true).find_map(seen_at)?;
    let fall = (below.z - above.z).abs();
    let half = 0.5 * s.voxel_m;
    let at = |jy: usize, cell: &Cell, toward: f32| {
        let level = cell.top - cell.low <= ACROSS_LEVEL_SHARE * fall;
        let y = s.y_centre(jy) + if level { toward * half } else { 0.0 };
        (y, cell.z)
    };
    (fall >= ACROSS_DROP_M).then(|| (at(jb, &below, 1.0), at(ja, &above, -1.0)))
}

/// A fall across a strip's row: (y, height) of its two ends, metres, the lower y
/// first ([`across_row`]).
type Fall = ((f32, f32), (f32, f32));

/// How many strips to either side [`grazing_across`] looks for seen ground.
const ACROSS_STRIPS: usize = 3;
/// Least fall across between those seen cells for [`grazing_across`], metres.
const ACROSS_DROP_M: f32 = 0.1;
/// Least share of the fall across that the strip's last seen ground stands over its
/// foot for [`grazing_across`].
const ACROSS_OFF_FOOT_SHARE: f32 = 0.1;
/// Most share of the fall across that a cell's points may span for [`across_row`] to
/// take it as level, with no part of the fall in it.
const ACROSS_LEVEL_SHARE: f32 = 0.1;

/// What the unseen run of cells `start..end` in strip `iy` is, given the two seen
/// cells before it and the first seen cell after it (x, z).
#[allow(clippy::too_many_arguments)]
fn judge_gap(
    f: &Frame,
    iy: usize,
    start: usize,
    end: usize,
    before: Recent,
    after: Option<(f32, f32)>,
    r: f32,
    tan_max: f32,
) -> Option<HazardKind> {
    let s = f.spec;
    let Some((xb, zb)) = before.last() else {
        return Some(HazardKind::Unknown);
    };
    // The slope of the ground before the gap, only up to passable: a steeper face is
    // judged by the step and slope test.
    let k = before.slope().clamp(-tan_max, tan_max);
    let predicted = |x: f32| zb + k * (x - xb);
    // The ground before the gap continued from the line through the recent cells (its
    // slope up to passable), which one odd last cell does not move.
    let on_line = before.line().map(|(kl, _, zl)| {
        let kl = kl.clamp(-tan_max, tan_max);
        move |x: f32| zl + kl * (x - xb)
    });
    // The same fall measured from that line: a last cell holding a face's points (a
    // belly band's edge beside a descending track) stands above the ground and would
    // make the ground beyond a drop.
    let below_line = |xa: f32, za: f32| on_line.is_none_or(|z| za < z(xa) - r);
    let unseen = (start..end).filter(|&j| f.expected[s.cell(j, iy)] && !f.seen[s.cell(j, iy)]);
    let c = f.camera;
    let grazing = unseen.clone().all(|j| {
        let (x, y) = (s.x_centre(j), s.y_centre(iy));
        let z = predicted(x);
        let (dx, dy) = (x - c[0], y - c[1]);
        let d = dx.hypot(dy);
        let depression = (c[2] - z).atan2(d);
        let descent = (-k * dx / d).atan();
        depression - descent < GRAZING_DEG.to_radians()
    });
    if grazing && k < 0.0 {
        return None;
    }
    let bumps = || bump_shadow(f, iy, start, end, before);
    // On ground falling away across the strip, met as grazingly; not where the ground
    // beyond is seen a wheel radius down (a drop proven, below).
    let last_ix = s.cell_at(xb, s.y_centre(iy)).map_or(start, |(ix, _)| ix);
    let across = || grazing_across(f, iy, unseen.clone(), k, (last_ix, zb));
    // Seen beside the strip where the camera's rows fall too sparsely to give every
    // cell points.
    let sampled_out = || {
        let ground = |j: usize| (predicted(s.x_centre(j)), k);
        unseen.clone().all(|j| between_rows(f, j, iy, ground(j), r))
            || sparse_ground(f, iy, unseen.clone().map(|j| (j, ground(j))))
    };
    match after {
        None => {
            // Nothing seen beyond: a drop-off, unless the ground before the gap,
            // continued at its slope, would be hidden all along by something seen
            // (ground falling away beyond an edge beside the strip: a sideways shadow),
            // or fell between the camera's rows. Continued from the line through the
            // recent cells too: a last cell of a few stray points (mixed pixels off the
            // edge above) stands above the ground, and ground continued from it would
            // be in view.
            let hidden_at = |z: &dyn Fn(f32) -> f32| {
                unseen
                    .clone()
                    .all(|j| super::visibility::explained(f, j, iy, z(s.x_centre(j))))
            };
            let hidden = hidden_at(&predicted) || on_line.is_some_and(|z| hidden_at(&z));
            (!hidden && !bumps() && !sampled_out() && !across()).then_some(HazardKind::DropOff)
        }
        Some((xa, za)) if za < zb - r && za < predicted(xa) - r && below_line(xa, za) => {
            Some(HazardKind::DropOff)
        }
        Some((_, za)) => {
            let all_shadowed = unseen
                .clone()
                .all(|j| super::visibility::explained(f, j, iy, za));
            (!all_shadowed && !bumps() && !sampled_out() && !across())
                .then_some(HazardKind::Unknown)
        }
    }
}

/// Whether unseen cell (`ix`, `iy`), its ground expected at `z` with slope `k`
/// (dz/dx), fell between the camera's pixel rows: ground there would be crossed by fewer than
/// [`SPARSE_ROWS`] rows per cell (far, at low incidence, or a coarse camera: a
/// 320×240 camera's rows lie 5 cm apart on a 12° descent 3 m out), and the strips
/// on both sides see ground in that row or the next one either way, within a wheel
/// radius of the ground's slope continued. A drop-off's gap spans the strips beside
/// it too, from its edge on.
fn between_rows(f: &Frame, ix: usize, iy: usize, (z, k): (f32, f32), r: f32) -> bool {
    let s = f.spec;
    let x = s.x_centre(ix);
    let beside_seen = [iy.checked_sub(1), Some(iy + 1)].into_iter().all(|side| {
        side.filter(|&n| n < s.ny).is_some_and(|n| {
            (ix.saturating_sub(1)..(ix + 2).min(s.nx)).any(|jx| {
                let c = s.cell(jx, n);
                f.seen[c] && (f.cells[c].z - (z + k * (f.cells[c].x - x))).abs() <= r
            })
        })
    });
    beside_seen && rows_per_cell(f, ix, iy, (z, k)) < SPARSE_ROWS
}

/// How many of the camera's pixel rows cross cell (`ix`, `iy`) of ground at height
/// `z` with slope `k` (dz/dx): `cell · sin(incidence) · fy / range`.
fn rows_per_cell(f: &Frame, ix: usize, iy: usize, (z, k): (f32, f32)) -> f32 {
    let s = f.spec;
    let cam = f.camera;
    let (dx, dy) = (s.x_centre(ix) - cam[0], s.y_centre(iy) - cam[1]);
    let (d, h) = (dx.hypot(dy), cam[2] - z);
    let range = d.hypot(h);
    let incidence = h.atan2(d) - (-k * dx / d).atan();
    s.voxel_m * incidence.sin() * f.fy_px / range
}

/// Whether the unseen cells `(ix, (z, k))` of strip `iy` (their ground expected at
/// `z` with slope `k`) are ground the camera's rows cross too sparsely to give a
/// cell the points it needs, and not a hole: every cell gets under [`SPARSE_ROWS`]
/// rows, and the few points it got lie on the ground continued (within
/// [`SPARSE_GROUND_M`]) in at least half the cells and in one of the last two. Rough
/// ground descending far out, seen from a low camera, gives runs of such cells
/// several strips wide, where [`between_rows`] finds no seen strip beside them. A
/// drop-off's shadow gets no points (a ray past the edge meets the lower ground far
/// beyond), and the lower ground beyond a shadow lies below the continued ground.
fn sparse_ground(f: &Frame, iy: usize, cells: impl Iterator<Item = (usize, (f32, f32))>) -> bool {
    let s = f.spec;
    let (mut n, mut on_ground, mut last_on_ground) = (0usize, 0usize, 0usize);
    for (ix, (z, k)) in cells {
        if rows_per_cell(f, ix, iy, (z, k)) >= SPARSE_ROWS {
            return false;
        }
        let c = &f.cells[s.cell(ix, iy)];
        n += 1;
        if c.n > 0 && (c.z - (z + k * (c.x - s.x_centre(ix)))).abs() <= SPARSE_GROUND_M {
            on_ground += 1;
            last_on_ground = n;
        }
    }
    n > 0 && 2 * on_ground >= n && last_on_ground + 1 >= n
}

/// How far from the ground continued the few points of a sparsely crossed cell may
/// lie for [`sparse_ground`], metres: rough ground's peak to peak (±2.5 cm).
const SPARSE_GROUND_M: f32 = 0.05;

/// Pixel rows per cell under which a cell may get none (rows fall at their own
/// spacing, the cells at theirs).
const SPARSE_ROWS: f32 = 2.0;

/// Whether the unseen run `start..end` of strip `iy` is no longer than the shadow that
/// rough ground's bumps cast at the camera's incidence on the ground before it: a
/// bump [`BUMP_RMS`] residuals high hides `h / tan(incidence)` behind it. Smooth
/// ground (even noisy: a cell's mean height varies by millimetres) casts none worth a
/// cell, so a drop-off's gap there stays a gap.
fn bump_shadow(f: &Frame, iy: usize, start: usize, end: usize, before: Recent) -> bool {
    let (Some((k, rms, _)), Some((xb, zb))) = (before.line(), before.last()) else {
        return false;
    };
    let s = f.spec;
    let c = f.camera;
    let (x, y) = (s.x_centre(start), s.y_centre(iy));
    let (dx, dy) = (x - c[0], y - c[1]);
    let d = dx.hypot(dy);
    let depression = (c[2] - (zb + k * (x - xb))).atan2(d);
    let incidence = depression + (k * dx / d).atan();
    let gap_m = (end - start) as f32 * s.voxel_m;
    incidence > 0.0 && gap_m * incidence.tan() <= BUMP_RMS * rms
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_by_selection_is_the_sorted_middle() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        assert!(median(&mut []).is_nan());
        for len in 1..=14 {
            for _ in 0..50 {
                // Few distinct values, so that ties are common.
                let mut v: Vec<f32> = (0..len)
                    .map(|_| f32::from(rng.gen_range(-4i8..4)) * 0.01)
                    .collect();
                let mut sorted = v.clone();
                sorted.sort_unstable_by(f32::total_cmp);
                let n = sorted.len();
                let want = if n % 2 == 1 {
                    sorted[n / 2]
                } else {
                    0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
                };
                assert_eq!(median(&mut v), want, "{sorted:?}");
            }
        }
    }

    /// A cell centred at (1.025, 0.675) with the given surfaces and their centroids.
    fn cell(crest: f32, crest_xy: [f32; 2], foot: f32, foot_xy: [f32; 2]) -> Cell {
        Cell {
            n: 100,
            x: 1.025,
            y: 0.675,
            z: 0.5 * (crest + foot),
            top: crest,
            top_xy: crest_xy,
            low: foot,
            crest,
            foot,
            crest_xy,
            foot_xy,
        }
    }

    const VS: f32 = 0.05;
    const MID: f32 = 0.675;

    #[test]
    fn a_cell_whose_one_surface_slopes_across_reads_its_mean_but_a_face_beside_ground_does_not() {
        // A ramp's side sloping across the cell, 0.5 to 0.95 of its 39 cm height over
        // its width (`sweep -- bevelled 60 904 default 0` #24, 1.525 m): the points
        // spread evenly, the bands lie either side of the middle.
        let mut c = cell(0.331, [1.026, MID - 0.014], 0.214, [1.024, MID + 0.016]);
        (c.z, c.top, c.low, c.top_xy) = (0.274, 0.354, 0.187, [1.038, MID - 0.020]);
        assert!(slopes_across(&c, MID, VS));
        // The same with too few points in its lower band for a surface: one band.
        let mut one = c;
        (one.foot, one.foot_xy) = (one.crest, one.crest_xy);
        assert!(slopes_across(&one, MID, VS));
        // The mean pulled toward the top: a flat surface with a vertical face's points
        // beside it (the ramp's top and its sharp side, `families 100 5501 random` #97).
        let mut face = one;
        (face.z, face.low) = (0.325, 0.03);
        assert!(!slopes_across(&face, MID, VS));
        // The points' mean off the middle: a face hugging the cell's side.
        let mut hug = c;
        hug.y = MID + 0.01;
        assert!(!slopes_across(&hug, MID, VS));
        // The bands apart forward rather than sideways: a face across the strip.
        let mut step = c;
        (step.crest_xy, step.foot_xy) = ([1.045, MID - 0.005], [1.005, MID + 0.005]);
        assert!(!slopes_across(&step, MID, VS));
        // Within rough ground's spread: no slope to read.
        let mut flat = c;
        flat.top = flat.low + 0.03;
        assert!(!slopes_across(&flat, MID, VS));
    }

    /// A strip of seen cells 5 cm apart at heights `z`.
    fn strip(z: &[f32]) -> Vec<StripCell> {
        z.iter()
            .enumerate()
            .map(|(i, &z)| StripCell {
                x: 1.0 + 0.05 * i as f32,
                z,
                ix: 20 + i,
                past: false,
                wheel: z,
            })
            .collect()
    }

    /// The hazards `strip_hazards` reports on a strip at heights `z(x)`, x from 1.0 m
    /// in 5 cm cells (wheel radius 0.11 m, limit 30°, wheelbase 0.6 m).
    fn hazards_on(z: impl Fn(f32) -> f32) -> Vec<Hazard> {
        let mut run = strip(&(0..30).map(|i| z(0.05 * i as f32)).collect::<Vec<_>>());
        wheel_heights(&mut run, 0.11);
        let mut v = Verdict::default();
        strip_hazards(
            &run,
            Region::Left,
            (0.11, 30f32.to_radians().tan(), 0.6, 2),
            VS,
            &mut v,
        );
        v.hazards.to_vec()
    }

    /// The slope hazards of [`hazards_on`].
    fn slopes(z: impl Fn(f32) -> f32) -> Vec<Hazard> {
        let mut h = hazards_on(z);
        h.retain(|h| h.kind == HazardKind::Slope);
        h
    }

    /// The hazards `strip_hazards` reports on flat ground at z = 0 from 1.0 m that
    /// falls by `fall` after `hole` unseen cells past 1.45 m (gaps from 2 cells).
    fn across_hole(hole: usize, fall: f32) -> Vec<Hazard> {
        let mut run: Vec<StripCell> = (0..10)
            .map(|i| (i, 0.0))
            .chain((10 + hole..30).map(|i| (i, fall)))
            .map(|(i, z)| StripCell {
                x: 1.0 + 0.05 * i as f32,
                z,
                ix: 20 + i,
                past: false,
                wheel: z,
            })
            .collect();
        wheel_heights(&mut run, 0.11);
        let mut v = Verdict::default();
        let limits = (0.11, 30f32.to_radians().tan(), 0.6, 2);
        strip_hazards(&run, Region::Right, limits, VS, &mut v);
        v.hazards.to_vec()
    }

    #[test]
    fn a_fall_across_a_hole_shorter_than_a_gap_is_a_step_and_across_a_gap_is_not_measured() {
        // One unseen cell (a step's shadow seen from high above): the fall is measured.
        let h = across_hole(1, -0.22);
        assert_eq!(h.len(), 1, "{h:?}");
        assert_eq!(
            (h[0].kind, h[0].side),
            (HazardKind::Step, crate::verdict::Side::Right)
        );
        assert!((h[0].distance_m - 1.5).abs() < 0.06, "{h:?}");
        // Under a wheel radius, it is driven down.
        assert!(across_hole(1, -0.09).is_empty());
        // Two or more unseen cells are a gap: the gap test judges it, not this one.
        assert!(across_hole(2, -0.22).is_empty());
        assert!(across_hole(0, -0.22)
            .iter()
            .any(|h| h.kind == HazardKind::Step));
    }

    /// A pseudo-random bump field of ±2.5 cm, correlated over ~10 cm.
    fn rough(x: f32) -> f32 {
        0.0125 * ((x * 41.0).sin() + (x * 67.0 + 1.3).sin()) + 0.005 * (x * 131.0).sin()
    }

    #[test]
    fn rough_ground_on_a_climbable_slope_is_not_a_slope_hazard() {
        let k = 25f32.to_radians().tan();
        // The wheel-radius runs on the bumps are steeper than 30° somewhere...
        let mut run = strip(
            &(0..30)
                .map(|i| k * 0.05 * i as f32 + rough(0.05 * i as f32))
                .collect::<Vec<_>>(),
        );
        wheel_heights(&mut run, 0.11);
        let steepest = run.windows(4).map(fitted_slope).fold(0.0, f32::max);
        assert!(
            steepest > 30f32.to_radians().tan(),
            "{}",
            steepest.atan().to_degrees()
        );
        // ...but the wheelbase they lie on is a 25° line.
        assert!(slopes(|x| k * x + rough(x)).is_empty());
    }

    #[test]
    fn slopes_past_the_limit_stop_long_or_short() {
        for deg in [32f32, 35.0] {
            let k = deg.to_radians().tan();
            assert!(!slopes(|x| k * x).is_empty(), "{deg}° slope");
            assert!(
                !slopes(|x| k * x + rough(x)).is_empty(),
                "rough {deg}° slope"
            );
        }
        // A 34° bank 0.45 m long, then flat: its wheelbase fit is under 30°, but the
        // bank and the flat are not one line.
        let k = 34f32.to_radians().tan();
        assert!(!slopes(|x| k * x.clamp(0.3, 0.75)).is_empty());
    }

    #[test]
    fn a_ramp_too_steep_that_rises_a_wheel_radius_within_a_few_cells_is_a_slope_not_a_step() {
        // From its toe 1.5 m out, a ramp of 37-50° rises a wheel radius within three
        // cells, as a step does; but the ground past its toe lies on one line.
        for deg in [37f32, 40.0, 50.0] {
            let k = deg.to_radians().tan();
            for bumps in [0.0, 1.0] {
                let h = hazards_on(|x| k * (x - 0.5).max(0.0) + bumps * rough(x));
                let first = nearest(&h).expect("a ramp over the limit stops");
                assert_eq!(
                    first.kind,
                    HazardKind::Slope,
                    "{deg}° (bumps {bumps}): {h:?}"
                );
                // Where the wheel first touches it: up to a wheel radius before.
                assert!((1.39..=1.55).contains(&first.distance_m), "{deg}°: {h:?}");
            }
        }
        // Steps of 15-30 cm (on rough ground too), and a 45° bank 15 cm high with the
        // flat above it, are steps.
        for z in [
            |x: f32| if x > 0.5 { 0.15 } else { 0.0 },
            |x: f32| if x > 0.5 { 0.3 } else { 0.0 },
            |x: f32| if x > 0.5 { 0.2 + rough(x) } else { rough(x) },
            |x: f32| (x - 0.5).clamp(0.0, 0.15),
        ] {
            let h = hazards_on(z);
            assert_eq!(nearest(&h).map(|h| h.kind), Some(HazardKind::Step), "{h:?}");
        }
    }

    /// The nearest of `hazards` (the one that decides the verdict).
    fn nearest(hazards: &[Hazard]) -> Option<&Hazard> {
        hazards
            .iter()
            .min_by(|a, b| a.distance_m.total_cmp(&b.distance_m))
    }

    #[test]
    fn a_wheel_bridges_a_dip_but_meets_a_step_in_full() {
        let r = 0.11;
        // A 5 cm dip before a 9 cm pebble on flat ground: 14 cm from the dip's bottom,
        // but the wheel resting over the dip is held up by the ground beside it.
        let mut s = strip(&[0.0, 0.0, -0.05, 0.09, 0.0, 0.0]);
        wheel_heights(&mut s, r);
        assert!(s[2].wheel > -0.02, "{:?}", s[2]);
        assert!((s[3].wheel - 0.09).abs() < 1e-6);
        let rise = s[3].wheel - s.iter().map(|c| c.wheel).fold(f32::INFINITY, f32::min);
        assert!(rise <= r, "the wheel climbs {rise} m");
        // A 15 cm step: the wheel's lowest point still rises by all of it.
        let mut s = strip(&[0.0, 0.0, 0.0, 0.0, 0.15, 0.15, 0.15, 0.15]);
        wheel_heights(&mut s, r);
        assert_eq!(s[0].wheel, 0.0);
        assert!((s[7].wheel - s[0].wheel - 0.15).abs() < 1e-6);
        // Across a hole nothing holds the wheel up.
        let mut s = strip(&[0.0, 0.2]);
        s[1].ix += 2;
        wheel_heights(&mut s, r);
        assert_eq!(s[0].wheel, 0.0);
    }

    #[test]
    fn a_wall_along_the_strip_leaves_the_floor_as_ground() {
        // A trench's outer wall at y = 0.7: its points (the crest) hug the side.
        let c = cell(-0.05, [1.025, 0.698], -0.20, [1.025, 0.680]);
        assert_eq!(ground_beside_face(&c, MID, VS), Some(-0.20));
        // A ramp's side face at the cell's inner edge: the foot hugs the side.
        let c = cell(0.30, [1.025, 0.676], 0.12, [1.025, 0.652]);
        assert_eq!(ground_beside_face(&c, MID, VS), Some(0.30));
    }

    #[test]
    fn a_face_across_the_strip_or_close_surfaces_are_left_to_the_strip() {
        // A step's face: the crest lies behind the foot, not beside it.
        let c = cell(0.15, [1.040, 0.690], 0.0, [1.008, 0.675]);
        assert_eq!(ground_beside_face(&c, MID, VS), None);
        // Rough ground: two bands 3 cm apart are one surface.
        let c = cell(0.02, [1.025, 0.699], -0.01, [1.025, 0.675]);
        assert_eq!(ground_beside_face(&c, MID, VS), None);
        // Both bands spread across the cell: no side to hug.
        let c = cell(0.10, [1.025, 0.682], 0.0, [1.025, 0.672]);
        assert_eq!(ground_beside_face(&c, MID, VS), None);
    }

    #[test]
    fn a_seen_cell_shows_a_wall_by_its_top_alone_only_at_the_strips_side() {
        // One surface, the floor 22 cm under the belly's level; the wall's points too
        // few for a band of their own, its top voxel at the strip's side.
        let floor = |top: f32, top_y: f32| Cell {
            top,
            top_xy: [1.025, top_y],
            ..cell(-0.22, [1.025, 0.675], -0.22, [1.025, 0.675])
        };
        let r = 0.11;
        assert!(fringe_of_wall(&floor(0.0, 0.698), -0.22, MID, r, VS));
        // A top a wheel radius or less over the floor, or on the strip's centre line.
        assert!(!fringe_of_wall(&floor(-0.12, 0.698), -0.22, MID, r, VS));
        assert!(!fringe_of_wall(&floor(0.0, 0.68), -0.22, MID, r, VS));
        // Two surfaces: the wall is one of its own, judged by ground_beside_face.
        let two = cell(-0.05, [1.025, 0.698], -0.20, [1.025, 0.680]);
        assert!(!fringe_of_wall(&two, -0.20, MID, r, VS));
    }

    #[test]
    fn a_cut_cell_reads_as_the_wall_only_where_its_top_runs_on_along_the_wall() {
        // The strip's last seen cell: the wall at y = 0.7, its top at 0 over a floor
        // 22 cm down, 5 cm back.
        let wall = Some([0.975, 0.0, 0.699]);
        // A cut cell of floor whose top (too few points for a surface) is the wall's.
        let floor = |top: f32, top_y: f32| Cell {
            top,
            top_xy: [1.025, top_y],
            ..cell(-0.22, [1.025, 0.675], -0.22, [1.025, 0.675])
        };
        assert!(wall_goes_on(&floor(-0.03, 0.697), wall, MID, VS));
        // Noise-lifted by up to rough ground's spread, still the wall.
        assert!(wall_goes_on(&floor(0.012, 0.697), wall, MID, VS));
        // Higher than the wall: something new stands there.
        assert!(!wall_goes_on(&floor(0.03, 0.697), wall, MID, VS));
        // A top on the strip's centre line or off the wall's line: a post in the strip.
        assert!(!wall_goes_on(&floor(-0.05, 0.675), wall, MID, VS));
        assert!(!wall_goes_on(&floor(-0.05, 0.652), wall, MID, VS));
        // No wall before it, or the wall seen too far back.
        assert!(!wall_goes_on(&floor(-0.03, 0.697), None, MID, VS));
        assert!(!wall_goes_on(
            &floor(-0.03, 0.697),
            Some([0.8, 0.0, 0.699]),
            MID,
            VS
        ));
        // An upper band with points enough to be a surface is judged as one.
        let surface = Cell {
            top: -0.03,
            top_xy: [1.025, 0.697],
            ..cell(-0.05, [1.045, 0.675], -0.22, [1.010, 0.675])
        };
        assert!(!wall_goes_on(&surface, wall, MID, VS));
        // An upper band on the wall's line is the wall's fringe, over the floor, even
        // where the floor's points centre too near the wall for the two to be told
        // apart as a face and the ground beside it.
        let fringe = |crest_y: f32| Cell {
            top: -0.03,
            top_xy: [1.025, 0.697],
            ..cell(-0.05, [1.020, crest_y], -0.20, [1.023, 0.688])
        };
        assert_eq!(ground_beside_face(&fringe(0.697), MID, VS), None);
        assert!(wall_goes_on(&fringe(0.697), wall, MID, VS));
        assert!(!wall_goes_on(&fringe(0.680), wall, MID, VS));
    }
}
