//! Steps and slopes along one wheel track's strip: where the wheel rests on each cell,
//! and whether what it climbs is a step, a slope too steep, or ground it crosses.

use super::{
    line_fit, plane_fit, stone_height, Region, StripCell, ROUGH_LINE_RMS_M, UNSEEN_FOOT_MARGIN_M,
};
use crate::analysis::plane::{Plane, PlaneFit};
use crate::verdict::{Hazard, HazardKind, Verdict};

/// Where a wheel of radius `r` rests on each cell of a strip: the lowest point of a
/// wheel centred over the cell, held up by whatever stands within `r` of it along
/// the strip (`z_j − (r − √(r² − dx²))`, the rim's height over a neighbour at dx).
/// A dip narrower than the wheel is bridged and a pebble is climbed from the ground
/// the wheel stands on, not from the bottom of the dip beside it; a step still rises
/// by its full height within a wheel radius. Neighbours across a hole or past the
/// horizon do not count (their heights are unknown or only bounds).
pub(super) fn wheel_heights(strip: &mut [StripCell], r: f32) {
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
pub(super) fn on_rim(z: f32, dx: f32, r: f32) -> Option<f32> {
    (dx < r).then(|| z - (r - (r * r - dx * dx).sqrt()))
}

/// Steps and slopes along one strip's seen cells (see
/// [`steps_and_slopes`](super::steps_and_slopes)); with `rises_only`, only rises from
/// cells before a sharp top (the test of sharp tops: each cell's `z` is then its
/// highest point where that is a sharp top, and `peak` the height the first pass
/// read), steps and slopes alike. A rise or fall between two cells for which
/// `face_along` holds (the track's edge strip reading a face along the band edge
/// under the track's surface, [`super::face_under_track`]) is none. Returns whether
/// it found any.
pub(super) fn strip_hazards(
    strip: &[StripCell],
    region: Region,
    (r, tan_max, wheelbase, min_gap): (f32, f32, f32, usize),
    (vs, rises_only): (f32, bool),
    face_along: &dyn Fn(&StripCell, &StripCell) -> bool,
    verdict: &mut Verdict,
) -> bool {
    let mut found = false;
    // No pair differs by more than `r` from a cell within `r` of the strip's highest
    // and lowest wheels: such a cell is skipped without looking at its pairs.
    let (low, high) = wheel_span(strip);
    let all_finite = strip.iter().all(|c| c.wheel.is_finite());
    // Rises only: from a cell before the last sharp top (one whose `z` and `peak`
    // differ). The first pass found nothing, so only a rise whose wheels a sharp top
    // lifted can be one now.
    let before = if rises_only {
        strip.iter().rposition(|c| c.z != c.peak).unwrap_or(0)
    } else {
        strip.len()
    };
    for (i, a) in strip.iter().enumerate().take(before) {
        let (xi, zi) = (a.x, a.wheel);
        if all_finite && high - zi <= r && zi - low <= r {
            continue;
        }
        // How much of a rise from this cell is rough ground's: the same for every
        // cell ahead, so measured once, when a rise first needs it.
        let mut rough_rise = None;
        for (j, b) in strip.iter().enumerate().skip(i + 1) {
            let (xj, zj) = (b.x, b.wheel);
            let (dx, dz) = (xj - xi, zj - zi);
            if dz.abs() <= r || (rises_only && dz < 0.0) {
                continue;
            }
            let rough = if dz > 0.0 {
                *rough_rise
                    .get_or_insert_with(|| rough_at_foot(strip, i, true, (wheelbase, min_gap)))
            } else {
                rough_at_foot(strip, j, false, (wheelbase, min_gap))
            };
            if dz.abs() - rough <= r {
                continue; // a wheel radius or less over the ground the wheel comes from
            }
            if holey(&strip[i..=j], min_gap) {
                break; // unseen ground in between: the gap test judges it
            }
            if (dz > 0.0 && a.past) || (dz < 0.0 && b.past) {
                break; // a bound that proves nothing: the view ends here
            }
            if dx > 0.0 && dz.abs() >= tan_max * dx {
                let kind = if dx <= STEP_REACH_VOXELS * vs {
                    // A window on one line under the limit: a rough ramp's bumps. Every
                    // window on one line over it: a ramp too steep, not a step (which
                    // leaves no window on one line).
                    // A rise onto a stone under a wheel radius on a climbable line is
                    // climbed ([`stone_windows`]); a fall from one onto such a line
                    // is descended ([`fall_onto_line`]).
                    let window = wheelbase.min(STEP_WINDOW_MAX_M);
                    let stone =
                        (dz > 0.0).then(|| stone_windows(strip, i, j, (window, r, min_gap)));
                    let onto = (dz < 0.0)
                        .then(|| fall_onto_line(strip, i, j, (wheelbase, r, tan_max)))
                        .flatten();
                    let line = line_windows(strip, i, j, window)
                        .chain(stone.into_iter().flatten())
                        .chain(onto)
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
                if face_along(a, b) {
                    break;
                }
                if dz > 0.0
                    && dz - rough <= r + UNSEEN_FOOT_MARGIN_M
                    && unseen_foot(strip, i, min_gap)
                {
                    continue; // within the margin of a rise whose ground is not seen
                }
                verdict.add_hazard(Hazard {
                    kind,
                    side: region.side(),
                    distance_m: at.max(0.0),
                });
                found = true;
            }
            break;
        }
    }
    found
}

/// How much of a rise's (or fall's) height over its foot (`strip[foot]`: a rise's lowest
/// cell, `rise`, or a fall's) is rough ground's, not the obstacle's, metres. The ground
/// on the foot's side of it (the cells seen whole up to a `wheelbase` before a rise's
/// foot, or after a fall's, the foot included, contiguous, or across holes shorter
/// than `min_gap` cells, which the step test measures across too, whichever shows the
/// level: the ground the wheels stand on as they come to it, wider than rough ground's
/// dips) is level ground when it spans at most
/// rough ground's peak to peak (twice [`FOOT_DIP_MAX_M`]) over at least
/// [`FOOT_LEVEL_MIN_CELLS`] cells and lies on one line within rough ground's spread
/// ([`ROUGH_LINE_RMS_M`]). Then the wheels come to the rise from that line, not from the
/// bottom of a dip at its foot: how far the foot's wheel height lies under the line (at
/// most [`FOOT_DIP_MAX_M`]) does not count, nor does the line's own RMS spread up to
/// [`UNSEEN_FOOT_MARGIN_M`] (the margin for rough ground's bumps that a rise whose foot
/// is not seen gets: what stands within it of a wheel radius over the ground is within
/// the bumps of a 9 cm pebble). An 8.7 cm stone whose foot lies in a 2 cm dip of lumpy
/// ground stood 12.2 cm over the dip, a `slope` (`sweep -- natural 200 6824 random 6`
/// #151); a 15 cm stone, or a step of a wheel radius and more over the ground's level,
/// still stands over it. Other ground there (a ramp, a trench's floor and the ground
/// beside it, a stone at the foot) is no level line and counts nothing: the rise is
/// measured from its foot. A foot among the strip's first cells has too few before it
/// for a line (what is before them lies below the image's bottom edge): the step test
/// gives such a rise the margin of [`unseen_foot`] instead. A 7.2 cm boulder whose
/// front the view starts on, its first cell in a 1.9 cm dip of lumpy ground, stood
/// 11.1 cm over that cell, a `step` (`sweep -- natural 100 4110 random 6` #65, clean
/// and noisy); a 13 cm step there still stops. Cut at a one-cell shadow of a bump, the
/// ground before an 8.7 cm boulder whose foot lay in a 2 cm dip just past it was too
/// short to be a line, and the boulder, 9.9 cm over the ground, stood 12 cm over the
/// dip: a `step` (`sweep -- natural 100 3002 random` #83, clean and noisy). Across a
/// hole may lie another stone, no level line, where the cells short of the hole are
/// one: an 8.7 cm rock 9.1 cm over the ground became a `slope` (`families 100 6601
/// random` #61, clean).
fn rough_at_foot(
    strip: &[StripCell],
    foot: usize,
    rise: bool,
    (wheelbase, min_gap): (f32, usize),
) -> f32 {
    // Contiguous cells, and across short holes: the level either shows.
    let x = strip[foot].x;
    let ground = |step: usize| {
        if rise {
            &strip[reach_back(strip, foot, step, (x, wheelbase))..=foot]
        } else {
            &strip[foot..=reach_on(strip, foot, step, (x, wheelbase))]
        }
    };
    let (near, across) = (ground(1), ground(min_gap.max(1)));
    let level = level_below(near, &strip[foot]);
    if across.len() == near.len() {
        level
    } else {
        level.max(level_below(across, &strip[foot]))
    }
}

/// Whether the rise from `strip[foot]` comes from ground not seen: the foot is among
/// the strip's first cells, fewer than [`FOOT_LEVEL_MIN_CELLS`] from its start,
/// contiguous or across holes shorter than `min_gap` cells (what is before them lies
/// below the image's bottom edge), so that [`rough_at_foot`] has no line before it.
/// Such a rise counts [`UNSEEN_FOOT_MARGIN_M`] over a wheel radius, as other rises
/// whose foot is not seen do: the foot's cell may be one of rough ground's dips. The
/// margin only spares a pair of cells the step test would call a hazard, and the test
/// goes on to the cells past it (a step rises by more a cell later, as the wheel
/// meets it); a pair it does not call a hazard still ends the search there. Had the
/// margin raised the height that starts the search instead, the first pair judged
/// would move on: a 9 cm cone whose rise from the strip's first cell, a rough ramp's
/// bumps to the step test, passed the wheel radius and the margin over a longer run
/// was judged a `slope` there (`sweep -- natural 200 6822 random 7` #52).
fn unseen_foot(strip: &[StripCell], foot: usize, min_gap: usize) -> bool {
    foot + 1 < FOOT_LEVEL_MIN_CELLS
        && reach_back(strip, foot, min_gap.max(1), (strip[foot].x, f32::INFINITY)) == 0
}

/// How far `foot`'s wheel lies under the level line of `ground` (at most
/// [`FOOT_DIP_MAX_M`]) plus that line's RMS spread (at most [`UNSEEN_FOOT_MARGIN_M`]),
/// metres; 0 when `ground` is no level line (see [`rough_at_foot`]).
fn level_below(ground: &[StripCell], foot: &StripCell) -> f32 {
    let x = foot.x;
    let (low, high) = wheel_span(ground);
    if ground.len() < FOOT_LEVEL_MIN_CELLS || high - low > 2.0 * FOOT_DIP_MAX_M {
        return 0.0;
    }
    match line_fit(ground.iter().map(|c| (c.x, c.wheel))) {
        Some((line, rms)) if rms <= f64::from(ROUGH_LINE_RMS_M) => {
            let dip = line.z(f64::from(x), 0.0) as f32 - foot.wheel;
            dip.clamp(0.0, FOOT_DIP_MAX_M) + (rms as f32).min(UNSEEN_FOOT_MARGIN_M)
        }
        _ => 0.0,
    }
}

/// The lowest and highest wheel heights of `cells`, metres (infinite when empty).
fn wheel_span(cells: &[StripCell]) -> (f32, f32) {
    cells
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), c| {
            (lo.min(c.wheel), hi.max(c.wheel))
        })
}

