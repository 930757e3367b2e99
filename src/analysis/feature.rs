//! Obstacle feature (paper §3.2, with docs/design.md's definitions): which of the ten
//! workcases the wheel tracks face, and the toe line's distance, the face's gradient
//! and the toe line's angle.
//!
//! 1. In each track strip, the *onset* is the first seen cell that rises (or falls)
//!    more than `rise_threshold_m` from the ground, confirmed by the next seen cell.
//! 2. A track is affected when at least half of its seen strips have an onset of the
//!    same direction; which tracks are affected, and how, gives the workcase family.
//! 3. The face is fitted as a plane `z = a·x + b·y + c` to the cells past the onsets
//!    (weighted by their point counts after a first unweighted fit; cells holding a
//!    face along their strip whose ground cannot be told are left out), iteratively:
//!    cells off the plane by three standard deviations (the smaller of the RMS's and
//!    the median residual's estimate: the crest, a plateau, a wall's points along a
//!    band edge) and cells that straddle the toe line are dropped, as are whole strips
//!    whose cells lie off it together (a band's sloping side in a track's edge strip),
//!    then the fit is extended to every consistent cell of the affected strips. A
//!    face under one track also leaves out, from its first window's fit on, its edge
//!    strips that stand a share of its height low (the strip beside a sloping side).
//! 4. The toe line is where the face meets the ground plane z = 0: its distance is
//!    read at the centre line (both tracks) or the affected track's centre; the
//!    gradient is the plane's steepest slope; alpha is `atan(b/a)`, positive when
//!    the toe line's left end is nearer. A face too steep to fit as a plane (a low
//!    step) is measured from the onsets, with a gradient of ±90°.

use super::crossing::{
    cut_cells, first_cut, ground_beside_face, median, unresolved_face_along, FRONT_RISING_M,
    STEEP_EXIT_RISE_M,
};
use super::plane::{Plane, PlaneFit};
use super::{Frame, Region};
use crate::grid::{Cell, GridSpec};
use crate::verdict::Feature;

/// Which way the ground goes at an onset.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dir {
    /// Rising.
    Up,
    /// Falling.
    Down,
}

/// Where a strip's ground starts to rise or fall.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Onset {
    /// Cell row.
    pub ix: usize,
    /// Rising or falling.
    pub dir: Dir,
}

/// A face flatter than this is a plateau behind a step, not a slope, degrees.
const MIN_FACE_DEG: f64 = 2.0;
/// Window of the first fit past the onset, metres.
const FIRST_WINDOW_M: f32 = 0.25;
/// Least residual tolerance of the face fit, metres.
const MIN_TOLERANCE_M: f64 = 0.006;

/// Whether strips of `region` take part when the left and/or right track is used.
fn chosen(region: Region, use_left: bool, use_right: bool) -> bool {
    match region {
        Region::Left => use_left,
        Region::Right => use_right,
        Region::Belly => false,
    }
}

/// How many cells before a strip's onset the face fit may take from the band where
/// the plane runs under the rise threshold: the band of a face steeper than ~12°
/// (the threshold over the gradient), not the flat before a low step.
const TOE_BAND_CELLS: usize = 3;

/// A fitted face: its plane and how much of it the fit saw.
#[derive(Debug, Clone, Copy)]
struct Face {
    /// The face's plane, its toe line and gradient: the fit's, or past a rounded toe
    /// the plane of the cells beyond the rounding ([`past_rounding`]).
    plane: Plane,
    /// The least-squares plane of every cell the fit took, for comparing fits
    /// ([`one_face_or_nearer`]).
    fit: Plane,
    /// How far past the toe line the farthest cell of the fit lies, along the
    /// gradient, metres.
    run_m: f64,
    /// The cells' spread about the plane (one standard deviation, robust), metres.
    spread_m: f64,
    /// How far the cells of the fit spread along the gradient ([`along_spread`]),
    /// metres. The gradient's standard error is the cells' noise over this
    /// ([`noise_sd_deg`]).
    along_m: f64,
    /// Whether the face runs on to where the view ends: past some cell of the fit,
    /// its strip shows no more ground below the sensor's horizon within
    /// [`VIEW_END_CELLS`]. A ramp rising out of the image does; a stone or a capped
    /// ramp seen whole, with ground beyond it, does not.
    to_view_end: bool,
    /// Whether the face runs on to where the view ends only into shadows: some strip's
    /// cells past it, inside the corridor, are unseen but none lies past the sensor's
    /// horizon, and no strip's view ends at the horizon (a strip's cells past the face
    /// may also be none: the corridor ends). What hides them stands on the face (a
    /// stone's front, its far side hidden); a ramp rising out of the image ends at the
    /// horizon instead.
    in_shadow: bool,
}

/// How many cells past a face's last cell in a strip ground seen below the horizon
/// shows that the face ends inside the view.
const VIEW_END_CELLS: usize = 2;

impl Face {
    /// The face of plane `plane` measured over the cells `sel` takes, `fit` their
    /// least-squares plane.
    fn measured(f: &Frame, g: &Ground, sel: &Selection, plane: Plane, fit: Plane) -> Face {
        let s = f.spec;
        let slope = plane.a.hypot(plane.b).max(1e-9);
        let mut run_m = 0.0f64;
        let mut spread = Spread::default();
        // Each cell's distance along the gradient past the toe line: their count,
        // sum and sum of squares.
        let mut along = (0.0f64, 0.0f64, 0.0f64);
        // Cells of the fit whose strip's view ends in a shadow, and at the horizon.
        let (mut to_view_end, mut shadow, mut horizon) = (false, false, false);
        for (c, cell) in sel.taken(f) {
            let on_plane = plane.z(f64::from(cell.x), f64::from(cell.y));
            let u = on_plane / slope;
            run_m = run_m.max(u.abs());
            along = (along.0 + 1.0, along.1 + u, along.2 + u * u);
            spread.add(f64::from(g.z[c]) - on_plane);
            let (ix, iy) = (c / s.ny, c % s.ny);
            let beyond = (ix + VIEW_END_CELLS + 1..s.nx).map(|k| s.cell(k, iy));
            if !beyond.clone().any(|k| f.seen_whole(k)) {
                to_view_end = true;
                if (ix + 1..s.nx).any(|k| f.past[s.cell(k, iy)]) {
                    horizon = true;
                } else {
                    shadow |= beyond.len() > 0;
                }
            }
        }
        Face {
            plane,
            fit,
            run_m,
            spread_m: spread.sigma().unwrap_or(SPREAD_BINS as f64 / 1000.0),
            along_m: along_spread(along),
            to_view_end,
            in_shadow: shadow && !horizon,
        }
    }

    /// This face measured past a rounded toe ([`past_rounding`]; `sel` the cells it
    /// was fitted to, `dir` its way), or as it is where the toe shows no rounding.
    fn past_rounding(self, f: &Frame, g: &Ground, sel: &mut Selection, dir: Dir) -> Face {
        match past_rounding(f, g, sel, &self.fit, dir) {
            Some(plane) => Face::measured(f, g, sel, plane, self.fit),
            None => self,
        }
    }
}

/// Step 3: fit the face of the tracks `a` chooses, its way, as a plane (see the module
/// doc); with `sag`, and one track chosen, without its sagging edge strips
/// ([`without_sagging_edges`]).
fn fit_face(
    f: &Frame,
    g: &Ground,
    onset: &[Option<Onset>],
    sel: &mut Selection,
    a: Affected,
    sag: bool,
) -> Option<Face> {
    let s = f.spec;
    let (dir, use_left, use_right) = (a.dir, a.left, a.right);
    let threshold = f.cfg.analysis.rise_threshold_m as f32;
    // Only the chosen strips with an onset the face's way take part, and only from
    // TOE_BAND_CELLS before it: no other cell is ever eligible.
    let strips = || {
        (0..s.ny).filter_map(move |iy| {
            onset[iy]
                .filter(|o| o.dir == dir && chosen(f.region[iy], use_left, use_right))
                .map(|o| (iy, o))
        })
    };
    let candidate = |ix: usize, iy: usize, o: Onset| -> bool {
        let c = s.cell(ix, iy);
        ix >= o.ix && g.usable[c] && status(g.z[c], threshold) == Some(dir)
    };
    let window_end = |iy: usize, o: Onset| first_window_end(f, iy, o);
    // Once the plane is known, the cells where it runs between the ground and the rise
    // threshold (the band along its toe, up to TOE_BAND_CELLS before the strip's
    // onset) take part whatever their height: keeping only those over the threshold
    // would keep rough ground's bumps there and drop its dips, lifting the face's
    // foot and pulling the toe nearer.
    let toe_band = |p: &Plane, ix: usize, iy: usize| {
        let c = s.cell(ix, iy);
        let cell = &f.cells[c];
        g.usable[c] && p.z(f64::from(cell.x), f64::from(cell.y)).abs() < f64::from(threshold)
    };
    sel.eligible.clear();
    for ix in 0..s.nx {
        for (iy, o) in strips() {
            if ix >= o.ix.saturating_sub(TOE_BAND_CELLS) {
                // Capacity is the cell count: never reallocates.
                sel.eligible.push(s.cell(ix, iy) as u32);
            }
        }
    }
    sel.clear();
    for (iy, o) in strips() {
        let end = window_end(iy, o);
        for ix in o.ix..=end.min(s.nx - 1) {
            if candidate(ix, iy, o) {
                sel.on[s.cell(ix, iy)] = true;
            }
        }
    }
    let mut plane: Option<Plane> = None;
    for iteration in 0..10 {
        let Some((mut p, tol)) = weighted_plane(f, g, sel, iteration) else {
            break;
        };
        if iteration >= 1 {
            sel.reject_strips(f, g, &p);
        }
        // Judged on the first window's weighted fit, before the fit runs on: past a
        // capped descent's face, a sagging strip that tilts the plane brings the floor
        // within the tolerance, and the floor's cells flatten it further.
        if iteration == 1 && sag && use_left != use_right {
            if let Some(q) = without_sagging_edges(f, g, sel) {
                p = q;
            }
        }
        let mut changed = false;
        for (iy, o) in strips() {
            let end = window_end(iy, o);
            for ix in o.ix.saturating_sub(TOE_BAND_CELLS)..s.nx {
                let c = s.cell(ix, iy);
                let eligible = candidate(ix, iy, o) || (iteration >= 2 && toe_band(&p, ix, iy));
                if !eligible {
                    if sel.on[c] {
                        sel.on[c] = false;
                        changed = true;
                    }
                    continue;
                }
                let cell = &f.cells[c];
                let r = g.off(c, cell, &p);
                let ok = !sel.off_strip[iy]
                    && r.abs() <= tol
                    && past_toe(s, &p, dir, ix, iy)
                    && (iteration >= 2 || ix <= end);
                if ok != sel.on[c] {
                    sel.on[c] = ok;
                    changed = true;
                }
            }
        }
        plane = Some(p);
        if !changed && iteration >= 2 {
            break;
        }
    }
    plane.map(|p| Face::measured(f, g, sel, p, p))
}

