//! Obstacle feature (paper §3.2, with ARCHITECTURE.md's definitions): which of the ten
//! workcases the wheel tracks face, and the toe line's distance, the face's gradient
//! and the toe line's angle.
//!
//! 1. In each track strip, the *onset* is the first seen cell that rises (or falls)
//!    more than `rise_threshold_m` from the ground, confirmed by the next seen cell.
//! 2. A track is affected when at least half of its seen strips have an onset of the
//!    same direction; which tracks are affected, and how, gives the workcase family.
//! 3. The face is fitted as a plane `z = a·x + b·y + c` to the cells past the onsets
//!    (weighted by their point counts), iteratively: cells off the plane (the crest, a
//!    plateau) and cells that straddle the toe line are dropped, then the fit is
//!    extended to every consistent cell of the affected strips.
//! 4. The toe line is where the face meets the ground plane z = 0: its distance is
//!    read at the centre line (both tracks) or the affected track's centre; the
//!    gradient is the plane's steepest slope; alpha is `atan(b/a)`, positive when
//!    the toe line's left end is nearer. A face too steep to fit as a plane (a low
//!    step) is measured from the onsets, with a gradient of ±90°.

use super::crossing::ground_beside_face;
use super::plane::{Plane, PlaneFit};
use super::{Frame, Region};
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

/// Step 3: fit the face of the chosen tracks as a plane (see the module doc).
fn fit_face(
    f: &Frame,
    onset: &[Option<Onset>],
    use_cell: &mut [bool],
    dir: Dir,
    use_left: bool,
    use_right: bool,
) -> Option<Plane> {
    let s = f.spec;
    let threshold = f.cfg.analysis.rise_threshold_m as f32;
    let chosen = |iy: usize| chosen(f.region[iy], use_left, use_right);
    let candidate = |ix: usize, iy: usize| -> bool {
        let c = s.cell(ix, iy);
        chosen(iy)
            && matches!(onset[iy], Some(o) if o.dir == dir && ix >= o.ix)
            && f.seen[c]
            && status(height(f, c), threshold) == Some(dir)
    };
    let in_window = |ix: usize, iy: usize| match onset[iy] {
        Some(o) => s.x_centre(ix) <= s.x_centre(o.ix) + FIRST_WINDOW_M,
        None => false,
    };
    use_cell.fill(false);
    for ix in 0..s.nx {
        for iy in 0..s.ny {
            if candidate(ix, iy) && in_window(ix, iy) {
                use_cell[s.cell(ix, iy)] = true;
            }
        }
    }
    let vs = f64::from(s.voxel_m);
    let past_toe = |p: &Plane, ix: usize, iy: usize| {
        let x0 = f64::from(s.origin[0]) + ix as f64 * vs;
        let y0 = f64::from(s.origin[1]) + iy as f64 * vs;
        [(0.0, 0.0), (vs, 0.0), (0.0, vs), (vs, vs)]
            .iter()
            .all(|(dx, dy)| {
                let z = p.z(x0 + dx, y0 + dy);
                match dir {
                    Dir::Up => z > 0.0,
                    Dir::Down => z < 0.0,
                }
            })
    };
    let mut plane: Option<Plane> = None;
    for iteration in 0..10 {
        let mut fit = PlaneFit::default();
        let mut used = 0usize;
        for (c, cell) in f.cells.iter().enumerate() {
            if use_cell[c] {
                fit.add(
                    f64::from(cell.x),
                    f64::from(cell.y),
                    f64::from(height(f, c)),
                    f64::from(cell.n),
                );
                used += 1;
            }
        }
        let Some(p) = (used >= 3).then(|| fit.solve()).flatten() else {
            break;
        };
        let mut sq = 0.0;
        for (c, cell) in f.cells.iter().enumerate() {
            if use_cell[c] {
                let z = height(f, c);
                let r = f64::from(z) - p.z(f64::from(cell.x), f64::from(cell.y));
                sq += f64::from(cell.n) * r * r;
            }
        }
        let tol = MIN_TOLERANCE_M.max(3.0 * (sq / fit.weight()).sqrt());
        let mut changed = false;
        for ix in 0..s.nx {
            for iy in 0..s.ny {
                if !candidate(ix, iy) {
                    continue;
                }
                let c = s.cell(ix, iy);
                let cell = &f.cells[c];
                let z = height(f, c);
                let r = f64::from(z) - p.z(f64::from(cell.x), f64::from(cell.y));
                let ok =
                    r.abs() <= tol && past_toe(&p, ix, iy) && (iteration >= 2 || in_window(ix, iy));
                if ok != use_cell[c] {
                    use_cell[c] = ok;
                    changed = true;
                }
            }
        }
        plane = Some(p);
        if !changed && iteration >= 2 {
            break;
        }
    }
    plane
}

/// Whether two faces fitted to one track each are one face: their heights agree
/// within [`SAME_FACE_M`] at both track centres, at the distances where they rise.
fn same_face(l: &Plane, r: &Plane, tc: f64) -> bool {
    let x = 0.5 * (l.toe_x(tc) + r.toe_x(-tc)) + 0.3;
    [tc, -tc].iter().all(|&y| {
        (l.z(x, y) - r.z(x, y)).abs() <= SAME_FACE_M
            && (l.z(x + 0.3, y) - r.z(x + 0.3, y)).abs() <= SAME_FACE_M
    })
}

