//! Ground the camera should have seen and did not: gaps, drop-offs, and the shadows,
//! grazing views and pixel rows that explain a missing cell.

use nalgebra::Vector3;

use super::hidden::BLIND_FIT_M;
use super::{line_fit, plane_fit, stone_height, Frame, Region, ROUGH_LINE_RMS_M, ROUGH_SPREAD_M};
use crate::analysis::plane::{Plane, PlaneFit};
use crate::analysis::visibility;
use crate::grid::Cell;
use crate::verdict::{Hazard, HazardKind, Verdict};

/// Gaps: runs of cells the camera should see on flat ground, does not, and that are
/// not in the shadow of something seen in front of them.
///
/// - A gap with no ground seen before it in its strip is unknown ground.
/// - A gap where the surface before it, continued at its slope, would be seen at
///   grazing incidence (under [`GRAZING_DEG`]) is explained: a passable downslope
///   seen from afar gives few points per cell, not none because of a hole.
/// - A gap after seen ground with nothing seen beyond it, or with ground beyond it
///   more than a wheel radius below the ground before it (its last cell, that
///   cell's slope continued, and the line through the last cells), is a drop-off;
///   measured against a descending line the ground beyond lies on, the last cells
///   decide both ways: a stone under a wheel radius on that line casts a shadow,
///   one standing a wheel radius over it has a fall behind ([`judge_gap`]).
/// - A gap with ground beyond it at a climbable level is the shadow of a low step
///   down when that ground explains it (the line of sight to the gap at the far
///   ground's height passes below the near edge); otherwise it is unknown ground.
/// - Neither is a gap whose every cell fell between the camera's pixel rows
///   ([`between_rows`]): ground there, continued from before the gap, would be
///   crossed by under two rows per cell, and the strips on both sides see it.
/// - A gap ending at a cell the far range limit cuts ([`Frame::range_cut`], with
///   points, not seen ground: they are the nearer, upper part of what is there) is
///   judged as one ending at seen ground, that cell's height the ground beyond: the
///   lower ground past a 0.42 m step down, seen only where it left a 3 m range,
///   proves the drop (`sweep -- edges 100 3305` #12 with `MAX_RANGE=3`), and a
///   ditch's far rim there leaves its floor unknown ground.
/// - A gap ending at a cell past the horizon ([`Frame::past`]) is judged by that
///   cell's lowest surface where it lies under the ground read: the image's top edge
///   shows only the lower part of a face rising out of it, and the ground at the
///   face's foot lies lower still (a 0.49 m pit's far wall, seen 5-15 cm down, read
///   at its mean as a low step's lower ground, made the pit a go: `sweep -- edges
///   100 4505 random` #16).
///
/// A track cell's height is the surface its strip followed (`surface`, from
/// [`steps_and_slopes`](super::steps_and_slopes); NaN elsewhere), other cells' their mean.
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
        // The first row of a shadow met since the last seen cell.
        let mut shade: Option<usize> = None;
        let mut run: Option<(usize, usize)> = None; // (first ix, length)
        for ix in 0..=s.nx {
            let c = (ix < s.nx).then(|| s.cell(ix, iy));
            let seen_here = c.is_some_and(|c| f.seen[c] && !spilt(c));
            // A cell the far range limit cuts, with points: not seen ground (it holds
            // the nearer, upper part of what is there), but it ends a gap as seen
            // ground does. Read a wheel radius below the ground before the gap, what
            // is there is lower still: a drop.
            let range_end = c.is_some_and(|c| {
                f.range_cut.get(c) == Some(&true)
                    && f.cells[c].n >= f.cfg.analysis.min_points_per_cell
            });
            if seen_here || range_end || ix == s.nx {
                let shade_from = shade.take();
                let mut judged = false;
                if let Some((start, len)) = run.take() {
                    // Right after a shadow, cells holding a few points on the ground
                    // the run ends at: the shadow's edge, judged as the shadow (asked
                    // only of a run long enough to be judged).
                    let after_shadow = shade_from.is_some() && seen_here;
                    if len >= min_run
                        && !(after_shadow
                            && c.is_some_and(|c| shadow_edge(f, iy, start..ix, ground(c).1)))
                    {
                        judged = true;
                        let end = (c.filter(|_| seen_here || range_end), seen_here);
                        let limits = (r, tan_max);
                        if let Some(kind) =
                            judge_run(f, iy, (start, ix), end, before, ground, limits)
                        {
                            verdict.add_hazard(Hazard {
                                kind,
                                side,
                                distance_m: s.origin[0] + start as f32 * s.voxel_m,
                            });
                        }
                    }
                }
                if let (Some(from), Some(c), false) = (shade_from, c, judged) {
                    // A shadow behind a tall stone's top on a descent: its fall.
                    let limits = (r, tan_max);
                    if track
                        && seen_here
                        && fall_behind(f, iy, ix, &before, ground(c), ground, limits)
                    {
                        verdict.add_hazard(Hazard {
                            kind: HazardKind::DropOff,
                            side,
                            distance_m: s.origin[0] + from as f32 * s.voxel_m,
                        });
                    }
                }
                if let Some(c) = c.filter(|_| seen_here) {
                    let (x, z) = ground(c);
                    // A stone's apex cell reads its mean low: its highest point too.
                    before.push(x, z, f.cells[c].peak.max(z));
                }
                continue;
            }
            let c = s.cell(ix, iy);
            if !f.expected[c] {
                continue; // outside the view: neither seen nor a gap
            }
            if f.shadowed[c] || f.beyond[c] {
                // A shadow or past the horizon: hidden by what is in front.
                if f.shadowed[c] {
                    shade.get_or_insert(ix);
                }
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

/// What unseen run `start..end` of strip `iy` is ([`gaps`]): `end_cell`, the cell
/// that ends it (seen whole when `seen_here`, else one the far range limit cuts; `None`
/// at the corridor's end), against `before`, the ground seen before it, each cell's
/// height `ground`'s; `r` the wheel radius (metres) and `tan_max` the slope limit.
/// Below the image's bottom edge, ground the view starts past is no gap. `None`: no
/// hazard.
fn judge_run(
    f: &Frame,
    iy: usize,
    (start, end): (usize, usize),
    (end_cell, seen_here): (Option<usize>, bool),
    before: Recent,
    ground: impl Fn(usize) -> (f32, f32) + Copy,
    (r, tan_max): (f32, f32),
) -> Option<HazardKind> {
    if before.last().is_none() && seen_here && below_view(f, iy, start, end, ground, tan_max) {
        return None;
    }
    let after = end_cell.map(|c| {
        let (x, z) = ground(c);
        // Past the horizon the cell shows only what lies under the image's top edge:
        // of a face rising out of it (a pit's far wall), its lower part. The ground at
        // its foot lies at or under its lowest surface.
        (x, if f.past[c] { z.min(f.cells[c].low) } else { z })
    });
    // The ground past the gap, seen whole, as one line.
    let landing = seen_here
        .then(|| line_past(f, iy, end, ground, LANDING_M, true))
        .flatten();
    let after = after.map(|at| (at, landing));
    judge_gap(f, iy, start, end, before, after, r, tan_max)
}

/// Whether unseen run `run` of strip `iy`, which follows a shadow, is that shadow's
/// edge: each of its unseen cells holds points (too few to be seen), their mean within
/// rough ground's spread ([`ROUGH_SPREAD_M`]) of `za`, the height of the ground seen
/// past the run, metres. The shadow test casts one line of sight, to a cell's centre,
/// so a cell the shadow's edge crosses may be lit at its centre and still get only the
/// points of its lit part; those points show the ground going on at the level it is
/// seen past the run, and the run is judged as the shadow before it is (the belly band
/// clears what stands in front; a track's fall behind it is [`fall_behind`]'s). A
/// 24 cm rock under the belly 2 m out hid the strip on its flank from a 320×240
/// camera 0.63 m high to 2.7 m, and the next three cells got two points each on the
/// ground: a `drop_off` off the rock's flank (`sweep -- families 100 12309 random 11`
/// #36, clean and noisy). An edge's shadow leaves its cells without points, and the
/// lower ground past a drop lies far under what those points show.
fn shadow_edge(f: &Frame, iy: usize, run: std::ops::Range<usize>, za: f32) -> bool {
    run.map(|j| f.spec.cell(j, iy))
        .filter(|&c| f.expected[c] && !f.seen[c])
        .all(|c| f.cells[c].n > 0 && (f.cells[c].z - za).abs() <= ROUGH_SPREAD_M)
}

/// Whether a line of slope `k` through height `z0` at `x0` (metres), continued back to
/// `origin_x`, stands there at most `rise` (metres) off the rover's ground (z = 0) on the
/// near side: below it for a rise, above it for a fall. Its toe then lies ahead of
/// `origin_x`, or so little behind that the ground there is flat by the onset's own
/// measure. [`blind_rise`](super::blind_rise) and [`below_view`] take a ramp whose toe is
/// below the image by it.
pub(super) fn from_rover_ground((k, z0, x0): (f32, f32, f32), origin_x: f32, rise: f32) -> bool {
    (z0 + k * (origin_x - x0)) * k.signum() <= rise
}

/// Whether the unseen run `start..end` at the near end of strip `iy` (no ground seen
/// before it) is ground lowered out of the image: the ground seen from `end` on lies on
/// one line over [`BLIND_FIT_M`] (within rough ground's spread, [`ROUGH_LINE_RMS_M`]),
/// descending at a passable slope, which continued back to the grid's near edge stands
/// there at most `rise_threshold_m` below the rover's ground (z = 0: its toe ahead, or
/// just behind, as in [`blind_rise`](super::blind_rise)), and at that height (never above
/// z = 0) no cell of the run falls whole inside the image. The camera sees flat ground
/// there; a descent whose toe lies below the image drops that ground under the image's
/// bottom edge, so its first rows see the descent farther out.
/// [`blind_rise`](super::blind_rise) judges whether such a change below the image is a
/// ramp. Ground that stays lower than a ramp from the rover's ground would (a drop hidden
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
    let Some((line, rms, _, x0)) = line_past(f, iy, end, ground, BLIND_FIT_M, false) else {
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
            !visibility::in_view(s, f.projector, f.cfg, j, iy, z)
        })
}