/// The last row of strip `iy`'s first window past its onset `o`: [`FIRST_WINDOW_M`] past
/// the onset, and on to the next seen cell when none lies within it (ground met at a
/// grazing angle is seen one pixel row every several cells, and a window holding the
/// onset's row alone fits no slope).
fn first_window_end(f: &Frame, iy: usize, o: Onset) -> usize {
    let s = f.spec;
    let reach = s.x_centre(o.ix) + FIRST_WINDOW_M;
    let within = (o.ix..s.nx)
        .take_while(|&ix| s.x_centre(ix) <= reach)
        .last();
    let next_seen = (o.ix + 1..s.nx)
        .find(|&k| f.seen[s.cell(k, iy)])
        .unwrap_or(s.nx);
    within.unwrap_or(o.ix).max(next_seen)
}

/// Whether the whole of cell (ix, iy) lies past the toe line of plane `p`, a face
/// going `dir`: the plane is linear, so its lowest corner over the cell (its highest,
/// for a fall) decides.
fn past_toe(s: &GridSpec, p: &Plane, dir: Dir, ix: usize, iy: usize) -> bool {
    let vs = f64::from(s.voxel_m);
    let up = dir == Dir::Up;
    let x = f64::from(s.origin[0]) + ix as f64 * vs + if (p.a < 0.0) == up { vs } else { 0.0 };
    let y = f64::from(s.origin[1]) + iy as f64 * vs + if (p.b < 0.0) == up { vs } else { 0.0 };
    let z = p.z(x, y);
    if up {
        z > 0.0
    } else {
        z < 0.0
    }
}

/// Least sag of an edge strip, as a share of the face's height, that
/// [`without_sagging_edges`] leaves out: 1 %.
const SAG_MIN_SHARE: f64 = 0.01;
/// How many standard errors the sag must also pass.
const SAG_SES: f64 = 5.0;
/// Least strips the fit keeps besides one [`without_sagging_edges`] judges.
const SAG_MIN_OTHER_STRIPS: usize = 3;

/// The plane of the cells `sel` takes for one track's face, refitted without the
/// strips at the edges of the track's taken strips whose ground stands a share of the
/// face's height nearer the ground than the face (the strip beside its sloping side),
/// which `sel` then leaves out; `None` where no strip sags so. [`fit_face`] asks on
/// its first window's weighted fit, before the fit runs on.
///
/// A face whose side slopes down to the ground beside it (a ramp on one track whose
/// side is no wall but a bank) stands lower, near its side, by a share of its height:
/// a strip there holds ground at `s · h` where the face stands at `h`, `s < 1`. The
/// strip wholly on the bank lies off the face together and [`Selection::reject_strips`]
/// leaves it out; the strip next to it, partly on the bank, stands off by a few per
/// cent, within the residual tolerance, and tilts the plane across the track: 2.6°
/// of alpha for a 23° ramp whose 13.5 cm bank reaches 7 cm into the track (`sweep --
/// bevelled 100 11006 random 0` #87). So each track's outermost taken strips are
/// judged against the plane of the others: their residuals `r` against that plane's
/// height `h` give the share `k = Σ r·h / Σ h²` (the least-squares slope through the
/// toe line, where both are 0), and a strip whose share is below −[`SAG_MIN_SHARE`]
/// by [`SAG_SES`] standard errors (the other cells' spread over `√Σ h²`) is left out,
/// and the next strip in judged in its turn. On rough ground the spread hides a sag of
/// a few per cent, and the fit stands as it is. Past the outermost strips of
/// [`STRIP_MIN_CELLS`] cells, the outermost with fewer are judged first: beside a
/// one-track capped descent's wall on the corridor's edge, seen from a 320×240 camera,
/// the outer strip's two cells in the first window held 16-23 points each (the wall's
/// and the floor's) to the face's 4-9 and stood 1 cm over it; they tilted the plane
/// across the track, the tolerance let the floor in, and the fit ran on to 10.1° for a
/// 12.9° descent, its toe 4.6 cm early (`sweep -- families 100 12401 random` #25).
///
/// Judged on the converged fit instead, a capped descent's sagging strip had already
/// tilted the plane until the floor past the face came within the tolerance, and the
/// floor's cells flattened it further: toe 6 cm early, 14.4° read 10.6° (`sweep --
/// bevelled 100 12 default 3` #28). Only the face of one track is judged, once told
/// from the other's ([`one_face_or_nearer`]): judged in the fits that tell them apart,
/// the strips that showed two faces went, and left them one (`sweep -- bevelled 100
/// 10312 random 9` #68, a 19.6° ramp under the right track from 1.41 m and a 17.9° one
/// under the left from 1.76 m: workcase 7).
fn without_sagging_edges(f: &Frame, g: &Ground, sel: &mut Selection) -> Option<Plane> {
    let s = f.spec;
    let mut p = None;
    let weight = |cell: &Cell| f64::from(cell.n);
    // Strips already left out take no part.
    for iy in 0..s.ny {
        if sel.off_strip[iy] {
            sel.leave_out(s, iy);
        }
    }
    let count = |sel: &Selection, iy: usize| (0..s.nx).filter(|&ix| sel.on[s.cell(ix, iy)]).count();
    for region in [Region::Left, Region::Right] {
        let strips = || (0..s.ny).filter(move |&iy| f.region[iy] == region);
        loop {
            // The outermost strips of STRIP_MIN_CELLS or more cells taken, and past
            // them the outermost with any: a strip's few cells beside a face seen
            // along it each hold many of its points, and weigh in the fit.
            let (mut first, mut last, mut judged) = (usize::MAX, 0, 0);
            let (mut first_any, mut last_any) = (usize::MAX, 0);
            for iy in strips() {
                let n = count(sel, iy);
                if n > 0 {
                    (first_any, last_any) = (first_any.min(iy), iy);
                }
                if n >= STRIP_MIN_CELLS {
                    (first, last, judged) = (first.min(iy), iy, judged + 1);
                }
            }
            if judged < SAG_MIN_OTHER_STRIPS + 1 {
                break;
            }
            // The strip judged, and which way its track's edge lies from it; each
            // strip once (the outermost with any cell is most often one of the others).
            let edges = [
                (first_any, false),
                (first, false),
                (last_any, true),
                (last, true),
            ];
            let once = |&(k, (iy, _)): &(usize, (usize, bool))| k % 2 == 0 || iy != edges[k - 1].0;
            let sagging = edges
                .into_iter()
                .enumerate()
                .filter(once)
                .map(|(_, e)| e)
                .find(|&(iy, _)| {
                    let others = || sel.taken(f).filter(|&(c, _)| s.strip_of(c) != iy);
                    let Some(fit) = fit_cells(g, others, weight) else {
                        return false;
                    };
                    let (mut rh, mut hh) = (0.0, 0.0);
                    for (c, cell) in sel.taken(f).filter(|&(c, _)| s.strip_of(c) == iy) {
                        let h = fit.plane.z(f64::from(cell.x), f64::from(cell.y));
                        rh += g.off(c, cell, &fit.plane) * h;
                        hh += h * h;
                    }
                    let share = rh / hh.max(1e-12);
                    let se = fit.sigma / hh.max(1e-12).sqrt();
                    share < -SAG_MIN_SHARE && -share > SAG_SES * se
                });
            let Some((iy, outward_up)) = sagging else {
                break;
            };
            // The strip and any thinner ones past it, toward the edge, lie on the side.
            for k in strips().filter(|&k| if outward_up { k >= iy } else { k <= iy }) {
                sel.leave_out(s, k);
            }
            match fit_cells(g, || sel.taken(f), weight) {
                Some(fit) => p = Some(fit.plane),
                None => break,
            }
        }
    }
    p
}

/// How far past the toe line, along the gradient, a rounded toe may bend the ground
/// off the face's plane, metres: half the longest rounding [`past_rounding`] undoes
/// (0.4 m across the toe line).
const ROUNDING_REACH_M: f64 = 0.2;
/// Least cells past [`ROUNDING_REACH_M`] that [`past_rounding`] fits a plane to.
const ROUNDING_MIN_CELLS: usize = 6;
/// Fits [`past_rounding`] makes of the cells past [`ROUNDING_REACH_M`], each leaving
/// out those off the last by three standard deviations: the second drops a cap's first
/// plateau cells. (Four read a capped descent's toe 2.8 mm nearer its drawn one,
/// `sweep -- rounded 100 3725 random` #69, and cost 25 µs more on `diagonal_full.png`.)
const ROUNDING_PASSES: usize = 2;
/// Spread of those cells about their plane (RMS, metres) over which [`past_rounding`]
/// leaves the fit alone: rough ground's bumps (centimetres) hide a rounding of a
/// centimetre or two, and its toe is read within rough ground's 4 cm anyway.
const ROUNDING_SMOOTH_M: f64 = 0.004;
/// Least lift of the cells within [`ROUNDING_REACH_M`] of the toe line over the plane
/// of those past it that [`past_rounding`] takes for a rounding, metres, and how many
/// standard errors of their mean it must also pass.
const ROUNDING_MIN_LIFT_M: f64 = 0.001;
/// See [`ROUNDING_MIN_LIFT_M`].
const ROUNDING_LIFT_SES: f64 = 4.0;

