//! Pictures and point clouds of one analysed frame, for people on the bench
//! (`rover-terrain inspect`), and the validation plots (`rover-terrain validate`).
//!
//! - `depth.png`: the depth image false-coloured by range (turbo, near red), no data
//!   black; the frame's size.
//! - `topdown.png`: the corridor from above in the rover frame (forward up, left
//!   left): ground cells coloured by height, unseen cells the camera should see
//!   hatched, cells out of view dark; wheel tracks and belly band outlined; hazards
//!   marked where they are; the toe line drawn; the verdict written beside it; a
//!   scale bar. Size: [`topdown::size`].
//! - `side.png`: height against forward distance of the left track, the belly band
//!   and the right track, with the wheel radius and belly clearance marked.
//!   [`side::WIDTH`] × [`side::HEIGHT`].
//! - `cloud.pcd` (PCL, binary, `x y z rgb`) and `cloud.ply` (ASCII, `x y z` float and
//!   `red green blue` uchar): the voxel centroids in the rover frame, coloured by
//!   hazard: red in a hazard, amber on the feature's face past the toe line, grey-green
//!   elsewhere.

pub mod canvas;
pub mod cloud;
pub mod plots;
pub mod side;
pub mod topdown;

use std::path::{Path, PathBuf};

use rover_terrain_drivers::DepthFrame;

use crate::config::Config;
use crate::grid::{Cell, GridSpec, Voxel};
use crate::verdict::{HazardKind, Side, Verdict};
use crate::{Error, Pipeline};

use canvas::{rgb, Canvas};

/// Colour of a voxel in a hazard.
pub const HAZARD_RGB: [u8; 3] = [230, 30, 30];
/// Colour of a voxel on the feature's face.
pub const FEATURE_RGB: [u8; 3] = [255, 170, 0];
/// Colour of any other voxel.
pub const GROUND_RGB: [u8; 3] = [140, 190, 140];
/// How far past a hazard's near edge its voxels are marked, metres.
pub const HAZARD_DEPTH_M: f32 = 0.25;

/// What one analysed frame shows: the grid, the analysis and the verdict.
#[derive(Debug, Clone, Copy)]
pub struct Scene<'a> {
    /// The configuration in force.
    pub config: &'a Config,
    /// The grid's geometry.
    pub spec: &'a GridSpec,
    /// Ground cells, indexed by [`GridSpec::cell`].
    pub cells: &'a [Cell],
    /// Occupied voxels.
    pub voxels: &'a [Voxel],
    /// Cells the camera should see on flat ground.
    pub expected: &'a [bool],
    /// The verdict.
    pub verdict: &'a Verdict,
    /// The terrain memory (how long ago each cell was last seen), when enabled.
    pub memory: Option<&'a crate::memory::TerrainMemory>,
}

/// The class of a voxel for colouring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// In a hazard.
    Hazard,
    /// On the feature's face, past the toe line.
    Feature,
    /// Anything else.
    Ground,
}

impl Class {
    /// Its colour.
    pub fn rgb(self) -> [u8; 3] {
        match self {
            Class::Hazard => HAZARD_RGB,
            Class::Feature => FEATURE_RGB,
            Class::Ground => GROUND_RGB,
        }
    }
}

impl<'a> Scene<'a> {
    /// The scene of the frame `pipeline` last processed, whose verdict is `verdict`.
    pub fn of(pipeline: &'a Pipeline, verdict: &'a Verdict) -> Self {
        Scene {
            config: pipeline.config(),
            spec: pipeline.grid().spec(),
            cells: pipeline.analysed_cells(),
            voxels: pipeline.grid().voxels(),
            expected: pipeline.analyzer().expected(),
            verdict,
            memory: pipeline.memory(),
        }
    }

    /// For a cell out of the camera's view that the verdict took from the terrain
    /// memory: the travel since it was last seen, metres.
    pub fn remembered_travel(&self, ix: usize, iy: usize) -> Option<f32> {
        let i = self.spec.cell(ix, iy);
        if self.expected[i] || !self.seen(i) {
            return None;
        }
        let (_, travel) = self.memory?.age_at(ix, iy)?;
        (travel > 0.0).then_some(travel)
    }

    /// For a cell out of the camera's view that the verdict took from the terrain
    /// memory: its confidence, 0..=1 (1: just seen from near).
    pub fn remembered_confidence(&self, ix: usize, iy: usize) -> Option<f32> {
        let i = self.spec.cell(ix, iy);
        let k = *self.memory?.confidence().get(i)?;
        (k > 0.0 && !self.expected[i] && self.seen(i)).then_some(k)
    }

    /// Whether cell `i` has enough points to count as seen.
    pub fn seen(&self, i: usize) -> bool {
        self.cells[i].n >= self.config.analysis.min_points_per_cell
    }

    /// The side of the corridor a lateral position is on.
    pub fn side_of(&self, y: f32) -> Side {
        let b = self.config.rover.belly_half_width_m as f32;
        if y >= b {
            Side::Left
        } else if y <= -b {
            Side::Right
        } else {
            Side::Centre
        }
    }

