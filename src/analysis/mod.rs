//! Terrain analysis over the ground cells of one frame: pure functions over plain
//! data, no I/O. [`Analyzer`] holds what is fixed per configuration (which strips are
//! tracks or belly, which cells the camera should see) and scratch space sized once,
//! so analysing a frame allocates nothing.

mod crossing;
mod feature;
pub mod plane;
mod tilt;
mod visibility;

use std::time::Instant;

use crate::config::Config;
use crate::grid::{Cell, GridSpec, VoxelGrid};
use crate::projection::Projector;
use crate::verdict::{Decision, Hazard, HazardKind, SeenTo, Side, Verdict};
use crate::Error;

/// Which lateral band of the corridor a strip of cells lies in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Region {
    /// Right wheel track: `−track_outer ≤ y ≤ −belly_half_width`.
    Right,
    /// Under the belly: `|y| < belly_half_width`.
    Belly,
    /// Left wheel track: `belly_half_width ≤ y ≤ track_outer`.
    Left,
}

impl Region {
    /// The hazard side of this region.
    pub fn side(self) -> Side {
        match self {
            Region::Right => Side::Right,
            Region::Belly => Side::Centre,
            Region::Left => Side::Left,
        }
    }
}

/// One seen cell of a track strip, as the step and slope test reads it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StripCell {
    /// Mean x of the cell's points, metres.
    pub x: f32,
    /// The cell's height, metres: the one of its surfaces (crest or foot) that
    /// continues the strip, or for a cell past the horizon its top (a lower bound on
    /// what stands there).
    pub z: f32,
    /// Cell row.
    pub ix: usize,
    /// Whether the cell is at or past the sensor's horizon ([`Frame::past`]).
    pub past: bool,
}

/// Per-frame analysis state, sized once from the configuration.
#[derive(Debug, Clone)]
pub struct Analyzer {
    cfg: Config,
    spec: GridSpec,
    region: Vec<Region>,
    expected: Vec<bool>,
    expected_count: usize,
    camera: [f32; 3],
    paths: visibility::ShadowPaths,
    // Scratch, reused every frame.
    seen: Vec<bool>,
    shadowed: Vec<bool>,
    beyond: Vec<bool>,
    past: Vec<bool>,
    strip: Vec<StripCell>,
    values: Vec<f32>,
    track_ref: Vec<[f32; 2]>,
    surface: Vec<f32>,
    profile: Vec<[f32; 2]>,
    onset: Vec<Option<feature::Onset>>,
    use_cell: Vec<bool>,
}

/// Everything the analysis functions read about one frame.
pub(crate) struct Frame<'a> {
    pub spec: &'a GridSpec,
    pub cells: &'a [Cell],
    pub seen: &'a [bool],
    /// Expected, unseen, and in the shadow of something seen (see
    /// [`visibility::explained`]).
    pub shadowed: &'a [bool],
    /// Cells at or past the sensor's horizon: the image's top edge cuts through them,
    /// or through a cell in front of them (along their strip or their line of
    /// sight). What is seen of them is only what lies below the edge: their height is
    /// a lower bound.
    pub past: &'a [bool],
    /// Expected, unseen, and beyond the sensor's horizon: the line of sight to them
    /// crosses a cell where the surface leaves the image.
    pub beyond: &'a [bool],
    pub expected: &'a [bool],
    pub region: &'a [Region],
    pub cfg: &'a Config,
    pub camera: [f32; 3],
}

impl Frame<'_> {
    /// Strips (iy) of one region.
    pub fn strips(&self, r: Region) -> impl Iterator<Item = usize> + '_ {
        self.region
            .iter()
            .enumerate()
            .filter(move |(_, &q)| q == r)
            .map(|(i, _)| i)
    }
}

impl Analyzer {
    /// Prepare the analysis for `config`'s corridor as seen through `projector`.
    /// Fails when the camera, as mounted, sees none of the corridor.
    pub fn new(config: &Config, spec: GridSpec, projector: &Projector) -> Result<Self, Error> {
        let bhw = config.rover.belly_half_width_m as f32;
        let region: Vec<Region> = (0..spec.ny)
            .map(|iy| {
                let y = spec.y_centre(iy);
                if y.abs() < bhw {
                    Region::Belly
                } else if y > 0.0 {
                    Region::Left
                } else {
                    Region::Right
                }
            })
            .collect();
        let expected = visibility::expected_cells(&spec, projector, config);
        let expected_count = expected.iter().filter(|&&e| e).count();
        let paths = visibility::ShadowPaths::new(&spec, projector.origin(), &expected);
        if expected_count == 0 {
            return Err(Error::Setup(
                "the camera, as mounted, sees none of the corridor on flat ground; check [mount] and [camera]".into(),
            ));
        }
        Ok(Analyzer {
            cfg: config.clone(),
            spec,
            region,
            expected,
            expected_count,
            camera: projector.origin(),
            paths,
            seen: vec![false; spec.cell_count()],
            shadowed: vec![false; spec.cell_count()],
            beyond: vec![false; spec.cell_count()],
            past: vec![false; spec.cell_count()],
            strip: Vec::with_capacity(spec.nx),
            values: Vec::with_capacity(spec.ny),
            track_ref: vec![[f32::NAN; 2]; spec.nx],
            surface: vec![f32::NAN; spec.cell_count()],
            profile: vec![[f32::NAN; 2]; spec.nx],
            onset: vec![None; spec.ny],
            use_cell: vec![false; spec.cell_count()],
        })
    }