/// The face's plane past a rounded toe, or `None` where the toe shows no rounding.
///
/// Real toes are rounded: across the toe line the ground bends from the level to the
/// face over some length, the two planes still meeting at the toe line. The fit takes
/// the bend's first rise (or fall) with the face, as it lies within the residual
/// tolerance, and over the bend's near half that ground stands off the face's plane
/// its way (by up to tan(gradient) · length / 8 at the toe line, for a parabolic
/// bend): the fitted plane reads the toe early and the face shallow (by up to 2.8 cm
/// and 1.2° for roundings up to 40 cm long, where the clean bars are 1 cm and 0.5°).
///
/// So the face is fitted again to the taken cells more than [`ROUNDING_REACH_M`] past
/// the fit's toe line (`fit`), weighted by their points, and refitted without those
/// off it by three standard deviations (a cap's first plateau cells, which the fit's
/// 6 mm floor keeps; [`ROUNDING_PASSES`]); if the cells nearer the toe
/// line stand off that plane the face's way (`dir`), on average, by over
/// [`ROUNDING_MIN_LIFT_M`] and [`ROUNDING_LIFT_SES`] standard errors (the far cells'
/// spread over the near ones' count), the toe is rounded and the far cells' plane is
/// the face's. A sharp toe's near cells lie on the far plane (its toe read as
/// before). Only for a fit that slopes the face's way (a plane [`measures`] takes),
/// on smooth ground (the far cells within [`ROUNDING_SMOOTH_M`] RMS),
/// with [`ROUNDING_MIN_CELLS`] far cells reaching twice [`ROUNDING_REACH_M`] past the
/// toe line, and a far plane that still slopes the face's way by [`MIN_FACE_DEG`]. The
/// far plane is carried back to the toe line no farther than the length it is fitted
/// over: fitted over a shorter one, millimetres of a bevelled band's edge strip
/// tilted it 0.6° (`validate`'s bevelled one-track ramp on a random rig).
fn past_rounding(
    f: &Frame,
    g: &Ground,
    sel: &mut Selection,
    fit: &Plane,
    dir: Dir,
) -> Option<Plane> {
    let sign = if dir == Dir::Up { 1.0 } else { -1.0 };
    if fit.a * sign <= 0.0 || fit.gradient_deg() < MIN_FACE_DEG {
        return None; // no slope the face's way: measured as a step, from the onsets
    }
    let slope = fit.a.hypot(fit.b);
    // How far past the fit's toe line a cell lies, along the gradient, metres.
    let past = |cell: &Cell| sign * fit.z(f64::from(cell.x), f64::from(cell.y)) / slope;
    // The taken cells past the reach and within it, in cell order (capacity: the
    // cell count; never reallocates).
    let Selection {
        eligible,
        on,
        far,
        near,
        ..
    } = sel;
    far.clear();
    near.clear();
    for &c in eligible.iter().filter(|&&c| on[c as usize]) {
        if past(&f.cells[c as usize]) > ROUNDING_REACH_M {
            far.push(c);
        } else {
            near.push(c);
        }
    }
    let cell_of = |&c: &u32| (c as usize, &f.cells[c as usize]);
    // The far plane, refitted to the far cells within three standard deviations of
    // the last one (unless none leaves).
    let mut last: Option<CellsFit> = None;
    for _ in 0..ROUNDING_PASSES {
        let kept = last.map(|fit| (fit.plane, 3.0 * fit.sigma));
        let keep = move |&(c, cell): &(usize, &Cell)| {
            kept.is_none_or(|(q, tol)| g.off(c, cell, &q).abs() <= tol)
        };
        let cells = || far.iter().map(cell_of).filter(keep);
        let fit = fit_cells(g, cells, |cell| f64::from(cell.n))?;
        let reaches = cells().any(|(_, cell)| past(cell) >= 2.0 * ROUNDING_REACH_M);
        if fit.n < ROUNDING_MIN_CELLS || !reaches {
            return None;
        }
        if last.is_some_and(|last| last.n == fit.n) {
            break;
        }
        let q = fit.plane;
        if q.a * sign <= 0.0 || q.gradient_deg() < MIN_FACE_DEG {
            return None;
        }
        last = Some(fit);
    }
    let CellsFit { plane: p, rms, .. } = last?;
    let lift = near
        .iter()
        .map(cell_of)
        .map(|(c, cell)| sign * g.off(c, cell, &p))
        .sum::<f64>()
        / near.len().max(1) as f64;
    let rounded = rms <= ROUNDING_SMOOTH_M
        && !near.is_empty()
        && lift > ROUNDING_MIN_LIFT_M.max(ROUNDING_LIFT_SES * rms / (near.len() as f64).sqrt());
    rounded.then_some(p)
}

/// One fit of [`fit_face`]: the plane through the cells `sel` takes and the
/// tolerance about it that keeps a cell on the face (metres), or `None` with under
/// three cells or a degenerate fit.
///
/// Cells weigh by their points, except in the first fit (`iteration` 0): a cell whose
/// points are mostly a face turned to the camera (a trench's wall along the band's
/// edge) has several times more, and would steer the first plane so far that the
/// residuals could not tell it apart. Once judged by an unweighted plane, such cells
/// are off it and dropped. The tolerance is three standard deviations of the
/// residuals, the smaller of the RMS's and the median's estimate (a strip of cells off
/// the face, such as a wall's points along a band edge or a plateau, inflates the RMS
/// and would keep itself in), and at least [`MIN_TOLERANCE_M`].
fn weighted_plane(
    f: &Frame,
    g: &Ground,
    sel: &Selection,
    iteration: usize,
) -> Option<(Plane, f64)> {
    let weight = |cell: &Cell| {
        if iteration == 0 {
            1.0
        } else {
            f64::from(cell.n)
        }
    };
    let fit = fit_cells(g, || sel.taken(f), weight)?;
    Some((fit.plane, MIN_TOLERANCE_M.max(3.0 * fit.sigma)))
}

/// A plane fitted to cells' ground heights ([`fit_cells`]) and how far they lie off it.
#[derive(Debug, Clone, Copy)]
struct CellsFit {
    plane: Plane,
    /// How many cells it was fitted to.
    n: usize,
    /// The residuals' weighted RMS, metres.
    rms: f64,
    /// One standard deviation of the residuals, metres: the smaller of the RMS's and
    /// the median absolute residual's estimate (a strip of cells off the face, such as
    /// a wall's points along a band edge or a plateau, inflates the RMS).
    sigma: f64,
}

/// The weighted least-squares plane through the ground heights (`g.z`) of `cells`
/// (cell index and cell), each weighing `weight`, and the spread of the heights about
/// it; `None` with under three cells or a degenerate fit.
fn fit_cells<'c, I>(
    g: &Ground,
    cells: impl Fn() -> I,
    weight: impl Fn(&Cell) -> f64,
) -> Option<CellsFit>
where
    I: Iterator<Item = (usize, &'c Cell)>,
{
    let mut sums = PlaneFit::default();
    let mut n = 0usize;
    for (c, cell) in cells() {
        let (x, y) = (f64::from(cell.x), f64::from(cell.y));
        sums.add(x, y, f64::from(g.z[c]), weight(cell));
        n += 1;
    }
    if n < 3 {
        return None;
    }
    let plane = sums.solve()?;
    let (mut sq, mut spread) = (0.0, Spread::default());
    for (c, cell) in cells() {
        let r = g.off(c, cell, &plane);
        sq += weight(cell) * r * r;
        spread.add(r);
    }
    let rms = (sq / sums.weight()).sqrt();
    Some(CellsFit {
        plane,
        n,
        rms,
        sigma: spread.sigma().map_or(rms, |m| m.min(rms)),
    })
}

/// A histogram of absolute residuals in millimetre bins, for their median without
/// sorting or a buffer.
struct Spread {
    bins: [u32; SPREAD_BINS],
    n: u32,
}

impl Default for Spread {
    fn default() -> Self {
        Spread {
            bins: [0; SPREAD_BINS],
            n: 0,
        }
    }
}

/// Bins of [`Spread`], each 1 mm; larger residuals share the last.
const SPREAD_BINS: usize = 64;

impl Spread {
    fn add(&mut self, r: f64) {
        let k = ((r.abs() * 1000.0) as usize).min(SPREAD_BINS - 1);
        self.bins[k] += 1;
        self.n += 1;
    }

    /// The standard deviation a normal spread with this median absolute residual
    /// has (1.4826 × the median, rounded up to its bin), metres; `None` when the
    /// median lies past the last bin.
    fn sigma(&self) -> Option<f64> {
        let half = self.n.div_ceil(2);
        let mut seen = 0;
        for (k, &b) in self.bins.iter().enumerate().take(SPREAD_BINS - 1) {
            seen += b;
            if seen >= half && self.n > 0 {
                return Some(1.4826 * (k + 1) as f64 / 1000.0);
            }
        }
        None
    }
}

/// How well a plane explains the cells `sel` takes: the sum of squared height
/// residuals, metres², and the number of cells.
fn residuals(f: &Frame, g: &Ground, sel: &Selection, p: &Plane) -> (f64, usize) {
    let mut sse = 0.0;
    let mut n = 0;
    for (c, cell) in sel.taken(f) {
        let r = g.off(c, cell, p);
        sse += r * r;
        n += 1;
    }
    (sse, n)
}

/// Whether the two tracks' cells lie on one face: the plane fitted to both explains
/// them about as well as a plane per track does. `own` is the two one-track fits'
/// summed squared residuals, `joint` the joint plane's over the same cells, `n` the
/// cells: an F ratio of the three parameters the second plane adds against the
/// per-cell variance left, under [`SAME_FACE_F`] times the cells whose residuals move
/// together. Two ramps with toes 0.3 m apart on smooth ground leave centimetres on
/// every cell (F of 1,000 and more); one face on rough ground leaves F in the tens to
/// hundreds, its residuals correlated over many cells.
///
/// How many cells move together depends on what the variance left is: depth noise
/// (up to [`FACE_NOISE_M`], the floor) counts [`NOISE_CORRELATED_CELLS`]; the share
/// past it is rough ground's, whose residuals move together over its correlation
/// area ([`ROUGH_CORRELATED_CELLS`]). With 16 cells for both, one 11.9° rough
/// descent fitted per track read 12.5° and 10.3° with toes 1 cm apart, its cells
/// 6 mm about each plane, F 500: two faces, the left track's alone (workcase 9 for
/// 8: `sweep -- families 100 11401 random` #38, clean). Of 350 rough ramps and
/// descents (`sweep -- families 200 11450 random 5` and `11451`) 4 read F 480-777,
/// their cells 6-11 mm about the planes; of 462 frames of two smooth ramps under the
/// tracks (`... 9`), none read under 994, their cells within 1.3 mm.
fn same_face(own: f64, joint: f64, n: usize) -> bool {
    let floor = FACE_NOISE_M * FACE_NOISE_M;
    let variance = (own / n.saturating_sub(6).max(1) as f64).max(floor);
    let rough_share = 1.0 - floor / variance;
    let cells =
        NOISE_CORRELATED_CELLS + (ROUGH_CORRELATED_CELLS - NOISE_CORRELATED_CELLS) * rough_share;
    (joint - own).max(0.0) / 3.0 / variance <= SAME_FACE_F * cells
}

/// The F ratio above which two one-track faces are different faces, for
/// independent cells; [`same_face`] multiplies it by the cells whose residuals move
/// together.
const SAME_FACE_F: f64 = 30.0;
/// The cells counted as one where a face's cells spread about it by depth noise alone:
/// the 16 of a 20 cm patch (the limit measured before rough ground's share counted).
const NOISE_CORRELATED_CELLS: f64 = 16.0;
/// The cells of rough ground's correlation area, counted as one where a face's cells
/// spread about it by rough ground: a height field correlated over a length L moves
/// together over about π·L², 50 cells of 5 cm at the 20 cm the rough ground of the
/// issue reaches.
const ROUGH_CORRELATED_CELLS: f64 = 50.0;
/// Least per-cell height noise the F ratio assumes, metres (clean frames leave
/// millimetres).
const FACE_NOISE_M: f64 = 0.003;

/// How many spreads of the strips' mean residuals off their median leave a strip out
/// of the face fit ([`Selection::reject_strips`]).
const STRIP_OFF_MADS: f32 = 4.0;
/// Least taken cells for [`Selection::reject_strips`] to judge a strip.
const STRIP_MIN_CELLS: usize = 3;
/// Least strips judged for [`Selection::reject_strips`] to leave any out.
const STRIPS_JUDGED: usize = 4;

/// The feature analysis's buffers, sized for the grid and reused every frame.
#[derive(Debug, Clone)]
pub(crate) struct Scratch {
    onset: Vec<Option<Onset>>,
    selection: Selection,
    z: Vec<f32>,
    usable: Vec<bool>,
}

impl Scratch {
    /// Buffers for `spec`'s grid.
    pub fn new(spec: &GridSpec) -> Self {
        let cells = spec.cell_count();
        Scratch {
            onset: vec![None; spec.ny],
            selection: Selection {
                eligible: Vec::with_capacity(cells),
                on: vec![false; cells],
                off_strip: vec![false; spec.ny],
                strip_sums: vec![(0.0, 0); spec.ny],
                means: Vec::with_capacity(spec.ny),
                far: Vec::with_capacity(cells),
                near: Vec::with_capacity(cells),
            },
            z: vec![0.0; cells],
            usable: vec![false; cells],
        }
    }
}

/// The cells one face fit may take, and those it takes.
#[derive(Debug, Clone)]
struct Selection {
    /// Every cell the fit may take (the chosen strips' cells from
    /// [`TOE_BAND_CELLS`] before their onsets on), in cell order.
    eligible: Vec<u32>,
    /// Per cell, whether the fit takes it.
    on: Vec<bool>,
    /// Per strip, whether the fit leaves it out: its cells lie off the face together
    /// ([`Selection::reject_strips`]).
    off_strip: Vec<bool>,
    /// Per strip, the sum of its taken cells' residuals (metres) and their count.
    strip_sums: Vec<(f64, u32)>,
    /// The strips' mean residuals, for their median (capacity: the strip count).
    means: Vec<f32>,
    /// The taken cells past a rounded toe's reach, and within it
    /// ([`past_rounding`]; capacity: the cell count).
    far: Vec<u32>,
    /// See `far`.
    near: Vec<u32>,
}

impl Selection {
    /// Take no cell and leave out no strip, for a new fit.
    fn clear(&mut self) {
        self.on.fill(false);
        self.off_strip.fill(false);
    }

    /// Leave strip `iy` out of the fit, its cells untaken.
    fn leave_out(&mut self, s: &GridSpec, iy: usize) {
        self.off_strip[iy] = true;
        for ix in 0..s.nx {
            self.on[s.cell(ix, iy)] = false;
        }
    }

    /// Mark the strips whose taken cells lie off plane `p` together: their mean
    /// residual off the strips' median by more than [`STRIP_OFF_MADS`] times the
    /// spread of the strips' means (their median absolute deviation, scaled to a
    /// standard deviation), and at least [`MIN_TOLERANCE_M`]. Only strips with
    /// [`STRIP_MIN_CELLS`] taken cells are judged, and only when [`STRIPS_JUDGED`] are;
    /// a strip with fewer keeps its mark.
    ///
    /// A track's edge strip beside a band's sloping side holds its means, a share of
    /// the band's height: taken, two such strips of a capped one-track descent pulled
    /// the face 2-5° shallower and widened its tolerance until the fit ran on into the
    /// floor past the cap (`sweep -- bevelled 60 909 default 3`).
    fn reject_strips(&mut self, f: &Frame, g: &Ground, p: &Plane) {
        self.strip_sums.fill((0.0, 0));
        for &c in &self.eligible {
            let c = c as usize;
            if self.on[c] {
                let cell = &f.cells[c];
                let r = g.off(c, cell, p);
                let sum = &mut self.strip_sums[f.spec.strip_of(c)];
                *sum = (sum.0 + r, sum.1 + 1);
            }
        }
        let mean = |(sum, n): (f64, u32)| {
            (n as usize >= STRIP_MIN_CELLS).then(|| (sum / f64::from(n)) as f32)
        };
        self.means.clear();
        self.means
            .extend(self.strip_sums.iter().filter_map(|&s| mean(s)));
        if self.means.len() < STRIPS_JUDGED {
            return;
        }
        let middle = median(&mut self.means);
        for m in &mut self.means {
            *m = (*m - middle).abs();
        }
        let spread = 1.4826 * median(&mut self.means);
        let limit = (MIN_TOLERANCE_M as f32).max(STRIP_OFF_MADS * spread);
        for (off, &s) in self.off_strip.iter_mut().zip(&self.strip_sums) {
            if let Some(m) = mean(s) {
                *off = (m - middle).abs() > limit;
            }
        }
    }

    /// The cells taken, in cell order (the order the fit's sums run in).
    fn taken<'a>(&'a self, f: &'a Frame) -> impl Iterator<Item = (usize, &'a Cell)> + 'a {
        self.eligible
            .iter()
            .map(|&c| c as usize)
            .filter(|&c| self.on[c])
            .map(|c| (c, &f.cells[c]))
    }
}