    /// Lateral centre of a side, metres.
    pub fn side_centre(&self, side: Side) -> f32 {
        let mid = self.config.rover.track_centre_m() as f32;
        match side {
            Side::Left => mid,
            Side::Centre => 0.0,
            Side::Right => -mid,
        }
    }

    /// The toe line of a go verdict's feature: the lateral span it covers and the
    /// forward distance at each lateral position.
    pub fn toe_line(&self) -> Option<((f32, f32), impl Fn(f32) -> f32)> {
        let f = self.verdict.feature?;
        let d = f.distance_m?;
        let r = &self.config.rover;
        let (b, o) = (r.belly_half_width_m as f32, r.track_outer_m as f32);
        let (span, y_ref) = match f.workcase {
            3 | 4 | 9 => ((b, o), self.side_centre(Side::Left)),
            5 | 6 | 10 => ((-o, -b), self.side_centre(Side::Right)),
            _ => ((-o, o), 0.0),
        };
        let t = f.alpha_deg.unwrap_or(0.0).to_radians().tan();
        Some((span, move |y: f32| d - t * (y - y_ref)))
    }

    /// The class of a point at (x, y).
    pub fn class_at(&self, x: f32, y: f32) -> Class {
        let side = self.side_of(y);
        let half = self.spec.voxel_m / 2.0;
        for h in &self.verdict.hazards {
            let here = h.side == side
                || (h.side == Side::Centre
                    && matches!(h.kind, HazardKind::Unknown | HazardKind::Tilt));
            let far = match h.kind {
                // A slope or drop-off goes on; a step or rock has a near edge.
                HazardKind::Slope | HazardKind::DropOff => f32::INFINITY,
                _ => h.distance_m + HAZARD_DEPTH_M,
            };
            if here && x >= h.distance_m - half && x <= far {
                return Class::Hazard;
            }
        }
        if let Some(((lo, hi), toe)) = self.toe_line() {
            if (lo..=hi).contains(&y) && x >= toe(y) {
                return Class::Feature;
            }
        }
        Class::Ground
    }
}

/// The files [`write_frame_set`] wrote.
#[derive(Debug, Clone)]
pub struct FrameSet {
    /// `depth.png`.
    pub depth: PathBuf,
    /// `topdown.png`.
    pub topdown: PathBuf,
    /// `side.png`.
    pub side: PathBuf,
    /// `cloud.pcd`.
    pub pcd: PathBuf,
    /// `cloud.ply`.
    pub ply: PathBuf,
}

fn write(path: PathBuf, bytes: &[u8]) -> Result<PathBuf, Error> {
    std::fs::write(&path, bytes).map_err(|e| Error::Io {
        path: path.clone(),
        source: e,
    })?;
    Ok(path)
}

/// Write the pictures and clouds of one analysed frame into `dir` (created if needed).
pub fn write_frame_set(
    frame: &DepthFrame,
    scene: &Scene<'_>,
    dir: &Path,
) -> Result<FrameSet, Error> {
    std::fs::create_dir_all(dir).map_err(|e| Error::Io {
        path: dir.to_path_buf(),
        source: e,
    })?;
    Ok(FrameSet {
        depth: write(dir.join("depth.png"), &depth_png(frame, scene.config).png())?,
        topdown: write(dir.join("topdown.png"), &topdown::draw(scene).png())?,
        side: write(dir.join("side.png"), &side::draw(scene).png())?,
        pcd: write(dir.join("cloud.pcd"), &cloud::pcd(scene))?,
        ply: write(dir.join("cloud.ply"), &cloud::ply(scene))?,
    })
}

/// The depth image false-coloured by range (near red, far blue), no data black, with
/// a small range legend in the corner.
pub fn depth_png(frame: &DepthFrame, config: &Config) -> Canvas {
    let (w, h) = (frame.width() as u32, frame.height() as u32);
    let mut c = Canvas::new(w.max(1), h.max(1), rgb(0, 0, 0));
    let lo = config.camera.min_range_m * 1000.0;
    let hi = config.camera.max_range_m * 1000.0;
    for (i, &mm) in frame.pixels().iter().enumerate() {
        if mm == 0 {
            continue;
        }
        let t = 1.0 - (f64::from(mm) - lo) / (hi - lo);
        let (x, y) = ((i % frame.width()) as i32, (i / frame.width()) as i32);
        c.set(x, y, canvas::turbo(t));
    }
    let legend = format!(
        "{:.1} m (red) .. {:.1} m (blue), black = no data",
        config.camera.min_range_m, config.camera.max_range_m
    );
    if w > 300 && h > 20 {
        c.fill(
            2,
            h as i32 - 16,
            legend.len() as u32 * 6 + 6,
            14,
            rgb(0, 0, 0),
        );
        c.text(&legend, 5, h as i32 - 14, canvas::SMALL, rgb(255, 255, 255));
    }
    c
}
