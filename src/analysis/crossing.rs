//! Crossing possibility (paper §3.1, with ARCHITECTURE.md's fixes): slopes and steps
//! in the wheel tracks, anything too tall under the belly, and ground that should be
//! seen but is not (gaps, drop-offs).

use super::visibility::explained;
use super::{Frame, Region};
use crate::verdict::{Hazard, HazardKind, Verdict};

/// Steps and slopes in the wheel tracks.
///
/// Along each track strip, from every seen cell, find the first cell ahead whose mean
/// height differs by more than the wheel radius. If the slope between the two is at
/// or above the maximum, the terrain is impassable there: a *step* when the change
/// happens within two cells (≤ 0.1 m at the default voxel), a *slope* otherwise. A
/// change smaller than the wheel radius is climbable however steep (a low step); a
/// long climb is impassable only if it is steep.
pub fn steps_and_slopes(f: &Frame, strip: &mut Vec<(f32, f32)>, verdict: &mut Verdict) {
    let r = f.cfg.rover.wheel_radius_m as f32;
    let tan_max = (f.cfg.rover.max_slope_deg as f32).to_radians().tan();
    let vs = f.spec.voxel_m;
    for region in [Region::Left, Region::Right] {
        for iy in f.strips(region) {
            strip.clear();
            for ix in 0..f.spec.nx {
                let c = f.spec.cell(ix, iy);
                if f.seen[c] {
                    strip.push((f.cells[c].x, f.cells[c].z));
                }
            }
            for (i, &(xi, zi)) in strip.iter().enumerate() {
                for (j, &(xj, zj)) in strip.iter().enumerate().skip(i + 1) {
                    let (dx, dz) = (xj - xi, zj - zi);
                    if dz.abs() <= r {
                        continue;
                    }
                    if dx > 0.0 && dz.abs() >= tan_max * dx {
                        let kind = if dx <= 3.5 * vs {
                            Some((HazardKind::Step, 0.5 * (xi + xj)))
                        } else if sustained(&strip[i..=j]) {
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
    }
}

/// Whether every cell between the ends lies on the straight line between them
/// (within [`SLOPE_STRAIGHTNESS_M`]): a slope, not flat ground and a jump.
fn sustained(run: &[(f32, f32)]) -> bool {
    let (&(x0, z0), &(x1, z1)) = (
        run.first().expect("run has ends"),
        run.last().expect("run has ends"),
    );
    let k = (z1 - z0) / (x1 - x0);
    run.iter()
        .all(|&(x, z)| (z - (z0 + k * (x - x0))).abs() <= SLOPE_STRAIGHTNESS_M)
}

/// How far a cell may sit off the line for a run to count as one slope, metres.
const SLOPE_STRAIGHTNESS_M: f32 = 0.03;

/// Anything under the belly taller than the belly clearance above the higher of the
/// two wheel tracks at the same distance (the median height of each track's cells in
/// that row; a row with no track data borrows the nearest row within 3 cells, else
/// the ground plane z = 0).
pub fn belly(f: &Frame, values: &mut Vec<f32>, track_ref: &mut [[f32; 2]], verdict: &mut Verdict) {
    let clearance = f.cfg.rover.belly_clearance_m as f32;
    let s = f.spec;
    for (ix, row) in track_ref.iter_mut().enumerate() {
        for (k, region) in [Region::Left, Region::Right].into_iter().enumerate() {
            values.clear();
            for iy in f.strips(region) {
                let c = s.cell(ix, iy);
                if f.seen[c] {
                    values.push(f.cells[c].z);
                }
            }
            row[k] = median(values);
        }
    }
    for ix in 0..s.nx {
        let mut reference = f32::NEG_INFINITY;
        for k in 0..2 {
            let near = (0..=3usize)
                .flat_map(|d| [ix.checked_sub(d), Some(ix + d)])
                .flatten()
                .filter_map(|j| track_ref.get(j).map(|r| r[k]))
                .find(|v| !v.is_nan());
            if let Some(v) = near {
                reference = reference.max(v);
            }
        }
        if reference == f32::NEG_INFINITY {
            reference = 0.0;
        }
        for iy in f.strips(Region::Belly) {
            let c = s.cell(ix, iy);
            if f.seen[c] && f.cells[c].top - reference > clearance {
                verdict.add_hazard(Hazard {
                    kind: HazardKind::Belly,
                    side: Region::Belly.side(),
                    distance_m: s.origin[0] + ix as f32 * s.voxel_m,
                });
            }
        }
    }
}

fn median(values: &mut [f32]) -> f32 {
    if values.is_empty() {
        return f32::NAN;
    }
    values.sort_unstable_by(f32::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// Gaps: runs of cells the camera should see on flat ground, does not, and that are
/// not in the shadow of something seen in front of them.
///
/// A gap with no ground seen before it in its strip is unknown ground. A gap after
/// seen ground with nothing seen beyond it, or with ground beyond it lower than a
/// wheel radius below the ground before it, is a drop-off. A gap with ground beyond it at a
/// climbable level is the shadow of a low step down when that ground explains it (the
/// line of sight to the gap at the far ground's height passes below the near edge);
/// otherwise it is unknown ground.
pub fn gaps(f: &Frame, verdict: &mut Verdict) {
    let s = f.spec;
    let r = f.cfg.rover.wheel_radius_m as f32;
    let min_run = f.cfg.analysis.gap_min_cells as usize;
    for iy in 0..s.ny {
        let side = f.region[iy].side();
        let mut before: Option<f32> = None;
        let mut run: Option<(usize, usize)> = None; // (first ix, length)
        for ix in 0..=s.nx {
            let c = (ix < s.nx).then(|| s.cell(ix, iy));
            let seen_here = c.is_some_and(|c| f.seen[c]);
            let end = ix == s.nx;
            if seen_here || end {
                if let Some((start, len)) = run.take() {
                    if len >= min_run {
                        let after = c.filter(|_| seen_here).map(|c| f.cells[c].z);
                        let kind = match (before, after) {
                            (None, _) => Some(HazardKind::Unknown),
                            (Some(_), None) => Some(HazardKind::DropOff),
                            (Some(floor), Some(z)) if z < floor - r => Some(HazardKind::DropOff),
                            (Some(_), Some(z)) => {
                                let all_shadowed = (start..ix)
                                    .filter(|&j| {
                                        f.expected[s.cell(j, iy)] && !f.seen[s.cell(j, iy)]
                                    })
                                    .all(|j| explained(f, j, iy, z));
                                (!all_shadowed).then_some(HazardKind::Unknown)
                            }
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
                    before = Some(f.cells[c].z);
                }
                continue;
            }
            let c = s.cell(ix, iy);
            if !f.expected[c] {
                continue; // outside the view: neither seen nor a gap
            }
            if f.shadowed[c] {
                run = None; // a shadow: the cell is hidden by what is in front
                continue;
            }
            run = Some(match run {
                Some((start, len)) => (start, len + 1),
                None => (ix, 1),
            });
        }
    }
}