/// What the steps read of each cell, worked out once per frame.
struct Ground<'a> {
    /// A cell's ground height, metres: its mean, or beside a face along its strip (a
    /// trench's wall, a ramp's side) the surface spread across the cell
    /// ([`ground_beside_face`]).
    z: &'a [f32],
    /// Whether the face fit may take the cell: seen, and its height one surface's.
    /// Not so for a face along its strip seen broadside whose points outnumber the
    /// ground's there (a trench's wall on the corridor's edge,
    /// [`unresolved_face_along`]): point-weighted, a strip of such cells would bend
    /// the plane toward itself and stay within its tolerance.
    usable: &'a [bool],
}

impl Ground<'_> {
    /// How far cell `c`'s ground (`cell` its grid cell) stands above plane `p`, metres.
    fn off(&self, c: usize, cell: &Cell, p: &Plane) -> f64 {
        f64::from(self.z[c]) - p.z(f64::from(cell.x), f64::from(cell.y))
    }
}

/// Fill [`Ground::z`] for the cells of the track strips (the steps read no other).
fn fill_heights(f: &Frame, z: &mut [f32]) {
    let s = f.spec;
    for iy in (0..s.ny).filter(|&iy| f.region[iy] != Region::Belly) {
        let y_mid = s.y_centre(iy);
        for ix in 0..s.nx {
            let c = s.cell(ix, iy);
            let cell = &f.cells[c];
            z[c] = ground_beside_face(cell, y_mid, s.voxel_m).unwrap_or(cell.z);
        }
    }
}

/// Fill [`Ground::usable`] for the cells of the track strips.
fn fill_usable(f: &Frame, usable: &mut [bool]) {
    let s = f.spec;
    for iy in (0..s.ny).filter(|&iy| f.region[iy] != Region::Belly) {
        let y_mid = s.y_centre(iy);
        for ix in 0..s.nx {
            let c = s.cell(ix, iy);
            usable[c] =
                f.seen[c] && !unresolved_face_along(&f.cells[c], s.x_centre(ix), y_mid, s.voxel_m);
        }
    }
}

fn status(z: f32, threshold: f32) -> Option<Dir> {
    if z > threshold {
        Some(Dir::Up)
    } else if z < -threshold {
        Some(Dir::Down)
    } else {
        None
    }
}

/// Which tracks a face affects, and which way it goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Affected {
    dir: Dir,
    left: bool,
    right: bool,
}

impl Affected {
    /// Whether strip `iy` takes part in the fit and the measures.
    fn chosen(self, f: &Frame, iy: usize) -> bool {
        chosen(f.region[iy], self.left, self.right)
    }
}

/// The feature of a passable corridor: onsets, affected tracks, the face's plane,
/// its measures and the workcase they make (see the module doc).
///
/// Also returns how uncertain the gradient is (one standard deviation, degrees) when
/// the face runs on to where the view ends, so that only its first stretch is seen:
/// the larger of the rough ground's share ([`gradient_sd_deg`]) and the face's own
/// cells' noise ([`noise_sd_deg`]); else (the face seen whole, flat ground, a step)
/// 0. And, for a face measured as a step (±90°), its [`StepRelief`]: how far the
/// ground past its onsets stands off the ground before them its way (a low step
/// stands under a wheel radius), and whether its top is seen.
pub fn analyse(f: &Frame, scratch: &mut Scratch) -> (Feature, f64, Option<StepRelief>) {
    let Scratch {
        onset,
        selection,
        z,
        usable,
    } = scratch;
    fill_heights(f, z);
    find_onsets(f, z, onset);
    let Some(affected) = affected_tracks(f, onset) else {
        return (Feature::FLAT, 0.0, None);
    };
    fill_usable(f, usable);
    let g = Ground { z, usable };
    let (affected, face) = one_face_or_nearer(f, &g, onset, selection, affected);
    let plane = face.map(|face| face.plane);
    let (mut at_ref, mut gradient, mut alpha, mut nearest) = measures(f, onset, plane, affected);
    // A face too steep for a slope, seen whole (ground beyond it) and standing nowhere
    // more than a wheel radius and rough ground's margin off the ground before it (as
    // for a step's relief, `high_or_unseen_step`), is a low step: a wheel climbs it as one,
    // whatever its flank (two 8 cm pebbles one behind the other in a track fitted as
    // a 40° face stopped the rover on flat ground). Measured as one, from the onsets.
    // So is one whose view ends only in its own shadow: a stone's front whose far side
    // is hidden to the corridor's end, too steep with the uncertainty of a short face
    // (an 8.6 cm stone on lumpy ground, 11.2 cm over the ground before it, read 25° ±
    // 3.6°: `sweep -- natural 200 7022 random 6` #80), with the uncertainty its slope
    // is judged with (two 7 cm boulders 0.3 m apart on a diagonal in one track, 9.2 cm
    // over the ground before them, fitted as a 22.9° face: ± 2.6° from the ground's
    // roughness, ± 4.5° from its cells' 2.4 cm spread; taken for no low step with the
    // first and judged with the second, it was a `slope`: `natural 100 11510 random 6`
    // #51). What its shadow hides, the crossing tests judge (the ground beside it, a
    // hidden top).
    let too_steep = |gradient: f64, sd: f64| {
        (f.cfg.rover.max_slope_deg..90.0).contains(&(gradient.abs() + super::FACE_MARGIN_SDS * sd))
    };
    let relief = || relief_past_onsets(f, g.z, onset, affected);
    // The gradient's uncertainty: the larger of the ground's roughness's and the face's
    // own cells' noise's.
    let mut sd = match face {
        Some(face) if face.to_view_end && gradient.abs() < 90.0 => {
            let ground =
                ground_spread(f, &g, onset, affected, &face.plane).unwrap_or(face.spread_m);
            gradient_sd_deg(gradient, ground, face.run_m).max(noise_sd_deg(
                gradient,
                face.spread_m,
                ground,
                face.along_m,
            ))
        }
        _ => 0.0,
    };
    let low_step_face = || {
        face.is_some_and(|face| {
            (!face.to_view_end && too_steep(gradient, 0.0))
                || (face.in_shadow && too_steep(gradient, sd))
        }) && super::low_step(relief(), &f.cfg.rover)
    };
    // Stones fitted as one plane: its cells spread about it by more than rough
    // ground's, and every strip comes back down past its top, or those that do stand
    // too high for a low step (`stones_fall_back`). Measured as a step from the
    // onsets, its relief decides. A 15.1 cm cone 1.57 m out, 12.4-12.6 cm over
    // the ground before it, was fitted with the corridor's other stones as a 2.8-3.1°
    // face, its cells 2.4-2.5 cm about it: a go (`sweep -- natural 200 5008 random 7`
    // #76, clean and noisy, a 320×240 camera).
    let stones = || {
        face.is_some_and(|face| face.spread_m > STONES_SPREAD_M)
            && stones_fall_back(f, g.z, onset, affected)
    };
    if low_step_face() || stones() {
        (at_ref, gradient, alpha, nearest) = measures(f, onset, None, affected);
        sd = 0.0;
    }
    let step_relief = (gradient.abs() >= 90.0).then(|| StepRelief {
        relief_m: relief(),
        unseen_top_m: unseen_tops(f, g.z, onset, affected),
        onset_m: nearest_onsets(f, onset, affected),
    });
    // A face met almost side-on (a side slope) has its toe line meet the reference
    // line behind the rover, or far past the corridor, or never: its distance is then
    // where the toe line is nearest within the affected tracks, and 0 for a track
    // already on the face.
    let length = f.cfg.analysis.corridor_length_m;
    let distance = if (0.0..=length).contains(&at_ref) {
        at_ref
    } else if nearest.is_finite() {
        nearest.clamp(0.0, length)
    } else {
        0.0
    };
    let diagonal = alpha.abs() >= f.cfg.analysis.diagonal_min_deg;
    let workcase = workcase(affected, diagonal);
    let vs = f64::from(f.spec.voxel_m);
    let feature = Feature {
        workcase,
        toe_seen: distance >= nearest_seen(f, affected) - vs,
        distance_m: Some(distance as f32),
        gradient_deg: Some(gradient as f32),
        alpha_deg: matches!(workcase, 4 | 6 | 7).then_some(alpha as f32),
    };
    (feature, sd, step_relief)
}

