//! Which corridor cells the camera should see, and whether an unseen cell is
//! explained by something in front of it.

use nalgebra::Vector3;

use super::Frame;
use crate::config::Config;
use crate::grid::GridSpec;
use crate::projection::Projector;

/// Margin kept from the range limits when deciding what should be seen, metres.
const RANGE_MARGIN_M: f64 = 0.1;

/// Cells whose whole ground square (z = 0) falls inside the image and the range
/// limits: on flat ground the camera must have points there.
pub fn expected_cells(spec: &GridSpec, projector: &Projector, config: &Config) -> Vec<bool> {
    let mut out = vec![false; spec.cell_count()];
    for ix in 0..spec.nx {
        for iy in 0..spec.ny {
            out[spec.cell(ix, iy)] = in_view(spec, projector, config, ix, iy, 0.0);
        }
    }
    out
}

/// Whether cell (ix, iy)'s whole square, at height `z` (metres, rover frame), falls
/// inside the image (half a pixel clear of its edges) and the range limits (kept
/// [`RANGE_MARGIN_M`] clear): each of its corners is [`point_in_view`].
pub fn in_view(
    spec: &GridSpec,
    projector: &Projector,
    config: &Config,
    ix: usize,
    iy: usize,
    z: f32,
) -> bool {
    let depths = view_depths(config);
    let vs = f64::from(spec.voxel_m);
    let x0 = f64::from(spec.origin[0]) + ix as f64 * vs;
    let y0 = f64::from(spec.origin[1]) + iy as f64 * vs;
    [(0.0, 0.0), (vs, 0.0), (0.0, vs), (vs, vs)]
        .iter()
        .all(|(dx, dy)| {
            point_in_view(
                projector,
                depths,
                Vector3::new(x0 + dx, y0 + dy, f64::from(z)),
            )
        })
}

/// The optical depths between which a point counts as in view, metres: the camera's
/// range limits, kept [`RANGE_MARGIN_M`] clear.
pub(crate) fn view_depths(config: &Config) -> (f64, f64) {
    (
        config.camera.min_range_m + RANGE_MARGIN_M,
        config.camera.max_range_m - RANGE_MARGIN_M,
    )
}

/// Whether rover-frame point `p` (metres) falls inside the image, half a pixel clear
/// of its edges, at an optical depth within `(near, far)` ([`view_depths`]).
pub(crate) fn point_in_view(
    projector: &Projector,
    (near, far): (f64, f64),
    p: Vector3<f64>,
) -> bool {
    projector
        .project(p)
        .is_some_and(|(u, v, d)| projector.in_image(u, v) && d >= near && d <= far)
}

/// Whether the camera's line of sight to the centre of cell (ix, iy) at height
/// `target_z` passes below a seen surface on the way: then the cell is in the shadow
/// of that surface, and its being unseen is explained.
pub fn explained(f: &Frame, ix: usize, iy: usize, target_z: f32) -> bool {
    let s = f.spec;
    let c = f.camera;
    let (gx, gy) = (s.x_centre(ix), s.y_centre(iy));
    let (dx, dy, dz) = (gx - c[0], gy - c[1], target_z - c[2]);
    let horizontal = dx.hypot(dy);
    let steps = ((horizontal / (0.5 * s.voxel_m)).ceil() as usize).max(1);
    let target = s.cell(ix, iy);
    for k in 1..steps {
        let t = k as f32 / steps as f32;
        let (x, y, z) = (c[0] + t * dx, c[1] + t * dy, c[2] + t * dz);
        if let Some((jx, jy)) = s.cell_at(x, y) {
            let j = s.cell(jx, jy);
            if j != target && f.seen[j] && f.cells[j].top >= z - 0.01 {
                return true;
            }
        }
    }
    false
}

/// The fixed lines of sight from the camera to every expected cell's centre on the
/// ground (z = 0): for each, the cells the line crosses with the line's lowest height
/// in each. Built once; tells per frame which unseen cells are in a shadow without
/// casting rays.
#[derive(Debug, Clone)]
pub struct ShadowPaths {
    start: Vec<u32>,
    entries: Vec<(u32, f32)>,
    /// Whether every line descends from the camera (the camera above the ground):
    /// then each path's heights only fall from its first entry to its last.
    descending: bool,
}

impl ShadowPaths {
    /// Trace the lines of sight of the expected cells.
    pub fn new(spec: &GridSpec, camera: [f32; 3], expected: &[bool]) -> Self {
        let mut start = Vec::with_capacity(spec.cell_count() + 1);
        let mut entries: Vec<(u32, f32)> = Vec::new();
        for ix in 0..spec.nx {
            for iy in 0..spec.ny {
                let target = spec.cell(ix, iy);
                start.push(entries.len() as u32);
                if !expected[target] {
                    continue;
                }
                let (gx, gy) = (spec.x_centre(ix), spec.y_centre(iy));
                let (dx, dy, dz) = (gx - camera[0], gy - camera[1], -camera[2]);
                let steps = ((dx.hypot(dy) / (0.25 * spec.voxel_m)).ceil() as usize).max(1);
                let first = entries.len();
                for k in 1..steps {
                    let t = k as f32 / steps as f32;
                    let (x, y, z) = (camera[0] + t * dx, camera[1] + t * dy, camera[2] + t * dz);
                    let Some((jx, jy)) = spec.cell_at(x, y) else {
                        continue;
                    };
                    let j = spec.cell(jx, jy) as u32;
                    if j as usize == target {
                        continue;
                    }
                    match entries[first..].last_mut() {
                        Some(last) if last.0 == j => last.1 = last.1.min(z),
                        _ => entries.push((j, z)),
                    }
                }
            }
        }
        start.push(entries.len() as u32);
        ShadowPaths {
            start,
            entries,
            descending: camera[2] >= 0.0,
        }
    }

    /// Whether the line of sight to `cell`'s ground crosses a cell flagged in `flags`.
    pub fn crosses(&self, cell: usize, flags: &[bool]) -> bool {
        let (a, b) = (self.start[cell] as usize, self.start[cell + 1] as usize);
        self.entries[a..b].iter().any(|&(j, _)| flags[j as usize])
    }

    /// Whether the line of sight to `cell`'s ground passes below the top of a seen cell
    /// (within 1 cm). `shade`: per cell, a seen cell's top and −∞ for one not seen;
    /// `highest`: the highest of them.
    pub fn shadowed(&self, cell: usize, shade: &[f32], highest: f32) -> bool {
        let (a, b) = (self.start[cell] as usize, self.start[cell + 1] as usize);
        // A line descending from the camera to the cell, walked back from the cell,
        // only rises: once it passes over the highest top, nothing farther back
        // reaches it.
        let reach = if self.descending {
            highest
        } else {
            f32::INFINITY
        };
        self.entries[a..b]
            .iter()
            .rev()
            .take_while(|&&(_, z)| z - 0.01 <= reach)
            .any(|&(j, z)| shade[j as usize] >= z - 0.01)
    }
}