/// How far two one-track fits of one face may disagree in height, metres.
const SAME_FACE_M: f64 = 0.03;

/// A track cell's ground height: its mean, or beside a face along its strip (a
/// trench's wall, a ramp's side) the surface spread across the cell
/// ([`ground_beside_face`]).
fn height(f: &Frame, c: usize) -> f32 {
    let s = f.spec;
    let cell = &f.cells[c];
    ground_beside_face(cell, s.y_centre(c % s.ny), s.voxel_m).unwrap_or(cell.z)
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

/// The feature of a passable corridor.
pub fn analyse(f: &Frame, onset: &mut [Option<Onset>], use_cell: &mut [bool]) -> Feature {
    let s = f.spec;
    let threshold = f.cfg.analysis.rise_threshold_m as f32;
    // 1. Onsets per track strip.
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
            let st = status(height(f, c), threshold);
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
    // 2. Affected tracks.
    let summary = |region: Region| -> Option<(Dir, usize)> {
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
    };
    let (left, right) = (summary(Region::Left), summary(Region::Right));
    let (dir, use_left, use_right) = match (left, right) {
        (None, None) => return Feature::FLAT,
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
    let tc = 0.5 * (f.cfg.rover.belly_half_width_m + f.cfg.rover.track_outer_m);
    let (mut use_left, mut use_right) = (use_left, use_right);
    if use_left && use_right {
        // Both tracks rise (or fall): one face across both, or a different face
        // under each? Fit each alone; if they disagree, the nearer one is the feature.
        let l = fit_face(f, onset, use_cell, dir, true, false);
        let r = fit_face(f, onset, use_cell, dir, false, true);
        if let (Some(l), Some(r)) = (l, r) {
            if !same_face(&l, &r, tc) {
                if l.toe_x(tc) <= r.toe_x(-tc) {
                    use_right = false;
                } else {
                    use_left = false;
                }
            }
        }
    }
    let chosen = |iy: usize| chosen(f.region[iy], use_left, use_right);
    let plane = fit_face(f, onset, use_cell, dir, use_left, use_right);
    let vs = f64::from(s.voxel_m);
    // 4. Measures.
    let y_ref = match (use_left, use_right) {
        (true, true) => 0.0,
        (true, false) => tc,
        _ => -tc,
    };
    let sign = if dir == Dir::Up { 1.0 } else { -1.0 };
    let sloped = plane.filter(|p| p.a * sign > 0.0 && p.gradient_deg() >= MIN_FACE_DEG);
    let (distance, gradient, alpha) = match sloped {
        Some(p) => (
            p.toe_x(y_ref),
            sign * p.gradient_deg(),
            (p.b / p.a).atan().to_degrees(),
        ),
        None => {
            // A step: the toe line through the onsets' near edges.
            let mut fit = PlaneFit::default();
            for (iy, o) in onset.iter().enumerate() {
                if let Some(o) = o.filter(|o| o.dir == dir && chosen(iy)) {
                    let x = f64::from(s.x_centre(o.ix)) - 0.5 * vs;
                    // Fit x = q·y + x0 as a "plane" in (y, ·): reuse the line fit.
                    fit.add(f64::from(s.y_centre(iy)), 0.0, x, 1.0);
                }
            }
            match fit.solve() {
                Some(line) => (
                    line.a * y_ref + line.c,
                    sign * 90.0,
                    (-line.a).atan().to_degrees(),
                ),
                None => {
                    let x = onset
                        .iter()
                        .enumerate()
                        .filter_map(|(iy, o)| o.filter(|o| o.dir == dir && chosen(iy)))
                        .map(|o| f64::from(s.x_centre(o.ix)) - 0.5 * vs)
                        .fold(f64::INFINITY, f64::min);
                    (x, sign * 90.0, 0.0)
                }
            }
        }
    };
    let diagonal = alpha.abs() >= f.cfg.analysis.diagonal_min_deg;
    let workcase = match (dir, use_left, use_right) {
        (Dir::Up, true, true) => {
            if diagonal {
                7
            } else {
                2
            }
        }
        (Dir::Up, true, false) => {
            if diagonal {
                4
            } else {
                3
            }
        }
        (Dir::Up, _, _) => {
            if diagonal {
                6
            } else {
                5
            }
        }
        (Dir::Down, true, true) => 8,
        (Dir::Down, true, false) => 9,
        (Dir::Down, _, _) => 10,
    };
    // The nearest seen ground in the affected strips: a toe before it is not seen.
    let nearest_seen = (0..s.ny)
        .filter(|&iy| chosen(iy))
        .filter_map(|iy| (0..s.nx).find(|&ix| f.seen[s.cell(ix, iy)]))
        .map(|ix| f64::from(s.x_centre(ix)) - 0.5 * vs)
        .fold(f64::INFINITY, f64::min);
    Feature {
        workcase,
        toe_seen: distance >= nearest_seen - vs,
        distance_m: Some(distance as f32),
        gradient_deg: Some(gradient as f32),
        alpha_deg: matches!(workcase, 4 | 6 | 7).then_some(alpha as f32),
    }
}