/// How a face measured as a step stands ([`analyse`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepRelief {
    /// How far the ground past the onsets stands off the ground before them, the
    /// step's way, over the cells seen below the sensor's horizon
    /// ([`relief_past_onsets`]), metres.
    pub relief_m: f32,
    /// Per wheel track, `[left, right]`, where the step's top is not seen: the nearest
    /// foot (its near edge, x, metres) of the climbs of a track whose strips still
    /// rise where their view ends ([`unseen_tops`]). There `relief_m` is only a lower
    /// bound.
    pub unseen_top_m: [Option<f32>; 2],
    /// Per wheel track, `[left, right]`, the nearest onset of the step among the
    /// track's affected strips ([`nearest_onsets`]): its cell's near edge, x, metres.
    pub onset_m: [Option<f32>; 2],
}

/// Per wheel track, `[left, right]`, the near edge (x, metres) of the nearest onset
/// the face's way among the track's affected strips, or `None` where it has none:
/// where the strips saw the step begin. A face measured as a step is drawn through its
/// onsets, so across a track its toe line runs through them; but met side-on (a
/// stone's front read with the stones beside it) that line reaches far nearer the
/// rover than any onset: a 15.5 cm mound 1.6-1.85 m out, behind a 7.3 cm one, made a
/// `step` 0.56 m out (`sweep -- natural 200 5008 random 7` #137).
fn nearest_onsets(f: &Frame, onset: &[Option<Onset>], a: Affected) -> [Option<f32>; 2] {
    let s = f.spec;
    let mut near: [Option<f32>; 2] = [None; 2];
    for (iy, ix) in onset_rows(f, onset, a) {
        let x = s.x_centre(ix) - 0.5 * s.voxel_m;
        let t = &mut near[usize::from(f.region[iy] != Region::Left)];
        *t = Some(t.map_or(x, |n| n.min(x)));
    }
    near
}

/// Fewest strips of a track that still rise where their view ends for [`unseen_tops`]
/// to take a rising step's top there as not seen: one strip may be a bump of rough
/// ground, or noise, at the cut.
const UNSEEN_TOP_STRIPS: usize = 2;

/// Per wheel track, `[left, right]`, whether a rising step's top is not seen there:
/// where [`UNSEEN_TOP_STRIPS`] or more of the track's affected strips with an onset
/// the step's way climb into the cells past the sensor's horizon ([`climb_into_cut`]),
/// the nearest of their climbs' feet (near edge, x, metres). What the face analysis
/// measures of such a step is only what lies below the image's top edge. A 15 cm
/// Gaussian mound 1.96 m out, the image's top edge across its front, rose into the cut
/// cells 8-10 cm over the ground before it in three strips, and the relief past the
/// onsets, 8.9 cm (a 9 cm mound before it), was a low step's: a go (`sweep -- natural
/// 200 5108 random 7` #53, clean and noisy, a Kinect v2 0.58 m high pitched 44°).
fn unseen_tops(f: &Frame, z: &[f32], onset: &[Option<Onset>], a: Affected) -> [Option<f32>; 2] {
    let mut tracks = [(0usize, f32::INFINITY); 2];
    if a.dir == Dir::Up {
        for (iy, from, base) in onset_strips(f, z, onset, a) {
            if let Some(foot) = climb_into_cut(f, z, iy, from, base) {
                let t = &mut tracks[usize::from(f.region[iy] != Region::Left)];
                *t = (t.0 + 1, t.1.min(foot));
            }
        }
    }
    tracks.map(|(n, foot)| (n >= UNSEEN_TOP_STRIPS).then_some(foot))
}

/// Least rise per run from cell to cell of a climb into the cut for
/// [`climb_into_cut`]'s foot (about 6°): rough ground's long gentle swells before it
/// are the ground the climb starts from. On a 10 cm lumpy swell that rose 1.8 cm over
/// 0.3 m to a 4.7 cm rock the view ends on, the foot read 0.3 m before the rock's.
const CLIMB_MIN_SLOPE: f32 = 0.1;

/// Where strip `iy` still rises where its view ends, past its onset at row `from`: its
/// last cell seen below the sensor's horizon is the one before its first cell past it
/// (`h`, [`first_cut`]), and the top of the cells past it from `h` ([`cut_cells`]:
/// what is seen of them lies under the image's top edge, a lower bound) stands
/// [`FRONT_RISING_M`] over that cell's top and [`STEEP_EXIT_RISE_M`] (rough ground's
/// peak to peak) over the strip's ground before its onset (`base`, metres), as the
/// crossing tests' [`steep_exit`](super::crossing::steep_exit) reads a front the view
/// ends on. Returns the climb's foot, the near edge (x, metres) of the cell from which
/// the strip's heights (`z`) rise cell by cell to the cut by [`CLIMB_MIN_SLOPE`] or
/// more, or `None`.
fn climb_into_cut(f: &Frame, z: &[f32], iy: usize, from: usize, base: f32) -> Option<f32> {
    let s = f.spec;
    let below = |ix: usize| {
        let c = s.cell(ix, iy);
        f.seen_whole(c)
    };
    let h = first_cut(f, iy, from + 1)?;
    if !below(h - 1) {
        return None;
    }
    let top = cut_cells(f, iy, h)
        .map(|(_, c)| c.top)
        .fold(f32::NEG_INFINITY, f32::max);
    let last = f.cells[s.cell(h - 1, iy)].top;
    if top < last + FRONT_RISING_M || top - base < STEEP_EXIT_RISE_M {
        return None;
    }
    let climbs = CLIMB_MIN_SLOPE * s.voxel_m;
    let mut foot = h - 1;
    while foot > from && below(foot - 1) && z[s.cell(foot, iy)] - z[s.cell(foot - 1, iy)] >= climbs
    {
        foot -= 1;
    }
    Some(s.x_centre(foot) - 0.5 * s.voxel_m)
}

/// The farthest the ground departs the face's way from the ground the wheel meets it
/// on, past the onsets of the affected tracks' strips, metres: the highest top for a
/// rise (a cell's highest point where the cell past it lies in its shadow,
/// [`Frame::shadow_past`]), the deepest low for a fall, over the seen cells below the
/// sensor's horizon, each strip measured from its ground before its onset
/// ([`ground_before`]).
///
/// A cell so shadowed is seen from its front only, and its highest point seen is the
/// nearest to its top: its top voxel's centroid lies up to two thirds of a voxel under
/// that. A 15.6 cm cone whose far side lay in its shadow read 11.2 cm over the ground
/// before it by that centroid, 12.3 cm by its highest point, the apex 12.9 cm, and was
/// a low step (`sweep -- natural 200 4608 random 7` #60, clean).
///
/// Measured from the rover's own ground (z = 0) instead, rough ground's bumps added
/// to it: an 8.9 cm rock on a 2 cm bump, the ground before it 1-2 cm up, stood 11.3 cm
/// over z = 0 and stopped the rover (`sweep -- bevelled 100 6401 random` #50, a rock
/// field due go, clean and noisy).
fn relief_past_onsets(f: &Frame, z: &[f32], onset: &[Option<Onset>], a: Affected) -> f32 {
    onset_strips(f, z, onset, a)
        .map(|(iy, from, base)| strip_relief(f, iy, from, base, a.dir))
        .fold(0.0, f32::max)
}

/// The farthest strip `iy` departs `dir`'s way from `base` (its ground before, metres)
/// over its seen cells below the horizon from row `from` on, metres: see
/// [`relief_past_onsets`].
fn strip_relief(f: &Frame, iy: usize, from: usize, base: f32, dir: Dir) -> f32 {
    let s = f.spec;
    let mut relief = 0.0f32;
    for ix in from..s.nx {
        let c = s.cell(ix, iy);
        if f.seen_whole(c) {
            let cell = &f.cells[c];
            relief = relief.max(match dir {
                Dir::Up if f.shadow_past(ix, iy) => cell.top.max(cell.peak) - base,
                Dir::Up => cell.top - base,
                Dir::Down => base - cell.low,
            });
        }
    }
    relief
}

/// How far a fitted face's cells may spread about its plane (one standard deviation,
/// robust) and still be a face, metres: rough ground's ±2.5 cm spreads by 1.1-1.3 cm,
/// a cell's own noise adds millimetres.
const STONES_SPREAD_M: f64 = 0.02;

/// Whether a rising face is stones: at least one affected strip rises and comes back
/// down (past its highest seen cell below the horizon, a seen cell stands within the
/// rise threshold of the strip's ground before its onset, [`ground_before`]), and
/// either every strip does or those that do stand too high for a low step
/// ([`strip_relief`]). A ramp rises out of the view or onto a plateau; stones fall back
/// to the ground they stand on. One stone too tall is a step whatever the strips the
/// view's end cuts.
fn stones_fall_back(f: &Frame, z: &[f32], onset: &[Option<Onset>], a: Affected) -> bool {
    let s = f.spec;
    let threshold = f.cfg.analysis.rise_threshold_m as f32;
    if a.dir != Dir::Up {
        return false;
    }
    let (mut every, mut tallest) = (true, None::<f32>);
    for (iy, from, base) in onset_strips(f, z, onset, a) {
        let (mut high, mut back) = (f32::NEG_INFINITY, false);
        for c in (from..s.nx)
            .map(|ix| s.cell(ix, iy))
            .filter(|&c| f.seen_whole(c))
        {
            if z[c] > high {
                (high, back) = (z[c], false);
            } else if z[c] - base <= threshold {
                back = true;
            }
        }
        if back {
            let relief = strip_relief(f, iy, from, base, a.dir);
            tallest = Some(tallest.map_or(relief, |t| t.max(relief)));
        } else {
            every = false;
        }
    }
    tallest.is_some_and(|t| every || !super::low_step(t, &f.cfg.rover))
}

/// The affected strips with an onset the face's way: each strip, its onset's row and
/// its ground before the onset ([`ground_before`], metres).
fn onset_strips<'f>(
    f: &'f Frame,
    z: &'f [f32],
    onset: &'f [Option<Onset>],
    a: Affected,
) -> impl Iterator<Item = (usize, usize, f32)> + 'f {
    onset_rows(f, onset, a).map(move |(iy, ix)| (iy, ix, ground_before(f, z, iy, ix)))
}

/// The affected strips with an onset the face's way: each strip and its onset's row.
fn onset_rows<'f>(
    f: &'f Frame,
    onset: &'f [Option<Onset>],
    a: Affected,
) -> impl Iterator<Item = (usize, usize)> + 'f {
    (0..f.spec.ny)
        .filter(move |&iy| a.chosen(f, iy))
        .filter_map(move |iy| Some((iy, onset[iy].filter(|o| o.dir == a.dir)?.ix)))
}