/// The least-squares line z = a·x + c (as a plane, b = 0) through strip `iy`'s seen
/// cells from row `end` on, up to `reach_m` metres past its centre (`whole`: seen
/// whole, not past the horizon, up to the first that is not), at their heights
/// `ground` gives (x, z), the RMS of their heights about it, metres, how many they
/// are, and where it starts (row `end`'s centre, x, metres); `None` with no two
/// distinct x.
fn line_past(
    f: &Frame,
    iy: usize,
    end: usize,
    ground: impl Fn(usize) -> (f32, f32),
    reach_m: f32,
    whole: bool,
) -> Option<LinePast> {
    let s = f.spec;
    let x0 = s.x_centre(end);
    let cells = (end..s.nx).take_while(|&ix| {
        let c = s.cell(ix, iy);
        f.seen[c] && !(whole && f.past[c]) && s.x_centre(ix) <= x0 + reach_m
    });
    let (line, rms, n) = plane_fit(cells.map(|ix| {
        let (x, z) = ground(s.cell(ix, iy));
        (x, 0.0, z)
    }))?;
    Some((line, rms, n, x0))
}

/// The ground past a gap or a shadow (`landing`, [`line_past`], starting at its
/// `x0`) as a climbable line (over [`LANDING_MIN_CELLS`] or more, within rough
/// ground's spread, under the slope limit `tan_max`), and how far the cells seen in
/// the last [`STONE_BEFORE_M`] before it stand over it, carried back, metres: the
/// most of their [`stone_height`]s over it, less the line's own spread (rough
/// ground's, in the stone's favour).
///
/// Where the ground before the gap descends on one line within rough ground's spread
/// ([`Recent::line`]: no stone among its cells) more steeply than the landing, the
/// landing is carried back from `x0` at that descent instead: the ground the gap hides
/// falls at least as the ground on both sides of it. A few cells of rough ground past
/// a gap may lie level on a bump's top; carried back over the gap at their own slope,
/// they stood a wheel radius under the descent before it (a 13.9° rough descent, four
/// cells 2.6-2.7 m out read 1.8°, the gap 0.3 m long): a `drop_off`
/// (`sweep -- rounded 100 11415 random` #71, clean and noisy).
fn stands_over(before: &Recent, landing: LinePast, tan_max: f32) -> Option<(Plane, f32)> {
    let (line, rms, n, x0) = landing;
    if n < LANDING_MIN_CELLS || rms > f64::from(ROUGH_LINE_RMS_M) || line.a.abs() as f32 >= tan_max
    {
        return None;
    }
    let z0 = line.z(f64::from(x0), 0.0) as f32;
    let descent = before
        .line()
        .filter(|&(k, spread, _)| spread <= ROUGH_LINE_RMS_M && f64::from(k) < line.a)
        .map(|(k, _, _)| k);
    let carried = |x: f32| match descent {
        Some(k) => z0 + k * (x - x0),
        None => line.z(f64::from(x), 0.0) as f32,
    };
    let over = before
        .within(STONE_BEFORE_M)
        .map(|(x, z, top)| stone_height(z, top, carried(x)))
        .fold(f32::NEG_INFINITY, f32::max);
    Some((line, over - rms as f32))
}