    /// How far each band is seen: per strip, the near edge of the first expected
    /// cell past the horizon, or the far edge of its last expected cell; the nearest
    /// over the band's strips.
    fn seen_to(&self) -> SeenTo {
        let s = &self.spec;
        let mut out = [f32::INFINITY; 3];
        for iy in 0..s.ny {
            let mut last = None;
            let mut to = None;
            for ix in 0..s.nx {
                let c = s.cell(ix, iy);
                if !self.expected[c] {
                    continue;
                }
                if self.past[c] {
                    to = Some(s.x_centre(ix) - 0.5 * s.voxel_m);
                    break;
                }
                last = Some(s.x_centre(ix) + 0.5 * s.voxel_m);
            }
            let k = match self.region[iy] {
                Region::Left => 0,
                Region::Belly => 1,
                Region::Right => 2,
            };
            if let Some(x) = to.or(last) {
                out[k] = out[k].min(x);
            }
        }
        let fin = |v: f32| if v.is_finite() { v } else { 0.0 };
        SeenTo {
            left: fin(out[0]),
            centre: fin(out[1]),
            right: fin(out[2]),
        }
    }

    /// Cells the camera should see on flat ground, indexed by [`GridSpec::cell`].
    pub fn expected(&self) -> &[bool] {
        &self.expected
    }

    /// The region of each strip iy.
    pub fn regions(&self) -> &[Region] {
        &self.region
    }

    /// Analyse the grid's cells into `verdict` (decision, feature, hazards, seen
    /// fraction, crossing and feature timings).
    pub fn analyze(&mut self, grid: &VoxelGrid, verdict: &mut Verdict) {
        let t0 = Instant::now();
        verdict.hazards.clear();
        verdict.feature = None;
        let min_pts = self.cfg.analysis.min_points_per_cell;
        let mut seen_expected = 0usize;
        let mut nearest_unseen = f32::INFINITY;
        for (i, (s, c)) in self.seen.iter_mut().zip(grid.cells()).enumerate() {
            *s = c.n >= min_pts;
            if self.expected[i] {
                if *s {
                    seen_expected += 1;
                } else {
                    let ix = i / self.spec.ny;
                    nearest_unseen = nearest_unseen.min(ix as f32 * self.spec.voxel_m);
                }
            }
        }
        verdict.seen_fraction = seen_expected as f32 / self.expected_count as f32;
        // Unseen cells past the sensor's horizon (the surface left the image in front
        // of them) and unseen cells hidden behind something seen: the camera could not
        // see them.
        let cut = grid.cut();
        // Past the horizon: a cell the top edge cuts, every cell behind one along its
        // strip, and every cell whose line of sight crosses one. Most frames cut no
        // cell (the top rows look past the corridor): then nothing is past.
        let any_cut = cut.contains(&true);
        for iy in 0..self.spec.ny {
            let mut past = false;
            for ix in 0..self.spec.nx {
                let i = self.spec.cell(ix, iy);
                past |= cut[i];
                self.past[i] = past || (any_cut && self.expected[i] && self.paths.crosses(i, cut));
            }
        }
        let mut hidden = 0usize;
        for i in 0..self.shadowed.len() {
            let unseen = self.expected[i] && !self.seen[i];
            self.beyond[i] = unseen && self.past[i];
            self.shadowed[i] =
                unseen && !self.beyond[i] && self.paths.shadowed(i, &self.seen, grid.cells());
            hidden += usize::from(self.beyond[i] || self.shadowed[i]);
        }
        let visible = self.expected_count - hidden;
        verdict.seen_to_m = self.seen_to();
        let seen_of_visible = if visible == 0 {
            0.0
        } else {
            seen_expected as f32 / visible as f32
        };
        let frame = Frame {
            spec: &self.spec,
            cells: grid.cells(),
            seen: &self.seen,
            shadowed: &self.shadowed,
            past: &self.past,
            beyond: &self.beyond,
            expected: &self.expected,
            region: &self.region,
            cfg: &self.cfg,
            camera: self.camera,
        };
        crossing::steps_and_slopes(&frame, &mut self.strip, &mut self.surface, verdict);
        tilt::track_profile(&frame, &self.surface, &mut self.values, &mut self.profile);
        tilt::fill(&mut self.profile, |ix| self.spec.x_centre(ix));
        verdict.tilt = tilt::predict(&frame, &self.profile, verdict);
        crossing::belly(&frame, &mut self.values, &mut self.track_ref, verdict);
        crossing::gaps(&frame, verdict);
        let t1 = Instant::now();
        verdict.timing_us.crossing = (t1 - t0).as_secs_f32() * 1e6;

        let stop = verdict
            .hazards
            .iter()
            .any(|h| h.kind != HazardKind::Unknown);
        // Too little seen of what nothing hides: the camera is blind, not occluded.
        let too_little = seen_of_visible < self.cfg.analysis.min_seen_fraction as f32;
        if too_little {
            verdict.add_hazard(Hazard {
                kind: HazardKind::Unknown,
                side: Side::Centre,
                distance_m: if nearest_unseen.is_finite() {
                    nearest_unseen
                } else {
                    0.0
                },
            });
        }
        verdict
            .hazards
            .sort_unstable_by(|a, b| a.distance_m.total_cmp(&b.distance_m));
        verdict.decision = if stop {
            Decision::Stop
        } else if too_little || !verdict.hazards.is_empty() {
            Decision::Unknown
        } else {
            Decision::Go
        };
        if verdict.decision == Decision::Go {
            verdict.feature = Some(feature::analyse(
                &frame,
                &mut self.onset,
                &mut self.use_cell,
            ));
        }
        verdict.timing_us.feature = t1.elapsed().as_secs_f32() * 1e6;
    }
}