/// The ground strip `iy` shows before its onset at row `ix`: the mean height (`z`) of
/// its seen cells within [`GROUND_BEFORE_M`] before it, metres, or the rover's own
/// (0) where it shows none (the onset is where its view starts). Those cells stand
/// within the onset's threshold of the rover's ground, so this moves the reference by
/// no more than rough ground's bumps.
fn ground_before(f: &Frame, z: &[f32], iy: usize, ix: usize) -> f32 {
    let s = f.spec;
    let reach = (GROUND_BEFORE_M / s.voxel_m).round() as usize;
    let (sum, n) = (ix.saturating_sub(reach)..ix)
        .map(|k| s.cell(k, iy))
        .filter(|&c| f.seen_whole(c))
        .fold((0.0f32, 0u32), |(sum, n), c| (sum + z[c], n + 1));
    if n == 0 {
        0.0
    } else {
        sum / n as f32
    }
}

/// How far before a strip's onset [`ground_before`] takes its ground from, metres.
const GROUND_BEFORE_M: f32 = 0.3;

/// How far a face's measured gradient (`gradient_deg`) may be off on rough ground,
/// one standard deviation, degrees, for ground whose heights spread by `ground_m`
/// (metres, one standard deviation) and a face seen `run_m` metres past its toe line:
/// the slope's error is `rough / √(max(run, ROUGH_MIN_RUN_M) · ROUGH_TILT_SCALE_M)`,
/// where `rough = √(ground² − FACE_NOISE_M²)` leaves out the cells' own noise.
///
/// This is measured, not derived: on the rough ground (±2.5 cm, 10-20 cm
/// correlation, ~1.1 cm spread) the face fit read 2.0-2.7° RMS off for runs of
/// 0.15-0.5 m, 1.8° for 0.5-0.8 m and 5.4° (up to 9°) under 0.15 m (the 226 go frames of
/// `near_edge -- 400 SEED rough`, seeds 30-34, `ALL=1`): far flatter in the run than
/// independent bumps would give (`L^-1.5`), since a plane fitted to a short face takes
/// the tilt of the one or two bumps on it. The scale matches those RMS figures. On
/// smooth ground (spread of millimetres) it is a fraction of a degree.
fn gradient_sd_deg(gradient_deg: f64, ground_m: f64, run_m: f64) -> f64 {
    // The cells' own noise (a millimetre bin, the sensor's noise over a cell's points)
    // tilts nothing: only the spread past it is the ground's.
    let rough = (ground_m * ground_m - FACE_NOISE_M * FACE_NOISE_M)
        .max(0.0)
        .sqrt();
    let slope_sd = rough / (run_m.max(ROUGH_MIN_RUN_M) * ROUGH_TILT_SCALE_M).sqrt();
    // d(atan s)/ds = cos²(gradient).
    gradient_deg.to_radians().cos().powi(2) * slope_sd.to_degrees()
}

/// How far `n` cells spread along a face's gradient, metres, from their count, the
/// sum and the sum of squares of their distances along it (`(n, sum, squares)`): the
/// root of their summed squared distances from their mean. (Taken as independent:
/// counting each row of cells as one, since a row's noise moves together, stopped
/// smooth climbable 18-27° ramps seen for 0.1-0.14 m, 19 of the 430 frames of
/// `near_edge -- 400 SEED passable`, seeds 30-34, where it mended one more steep go.)
fn along_spread((n, sum, squares): (f64, f64, f64)) -> f64 {
    if n < 1.0 {
        return 0.0;
    }
    (squares - sum * sum / n).max(0.0).sqrt()
}

/// How far a face's measured gradient (`gradient_deg`) may be off from its own cells'
/// noise, one standard deviation, degrees: the least-squares slope's standard error,
/// the noise over how far the cells spread along the gradient (`along_m`,
/// [`Face::along_m`]). The noise is the face's spread about its plane (`spread_m`)
/// past the ground's own (`ground_m`, which [`gradient_sd_deg`] counts), and at least
/// [`FACE_NOISE_M`].
///
/// On smooth ground the ground's share is nil, yet a face seen for its first 0.1-0.25
/// m where the view ends is no better measured: with Kinect v1 noise, ramps 30.6-32.2°
/// steep, their first 6-11 cm of rise seen 2.2-2.7 m out, read 1-4.4° shallow, under
/// the slope limit, and went; clean, each read within 0.1° and stopped. Over
/// `near_edge -- 300 SEED short`, seeds 71-100 (1,926 frames), 11 such frames went;
/// 4 go since (three whose rise no face was fitted to, and a 31° ramp read 27.5°,
/// seed 86 #171, noisy), and `near_edge -- 400 SEED passable` and `rough` (seeds
/// 30-34) are unchanged.
fn noise_sd_deg(gradient_deg: f64, spread_m: f64, ground_m: f64, along_m: f64) -> f64 {
    let noise = (spread_m * spread_m - ground_m * ground_m)
        .max(0.0)
        .sqrt()
        .max(FACE_NOISE_M);
    let slope_sd = noise / along_m.max(1e-3);
    gradient_deg.to_radians().cos().powi(2) * slope_sd.to_degrees()
}

/// Scale of [`gradient_sd_deg`]'s run, metres.
const ROUGH_TILT_SCALE_M: f64 = 0.16;
/// Shorter runs than this count as this long in [`gradient_sd_deg`], metres: two
/// cells.
const ROUGH_MIN_RUN_M: f64 = 0.1;

/// Least ground cells before the onsets that [`ground_spread`] judges from.
const GROUND_MIN_CELLS: u32 = 12;

/// The spread of the ground before the face `plane`, in the affected strips before
/// their onsets and wholly before the toe line (the face's own foot, under the
/// onset's threshold, is not ground): one standard deviation of the heights
/// (robust: 1.4826 × the median absolute height, so a stone or two do not count),
/// metres; `None` with fewer than [`GROUND_MIN_CELLS`] such cells seen (the toe
/// below the image).
fn ground_spread(
    f: &Frame,
    g: &Ground,
    onset: &[Option<Onset>],
    a: Affected,
    plane: &Plane,
) -> Option<f64> {
    let s = f.spec;
    let sign = if a.dir == Dir::Up { 1.0 } else { -1.0 };
    let half = 0.5 * s.voxel_m;
    let before_toe = |ix: usize, iy: usize| {
        let (x, y) = (s.x_centre(ix) + half, s.y_centre(iy));
        [y - half, y + half]
            .iter()
            .all(|&y| sign * plane.z(f64::from(x), f64::from(y)) <= 0.0)
    };
    let mut spread = Spread::default();
    for iy in (0..s.ny).filter(|&iy| a.chosen(f, iy)) {
        let Some(o) = onset[iy] else { continue };
        for ix in (0..o.ix).filter(|&ix| before_toe(ix, iy)) {
            let c = s.cell(ix, iy);
            if f.seen[c] {
                spread.add(f64::from(g.z[c]));
            }
        }
    }
    (spread.n >= GROUND_MIN_CELLS)
        .then(|| spread.sigma())
        .flatten()
}

/// Step 1: in each track strip, the first seen cell that rises (or falls) past the
/// threshold, confirmed by the next seen cell; else the last unconfirmed one.
fn find_onsets(f: &Frame, z: &[f32], onset: &mut [Option<Onset>]) {
    let s = f.spec;
    let threshold = f.cfg.analysis.rise_threshold_m as f32;
    for (iy, slot) in onset.iter_mut().enumerate() {
        *slot = None;
        if f.region[iy] == Region::Belly {
            continue;
        }
        let mut pending: Option<Onset> = None;
        for ix in 0..s.nx {
            let c = s.cell(ix, iy);
            if !f.seen[c] {
                continue;
            }
            let st = status(z[c], threshold);
            match (pending, st) {
                (Some(p), Some(d)) if p.dir == d => {
                    *slot = Some(p);
                    break;
                }
                _ => pending = st.map(|dir| Onset { ix, dir }),
            }
        }
        if slot.is_none() {
            *slot = pending;
        }
    }
}

/// Step 2 for one track: its direction and nearest onset row when at least half of
/// its seen strips have an onset that way (rising wins a tie).
fn track_onset(f: &Frame, onset: &[Option<Onset>], region: Region) -> Option<(Dir, usize)> {
    let s = f.spec;
    let (mut seen, mut up, mut down, mut near_up, mut near_down) =
        (0, 0, 0, usize::MAX, usize::MAX);
    for iy in f.strips(region) {
        if (0..s.nx).any(|ix| f.seen[s.cell(ix, iy)]) {
            seen += 1;
        }
        match onset[iy] {
            Some(Onset { ix, dir: Dir::Up }) => {
                up += 1;
                near_up = near_up.min(ix);
            }
            Some(Onset { ix, dir: Dir::Down }) => {
                down += 1;
                near_down = near_down.min(ix);
            }
            None => {}
        }
    }
    if up > 0 && up >= down && 2 * up >= seen {
        Some((Dir::Up, near_up))
    } else if down > 0 && 2 * down >= seen {
        Some((Dir::Down, near_down))
    } else {
        None
    }
}

/// Step 2: the affected tracks; when they go opposite ways, the one whose onset is
/// nearer. `None` on flat ground.
fn affected_tracks(f: &Frame, onset: &[Option<Onset>]) -> Option<Affected> {
    let left = track_onset(f, onset, Region::Left);
    let right = track_onset(f, onset, Region::Right);
    let (dir, left, right) = match (left, right) {
        (None, None) => return None,
        (Some((a, _)), Some((b, _))) if a == b => (a, true, true),
        (Some((a, _)), None) => (a, true, false),
        (None, Some((b, _))) => (b, false, true),
        (Some((a, na)), Some((b, nb))) => {
            if na <= nb {
                (a, true, false)
            } else {
                (b, false, true)
            }
        }
    };
    Some(Affected { dir, left, right })
}

