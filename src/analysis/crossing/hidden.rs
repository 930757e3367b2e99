//! Rises in a track whose top, foot or far side the camera does not see: a boulder
//! whose far side is hidden, a climb whose foot lies before the view, a climb that
//! leaves the view too steep to be a ramp.

use super::belly::belly_top_seen;
use super::faces::{top_hugs_side, two_levels, FACE_OFF_VOXELS};
use super::gaps::from_rover_ground;
use super::{
    followed, line_fit, sharp_apex, unknown_judged, Frame, Region, ROUGH_LINE_RMS_M,
    ROUGH_SPREAD_M, UNSEEN_FOOT_MARGIN_M,
};
use crate::analysis::plane::Plane;
use crate::analysis::{low_step, visibility};
use crate::grid::Cell;
use crate::verdict::{Hazard, HazardKind, Verdict};

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
/// lowest). A climb across a shadow is measured from a wheelbase before the shadow
/// too, its foot no nearer than the shadow's near edge ([`climb_start`]).
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
                let (start, shadow) = climb_start(f, iy, ix, wheelbase);
                let climb = (start..=ix)
                    .rev()
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
                // Past the ground seen low, a shadow: the hidden dip may begin at its
                // near edge.
                let foot_m = match shadow.filter(|&jx| jx > foot) {
                    Some(jx) => f.spec.x_centre(jx) - 0.5 * f.spec.voxel_m,
                    None => f.spec.x_centre(foot),
                }
                .max(0.0);
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