/// Whether the ground past a gap or a shadow, first seen at height `za`, lies more
/// than a wheel radius `r` under the last cell before it (`zb`, metres) on a
/// descending line ([`stands_over`]'s `landing`) that a cell before it stands a wheel
/// radius or more over: a fall off a tall stone's back. For wheel tracks only: the
/// belly band clears a stone by its clearance (a 20 cm rock under it, its shadow
/// behind it, is a go).
fn tall_back(zb: f32, za: f32, landing: Option<(Plane, f32)>, r: f32) -> bool {
    za < zb - r && landing.is_some_and(|(line, over)| line.a < 0.0 && over >= r)
}

/// Whether a shadow in strip `iy` ending at row `end`, whose first seen cell's ground
/// is `(_, za)` (`ground` gives each cell's), lies behind cells (`before`) one of
/// which stands a wheel radius or more over the descending ground past it
/// ([`tall_back`]). The shadow explains the unseen cells, not the fall: a 15.7 cm
/// cone 0.39 m down an 11° descent, its apex cell read 14.5 cm over the descent past
/// it, hid the cells behind it from a Kinect v2 0.6 m high, and went (`sweep --
/// natural 100 4304 random 12` #51). For wheel tracks only, as [`tall_back`]: the
/// caller asks it of track strips. `r` is the wheel radius, `tan_max` the slope limit.
fn fall_behind(
    f: &Frame,
    iy: usize,
    end: usize,
    before: &Recent,
    (_, za): (f32, f32),
    ground: impl Fn(usize) -> (f32, f32),
    (r, tan_max): (f32, f32),
) -> bool {
    let Some((_, zb)) = before.last() else {
        return false;
    };
    let landing = line_past(f, iy, end, ground, LANDING_M, true)
        .and_then(|l| stands_over(before, l, tan_max));
    tall_back(zb, za, landing, r)
}