/// Fewest cells of ground for [`rough_at_foot`]'s line.
const FOOT_LEVEL_MIN_CELLS: usize = 4;

/// Deepest dip [`rough_at_foot`] takes, metres: rough ground's amplitude (±2.5 cm).
const FOOT_DIP_MAX_M: f32 = 0.025;

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
        .chain(view_end_slope(strip, i, j, (wheelbase, r, min_gap)))
        .fold(fitted_slope(&strip[i..=j]), f32::min)
}

/// The slope |dz/dx| of a rough ramp that rises out of the view less than 0.9 of a
/// wheelbase past the run `strip[i..=j]`, so that [`line_windows`] has no window
/// ahead: over the wheelbase of cells seen whole that ends where the view does (the
/// next cell past the horizon, or none), contiguous but for holes as
/// [`stone_windows`] steps over (a stone's shadow), reaching back at least two cells
/// before the run's start, the best two lines joined at a hinge at or before the run's
/// start (the ground before the ramp's toe, the ramp after it), when they explain the
/// cells within rough ground's spread ([`ROUGH_LINE_RMS_M`]), a stone on the ramp
/// left out ([`hinge_under_stones`]), and the ramp's line is
/// at least [`VIEW_END_RAMP_M`] long; the ramp line's slope plus twice its standard
/// error (so a rough ramp just over the limit is not let through by its bumps: over
/// 0.45 m of ramp on ±2.5 cm ground the standard error is about 1.3°). A ramp's own
/// slope, not a dip-to-bump run's: on ±2.5 cm ground 0.2 m of a 24° ramp can climb
/// 32°. A short bank and the flat above it are not one line after the hinge, and
/// keep their steepness; so does a ramp seen for less than [`VIEW_END_RAMP_M`]. (A
/// wheelbase back from the view's end alone may start a cell before the run, leaving
/// no line before a hinge there: a 23.3° rough ramp whose bumps climbed 30.4° over
/// 0.2 m, 0.5 m before the view ended, was a `slope`: `sweep -- rounded 100 10515
/// random` #27, clean and noisy.)
fn view_end_slope(
    strip: &[StripCell],
    i: usize,
    j: usize,
    (wheelbase, r, min_gap): (f32, f32, usize),
) -> Option<f32> {
    if strip[i].past {
        return None;
    }
    // Over holes as [`stone_windows`] steps over them: a stone's shadow.
    let step = min_gap.max(STONE_SHADOW_CELLS + 1);
    let seen_end = if strip[j].past { j - 1 } else { j };
    let end = reach_on(strip, seen_end, step, (strip[seen_end].x, f32::INFINITY));
    let view_ends = end + 1 == strip.len() || strip[end + 1].past;
    if !view_ends || end < i || strip[end].x - strip[i].x >= 0.9 * wheelbase {
        return None;
    }
    // A wheelbase back from where the view ends, and at least two cells before the
    // run's start where they are seen, so that a hinge at the run's start has a line
    // before it.
    let mut start = reach_back(strip, i, step, (strip[end].x, wheelbase));
    while start + 2 > i && start > 0 && joined(strip, start - 1, step) {
        start -= 1;
    }
    let window = &strip[start..=end];
    // Two cells at least on the line before the hinge, so that it is a line.
    (start + 2..=i)
        .filter(|&h| strip[end].x - strip[h].x >= VIEW_END_RAMP_M)
        .filter_map(|h| hinge_under_stones(window, strip[h].x, r))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, slope)| slope)
}