/// The first row of the climb [`hidden_tops`] measures to the exit at row `ix` of
/// strip `iy`, and the nearest row of a shadow within it: the rows within a
/// `wheelbase` before the exit and, where a shadow lies among them, within a
/// `wheelbase` before the shadow's nearest cell too. The ground a shadow hides lies
/// under the line of sight, as low as the ground before what cast it may be: a
/// 15.3 cm rock standing 6 cm past an 8.3 cm one, the dip between them in the
/// smaller one's shadow, rose only 7 cm over the smaller one's top within a
/// wheelbase, and went (`sweep -- bevelled 100 2606 random` #18, clean and noisy).
/// Measured from the ground before the shadow it stands as high as alone, and its
/// foot is no nearer than the shadow's near edge, where the hidden dip may begin.
fn climb_start(f: &Frame, iy: usize, ix: usize, wheelbase: f32) -> (usize, Option<usize>) {
    let back = |x: f32| {
        (0..=ix)
            .find(|&jx| x - f.spec.x_centre(jx) <= wheelbase)
            .unwrap_or(ix)
    };
    let start = back(f.spec.x_centre(ix));
    match (start..ix).find(|&jx| f.shadowed[f.spec.cell(jx, iy)]) {
        Some(shadow) => (back(f.spec.x_centre(shadow)), Some(shadow)),
        None => (start, None),
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
/// analysis). Not when a shadow cuts that stretch short and the ground the strip sees
/// again past it ([`ground_beyond`]) lies more than a wheel radius and
/// [`UNSEEN_FOOT_MARGIN_M`] under what the stretch rose to: a ramp goes on rising
/// behind what hides it, and that ground is back at the foot of what stood there (a
/// 15.2 cm cone whose foot lay below the image fitted a 22° line through the cell
/// past its apex, and went: `sweep -- natural 200 7820 random 7` #159).
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
/// ([`inner_strips`]), nor does a strip that the image's edge cuts beside a strip
/// that saw the same ground climbed in view ([`continues_beside`]).
pub fn blind_rise(f: &Frame, surface: &[f32], verdict: &mut Verdict) {
    for region in [Region::Left, Region::Right] {
        let mut hidden = 0usize;
        let mut nearest = f32::INFINITY;
        for iy in inner_strips(f, region) {
            let Some(start) = unseen_change(f, surface, iy) else {
                continue;
            };
            if [-1, 1]
                .into_iter()
                .any(|d| continues_beside(f, surface, iy, start, d))
            {
                continue;
            }
            hidden += 1;
            nearest = nearest.min(f.spec.x_centre(start));
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

/// [`blind_rise`]'s judgement of inner strip `iy`: the row of its first followed
/// ground when the change it shows there from the rover's ground is unseen (no ramp
/// whose toe lies below the image, not seen from the ground), else `None`.
fn unseen_change(f: &Frame, surface: &[f32], iy: usize) -> Option<usize> {
    let r = f.cfg.rover.wheel_radius_m as f32;
    let rise = f.cfg.analysis.rise_threshold_m as f32;
    let tan_max = (f.cfg.rover.max_slope_deg as f32).to_radians().tan();
    let ground = |ix: usize| {
        let c = f.spec.cell(ix, iy);
        followed(f, surface, c).map(|z| (f.cells[c].x, z))
    };
    let start = (0..f.spec.nx).find(|&ix| ground(ix).is_some())?;
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
        straight && k * z0 > 0.0 && k.abs() < tan_max && from_rover_ground((k, z0, x0), 0.0, rise)
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
    // A sharp apex's cell reads its mean 2-4 cm under its highest point: there
    // the highest point counts (a 15.3 cm cone whose foot lies below the
    // image read 10.7 cm, its highest point 13 cm: `sweep -- natural 200 7324
    // random 7` #167, a go).
    if reach > 0.0 {
        let cell = &f.cells[f.spec.cell(start + at, iy)];
        reach = sharp_apex(cell, reach).unwrap_or(reach);
    }
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
    if (reach.abs() <= r + UNSEEN_FOOT_MARGIN_M && !level_over) || from_ground || from_foot {
        return None;
    }
    // A ramp goes on rising behind what hides it: ground seen again past a
    // shadow that cuts the stretch short, more than a wheel radius and rough
    // ground's margin under what the stretch rose to, is back at the foot of
    // what stood there, whatever line its front fits.
    let seen = near().count();
    let back_down = reach > 0.0
        && start + seen < f.spec.nx
        && ground(start + seen).is_none()
        && ground_beyond(f, surface, iy, start + seen)
            .is_some_and(|z| z < reach - r - UNSEEN_FOOT_MARGIN_M);
    let ramp =
        !back_down && fit(BLIND_FIT_M, 0).is_some_and(toe_ahead) && rest.is_none_or(toe_ahead);
    (!ramp).then_some(start)
}

/// Whether inner strip `iy`, first seen at row `start`, continues the ground of the
/// strip beside it toward `d` (±1): in the row before, its cell is not seen and lies
/// outside the image, on flat ground or at the height of the ground that neighbour,
/// an inner strip of the same band, follows there (the image's side edge, or a rolled
/// camera's slanted bottom edge, cuts this strip and not that one; a raised surface
/// leaves the image where the ground under it would not); in row `start`
/// the neighbour lies within rough ground's spread ([`ROUGH_SPREAD_M`]) of this
/// strip; and the neighbour's own change is seen ([`unseen_change`]), or continues
/// the next strip's the same way. The climb is then seen whole beside it, and the
/// step and slope test judges it there. A yawed camera whose image's side edge
/// crossed a track saw the outer strips of a 24.7° ramp capped at 24.5 cm first on
/// its top, beside strips that saw it rise to the same height, and the track was
/// `unknown` (`sweep -- widened 100 1213 random 0` #61, and so drawn as wide as the
/// track). A camera pitched 44.8° and yawed 9.5° saw the outer strips of a 22.7°
/// ramp capped at 27 cm first on its top, where the ground under the ramp was in the
/// image but the ramp's top was not (`sweep -- families 100 2901 random` #77).
fn continues_beside(f: &Frame, surface: &[f32], iy: usize, start: usize, d: isize) -> bool {
    let s = f.spec;
    let Some((prev, j)) = start.checked_sub(1).zip(iy.checked_add_signed(d)) else {
        return false;
    };
    let inner = inner_strips(f, f.region[iy]).any(|k| k == j);
    let out = s.cell(prev, iy);
    let ground = |ix: usize, k: usize| followed(f, surface, s.cell(ix, k));
    let outside =
        |z: f32| !f.expected[out] || !visibility::in_view(s, f.projector, f.cfg, prev, iy, z);
    inner
        && !f.seen[out]
        && ground(prev, j).is_some_and(outside)
        && ground(start, iy)
            .zip(ground(start, j))
            .is_some_and(|(z, zj)| (z - zj).abs() <= ROUGH_SPREAD_M)
        && unseen_change(f, surface, j).is_none_or(|sj| continues_beside(f, surface, j, sj, d))
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
/// foot (the rover stops already, and the verdict says why); so does one strip whose
/// steep climb rises more than a wheel radius and [`UNSEEN_FOOT_MARGIN_M`] (the margin
/// of every rise whose top is not seen): what it saw is already an obstacle's front
/// (a 15.5 cm mound the image's top edge cut in two strips, seen rising 12 cm at 31°
/// and 29° from its foot, was a go: `sweep -- natural 200 6822 random 7` #34). Runs
/// last of the crossing tests.
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
///
/// A belly strip's ground is its cells' mean, but a cell holding two levels
/// ([`two_levels`]: its points spanning 4 cm or more) reads its top: the strip has
/// been seen that high there. A one-track ramp drawn into the belly band puts its side
/// face inside a belly strip, the ramp's top on one side, the flat on the other; read at
/// their mean, which lies between the levels wherever each one's share of the points
/// puts it, such a strip's cells climbed into the ramp's top in the cut cells, a front
/// across it, `unknown` (a ramp 11 cm into the band, capped at 0.36 m: `sweep --
/// widened 100 1202 default 0` #21). The cell of a front seen before the cut, read at
/// its top, only steepens the climb to it. A cut cell's face or spread counts only
/// where it rises on past the strip's ground before the cut ([`fronts`]). A low front
/// (within a wheel radius and [`UNSEEN_FOOT_MARGIN_M`], [`low_step`]) whose top is
/// seen levelling off, in the strip or in strips of its band beside it, takes no part
/// ([`top_seen_level`]): the step test judges it. Nor does a belly strip whose cut
/// cells each show what stands there levelling off at a top seen
/// ([`belly_top_seen`]): the belly test measures that top against the clearance (a
/// 25 cm boulder whose level top the view ended on was `unknown`, `sweep -- natural
/// 100 12213 random 8` #12).
pub fn steep_exit(f: &Frame, surface: &[f32], verdict: &mut Verdict) {
    let rover = &f.cfg.rover;
    let tan_max = (rover.max_slope_deg as f32).to_radians().tan();
    let wheelbase = rover.wheelbase_m as f32;
    let r = rover.wheel_radius_m as f32;
    let s = f.spec;
    let found = [Region::Left, Region::Belly, Region::Right].map(|region| {
        let (mut tall, mut over, mut nearest) = (0usize, 0usize, f32::INFINITY);
        let (mut short, mut short_nearest, mut inner) = (0usize, f32::INFINITY, 0usize);
        let (mut any_tall, mut any_nearest) = (0usize, f32::INFINITY);
        let (mut bent, mut bent_nearest) = (0usize, f32::INFINITY);
        for iy in inner_strips(f, region) {
            inner += 1;
            let ground = |ix: usize| {
                let c = s.cell(ix, iy);
                let z = if region == Region::Belly {
                    let cell = &f.cells[c];
                    let z = if two_levels(cell) { cell.top } else { cell.z };
                    f.seen_whole(c).then_some(z)
                } else {
                    followed(f, surface, c)
                };
                z.map(|z| (f.cells[c].x, z))
            };
            let Some(h) = first_cut(f, iy, 1) else {
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
            let cut = cut_cells(f, iy, h).filter(|&(_, c)| !top_beside(f, iy, h, c));
            let top = cut
                .clone()
                .map(|(_, c)| c.top)
                .fold(f32::NEG_INFINITY, f32::max);
            let rise = top - foot.1;
            // No unseen front: a short rise, a low front whose top is seen levelling
            // off (the step test judges it), or a belly strip's top seen levelling
            // off (the belly test measures it).
            if rise < STEEP_EXIT_SHORT_RISE_M
                || (low_step(rise, rover)
                    && top_seen_level(f, region, (iy, h), (foot.1, top), tan_max))
                || (region == Region::Belly
                    && cut
                        .clone()
                        .all(|(ix, _)| belly_top_seen(f, ix, iy, foot.1 + r)))
            {
                continue;
            }
            // A face across the strip within one cut cell, or the climb and the cut
            // cells' upper surface on one line steeper than the limit (a face the
            // cell boundary splits, a steep ramp).
            let (face, spread) = fronts(f, iy, (foot.1, before()), tan_max, cut.clone());
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
                    over += usize::from(!low_step(rise, rover));
                    nearest = nearest.min(foot.0);
                }
            }
        }
        let (steep, nearest) = if tall >= 2 || over >= 1 {
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
        let judged = unknown_judged(verdict, region.side(), nearest);
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

/// Strip `iy`'s first seen cell past the sensor's horizon from row `from` on: where
/// its view ends.
pub(crate) fn first_cut(f: &Frame, iy: usize, from: usize) -> Option<usize> {
    let s = f.spec;
    (from..s.nx).find(|&ix| {
        let c = s.cell(ix, iy);
        f.seen[c] && f.past[c]
    })
}

/// Strip `iy`'s seen cells past the sensor's horizon among the [`CUT_CELLS`] from its
/// first one, `h` ([`first_cut`]), with their rows: what the view shows where it ends
/// (what is seen of each lies under the image's top edge, a lower bound).
pub(crate) fn cut_cells<'f>(
    f: &'f Frame,
    iy: usize,
    h: usize,
) -> impl Iterator<Item = (usize, &'f Cell)> + Clone + 'f {
    let s = f.spec;
    (h..(h + CUT_CELLS).min(s.nx))
        .map(move |ix| (ix, s.cell(ix, iy)))
        .filter(|&(_, c)| f.seen[c] && f.past[c])
        .map(|(ix, c)| (ix, &f.cells[c]))
}

/// How many cells from where a strip's view ends [`cut_cells`] reads: 15 cm at the
/// default voxel, a front's first centimetres past the cut.
const CUT_CELLS: usize = 3;

/// Whether strip `iy`'s cut cells (`cut`, from its first, `h`) show a front across
/// the strip, `(face, spread)`. `face`: a cell whose points span
/// [`STEEP_EXIT_RISE_M`] in 5 cm (steeper than 45°), its upper surface beyond its
/// lower one more than beside it, unlike a ramp's side face along the strip. `spread`:
/// a cell whose points span as much but whose two surfaces depth noise has merged
/// (`crest` and `foot` within rough ground's spread, [`ROUGH_SPREAD_M`], of each
/// other), so it has no orientation of its own; its points not hugging one side of
/// the cell, it is not along the strip (counted only where most of the band shows a
/// front). Merged surfaces need not be one mean: a noisy ramp's cell whose points
/// span a hair over the surface bands' reach leaves one fringe voxel out of each,
/// and its crest and foot stood 7 mm and 1 mm apart, an orientation drawn by noise
/// (`sweep -- bevelled 100 12412 random 9` #82, noisy: `unknown` on a 22.9° ramp).
///
/// Either cell's top must stand [`STEEP_EXIT_SHORT_RISE_M`] over the climb's `foot`
/// (metres) and rise on past the strip's ground before the cut (`before`, from
/// `h − 1` back, as [`steep_exit`] reads it): [`FRONT_RISING_M`] over its last cell
/// carried on at the slope its last [`FRONT_LINE_M`] climb (none if it falls, the
/// rover's limit `tan_max` at most) to the top's x. A front the view ends on stands over the
/// ground before it; a ramp's side face inside a belly strip, seen beside the flat
/// only up to where the image's top edge cuts it, stands under the ramp's top the
/// strip already climbed, and its upper points lie farther on as the ramp rises, so
/// its bands part forward (`sweep -- widened 100 1202 default 0` #2: `unknown`).
fn fronts<'c>(
    f: &Frame,
    iy: usize,
    (foot, before): (f32, impl Iterator<Item = (f32, f32)> + Clone),
    tan_max: f32,
    cut: impl Iterator<Item = (usize, &'c Cell)>,
) -> (bool, bool) {
    let y_mid = f.spec.y_centre(iy);
    let Some(last) = before.clone().next() else {
        return (false, false);
    };
    let recent = before.take_while(|&(x, _)| last.0 - x <= FRONT_LINE_M);
    let climbs = line_fit(recent).map_or(0.0, |(p, _)| (p.a as f32).clamp(0.0, tan_max));
    let rises = |c: &Cell| {
        c.top >= foot + STEEP_EXIT_SHORT_RISE_M
            && c.top >= last.1 + FRONT_RISING_M + climbs * (c.top_xy[0] - last.0).max(0.0)
    };
    cut.filter(|(_, c)| c.top - c.low >= STEEP_EXIT_RISE_M && rises(c))
        .fold((false, false), |(face, spread), (_, c)| {
            let (dx, dy) = (c.crest_xy[0] - c.foot_xy[0], c.crest_xy[1] - c.foot_xy[1]);
            let apart = c.crest - c.foot >= ROUGH_SPREAD_M;
            let merged = !apart && (c.y - y_mid).abs() < FACE_OFF_VOXELS * f.spec.voxel_m;
            (face || (apart && dx > dy.abs()), spread || merged)
        })
}

/// Whether cut cell `cell` of strip `iy` (whose view ends at row `h`) shows the
/// ground beside the strip, not a front across it: its top voxel hugs the strip's
/// side ([`top_hugs_side`]), and the strip on that side, seen
/// in the row before the view ends (row `h − 1`, not past the horizon), stands no
/// lower there than that top less rough ground's spread ([`ROUGH_SPREAD_M`]). Where
/// that strip's own view ends a row earlier (a rolled camera's image edge crosses the
/// corridor obliquely), its row before that is read: the last of [`BESIDE_ROWS`] rows
/// before `h` short of its horizon. A face
/// along the strip lies inside it, the higher ground beside on one side; where the
/// view ends, the cut cell may hold that ground's few points and none of the lower
/// ground's, and the strip "rose" to it. A one-track descent drawn 9 cm into the
/// belly band left a 1 cm sliver of level ground along a belly strip's side; 2.85 m
/// out, the cut cell held two of its points over the descent's 15 cm down, and the
/// strip was `unknown` (`sweep -- widened 100 11807 random 3` #54, noisy). The
/// strip beside must see that level before the cut: a front across the corridor
/// rises there too, and is still judged. A 9° descent drawn 15 cm into the belly
/// band, its side face 3 mm inside a belly strip, seen by a 320×240 camera rolled
/// −6.7°: the strip beside, on the level side, saw that level to one row before the
/// strip's last, and the strip was `unknown` (`sweep -- widened 100 12607 random 3`
/// #16, clean).
fn top_beside(f: &Frame, iy: usize, h: usize, cell: &Cell) -> bool {
    let s = f.spec;
    let y_mid = s.y_centre(iy);
    if !top_hugs_side(cell, y_mid, s.voxel_m) {
        return false;
    }
    let toward = if cell.top_xy[1] > y_mid {
        iy.checked_add(1)
    } else {
        iy.checked_sub(1)
    };
    let beside = toward.filter(|&j| j < s.ny).and_then(|j| {
        (h.saturating_sub(BESIDE_ROWS)..h)
            .rev()
            .map(|ix| s.cell(ix, j))
            .find(|&c| !f.past[c])
    });
    beside.is_some_and(|c| f.seen_whole(c) && cell.top <= f.cells[c].z + ROUGH_SPREAD_M)
}

/// How many rows before a strip's view ends [`top_beside`] reads the strip beside in:
/// its row before, or, where the strip beside's own view ended there, the row before
/// that (10 cm at the default voxel).
const BESIDE_ROWS: usize = 2;

/// Least run along a strip between the two level cells that show a front's top
/// seen ([`top_seen_level`]), in voxels: half a cell.
const LEVEL_RUN_VOXELS: f32 = 0.5;

/// Whether the top of the front strip `iy` of `region` climbs where its view ends
/// (`h`, its first cut cell; `(foot, top)` the climb's foot and its cut cells' top,
/// metres) is seen, and levels off: in this strip or in an inner strip of the band
/// reached from it through strips that each hold a level cell at that height (rows
/// `h − 1` to `h + CUT_CELLS − 1`), one cell holds the whole front, its points from
/// the foot to the top (within rough ground's spread, [`ROUGH_SPREAD_M`]), and the two
/// cells past it are level at the top over half a cell or more
/// ([`LEVEL_RUN_VOXELS`]), climbing between them at half the slope limit `tan_max` at
/// most. A level cell's points span rough ground's spread at most, its top within it
/// of `top`.
///
/// A low step across the corridor whose face a steeply pitched camera's view ends
/// just past was `unknown` in every strip where the image's top edge left only one
/// cell of the step's level top: a wall could rise on from there. Strips whose view
/// reaches farther see the face in one cell and the top level over the next two: the
/// front ends there, at a height the step test takes as a low step (`sweep -- hazards
/// 100 12004 random` #28: an 8.6 cm step, a camera 0.81 m high pitched 43°). A ramp
/// steeper than the limit rising out of view climbs on between any two of its cells;
/// a ramp under it, on which a mound's flank rises out of view, is level enough cell by
/// cell, but no cell before it holds a front (`natural 100 11702 random 10` #92, a
/// 19.9 cm mound up a 14.4° ramp, went without that).
fn top_seen_level(
    f: &Frame,
    region: Region,
    (iy, h): (usize, usize),
    (foot, top): (f32, f32),
    tan_max: f32,
) -> bool {
    let s = f.spec;
    let rows = h.saturating_sub(1)..(h + CUT_CELLS).min(s.nx);
    let at = |ix: usize, j: usize| {
        let c = s.cell(ix, j);
        f.seen[c].then_some(&f.cells[c])
    };
    let level = |ix: usize, j: usize| {
        at(ix, j).filter(|cell| {
            cell.peak - cell.low <= ROUGH_SPREAD_M && (cell.top - top).abs() <= ROUGH_SPREAD_M
        })
    };
    let whole_front = |ix: usize, j: usize| {
        at(ix, j).is_some_and(|cell| {
            cell.low <= foot + ROUGH_SPREAD_M && cell.peak >= top - ROUGH_SPREAD_M
        })
    };
    let at_top = |j: usize| rows.clone().any(|ix| level(ix, j).is_some());
    let plateau = |j: usize| {
        rows.clone().zip(rows.clone().skip(1)).any(|(a, b)| {
            a.checked_sub(1).is_some_and(|face| whole_front(face, j))
                && level(a, j).zip(level(b, j)).is_some_and(|(near, far)| {
                    let run = far.x - near.x;
                    run >= LEVEL_RUN_VOXELS * s.voxel_m
                        && (far.top - near.top).abs() <= 0.5 * tan_max * run
                })
        })
    };
    let inner = |j: usize| inner_strips(f, region).any(|k| k == j);
    // The strip itself once, then the strips reached from it either way.
    plateau(iy)
        || [-1isize, 1].into_iter().any(|d| {
            let mut j = iy;
            while let Some(k) = j.checked_add_signed(d).filter(|&k| inner(k) && at_top(k)) {
                if plateau(k) {
                    return true;
                }
                j = k;
            }
            false
        })
}

/// Where a strip's view ends (`h`, its first cut cell) on smooth ground, whether the
/// cut cells show a rise steeper than the rover climbs: the x of the last ground cell
/// on the smooth ground's line, metres, or `None`.
///
/// `before` is the strip's ground over the wheelbase before `h`, one cell after the
/// other from `h − 1` back (its k-th item is cell `h − 1 − k`); `cut` its seen cells
/// among the first three from `h`, with their column. The front may
/// begin up to [`FRONT_CELLS`] ground cells before the cut. For each such start, when
/// the ground cells before it lie on smooth ground's line ([`smooth_line`]: no bumps
/// that steepen a short stretch), a cut cell counts
/// when its top stands [`BEND_RISE_M`] or more above that line carried to the cell's
/// far edge (off the ground the strip was on), above the line where the front begins
/// by more than the slope limit `tan_max` climbs from there to the cell's far edge
/// (the gentlest the rise can be), or to its top voxel's centroid where the cut cells
/// seen past it stand [`FRONT_RISING_M`] or more higher still (a front no steeper than
/// the limit keeps every point, so their mean, under that line; a cut cell past it
/// not that high shows the top level, a low step's seen whole past its face: without
/// it a 4.5 cm step the view ends on was `unknown`, `sweep -- hazards 100 10704
/// random` #82; its noisy frame, the top seen in the last cut cell only, still is,
/// and since [`BENT_STRIPS`] asks for two strips, so is its clean frame, where two
/// strips see the top only in their last cut cell).
/// The far edge alone let a 19.4 cm mound 0.5 m up an 11° ramp, seen rising 5.6 cm
/// over 6.5 cm into the cut, pass as climbing 29° (`sweep -- natural 100 10902 random
/// 10` #87). And [`FRONT_RISING_M`] or more above the upper surface (`crest`) of the
/// front's cells before the cut (still rising where the view
/// ends: a stone seen whole, its top before the cut, is the step test's). Not their top
/// voxels: a few of the cut's points that depth noise moved nearer made a voxel 10.2
/// cm up in the last cell before the cut, as high as the cut cell's top, and a 15.2 cm
/// mound the view ends on was a noisy go (`sweep -- natural 200 3718 random 7` #173;
/// 6.5 cm clean). That is the front of a rock, a wall or a
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
        let window = before.clone().skip(lead);
        let line = smooth_line(window.clone())?;
        let (last_x, _) = window.clone().next()?;
        let end = h - 1 - lead;
        let front_top = (end + 1..h)
            .map(|ix| f.cells[s.cell(ix, iy)].crest)
            .fold(f32::NEG_INFINITY, f32::max);
        let on_line = |x: f32| line.z(f64::from(x), 0.0) as f32;
        let near = s.x_centre(end) + 0.5 * s.voxel_m;
        cut.clone()
            .any(|(ix, c)| {
                let far = s.x_centre(ix) + 0.5 * s.voxel_m;
                let bend = c.top - on_line(far);
                let steep_to = |x: f32| c.top - on_line(near) >= tan_max * (x - near).max(0.0);
                // Where the cut cells seen past it rise on, its top is not seen level
                // (a low step's top past its face): the climb is measured to its top
                // voxel's centroid. A front no steeper than the limit from `near` on
                // keeps all its points, so their mean, under that line.
                let rises_on = || {
                    cut.clone()
                        .filter(|&(k, _)| k > ix)
                        .all(|(_, d)| d.top >= c.top + FRONT_RISING_M)
                };
                let steep = steep_to(far) || (steep_to(c.top_xy[0].min(far)) && rises_on());
                bend >= BEND_RISE_M && steep && c.top >= front_top + FRONT_RISING_M
            })
            .then_some(last_x)
    })
}

/// The line of smooth ground a strip's cells lie on, `cells` from the nearest to a
/// front back: the first [`SMOOTH_GROUND_CELLS`] on one line within
/// [`SMOOTH_GROUND_RMS_M`], or, where they bend (a ramp's toe among them), the first
/// [`BENT_GROUND_CELLS`] on one line and the as many after them on another, each
/// within it: the nearer line, the ground the front rises from. A stone 0.15 m up a
/// smooth ramp has the toe's bend among the four cells before its front (a 15.3 cm
/// mound 0.15 m past a 13.5° ramp's toe, cut by a low 320×240 camera's top edge 6 cm
/// up its front, was a go: `sweep -- natural 100 3110 random 10` #65, clean and
/// noisy). A toe's bend steepens toward the front: the nearer line climbs at least as
/// steeply as the farther. Rough ground's cells lie on no such pair of lines; they can
/// lie on a pair that flattens toward the front, a crest of its relief: on a rough
/// 20.9° ramp, two neighbouring strips' last three cells lay within 1 mm of a 16° line
/// and the three before on a 24° one, and the nearer line, carried on, ran 2.3 cm under
/// the cut cell's top, a bend up where the view ends: `unknown` (`sweep -- families
/// 100 12601 random` #38, clean).
fn smooth_line(cells: impl Iterator<Item = (f32, f32)> + Clone) -> Option<Plane> {
    let fits = |skip: usize, n: usize| {
        let run = cells.clone().skip(skip).take(n);
        if run.clone().count() < n {
            return None;
        }
        line_fit(run)
            .and_then(|(line, rms)| (rms <= f64::from(SMOOTH_GROUND_RMS_M)).then_some(line))
    };
    fits(0, SMOOTH_GROUND_CELLS).or_else(|| {
        let near = fits(0, BENT_GROUND_CELLS)?;
        fits(BENT_GROUND_CELLS, BENT_GROUND_CELLS)
            .filter(|far| near.a >= far.a)
            .map(|_| near)
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
/// How many ground cells either side of a bend [`smooth_line`] fits a line to: 15 cm
/// at the default voxel, the nearer run the ground a front rises from.
const BENT_GROUND_CELLS: usize = 3;
/// Most ground cells of a front that [`bends_up`] looks for between the smooth
/// ground's line and the cut: 10 cm, a rock's or a mound's front.
const FRONT_CELLS: usize = 2;
/// How far back from a strip's last ground cell before the cut [`steep_exit`] fits
/// the line the strip climbs there, metres: three cells.
const FRONT_LINE_M: f32 = 0.15;
/// Least height of a cut cell's top over the tops of the front's cells before the cut
/// for [`bends_up`], metres: the front still rises where the view ends.
pub(crate) const FRONT_RISING_M: f32 = 0.01;
/// Least height of a cut cell's top above the smooth ground's line for [`bends_up`],
/// metres. The ground carried on into the cell has its top at or under the line at
/// the cell's far edge; 2 cm leaves room for depth noise, and a rock's front cut
/// after its first centimetres stands 2-5 cm above it.
const BEND_RISE_M: f32 = 0.02;
/// Fewest inner strips of a band whose view ends bending up steeply on smooth ground
/// ([`bends_up`]) for [`steep_exit`] to take it for an unseen front: 10 cm, so one
/// strip of noise does not count. On smooth ground (cells within
/// [`SMOOTH_GROUND_RMS_M`] of a line) a steep bend of [`BEND_RISE_M`] in two strips is
/// beyond depth noise, and how far it rises says nothing of how high the front goes:
/// a 19.9 cm mound 0.16 m in radius, 0.4 m up a smooth 14.4° ramp, showed only its
/// outer flank before the view ended, 2-3 cm over the ramp's line in four strips, two
/// of them bent steeply by 2.1 cm, and was a go at three (`sweep -- natural 100 11702
/// random 10` #92, clean and noisy); a 15.3 cm mound 0.15 m up a 13.5° ramp rose 5.2-5.8
/// cm in two strips (`natural 100 3110 random 10` #65). A 7.7 cm rock at the view's
/// end on rough ground whose cells lay on a line, bent 3.4-3.7 cm in two strips, is
/// `unknown` too (`families 100 3101 random` #28, clean): its top is not seen.
const BENT_STRIPS: usize = 2;

/// Least rise from a climb's foot to the top of the cut cells the view ends in for
/// [`steep_exit`], metres: more than rough ground's peak to peak (±2.5 cm).
pub(crate) const STEEP_EXIT_RISE_M: f32 = 0.05;
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
pub(super) const BLIND_FIT_M: f32 = 0.3;

/// How much of a track strip's nearest seen ground [`blind_rise`] takes for a
/// ramp's foot, metres: three or four cells.
const BLIND_FOOT_M: f32 = 0.15;

/// How far beside and beyond a climb leaving the view [`hidden_tops`] looks for the
/// ground it stands on, metres: a boulder's radius.
const HIDDEN_TOP_REACH_M: f32 = 0.25;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_ground_may_bend_once_at_a_ramp_s_toe_but_not_at_rough_ground_s_bumps() {
        // A strip's cells from a front back, on a smooth 13.5° ramp whose toe lies
        // between the third and the fourth (`sweep -- natural 100 3110 random 10` #65,
        // clean, strip 4 of the right track; metres, to the 0.1 mm).
        let toe = [
            (1.4764, 0.0331),
            (1.4249, 0.0203),
            (1.3751, 0.0084),
            (1.3266, 0.0003),
            (1.2747, 0.0000),
            (1.2244, 0.0000),
        ];
        let (_, rms) = line_fit(toe.iter().copied().take(SMOOTH_GROUND_CELLS)).unwrap();
        assert!(rms > f64::from(SMOOTH_GROUND_RMS_M), "{rms}");
        let line = smooth_line(toe.iter().copied()).expect("the ramp's line");
        let tan = 13.5_f64.to_radians().tan();
        assert!((line.a - tan).abs() < 0.01, "{} for {tan}", line.a);
        // Without the flat run beyond the bend, no smooth ground is shown.
        assert!(smooth_line(toe.iter().copied().take(5)).is_none());
        // On one line, four cells suffice.
        let ramp = (0..4).map(|k| (1.5 - 0.05 * k as f32, 0.04 - 0.012 * k as f32));
        assert!(smooth_line(ramp).is_some());
        // Rough ground's cell means: off a line by 2-4 mm either side of any bend.
        let rough = [
            (1.50, 0.012),
            (1.45, 0.016),
            (1.40, 0.011),
            (1.35, 0.004),
            (1.30, 0.007),
            (1.25, 0.002),
            (1.20, -0.004),
        ];
        assert!(smooth_line(rough.iter().copied()).is_none());
    }
}