/// A line through a strip's cells ([`line_past`]): the line (a plane, b = 0), the RMS
/// of the cells' heights about it, metres, how many they are, and the x of the row it
/// starts on, metres.
type LinePast = (Plane, f64, usize, f32);

/// How far past a gap [`judge_gap`] takes the ground it lands on as a line, metres.
const LANDING_M: f32 = 0.3;

/// Fewest cells of that ground for its line.
const LANDING_MIN_CELLS: usize = 4;

/// How far back from the last cell before a gap [`judge_gap`] takes the cells of a
/// stone that stands on the ground past it, metres: a pebble's width.
const STONE_BEFORE_M: f32 = 0.2;

/// The last few seen cells of a strip, oldest first (a fixed ring: no allocation).
#[derive(Debug, Default, Clone, Copy)]
struct Recent {
    cells: [(f32, f32); Recent::N],
    /// Each cell's highest point ([`Cell::peak`]), or its height if higher, metres.
    tops: [f32; Recent::N],
    len: usize,
}

impl Recent {
    const N: usize = 16;
    /// Cells farther back than this from the last one do not count for the slope.
    const SPAN_M: f32 = 0.4;

    fn push(&mut self, x: f32, z: f32, top: f32) {
        if self.len == Self::N {
            self.cells.copy_within(1.., 0);
            self.tops.copy_within(1.., 0);
            self.len -= 1;
        }
        self.cells[self.len] = (x, z);
        self.tops[self.len] = top;
        self.len += 1;
    }