/// The two lines joined at `hinge` (x, metres) that explain a window's wheel heights
/// within rough ground's spread ([`ROUGH_LINE_RMS_M`]) once a stone on the ramp is
/// left out, as [`line_under_stones`] leaves it out of one line: the cell standing
/// highest above the lines is left out and the lines refitted until they hold,
/// leaving out at most a third of the window, never its last cell, only a cell with
/// a cell kept past the hinge before it (a stone stands on the ramp), and no cell
/// stands a wheel radius `r` above them (nor has its highest point that and
/// [`UNSEEN_FOOT_MARGIN_M`] above). Returns their RMS and the ramp line's slope plus
/// twice its standard error (see [`view_end_slope`]); `None` otherwise, or for a
/// window over 64 cells. A 5.5 cm boulder 0.2 m up a 17.3° ramp that rose out of the
/// view 0.44 m past its toe stood 4.6 cm off the lines and left none: a `slope` at
/// the toe (`sweep -- natural 100 11202 random 10` #12, clean and noisy). Flat cells
/// by a hinge before a ramp's toe stand over lines bent too early, and are no stone:
/// left out, the lines of a 38° ramp seen for 0.25 m climbed 27° (`sweep -- edges
/// 100 10605 random` #95).
fn hinge_under_stones(window: &[StripCell], hinge: f32, r: f32) -> Option<(f64, f32)> {
    let after = |c: &StripCell| (c.x - hinge).max(0.0);
    // A stone stands on the ramp: a cell kept lies past the hinge before it.
    let on_ramp = |k: usize, out: u64| (0..k).any(|m| out & (1 << m) == 0 && window[m].x > hinge);
    let (p, rms, out) = fit_under_stones(window, |c| (c.x, after(c)), on_ramp)?;
    let on = |c: &StripCell| p.z(f64::from(c.x), f64::from(after(c))) as f32;
    if window
        .iter()
        .any(|c| stone_height(c.wheel, c.high, on(c)) >= r)
    {
        return None;
    }
    // The ramp line's slope, raised by twice its standard error: the line must be
    // climbable with confidence, not by the luck of the bumps.
    let ramp = || {
        kept(window, out)
            .map(|c| f64::from(c.x))
            .filter(|&x| x >= f64::from(hinge))
    };
    let (k, sum) = ramp().fold((0.0, 0.0), |(k, s), x| (k + 1.0, s + x));
    let spread: f64 = ramp().map(|x| (x - sum / k).powi(2)).sum();
    let m = (window.len() - out.count_ones() as usize) as f64;
    let sigma = rms * (m / (m - 3.0).max(1.0)).sqrt();
    let slope = (p.a + p.b).abs() + 2.0 * sigma / spread.sqrt();
    Some((rms, slope as f32))
}

/// The cells of `cells` whose bit in `out` is clear.
fn kept(cells: &[StripCell], out: u64) -> impl Iterator<Item = &StripCell> + Clone {
    cells
        .iter()
        .enumerate()
        .filter(move |(k, _)| out & (1 << k) == 0)
        .map(|(_, c)| c)
}