/// Step 3: the face's plane. Both tracks rise (or fall): one face across both, or a
/// different face under each? Fit each alone and both together; if the one-track
/// faces depart from the joint one ([`same_face`]), the nearer one is the feature:
/// the one that departs the ground by the rise threshold nearer, over its track's
/// centre line. By their toes, an 18.7° ramp under the left track, seen in 7 cells
/// before the image's top edge, fitted at 2.2° with its toe 0.9 m before where it
/// rises, was taken over a 15.7° ramp under the right track whose toe was 0.3 m
/// nearer (`sweep -- bevelled 100 4612 random 9` #79, clean: workcase 4 measured
/// 2.2°).
/// Returns the tracks the face affects and its face, measured past a rounded toe
/// (only the returned face is: the one-track fits are compared by their own planes).
fn one_face_or_nearer(
    f: &Frame,
    g: &Ground,
    onset: &[Option<Onset>],
    sel: &mut Selection,
    mut a: Affected,
) -> (Affected, Option<Face>) {
    let both = fit_face(f, g, onset, sel, a, true).map(|face| face.past_rounding(f, g, sel, a.dir));
    let Some(both) = both.filter(|_| a.left && a.right) else {
        return (a, both);
    };
    let tc = f.cfg.rover.track_centre_m();
    // Where a face departs the ground by the rise threshold over a track's centre line
    // at `y`, metres: where its wheels meet it. Its toe alone is the plane carried
    // down to the ground, and the plane of a few cells seen just past a toe, where
    // the view ends, may be far off.
    let threshold = f.cfg.analysis.rise_threshold_m;
    let rises_at = |p: &Plane, y: f64| p.toe_x(y) + threshold / p.a.abs();
    let mut one = |left: bool| {
        let track = Affected {
            left,
            right: !left,
            ..a
        };
        let face = fit_face(f, g, onset, sel, track, false)?;
        let (own, n) = residuals(f, g, sel, &face.fit);
        let (joint, _) = residuals(f, g, sel, &both.fit);
        Some((face, own, joint, n))
    };
    if let (Some(l), Some(r)) = (one(true), one(false)) {
        if !same_face(l.1 + r.1, l.2 + r.2, l.3 + r.3) {
            // The nearer track's face is fitted again, without its sagging edges.
            if rises_at(&l.0.plane, tc) <= rises_at(&r.0.plane, -tc) {
                a.right = false;
            } else {
                a.left = false;
            }
            let nearer = fit_face(f, g, onset, sel, a, true);
            return (a, nearer.map(|face| face.past_rounding(f, g, sel, a.dir)));
        }
    }
    (a, Some(both))
}

/// Step 4: (distance, gradient, alpha) of the face, and the toe line's nearest
/// distance within the affected tracks (at one of their edges), metres: from the
/// fitted plane when it is a slope the right way, else from the onsets (a low step).
fn measures(
    f: &Frame,
    onset: &[Option<Onset>],
    plane: Option<Plane>,
    a: Affected,
) -> (f64, f64, f64, f64) {
    let tc = f.cfg.rover.track_centre_m();
    let y_ref = match (a.left, a.right) {
        (true, true) => 0.0,
        (true, false) => tc,
        _ => -tc,
    };
    let (inner, outer) = (f.cfg.rover.belly_half_width_m, f.cfg.rover.track_outer_m);
    let edges = [(a.left, 1.0), (a.right, -1.0)]
        .into_iter()
        .filter(|&(on, _)| on)
        .flat_map(|(_, side)| [side * inner, side * outer]);
    let nearest = |toe: &dyn Fn(f64) -> f64| edges.clone().map(toe).fold(f64::INFINITY, f64::min);
    let sign = if a.dir == Dir::Up { 1.0 } else { -1.0 };
    let sloped = plane.filter(|p| p.a * sign > 0.0 && p.gradient_deg() >= MIN_FACE_DEG);
    match sloped {
        Some(p) => (
            p.toe_x(y_ref),
            sign * p.gradient_deg(),
            (p.b / p.a).atan().to_degrees(),
            nearest(&|y| p.toe_x(y)),
        ),
        None => {
            let (distance, alpha) = step_toe(f, onset, a, y_ref);
            let q = -alpha.to_radians().tan();
            (
                distance,
                sign * 90.0,
                alpha,
                nearest(&|y| distance + q * (y - y_ref)),
            )
        }
    }
}

/// A step's toe line: through the onsets' near edges (x = q·y + x0), read at
/// `y_ref`, and its angle; with a single onset row, the nearest edge, square on.
fn step_toe(f: &Frame, onset: &[Option<Onset>], a: Affected, y_ref: f64) -> (f64, f64) {
    let s = f.spec;
    let vs = f64::from(s.voxel_m);
    let edges = || {
        onset
            .iter()
            .enumerate()
            .filter_map(move |(iy, o)| {
                o.filter(|o| o.dir == a.dir && a.chosen(f, iy))
                    .map(|o| (iy, o))
            })
            .map(move |(iy, o)| {
                (
                    f64::from(s.y_centre(iy)),
                    f64::from(s.x_centre(o.ix)) - 0.5 * vs,
                )
            })
    };
    let mut fit = PlaneFit::default();
    for (y, x) in edges() {
        // Fit x = q·y + x0 as a "plane" in (y, ·): reuse the line fit.
        fit.add(y, 0.0, x, 1.0);
    }
    match fit.solve() {
        Some(line) => (line.a * y_ref + line.c, (-line.a).atan().to_degrees()),
        None => (edges().map(|(_, x)| x).fold(f64::INFINITY, f64::min), 0.0),
    }
}

/// The workcase of a face: its direction, the tracks it affects, whether its toe
/// line is diagonal (uphill only; downhill has no diagonal cases).
fn workcase(a: Affected, diagonal: bool) -> u8 {
    match (a.dir, a.left, a.right, diagonal) {
        (Dir::Up, true, true, false) => 2,
        (Dir::Up, true, true, true) => 7,
        (Dir::Up, true, false, false) => 3,
        (Dir::Up, true, false, true) => 4,
        (Dir::Up, false, _, false) => 5,
        (Dir::Up, false, _, true) => 6,
        (Dir::Down, true, true, _) => 8,
        (Dir::Down, true, false, _) => 9,
        (Dir::Down, false, _, _) => 10,
    }
}