    fn last(&self) -> Option<(f32, f32)> {
        self.len.checked_sub(1).map(|i| self.cells[i])
    }

    /// The recent cells within `m` metres before the last one (x, z, top), oldest
    /// first.
    fn within(&self, m: f32) -> impl Iterator<Item = (f32, f32, f32)> + '_ {
        let xl = self.last().map_or(0.0, |(x, _)| x);
        self.cells[..self.len]
            .iter()
            .zip(&self.tops)
            .map(|(&(x, z), &top)| (x, z, top))
            .filter(move |&(x, _, _)| xl - x <= m)
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
/// it faces away), or in the shadow of the fall's top edge: the line of sight to the
/// cell at the height of the fall's foot passes under something seen
/// ([`visibility::explained`]). In each cell's row the ground is taken as the line between the
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
///
/// A vertical edge seen across the strip from a low camera hides the ground past it
/// for a few centimetres. Where the strip beside the edge on its low side is in that
/// shadow too, the row's fall runs to a strip farther off and reads gentler than it
/// is: a 16 cm edge 4.4 cm inside the belly band, the fall taken over 15 cm, was
/// met at 9°, and the belly's edge strip, in the edge's shadow past 2.1 m, was a
/// `drop_off` (`sweep -- widened 100 11707 random 3` #40, noisy).
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
            // Met grazingly, or hidden by the fall's top edge at its foot's level.
            normal.dot(&to_camera).asin() < GRAZING_DEG.to_radians()
                || visibility::explained(f, ix, iy, za.min(zb))
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
    let z = beside(iy, s.ny, up, ACROSS_STRIPS).find_map(seen_z)?;
    let shift = z - za.max(zb);
    (shift.abs() <= 0.5 * ACROSS_DROP_M
        && beside(iy, s.ny, !up, ACROSS_STRIPS).all(|jy| seen_z(jy).is_none()))
    .then_some(((ya, za + shift), (yb, zb + shift)))
}