/// The plane `z = a·x + b·y + c` through the wheel heights of `cells` at `at(cell)` =
/// (x, y), once stones are left out: while the fit's RMS is over rough ground's
/// spread ([`ROUGH_LINE_RMS_M`]), the cell standing highest above it is left out and
/// the plane refitted. A cell may be left out only if it stands above the fit, is
/// not the last, leaves at most a third of `cells` out, and `may_leave_out(k, out)`
/// allows it (`k` its index, `out` the mask of those already left out). Returns the
/// plane, its RMS (metres) and the mask of the cells left out; `None` otherwise, or
/// for over 64 cells. The caller judges the stones left out ([`line_under_stones`],
/// [`hinge_under_stones`]).
fn fit_under_stones(
    cells: &[StripCell],
    at: impl Fn(&StripCell) -> (f32, f32),
    may_leave_out: impl Fn(usize, u64) -> bool,
) -> Option<(Plane, f64, u64)> {
    let n = cells.len();
    if n > 64 {
        return None;
    }
    let mut out = 0u64;
    loop {
        let points = kept(cells, out).map(|c| {
            let (x, y) = at(c);
            (x, y, c.wheel)
        });
        let (p, rms, _) = plane_fit(points)?;
        if rms <= f64::from(ROUGH_LINE_RMS_M) {
            return Some((p, rms, out));
        }
        let off = |c: &StripCell| {
            let (x, y) = at(c);
            c.wheel - p.z(f64::from(x), f64::from(y)) as f32
        };
        let (k, above) = cells
            .iter()
            .enumerate()
            .filter(|(k, _)| out & (1 << k) == 0)
            .map(|(k, c)| (k, off(c)))
            .max_by(|a, b| a.1.total_cmp(&b.1))?;
        let dropped = out.count_ones() as usize + 1;
        if above <= 0.0 || k == n - 1 || 3 * dropped > n || !may_leave_out(k, out) {
            return None;
        }
        out |= 1 << k;
    }
}

/// Whether strip cells `k` and `k + 1` are at most `step` rows apart (1: neighbouring
/// rows), both seen whole (not past the horizon): a window of [`line_windows`],
/// [`stone_windows`] or [`view_end_slope`] runs on.
fn joined(strip: &[StripCell], k: usize, step: usize) -> bool {
    strip[k + 1].ix <= strip[k].ix + step && !strip[k].past && !strip[k + 1].past
}

/// The first cell of the run joined to `strip[k]` ([`joined`], rows at most `step`
/// apart) back from it whose cells lie at most `len` metres before `x`.
fn reach_back(strip: &[StripCell], k: usize, step: usize, (x, len): (f32, f32)) -> usize {
    let mut a = k;
    while a > 0 && joined(strip, a - 1, step) && x - strip[a - 1].x <= len {
        a -= 1;
    }
    a
}

/// The last cell of the run joined to `strip[k]` ([`joined`], rows at most `step`
/// apart) on from it whose cells lie at most `len` metres past `x`.
fn reach_on(strip: &[StripCell], k: usize, step: usize, (x, len): (f32, f32)) -> usize {
    let mut b = k;
    while b + 1 < strip.len() && joined(strip, b, step) && strip[b + 1].x - x <= len {
        b += 1;
    }
    b
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
/// but stepping over holes shorter than `min_gap` cells, and over a stone's shadow of
/// up to [`STONE_SHADOW_CELLS`]) that lie on one line but for a stone on it
/// ([`line_under_stones`]): a 6 cm rock 0.25 m up a 17° ramp leaves no window on one
/// line (it stands off the line, and its shadow breaks the window), and the run from
/// the toe to its top climbed 31°: a `slope` (`sweep -- families 150 6921 random 10`
/// #82, clean and noisy). The stone, under a wheel radius, is a step the wheel climbs.
/// A 5.5 cm boulder 0.47 m up a 17.9° ramp, seen from 0.61 m up, hid the two cells
/// past it, and the window stopped at that hole: a `slope` (`sweep -- natural 100
/// 4102 random 10` #80, clean and noisy). The ground on both sides of the shadow is
/// the one line the window asks for; what the hole hides is the gap test's to judge.
fn stone_windows(
    strip: &[StripCell],
    i: usize,
    j: usize,
    (wheelbase, r, min_gap): (f32, f32, usize),
) -> impl Iterator<Item = f32> + '_ {
    let step = min_gap.max(STONE_SHADOW_CELLS + 1);
    windows(strip, i, j, wheelbase, step).filter_map(move |w| line_under_stones(w, r))
}

/// The slope |dz/dx| of the ground a fall `strip[i..=j]` lands on, when the fall is
/// under a wheel radius `r` measured from that ground: the cells from `j` on, seen
/// whole and contiguous over up to half a `wheelbase` (at least
/// [`FOOT_LEVEL_MIN_CELLS`]), lie on one line within rough ground's spread
/// ([`ROUGH_LINE_RMS_M`]) less steep than the limit (`tan_max`), and no cell from `i`
/// to `j` stands a wheel radius over that line carried back, nor has its highest
/// point ([`StripCell::high`]) a wheel radius and [`UNSEEN_FOOT_MARGIN_M`] over it
/// (as [`line_under_stones`] asks of a stone). `None` otherwise. A pebble on a
/// descent: the wheel comes down its back onto the descent, a fall of under a wheel
/// radius; measured between cells, the descent's own fall over the few cells past
/// the pebble adds to it (a 6 cm boulder 0.6 m down an 18° descent fell 11.5 cm
/// over 0.15 m, a `step`). A step down past a stone, or a stone on an edge, lands
/// on ground a step lower, and the cells before it stand over that ground's line
/// by the step. Rises have [`stone_windows`] instead: a window on one line with the
/// stone left out.
fn fall_onto_line(
    strip: &[StripCell],
    i: usize,
    j: usize,
    (wheelbase, r, tan_max): (f32, f32, f32),
) -> Option<f32> {
    let end = reach_on(strip, j, 1, (strip[j].x, 0.5 * wheelbase));
    let ground = &strip[j..=end];
    if ground.len() < FOOT_LEVEL_MIN_CELLS || ground.iter().any(|c| c.past) {
        return None;
    }
    let (line, rms) = line_fit(ground.iter().map(|c| (c.x, c.wheel)))?;
    let slope = line.a.abs() as f32;
    let under_r = under_a_wheel(&strip[i..j], &line, r);
    (rms <= f64::from(ROUGH_LINE_RMS_M) && slope < tan_max && under_r).then_some(slope)
}

/// Whether every cell of `cells` stands under a wheel radius `r` over `line`
/// ([`stone_height`], from its wheel height and highest point).
fn under_a_wheel(cells: &[StripCell], line: &Plane, r: f32) -> bool {
    cells.iter().all(|c| {
        let on_line = line.z(f64::from(c.x), 0.0) as f32;
        stone_height(c.wheel, c.high, on_line) < r
    })
}