/// The nearest seen ground in the affected strips, metres: a toe before it is not
/// seen.
fn nearest_seen(f: &Frame, a: Affected) -> f64 {
    let s = f.spec;
    let vs = f64::from(s.voxel_m);
    (0..s.ny)
        .filter(|&iy| a.chosen(f, iy))
        .filter_map(|iy| (0..s.nx).find(|&ix| f.seen[s.cell(ix, iy)]))
        .map(|ix| f64::from(s.x_centre(ix)) - 0.5 * vs)
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::{self, Element, Extent, Terrain};
    use crate::{Config, Pipeline};

    /// The pipeline after analysing a clean frame of `elements` (default rig).
    fn analysed(elements: Vec<Element>) -> Pipeline {
        let config = Config::default();
        let frame = sim::render(&Terrain::new(elements), &config);
        let mut p = Pipeline::new(config).unwrap();
        p.process(&frame).unwrap();
        p
    }

    /// What `analyse` works out before the face fit: heights, usable cells, onsets.
    fn prepared(f: &Frame) -> Scratch {
        let mut sc = Scratch::new(f.spec);
        fill_heights(f, &mut sc.z);
        fill_usable(f, &mut sc.usable);
        find_onsets(f, &sc.z, &mut sc.onset);
        sc
    }

    /// Both tracks affected, `dir` their way.
    fn both_tracks(dir: Dir) -> Affected {
        Affected {
            dir,
            left: true,
            right: true,
        }
    }

    /// The face of a rise under both tracks.
    fn fitted(f: &Frame) -> Face {
        let mut sc = prepared(f);
        let g = Ground {
            z: &sc.z,
            usable: &sc.usable,
        };
        let face = fit_face(
            f,
            &g,
            &sc.onset,
            &mut sc.selection,
            both_tracks(Dir::Up),
            false,
        )
        .unwrap();
        face.past_rounding(f, &g, &mut sc.selection, Dir::Up)
    }

    const LEFT_TRACK: Extent = Extent::Band {
        from_m: 0.2,
        to_m: 0.7,
    };

    #[test]
    fn onsets_lie_where_each_track_strip_first_rises() {
        let p = analysed(vec![Element::ramp(1.0, 0.0, 20.0, 0.0, Extent::Full)]);
        let f = p.analyzer().frame(p.grid());
        let onset = prepared(&f).onset;
        // 20° from x = 1.0: row 21 (1.05-1.10 m) has its mean at 1.075 m, 2.7 cm up,
        // under the 3 cm threshold; row 22's mean (1.125 m) is 4.5 cm up.
        for (iy, o) in onset.iter().enumerate() {
            match f.region[iy] {
                Region::Belly => assert_eq!(*o, None),
                _ => assert_eq!(
                    *o,
                    Some(Onset {
                        ix: 22,
                        dir: Dir::Up
                    }),
                    "strip {iy}"
                ),
            }
        }
    }

    #[test]
    fn the_affected_tracks_are_those_whose_strips_rise() {
        let p = analysed(vec![]);
        let f = p.analyzer().frame(p.grid());
        assert_eq!(affected_tracks(&f, &prepared(&f).onset), None);

        let p = analysed(vec![Element::ramp(1.0, 0.45, 15.0, 0.0, LEFT_TRACK)]);
        let f = p.analyzer().frame(p.grid());
        let a = affected_tracks(&f, &prepared(&f).onset).unwrap();
        assert_eq!((a.dir, a.left, a.right), (Dir::Up, true, false));
    }

    #[test]
    fn two_different_faces_leave_the_nearer_one() {
        let right = Extent::Band {
            from_m: -0.7,
            to_m: -0.2,
        };
        let p = analysed(vec![
            Element::ramp(1.0, 0.45, 15.0, 0.0, LEFT_TRACK),
            Element::ramp(1.5, -0.45, 22.0, 0.0, right),
        ]);
        let f = p.analyzer().frame(p.grid());
        let mut sc = prepared(&f);
        let both = affected_tracks(&f, &sc.onset).unwrap();
        assert!(both.left && both.right);
        let g = Ground {
            z: &sc.z,
            usable: &sc.usable,
        };
        let (a, plane) = one_face_or_nearer(&f, &g, &sc.onset, &mut sc.selection, both);
        assert!(a.left && !a.right, "{a:?}");
        // The face returned is the left ramp's: toe 1.0 m, 15°.
        let plane = plane.unwrap().plane;
        assert!((plane.toe_x(0.45) - 1.0).abs() < 0.02, "{plane:?}");
        assert!((plane.gradient_deg() - 15.0).abs() < 0.5, "{plane:?}");
    }

    #[test]
    fn a_face_running_out_of_view_is_told_from_one_seen_whole() {
        // An 18° ramp from 1.2 m rises out of the default camera's image at about
        // 2.5 m; capped 10 cm high, its top and the flat beyond are seen. Neither ends
        // in a shadow: the first at the horizon, the second not at all.
        for (cap_m, to_view_end) in [(None, true), (Some(0.1), false)] {
            let ramp = Element::ramp(1.2, 0.0, 18.0, 0.0, Extent::Full).capped(cap_m);
            let p = analysed(vec![ramp]);
            let f = p.analyzer().frame(p.grid());
            let face = fitted(&f);
            assert_eq!(face.to_view_end, to_view_end, "cap {cap_m:?}: {face:?}");
            assert!(!face.in_shadow, "cap {cap_m:?}: {face:?}");
        }
        // A 25 cm wall 10 cm thick across the corridor 2.5 m out, its front fitted as a
        // face: the ground behind it, to the corridor's end, lies in its shadow.
        let wall = Element::Block {
            x_m: 2.5,
            y_m: 0.0,
            length_m: 0.1,
            width_m: 2.0,
            height_m: 0.25,
        };
        let p = analysed(vec![wall]);
        let f = p.analyzer().frame(p.grid());
        let face = fitted(&f);
        assert!(face.to_view_end && face.in_shadow, "{face:?}");
    }

    #[test]
    fn a_strip_still_rising_where_its_view_ends_gives_its_climb_s_foot() {
        // A camera 0.6 m high pitched 45° sees level ground to 1.38 m (its image's top
        // edge 23.5° down). A 25° ramp from 0.8 m under the left track meets that ray
        // 1.08 m out, 13 cm up: its strips climb into the cut cells from the toe.
        // Capped 4.5 cm up, the ramp levels off before the cut, under rough ground's
        // peak to peak over the ground before it: no climb into the cut.
        let mut config = Config::default();
        (config.mount.z_m, config.mount.pitch_deg) = (0.6, 45.0);
        for (cap_m, rises) in [(None, true), (Some(0.045), false)] {
            let ramp = Element::ramp(0.8, 0.45, 25.0, 0.0, LEFT_TRACK).capped(cap_m);
            let frame = sim::render(&Terrain::new(vec![ramp]), &config);
            let mut p = Pipeline::new(config.clone()).unwrap();
            p.process(&frame).unwrap();
            let f = p.analyzer().frame(p.grid());
            let sc = prepared(&f);
            let iy = (0..f.spec.ny)
                .find(|&iy| (f.spec.y_centre(iy) - 0.475).abs() < 1e-3)
                .unwrap();
            let o = sc.onset[iy].expect("the ramp's strip rises");
            let base = ground_before(&f, &sc.z, iy, o.ix);
            let foot = climb_into_cut(&f, &sc.z, iy, o.ix, base);
            if rises {
                let foot = foot.expect("the strip climbs into the cut");
                assert!((0.8..=0.9).contains(&foot), "{foot}");
            } else {
                assert_eq!(foot, None, "cap {cap_m:?}");
            }
        }
    }

    #[test]
    fn the_gradient_uncertainty_follows_its_formula_by_hand() {
        // σ = 5 mm, 4 mm of it past the 3 mm noise floor, over a run of 0.16 m: a
        // slope error of 0.004 / √(0.16 · 0.16) = 0.025 rad, 1.432° on level ground;
        // cos²(45°) halves it at 45°.
        assert!((gradient_sd_deg(0.0, 0.005, 0.16) - 1.432).abs() < 1e-3);
        assert!((gradient_sd_deg(45.0, 0.005, 0.16) - 0.716).abs() < 1e-3);
        // Four times the run, half the error; under 0.1 m, as 0.1 m.
        let long = gradient_sd_deg(20.0, 0.011, 0.64);
        assert!((2.0 * long - gradient_sd_deg(20.0, 0.011, 0.16)).abs() < 1e-9);
        assert_eq!(
            gradient_sd_deg(20.0, 0.011, 0.02),
            gradient_sd_deg(20.0, 0.011, 0.1)
        );
        // Smooth ground, or the cells' noise alone: nothing.
        assert_eq!(gradient_sd_deg(25.0, 0.003, 0.2), 0.0);
    }

    #[test]
    fn the_noise_uncertainty_follows_its_formula_by_hand() {
        // Cells at 0, 0.05, 0.1 and 0.15 m along the gradient: √(2·0.075² + 2·0.025²)
        // = 0.1118 m.
        let cells = [0.0, 0.05, 0.1, 0.15];
        let sums = cells
            .iter()
            .fold((0.0, 0.0, 0.0), |(n, s, q), u| (n + 1.0, s + u, q + u * u));
        let along = along_spread(sums);
        assert!((along - 0.0125f64.sqrt()).abs() < 1e-12, "{along}");
        assert_eq!(along_spread((0.0, 0.0, 0.0)), 0.0);
        // A face 5 mm about its plane on ground 3 mm about its own: 4 mm of noise
        // over 0.1 m, 0.04 rad, 2.292° on level ground, cos²(30°) of it at 30°.
        let level = noise_sd_deg(0.0, 0.005, 0.003, 0.1);
        assert!((level - 2.2918).abs() < 1e-3, "{level}");
        assert!((noise_sd_deg(30.0, 0.005, 0.003, 0.1) - 0.75 * level).abs() < 1e-9);
        // At least the 3 mm floor: a face as smooth as the ground before it, or
        // smoother, still 0.03 rad over 0.1 m.
        let floor = (0.03f64).to_degrees();
        assert!((noise_sd_deg(0.0, 0.0015, 0.0, 0.1) - floor).abs() < 1e-9);
        assert!((noise_sd_deg(0.0, 0.011, 0.011, 0.1) - floor).abs() < 1e-9);
    }

    #[test]
    fn two_faces_are_told_against_noise_by_16_cells_and_rough_ground_by_up_to_50() {
        // 406 cells, 6 left for the variance: own 400·v, the F ratio (joint − own)/3/v.
        let (n, f) = (406, |v: f64, ratio: f64| {
            (400.0 * v, 400.0 * v + 3.0 * v * ratio)
        });
        // Cells within the 3 mm floor: 30·16 = 480, as before rough ground counted;
        // under it, the ratio is taken against the floor.
        let floor = 0.003f64 * 0.003;
        for own in [400.0 * floor, 200.0 * floor] {
            assert!(same_face(own, own + 3.0 * floor * 479.0, n));
            assert!(!same_face(own, own + 3.0 * floor * 481.0, n));
        }
        // 6 mm: three quarters of the variance rough ground's, 16 + 34·0.75 = 41.5
        // cells, a limit of 1,245.
        let v = 0.006f64 * 0.006;
        let (own, joint) = f(v, 1244.0);
        assert!(same_face(own, joint, n));
        let (own, joint) = f(v, 1246.0);
        assert!(!same_face(own, joint, n));
        // Far rougher: the limit tends to 30·50.
        let v = 0.1f64 * 0.1;
        let (own, joint) = f(v, 1499.0);
        assert!(same_face(own, joint, n));
        let (own, joint) = f(v, 1500.0);
        assert!(!same_face(own, joint, n));
    }

    #[test]
    fn the_face_fit_recovers_the_ramp_and_its_toe_line() {
        let p = analysed(vec![Element::ramp(1.2, 0.0, 18.0, 20.0, Extent::Full)]);
        let f = p.analyzer().frame(p.grid());
        let face = fitted(&f);
        let plane = face.plane;
        assert!((plane.gradient_deg() - 18.0).abs() < 0.3, "{plane:?}");
        // Clean: the cells lie on the plane within a few millimetres, and the fit
        // reaches well past the toe.
        assert!(face.spread_m < 0.004 && face.run_m > 0.5, "{face:?}");
        assert!((plane.toe_x(0.0) - 1.2).abs() < 0.01, "{plane:?}");
        assert!(((plane.b / plane.a).atan().to_degrees() - 20.0).abs() < 0.5);
    }

    #[test]
    fn a_rounded_toe_is_measured_past_its_rounding() {
        // An 18° ramp from 1.2 m and a -12° descent from 1.1 m, their toes sharp or
        // rounded over 0.35 m: a parabola from 0.175 m before the toe line to 0.175 m
        // past it, which stands tan(gradient) · 0.35 / 8 off the face at the toe line
        // (1.4 and 0.9 cm). The plane of every cell the fit takes reads a rounded toe
        // 3.8 mm early and the face 0.04-0.08° shallow; the face's plane, fitted past
        // the rounding, reads both within 1 mm and 0.02°. A sharp toe's face is the
        // fit's.
        for (toe, gradient) in [(1.2, 18.0), (1.1, -12.0)] {
            for round in [None, Some(0.35)] {
                let ramp = Element::ramp(toe, 0.0, gradient, 0.0, Extent::Full).toe_rounded(round);
                let p = analysed(vec![ramp]);
                let f = p.analyzer().frame(p.grid());
                let mut sc = prepared(&f);
                let g = Ground {
                    z: &sc.z,
                    usable: &sc.usable,
                };
                let dir = if gradient > 0.0 { Dir::Up } else { Dir::Down };
                let face = fit_face(
                    &f,
                    &g,
                    &sc.onset,
                    &mut sc.selection,
                    both_tracks(dir),
                    false,
                )
                .unwrap()
                .past_rounding(&f, &g, &mut sc.selection, dir);
                let (plane, fit) = (face.plane, face.fit);
                let case = format!("{gradient}° rounded {round:?}: {plane:?}, fit {fit:?}");
                assert!((plane.toe_x(0.0) - toe).abs() < 0.001, "{case}");
                assert!(
                    (plane.gradient_deg() - gradient.abs()).abs() < 0.02,
                    "{case}"
                );
                if round.is_some() {
                    assert!(fit.toe_x(0.0) < toe - 0.003, "{case}");
                    assert!(fit.gradient_deg() < gradient.abs() - 0.03, "{case}");
                } else {
                    assert_eq!(plane, fit, "{case}");
                }
            }
        }
    }

    #[test]
    fn a_rounded_toe_seen_over_a_short_face_is_measured_by_the_fit() {
        // The same ramp from 2.65 m: the corridor ends 0.35 m past its toe line, under
        // twice the rounding's reach, too short a face to carry a plane back from.
        let ramp = Element::ramp(2.65, 0.0, 18.0, 0.0, Extent::Full).toe_rounded(Some(0.35));
        let p = analysed(vec![ramp]);
        let f = p.analyzer().frame(p.grid());
        let face = fitted(&f);
        assert_eq!(face.plane, face.fit, "{face:?}");
        assert!(face.run_m < 0.4, "{face:?}");
    }

    #[test]
    fn a_rounded_toe_on_rough_ground_is_measured_by_the_fit() {
        // Rough ground's bumps (±2.5 cm) hide a rounding's centimetre: the face is
        // the fit's, whatever the rounding.
        let rough = Element::Rough {
            amplitude_m: 0.025,
            correlation_m: 0.15,
            seed: 7,
        };
        let ramp = Element::ramp(1.2, 0.0, 18.0, 0.0, Extent::Full).toe_rounded(Some(0.35));
        let p = analysed(vec![rough, ramp]);
        let f = p.analyzer().frame(p.grid());
        let face = fitted(&f);
        assert_eq!(face.plane, face.fit, "{face:?}");
        assert!((face.plane.toe_x(0.0) - 1.2).abs() < 0.04, "{face:?}");
    }

    #[test]
    fn a_low_steps_toe_line_runs_through_the_onsets_near_edges() {
        let step = Element::Step {
            x_m: 1.3,
            height_m: 0.08,
            extent: Extent::Full,
        };
        let p = analysed(vec![step]);
        let f = p.analyzer().frame(p.grid());
        let onset = prepared(&f).onset;
        let a = affected_tracks(&f, &onset).unwrap();
        let (x, alpha) = step_toe(&f, &onset, a, 0.0);
        assert!((x - 1.3).abs() < 0.03 && alpha.abs() < 0.5, "{x} {alpha}");
    }

    #[test]
    fn workcases_follow_direction_tracks_and_diagonal() {
        let a = |dir, left, right| Affected { dir, left, right };
        assert_eq!(workcase(a(Dir::Up, true, true), false), 2);
        assert_eq!(workcase(a(Dir::Up, true, false), false), 3);
        assert_eq!(workcase(a(Dir::Up, true, false), true), 4);
        assert_eq!(workcase(a(Dir::Up, false, true), false), 5);
        assert_eq!(workcase(a(Dir::Up, false, true), true), 6);
        assert_eq!(workcase(a(Dir::Up, true, true), true), 7);
        assert_eq!(workcase(a(Dir::Down, true, true), true), 8);
        assert_eq!(workcase(a(Dir::Down, true, false), false), 9);
        assert_eq!(workcase(a(Dir::Down, false, true), false), 10);
    }
}
