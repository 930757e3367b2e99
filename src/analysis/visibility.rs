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
    let (w, h) = (projector.width() as f64, projector.height() as f64);
    let (near, far) = (
        config.camera.min_range_m + RANGE_MARGIN_M,
        config.camera.max_range_m - RANGE_MARGIN_M,
    );
    let vs = f64::from(spec.voxel_m);
    let mut out = vec![false; spec.cell_count()];
    for ix in 0..spec.nx {
        for iy in 0..spec.ny {
            let x0 = f64::from(spec.origin[0]) + ix as f64 * vs;
            let y0 = f64::from(spec.origin[1]) + iy as f64 * vs;
            let visible = [(0.0, 0.0), (vs, 0.0), (0.0, vs), (vs, vs)]
                .iter()
                .all(
                    |(dx, dy)| match projector.project(Vector3::new(x0 + dx, y0 + dy, 0.0)) {
                        Some((u, v, z)) => {
                            u >= 0.5
                                && v >= 0.5
                                && u <= w - 1.5
                                && v <= h - 1.5
                                && z >= near
                                && z <= far
                        }
                        None => false,
                    },
                );
            out[spec.cell(ix, iy)] = visible;
        }
    }
    out
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