/// Longest hole a [`stone_windows`] window steps over, cells: the shadow a stone under
/// a wheel radius casts on a ramp that rises toward the camera's line of sight (two
/// cells at 2 m for 5.5 cm from 0.61 m up; the ramp shortens what flat ground would
/// show). Longer holes end the window.
const STONE_SHADOW_CELLS: usize = 3;

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
    let end = reach_on(strip, j, step, (strip[i].x, wheelbase));
    // A run may end on a cell past the horizon (its height only a bound): the window
    // behind it ends on the last cell seen whole. When that is the run's start, the
    // window holds none of the run's rise (flat ground before a post whose front the
    // view ends on read as a gentle line, and the post as a rough ramp's bump: a go):
    // there is no window behind.
    let last = if strip[j].past && j > i { j - 1 } else { j };
    let start = reach_back(strip, i, step, (strip[last].x, wheelbase));
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
/// test), nor has its highest point ([`StripCell::high`]) a wheel radius and
/// [`UNSEEN_FOOT_MARGIN_M`] above it (the margin for rough ground's bumps and depth
/// noise, which lift a 9 cm pebble's highest point 11-12 cm over the line): a 16 cm
/// mound up a ramp whose cells' means stood 8 cm over its line is no stone a wheel
/// climbs. Cells below the line are never left out: a bank's flat foot and its top
/// are not one line with a stone. `None` otherwise, or for a window over 64 cells.
fn line_under_stones(run: &[StripCell], r: f32) -> Option<f32> {
    let (line, _, _) = fit_under_stones(run, |c| (c.x, 0.0), |k, _| k > 0)?;
    under_a_wheel(run, &line, r).then_some(line.a.abs() as f32)
}

/// The least-squares slope |dz/dx| of a run's wheel heights when they lie on one line
/// within [`ROUGH_LINE_RMS_M`], else `None`.
fn line_slope(run: &[StripCell]) -> Option<f32> {
    let (p, rms) = line_fit(run.iter().map(|c| (c.x, c.wheel)))?;
    (rms <= f64::from(ROUGH_LINE_RMS_M)).then_some(p.a.abs() as f32)
}

/// Longest window for the step test's line (see
/// [`steps_and_slopes`](super::steps_and_slopes)), metres: over a window this long a step
/// just over a wheel radius leaves an RMS of at least 2.6 cm about its best line (with
/// the step anywhere in it), well over [`ROUGH_LINE_RMS_M`]; a longer window would dilute
/// it.
const STEP_WINDOW_MAX_M: f32 = 0.6;

/// How far a height change of more than a wheel radius, at or above the slope limit,
/// may run to be a step, voxels (0.175 m at 5 cm); over longer runs it is a slope.
pub(super) const STEP_REACH_VOXELS: f32 = 3.5;

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

#[cfg(test)]
mod tests {
    use super::*;

    const VS: f32 = 0.05;

    /// A cell of row `ix`, `x` metres out, seen whole at height `z` (its mean, peak,
    /// highest point and wheel alike).
    fn level(ix: usize, x: f32, z: f32) -> StripCell {
        StripCell {
            x,
            z,
            ix,
            past: false,
            peak: z,
            high: z,
            wheel: z,
        }
    }

    /// A strip of seen cells 5 cm apart at heights `z`.
    fn strip(z: &[f32]) -> Vec<StripCell> {
        z.iter()
            .enumerate()
            .map(|(i, &z)| level(20 + i, 1.0 + 0.05 * i as f32, z))
            .collect()
    }