/// The strips within `reach` of strip `iy` on one side, nearest first: above it
/// (higher index, of `ny`) when `up`, else below.
fn beside(iy: usize, ny: usize, up: bool, reach: usize) -> impl Iterator<Item = usize> {
    (1..=reach).filter_map(move |d| {
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
    let (jb, below) = beside(iy, s.ny, false, ACROSS_STRIPS).find_map(seen_at)?;
    let (ja, above) = beside(iy, s.ny, true, ACROSS_STRIPS).find_map(seen_at)?;
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
/// Least fall across between those seen cells for [`grazing_across`], metres: more
/// than rough ground's peak to peak (5 cm). The belly's edge strip beside a descent
/// drawn 4.4 cm into the belly band, its last seen cell 2.07 m out where the descent
/// had fallen 9.2 cm, was a `drop_off` at 10 cm (`sweep -- widened 100 11707 random
/// 3` #40, clean).
const ACROSS_DROP_M: f32 = 0.08;
/// Least share of the fall across that the strip's last seen ground stands over its
/// foot for [`grazing_across`].
const ACROSS_OFF_FOOT_SHARE: f32 = 0.1;
/// Most share of the fall across that a cell's points may span for [`across_row`] to
/// take it as level, with no part of the fall in it.
const ACROSS_LEVEL_SHARE: f32 = 0.1;

/// What the unseen run of cells `start..end` in strip `iy` is, given the seen cells
/// before it and the first seen cell after it (x, z) with the line through the
/// ground seen whole from it on ([`line_past`]).
///
/// Ground past the gap a wheel radius below the ground before it is a drop-off, unless
/// that ground lies on a climbable line (over [`LANDING_MIN_CELLS`] or more, within
/// rough ground's spread) which every cell seen in the last [`STONE_BEFORE_M`] before
/// the gap stands less than a wheel radius over, carried back (its [`stone_height`]
/// less the line's own spread): then those
/// cells are a stone on the ground the gap's far side continues, the fall off its
/// back is under a wheel radius, and the gap is its shadow when the line of sight to
/// every unseen cell at that line's height passes under something seen (else unknown
/// ground). A 9 cm boulder 0.3 m down a 12° descent hid 0.15 m behind it from the
/// default camera, and the ground past that, on the descent, stood 14 cm under its
/// top: a `drop_off`. On flat ground such a stone's shadow was always judged so
/// (the ground past it within a wheel radius of its top); a descent adds its fall.
/// Conversely, where a cell before the gap stands a wheel radius or more over a
/// descending line past it, the fall is a drop-off even though the ground past lies
/// on the line of the cells before (the descent continued): a 16 cm cone 0.6 m down
/// a 25° descent, its apex cell's mean 9 cm over the descent and its highest point
/// 14 cm, and the descent past its shadow on the line of the ground before it, was a
/// go.
#[allow(clippy::too_many_arguments)]
fn judge_gap(
    f: &Frame,
    iy: usize,
    start: usize,
    end: usize,
    before: Recent,
    after: Option<((f32, f32), Option<LinePast>)>,
    r: f32,
    tan_max: f32,
) -> Option<HazardKind> {
    let s = f.spec;
    let Some((xb, zb)) = before.last() else {
        return Some(HazardKind::Unknown);
    };
    // A wheel track's strip: the belly band clears what stands under a wheel radius
    // and more (a rock under it is judged by its clearance).
    let track = f.region[iy] != Region::Belly;
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
    let landing = after
        .and_then(|(_, landing)| landing)
        .and_then(|l| stands_over(&before, l, tan_max));
    let after = after.map(|(at, _)| at);
    match after {
        None => {
            // Nothing seen beyond: a drop-off, unless the ground before the gap,
            // continued at its slope, would be hidden all along by something seen
            // (ground falling away beyond an edge beside the strip: a sideways shadow),
            // or fell between the camera's rows. Continued from the line through the
            // recent cells too: a last cell of a few stray points (mixed pixels off the
            // edge above) stands above the ground, and ground continued from it would
            // be in view. Or at the level the strips beside it see in its rows
            // ([`ground_beside`]): behind a crest the ground may fall more steeply.
            let hidden_at = |z: &dyn Fn(f32) -> f32| {
                unseen
                    .clone()
                    .all(|j| visibility::explained(f, j, iy, z(s.x_centre(j))))
            };
            let hidden = hidden_at(&predicted) || on_line.is_some_and(|z| hidden_at(&z));
            let seen_beside = || {
                unseen.clone().all(|j| {
                    let least = predicted(s.x_centre(j)) - r;
                    ground_beside(f, j, iy, least)
                        .is_some_and(|z| visibility::explained(f, j, iy, z))
                })
            };
            (!hidden && !bumps() && !sampled_out() && !across() && !seen_beside())
                .then_some(HazardKind::DropOff)
        }
        // A fall of more than a wheel radius, by the cells' heights, from a cell standing
        // a wheel radius over the descent past the gap: a tall stone's back.
        Some((_, za)) if track && tall_back(zb, za, landing, r) => Some(HazardKind::DropOff),
        Some((xa, za))
            if za < zb - r
                && za < predicted(xa) - r
                && (below_line(xa, za) || landing.is_some_and(|(_, over)| over >= r)) =>
        {
            match landing {
                Some((line, over)) if over < r => {
                    let on_line = |j: usize| line.z(f64::from(s.x_centre(j)), 0.0) as f32;
                    let shadowed = unseen
                        .clone()
                        .all(|j| visibility::explained(f, j, iy, on_line(j)));
                    (!shadowed && !bumps() && !sampled_out() && !across())
                        .then_some(HazardKind::Unknown)
                }
                _ => Some(HazardKind::DropOff),
            }
        }
        Some((_, za)) => {
            let all_shadowed = unseen.clone().all(|j| visibility::explained(f, j, iy, za));
            (!all_shadowed && !bumps() && !sampled_out() && !across())
                .then_some(HazardKind::Unknown)
        }
    }
}

/// The ground of row `ix` across unseen strip `iy`, metres: the line between the
/// nearest cells seen below the horizon within [`BESIDE_STRIPS`] on either side, at
/// the strip's centre; `None` unless both sides see one, each no lower than `least`
/// (a wheel radius under the strip's own ground continued: ground beside a drop is
/// no level to judge the drop's cells by).
///
/// Where the strips beside a gap see the ground go on, what the gap hides lies at
/// that level, and the line of sight to it may pass under a seen bump that the line
/// to the strip's own ground continued clears: on a rough descent the ground behind
/// a crest falls more steeply than the cells before it do. The far end of a 12.7°
/// descent with a 0.34 m rounded toe, rough ground, seen at 10° from a camera 0.62 m
/// high, lay unseen in three strips from 2.78 m to the corridor's end behind a crest
/// at 2.73 m, with ground seen at the descent's level beside it 2-5 strips away:
/// a `drop_off` (`sweep -- rounded 100 4915 random` #93, clean and noisy).
fn ground_beside(f: &Frame, ix: usize, iy: usize, least: f32) -> Option<f32> {
    let s = f.spec;
    let seen_at = |jy: usize| {
        let c = s.cell(ix, jy);
        f.seen_whole(c).then(|| (s.y_centre(jy), f.cells[c].z))
    };
    let side = |up: bool| {
        beside(iy, s.ny, up, BESIDE_STRIPS)
            .find_map(seen_at)
            .filter(|&(_, z)| z >= least)
    };
    let ((ya, za), (yb, zb)) = (side(false)?, side(true)?);
    Some(za + (zb - za) * (s.y_centre(iy) - ya) / (yb - ya))
}

/// How many strips to either side [`ground_beside`] looks for seen ground: a
/// quarter metre at the default voxel.
const BESIDE_STRIPS: usize = 5;

/// Whether unseen cell (`ix`, `iy`), its ground expected at `z` with slope `k`
/// (dz/dx), fell between the camera's pixel rows: ground there would be crossed by fewer than
/// [`SPARSE_ROWS`] rows per cell (far, at low incidence, or a coarse camera: a
/// 320×240 camera's rows lie 5 cm apart on a 12° descent 3 m out), and the strips
/// on both sides (the one inside, for the corridor's outermost strips: the grid
/// holds nothing past them) see ground in that row or the next one either way,
/// within a wheel radius of the ground's slope continued. A drop-off's gap spans the
/// strips beside it too, from its edge on; one that spans the outermost strip alone
/// is a sliver under a wheel track's outer edge, and nearer, where the rows are
/// denser, it is judged again. The corridor's last two cells in its outermost strip,
/// on a 13.9° descent a 320×240 camera 0.65 m high saw at 7-8° there, got no row of
/// a noisy frame (5 points a cell in the clean one): a `drop_off` (`sweep --
/// families 100 12211 random 2` #71).
fn between_rows(f: &Frame, ix: usize, iy: usize, (z, k): (f32, f32), r: f32) -> bool {
    let s = f.spec;
    let x = s.x_centre(ix);
    let beside_seen = [iy.checked_sub(1), Some(iy + 1)].into_iter().all(|side| {
        side.filter(|&n| n < s.ny).is_none_or(|n| {
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
///
/// Where the ground goes on past the run in some other strip ([`ground_goes_on`]), how
/// rough it is, is the larger of the strip's own residuals about its line and the
/// patch's about its plane ([`patch_roughness`]): a strip may run along a ridge or a
/// furrow and show little of the roughness, while the line of sight, which crosses
/// strips, meets the bumps beside it too. The far end of rough descents, met at 7-9°,
/// lay 2-6 cells unseen behind bumps 2-3 cm high in strips whose own line showed 2-4
/// mm of roughness, and the rover stopped for a `drop_off` (`sweep -- families 200
/// 9001 random 5` #2, #39, `natural 200 9002 random 5` #139, #168). Read so without
/// the ground going on, a 0.5 m drop 0.2 m before the corridor's end on #39's and
/// #168's rigs went.
fn bump_shadow(f: &Frame, iy: usize, start: usize, end: usize, before: Recent) -> bool {
    let (Some((k, rms, zl)), Some((xb, zb))) = (before.line(), before.last()) else {
        return false;
    };
    let s = f.spec;
    let rms = if ground_goes_on(f, iy, end - 1, (k, zl, xb)) {
        rms.max(patch_roughness(f, iy, start).min(ROUGH_BUMP_MAX_M / BUMP_RMS))
    } else {
        rms
    };
    let c = f.camera;
    let (x, y) = (s.x_centre(start), s.y_centre(iy));
    let (dx, dy) = (x - c[0], y - c[1]);
    let d = dx.hypot(dy);
    let depression = (c[2] - (zb + k * (x - xb))).atan2(d);
    let incidence = depression + (k * dx / d).atan();
    let gap_m = (end - start) as f32 * s.voxel_m;
    incidence > 0.0 && gap_m * incidence.tan() <= BUMP_RMS * rms
}

/// Whether some other strip of the corridor sees ground in row `last`, the last of an
/// unseen run of strip `iy` (the corridor's last, for a run up to its end), within a
/// wheel radius of the line `(k, z, x)` (slope, height at `x`, metres) through the
/// ground before the run: the ground goes on past the run. An edge across the corridor
/// leaves no strip seeing its own ground from the edge on, nor the lower ground beyond
/// it, within the corridor. With the last two rows, the ground before an edge inside
/// the last one counted, and 0.5 m drops 2.91-2.93 m out on rough descents went that
/// the code before stopped (4 of 160 drawn 2.6-2.95 m out on 80 descents of `sweep --
/// families 200 9001 random 5`).
fn ground_goes_on(f: &Frame, iy: usize, last: usize, (k, z, x): (f32, f32, f32)) -> bool {
    let s = f.spec;
    let r = f.cfg.rover.wheel_radius_m as f32;
    (0..s.ny).filter(|&jy| jy != iy).any(|jy| {
        let c = s.cell(last, jy);
        let cell = &f.cells[c];
        f.seen_whole(c) && (cell.z - (z + k * (cell.x - x))).abs() <= r
    })
}

/// The RMS of the seen cells' heights about their least-squares plane, metres, over
/// the patch of ground before row `start` of strip `iy`: [`PATCH_ROWS`] rows back and
/// [`ACROSS_STRIPS`] strips to either side within the strip's band (track or belly),
/// cells seen whole with one surface (a face's cell mixes two levels: a band's side
/// would pass for roughness); 0 with fewer than [`PATCH_MIN_CELLS`]. Across the band's
/// edge, a trench's floor and the belly band's ground beside it made a patch 20 cm
/// rough, and a 1 m deep hole in the floor, seen past the trench's shadow, was taken
/// for a bump's shadow (`belly_ground_spilled_into_a_tracks_edge_strip_ends_no_gap`).
fn patch_roughness(f: &Frame, iy: usize, start: usize) -> f32 {
    let s = f.spec;
    let rows = start.saturating_sub(PATCH_ROWS)..start;
    let strips = (iy.saturating_sub(ACROSS_STRIPS)..(iy + ACROSS_STRIPS + 1).min(s.ny))
        .filter(|&jy| f.region[jy] == f.region[iy]);
    let cells = rows
        .flat_map(|ix| strips.clone().map(move |jy| s.cell(ix, jy)))
        .filter(|&c| f.seen_whole(c) && f.cells[c].crest == f.cells[c].foot)
        .map(|c| (f.cells[c].x, f.cells[c].y, f.cells[c].z));
    match plane_fit(cells) {
        Some((_, rms, n)) if n >= PATCH_MIN_CELLS => rms as f32,
        _ => 0.0,
    }
}

/// The tallest bump rough ground's patch may stand for in [`bump_shadow`], metres: its
/// crest to trough at ±2.5 cm. A patch holding two levels (a trench's floor beside the
/// belly band's ground) is no rough ground, however large its RMS.
const ROUGH_BUMP_MAX_M: f32 = 0.05;

/// Rows of ground before a gap that [`patch_roughness`] takes (0.4 m at the default
/// voxel).
const PATCH_ROWS: usize = 8;
/// Fewest cells [`patch_roughness`] fits a plane to.
const PATCH_MIN_CELLS: usize = 12;