    /// The hazards `strip_hazards` reports on a strip at heights `z(x)`, x from 1.0 m
    /// in 5 cm cells (wheel radius 0.11 m, limit 30°, wheelbase 0.6 m).
    fn hazards_on(z: impl Fn(f32) -> f32) -> Vec<Hazard> {
        hazards_with_hole(z, 0..0)
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
            .map(|(i, z)| level(20 + i, 1.0 + 0.05 * i as f32, z))
            .collect();
        wheel_heights(&mut run, 0.11);
        let mut v = Verdict::default();
        let limits = (0.11, 30f32.to_radians().tan(), 0.6, 2);
        strip_hazards(
            &run,
            Region::Right,
            limits,
            (VS, false),
            &|_, _| false,
            &mut v,
        );
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

    /// Cell heights along a track strip over lumpy ground, 5 cm apart: a 2 cm dip, then
    /// an 8.7 cm stone at 0.5 m (`sweep -- natural 200 6824 random 6` #151, clean,
    /// Kinect v2 1.17 m high, strip 20 from 0.73 m).
    const STONE_PAST_A_DIP: [f32; 30] = [
        -0.013, -0.022, -0.010, 0.003, -0.004, -0.020, -0.013, 0.021, 0.075, 0.103, 0.105, 0.092,
        0.075, 0.037, -0.010, -0.012, -0.015, -0.013, -0.005, -0.003, -0.007, -0.008, 0.006, 0.018,
        0.009, -0.007, -0.003, 0.008, 0.013, 0.017,
    ];

    #[test]
    fn a_stone_is_measured_from_the_ground_before_it_not_from_a_dip_at_its_foot() {
        // The stone's top stands 12.5 cm over the dip at its foot, but within a wheel
        // radius of the ground before it and a margin for its bumps.
        let z = STONE_PAST_A_DIP;
        assert!(z[10] - z[5] > 0.11);
        assert!(hazards_on(|x| z[(x / 0.05).round() as usize]).is_empty());
        // A 15 cm stone there is an obstacle, and so is a 15 cm step up or down on that
        // ground past the stone.
        let taller = |x: f32| {
            let i = (x / 0.05).round() as usize;
            z[i] + if (7..=13).contains(&i) { 0.065 } else { 0.0 }
        };
        assert_eq!(
            nearest(&hazards_on(taller)).map(|h| h.kind),
            Some(HazardKind::Step),
            "{:?}",
            hazards_on(taller)
        );
        let up = |x: f32| z[(x / 0.05).round() as usize] + if x > 0.93 { 0.15 } else { 0.0 };
        let down = |x: f32| z[(x / 0.05).round() as usize] - if x > 0.93 { 0.15 } else { 0.0 };
        assert!(!hazards_on(up).is_empty());
        assert!(!hazards_on(down).is_empty());
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

    /// Cell x and wheel heights along a left-track strip up a 23.3° ramp with a toe
    /// rounded over 0.36 m at 1.04 m, on ±2.5 cm ground, 0.94-1.83 m, the next cell
    /// past the horizon (`sweep -- rounded 100 10515 random` #27, clean, Kinect v1
    /// 0.9 m high pitched 38°).
    const RAMP_TO_VIEW_END: [(f32, f32); 20] = [
        (0.935, 0.0066),
        (0.977, 0.0016),
        (1.025, 0.0017),
        (1.075, 0.0151),
        (1.125, 0.0348),
        (1.174, 0.0550),
        (1.2246, 0.0745),
        (1.275, 0.0945),
        (1.325, 0.1182),
        (1.375, 0.1465),
        (1.425, 0.1775),
        (1.475, 0.2079),
        (1.525, 0.2339),
        (1.575, 0.2540),
        (1.625, 0.2690),
        (1.674, 0.2812),
        (1.724, 0.2946),
        (1.775, 0.3133),
        (1.8253, 0.3255),
        (1.865, 0.3507),
    ];

    /// The slope hazards on [`RAMP_TO_VIEW_END`] with `extra` added to the heights
    /// from 1.2 m on, times the distance past it.
    fn slopes_to_view_end(extra: f32) -> Vec<Hazard> {
        let n = RAMP_TO_VIEW_END.len();
        let run: Vec<StripCell> = RAMP_TO_VIEW_END
            .iter()
            .enumerate()
            .map(|(i, &(x, z))| {
                let z = z + extra * (x - 1.2).max(0.0);
                StripCell {
                    past: i + 1 == n,
                    ..level(18 + i, x, z)
                }
            })
            .collect();
        let mut h = hazards_of(&run);
        h.retain(|h| h.kind == HazardKind::Slope);
        h
    }

    #[test]
    fn a_rough_ramp_rising_out_of_view_half_a_wheelbase_past_a_steep_run_is_its_line() {
        // 1.325-1.525 m climbs 30.4° on the bumps, 0.5 m before the view ends: no
        // window of a wheelbase lies on the ramp ahead, and the wheelbase back from the
        // view's end began one cell before the run, leaving no line before a hinge there.
        // The ramp from two cells before the run to the view's end is a 22.3° line.
        assert!(slopes_to_view_end(0.0).is_empty());
        // The same cells on a ramp 34° steep (its 30° run steeper still) stop.
        let extra = 34f32.to_radians().tan() - 23.3f32.to_radians().tan();
        assert!(!slopes_to_view_end(extra).is_empty());
    }

    /// A strip's cells (x, z), metres, where the view ends 0.44 m up a 17.3° ramp
    /// whose toe lies at 1.265 m, a 5.5 cm boulder (radius 8.3 cm) standing 0.2 m up
    /// it and hiding the cell at 1.58 m (`sweep -- natural 100 11202 random 10` #12,
    /// clean, the left track's strip at y = 0.475 m).
    const BOULDER_TO_VIEW_END: [(f32, f32); 14] = [
        (1.025, 0.0),
        (1.075, 0.0),
        (1.124, 0.0),
        (1.174, 0.0),
        (1.224, 0.0),
        (1.277, 0.004),
        (1.325, 0.019),
        (1.383, 0.050),
        (1.421, 0.097),
        (1.475, 0.120),
        (1.513, 0.131),
        (1.630, 0.114),
        (1.675, 0.128),
        (1.712, 0.139),
    ];

    /// The hazards on [`BOULDER_TO_VIEW_END`] with `extra` added to the heights from
    /// 1.277 m on, times the distance past it, and `bump` to the boulder's cells.
    fn boulder_up_a_ramp_to_view_end(extra: f32, bump: f32) -> Vec<Hazard> {
        let mut run: Vec<StripCell> = BOULDER_TO_VIEW_END
            .iter()
            .map(|&(x, z)| {
                let on_boulder = (1.38..1.52).contains(&x);
                let z = z + extra * (x - 1.277).max(0.0) + if on_boulder { bump } else { 0.0 };
                level(20 + ((x - 1.0) / 0.05) as usize, x, z)
            })
            .collect();
        wheel_heights(&mut run, 0.11);
        hazards_of(&run)
    }

    #[test]
    fn a_pebble_up_a_ramp_that_rises_out_of_view_is_climbed_with_it() {
        // No wheelbase window lies ahead, and the run from the toe to the boulder's
        // top climbs 31°. The ramp's line to the view's end, the boulder left out (and
        // its shadow stepped over), is the slope.
        let h = boulder_up_a_ramp_to_view_end(0.0, 0.0);
        assert!(h.is_empty(), "{h:?}");
        // Up a ramp past the limit it stops, and so does a stone a wheel radius high.
        let extra = 32f32.to_radians().tan() - 17.3f32.to_radians().tan();
        assert!(!boulder_up_a_ramp_to_view_end(extra, 0.0).is_empty());
        assert!(!boulder_up_a_ramp_to_view_end(0.0, 0.07).is_empty());
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

    /// A track strip 2.9 cm beside a 15.6 cm cone's apex (38° flanks) on lumpy ground,
    /// as the sharp-top pass reads it: cell means (x, z) from 1.32 m, the apex cell's
    /// highest point 14.9 cm (its mean 12.6 cm), then the cone's shadow (`sweep --
    /// natural 200 7508 random 7` #45, clean, 848×480 camera 1.13 m high), every
    /// height scaled by `k`, with the sharp top at its highest point when `sharp`.
    fn beside_a_cone(k: f32, sharp: bool) -> Vec<StripCell> {
        let cells: [(f32, f32); 15] = [
            (1.324, 0.015),
            (1.373, 0.011),
            (1.425, -0.001),
            (1.477, -0.006),
            (1.526, 0.002),
            (1.574, 0.012),
            (1.625, 0.027),
            (1.674, 0.051),
            (1.726, 0.077),
            (1.774, 0.114),
            (1.814, 0.126),
            (2.039, 0.004),
            (2.075, -0.004),
            (2.128, -0.012),
            (2.176, -0.006),
        ];
        let mut run: Vec<StripCell> = cells
            .iter()
            .map(|&(x, z)| level((x / VS) as usize, x, k * z))
            .collect();
        if sharp {
            (run[10].z, run[10].peak) = (k * 0.149, k * 0.126);
        }
        wheel_heights(&mut run, 0.11);
        run
    }

    #[test]
    fn a_sharp_top_over_a_wheel_radius_up_a_flank_steeper_than_the_limit_stops() {
        let limits = (0.11, 30f32.to_radians().tan(), 0.6, 2);
        let found = |run: &[StripCell], rises_only: bool| {
            let mut v = Verdict::default();
            strip_hazards(
                run,
                Region::Left,
                limits,
                (VS, rises_only),
                &|_, _| false,
                &mut v,
            );
            v.hazards.to_vec()
        };
        // Read from its means, no rise of more than a wheel radius up the cone's flank
        // is steeper than 25°.
        assert!(found(&beside_a_cone(1.0, false), false).is_empty());
        // At its apex's highest point, the wheel over the top stands 12.7 cm over the
        // wheel at the flank's foot, 0.2 m before it: more than a wheel radius at 32°,
        // too long a rise for a step (0.175 m) but a slope the rover cannot climb. The
        // sharp-top pass measured steps alone, and this 15.6 cm cone was a go.
        let h = found(&beside_a_cone(1.0, true), true);
        assert_eq!(h.len(), 1, "{h:?}");
        assert_eq!(h[0].kind, HazardKind::Slope);
        assert!((h[0].distance_m - 1.574).abs() < 0.06, "{h:?}");
        // A 10.9 cm stone of that shape (its highest point 10.4 cm over the ground
        // before it) is climbed, read either way.
        assert!(found(&beside_a_cone(0.7, true), true).is_empty());
        assert!(found(&beside_a_cone(0.7, false), false).is_empty());
    }

    /// The hazards `strip_hazards` reports on a strip at heights `z(x)` from 1.0 m in
    /// 5 cm cells as [`hazards_on`], with the cells `unseen` left out (a shadow).
    fn hazards_with_hole(z: impl Fn(f32) -> f32, unseen: std::ops::Range<usize>) -> Vec<Hazard> {
        let mut run = strip(&(0..30).map(|i| z(0.05 * i as f32)).collect::<Vec<_>>());
        run.retain(|c| !unseen.contains(&(c.ix - 20)));
        wheel_heights(&mut run, 0.11);
        hazards_of(&run)
    }

    /// The hazards `strip_hazards` reports on the left track's strip `run`, its wheel
    /// heights as set (wheel radius 0.11 m, limit 30°, wheelbase 0.6 m, gaps from 2
    /// cells).
    fn hazards_of(run: &[StripCell]) -> Vec<Hazard> {
        let mut v = Verdict::default();
        strip_hazards(
            run,
            Region::Left,
            (0.11, 30f32.to_radians().tan(), 0.6, 2),
            (VS, false),
            &|_, _| false,
            &mut v,
        );
        v.hazards.to_vec()
    }

    /// A 17.9° ramp from 0.2 m with a mound `h` high (radius 9 cm) 0.55 m up it, at
    /// 0.75 m: heights at `x` metres along the strip.
    fn stone_on_a_ramp(h: f32) -> impl Fn(f32) -> f32 {
        move |x: f32| {
            let ramp = 17.9f32.to_radians().tan() * (x - 0.2).max(0.0);
            let d = (x - 0.75).abs() / 0.09;
            let mound = if d < 1.0 {
                h * (d * std::f32::consts::FRAC_PI_2).cos().powi(2)
            } else {
                0.0
            };
            ramp + mound
        }
    }

    #[test]
    fn a_stone_under_a_wheel_radius_on_a_climbable_ramp_is_climbed_shadow_or_not() {
        // The ramp's rise under the stone adds to it: within three cells the wheel
        // climbs more than its radius, steeper than the limit, as over a step. But
        // the ground before and past the stone is one 17.9° line, and the stone on it
        // is under a wheel radius (`sweep -- natural 100 4102 random 10` #17).
        let seen = stone_on_a_ramp(0.07);
        let (at, top) = (|x: f32| (x * 20.0).round() / 20.0, 0.75);
        assert!(seen(at(top)) - seen(at(top - 0.15)) > 0.11);
        assert!(hazards_on(&seen).is_empty(), "{:?}", hazards_on(&seen));
        // Two cells past it in its shadow (#80): the line goes on past the hole.
        let shadowed = hazards_with_hole(&seen, 16..18);
        assert!(shadowed.is_empty(), "{shadowed:?}");
        // A stone taller than a wheel radius on the ramp stops, shadow or not; so does
        // a step of a wheel radius and more up it, and a ramp over the limit.
        for h in [
            hazards_on(stone_on_a_ramp(0.14)),
            hazards_with_hole(stone_on_a_ramp(0.14), 16..18),
            hazards_with_hole(stone_on_a_ramp(0.14), 16..19),
            hazards_on(|x| stone_on_a_ramp(0.0)(x) + if x > 0.75 { 0.13 } else { 0.0 }),
            hazards_on(|x| {
                32f32.to_radians().tan() * (x - 0.2).max(0.0) + stone_on_a_ramp(0.07)(x)
                    - stone_on_a_ramp(0.0)(x)
            }),
        ] {
            assert!(!h.is_empty());
        }
    }

    /// A descent of `g` degrees from 0.2 m with a flat-topped stone `h` high (its top
    /// 10 cm across, its flanks 4 cm wide) 0.55 m down it, centred at 0.75 m: heights
    /// at `x` metres along the strip.
    fn stone_on_a_descent(h: f32, g: f32) -> impl Fn(f32) -> f32 {
        move |x: f32| {
            let descent = -g.to_radians().tan() * (x - 0.2).max(0.0);
            let d = (x - 0.75).abs();
            descent + h * ((0.09 - d) / 0.04).clamp(0.0, 1.0)
        }
    }

    #[test]
    fn a_fall_from_a_stone_under_a_wheel_radius_onto_a_climbable_descent_is_descended() {
        // The descent's fall past the stone adds to the stone's back: within three
        // cells the wheel comes down more than its radius, steeper than the limit, as
        // off a step. But the ground it lands on is a 20° line, and the stone stands
        // under a wheel radius over it.
        let seen = stone_on_a_descent(0.08, 20.0);
        assert!(seen(0.8) - seen(0.95) > 0.11);
        assert!(hazards_on(&seen).is_empty(), "{:?}", hazards_on(&seen));
        // Lower ground past it (a 12 cm step down 0.25 m past the stone), a ledge 12 cm
        // over the descent's line (the strip seen from its top on, level there, then
        // falling off the stone's back), and a descent over the limit stop.
        let step_down = |x: f32| seen(x) - if x > 1.02 { 0.12 } else { 0.0 };
        let tall_from_top = |x: f32| stone_on_a_descent(0.12, 20.0)(x.max(0.7));
        let steep = stone_on_a_descent(0.08, 32.0);
        for (name, h) in [
            ("step down", hazards_on(step_down)),
            ("tall", hazards_on(tall_from_top)),
            ("steep", hazards_on(steep)),
        ] {
            assert!(!h.is_empty(), "{name}");
        }
    }

    #[test]
    fn a_rise_from_the_strips_first_cells_is_given_the_margin_for_an_unseen_foot() {
        // Lumpy ground seen from 0.74 m, the first cell in a 1.9 cm dip right before a
        // 7.2 cm boulder: its top stands 11.1 cm over the dip (`sweep -- natural 100
        // 4110 random 6` #65, 848×480 camera 0.77 m high, left strip from ix 14).
        const FIRST_IN_A_DIP: [f32; 29] = [
            -0.019, 0.025, 0.084, 0.092, 0.074, 0.052, -0.021, -0.017, -0.013, -0.008, 0.005,
            0.016, 0.014, 0.002, -0.006, -0.005, -0.002, 0.0, -0.004, -0.010, -0.011, 0.001, 0.018,
            0.023, 0.015, 0.005, 0.002, -0.009, -0.018,
        ];
        let z = |x: f32| FIRST_IN_A_DIP[((x / 0.05).round() as usize).min(28)];
        assert!(z(0.15) - z(0.0) > 0.11);
        // What the wheels come from is not seen: the rise is within rough ground's
        // margin of a wheel radius, as a 9 cm pebble on a bump is.
        assert!(hazards_on(z).is_empty(), "{:?}", hazards_on(z));
        // A stone 4 cm taller, and a 13 cm step at the strip's first cells, stop.
        let taller = |x: f32| {
            z(x) + if (0.05..=0.25).contains(&x) {
                0.04
            } else {
                0.0
            }
        };
        assert!(!hazards_on(taller).is_empty());
        let step = |x: f32| if x > 0.07 { 0.13 } else { 0.0 };
        assert_eq!(
            nearest(&hazards_on(step)).map(|h| h.kind),
            Some(HazardKind::Step)
        );
        // Past the first cells the rise is measured from its foot as before.
        let later = |x: f32| z((x - 0.3).max(0.0)) - if x < 0.3 { 0.019 } else { 0.0 };
        assert!(!hazards_on(later).is_empty());
    }

    /// The right track's strip over a 5.9 cm mound 0.49 m up a 15.6° ramp, as the
    /// sharp-top pass reads it: cell centres and means (x, z), the mound's cell at its
    /// highest point 19.7 cm (its mean 16.6 cm), one cell past it unseen (`sweep --
    /// natural 100 4102 random 10` #17, Kinect v2 0.51 m high), the mound's top `lift`
    /// metres higher.
    fn mound_up_a_ramp(lift: f32) -> Vec<StripCell> {
        let cells: [(usize, f32, f32); 26] = [
            (17, 0.874, 0.0),
            (18, 0.924, 0.0),
            (19, 0.974, 0.0),
            (20, 1.025, 0.0),
            (21, 1.075, 0.006),
            (22, 1.125, 0.020),
            (23, 1.174, 0.034),
            (24, 1.224, 0.048),
            (25, 1.275, 0.062),
            (26, 1.324, 0.076),
            (27, 1.374, 0.090),
            (28, 1.425, 0.104),
            (29, 1.478, 0.125),
            (30, 1.519, 0.166),
            (32, 1.638, 0.165),
            (33, 1.676, 0.175),
            (34, 1.725, 0.189),
            (35, 1.775, 0.202),
            (36, 1.825, 0.216),
            (37, 1.874, 0.230),
            (38, 1.924, 0.244),
            (39, 1.974, 0.258),
            (40, 2.024, 0.272),
            (41, 2.075, 0.286),
            (42, 2.124, 0.300),
            (43, 2.174, 0.314),
        ];
        let mut run: Vec<StripCell> = cells.iter().map(|&(ix, x, z)| level(ix, x, z)).collect();
        (run[13].z, run[13].high) = (0.197 + lift, 0.197 + lift);
        wheel_heights(&mut run, 0.11);
        run
    }

    #[test]
    fn a_mound_up_a_ramp_read_at_its_sharp_top_is_climbed() {
        let found = |run: &[StripCell]| {
            let mut v = Verdict::default();
            let limits = (0.11, 30f32.to_radians().tan(), 0.6, 2);
            strip_hazards(
                run,
                Region::Right,
                limits,
                (VS, true),
                &|_, _| false,
                &mut v,
            );
            v.hazards.to_vec()
        };
        // From 0.15 m before it, the wheel climbs 11.1 cm to the top at 36°: a step,
        // were it not a stone under a wheel radius on the ramp's line.
        let run = mound_up_a_ramp(0.0);
        assert!(run[13].wheel - run[9].wheel > 0.11);
        assert!(found(&run).is_empty(), "{:?}", found(&run));
        // 4 cm higher (9.9 cm over the ramp, 12.4 cm past the cell's mean), and it is
        // still climbed; 7 cm higher, a wheel radius over the ramp, it stops.
        assert!(found(&mound_up_a_ramp(0.04)).is_empty());
        assert!(!found(&mound_up_a_ramp(0.07)).is_empty());
    }
}
