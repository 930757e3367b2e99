//! One frame through every stage: fused projection/transform/binning, voxel
//! centroids and ground cells, crossing analysis, feature analysis. Every buffer is
//! sized from the configuration at construction; [`Pipeline::process`] allocates
//! nothing (the `no_alloc` test proves it with a counting allocator).

use std::time::Instant;

use rover_terrain_drivers::DepthFrame;

use crate::analysis::Analyzer;
use crate::config::Config;
use crate::grid::{GridSpec, VoxelGrid};
use crate::memory::odometry::Untrusted;
use crate::memory::{MemoryState, Motion, TerrainMemory};
use crate::mixed_pixels::MixedPixels;
use crate::projection::Projector;
use crate::verdict::Verdict;
use crate::Error;

/// The processing stage with its preallocated state.
#[derive(Debug, Clone)]
pub struct Pipeline {
    config: Config,
    projector: Projector,
    grid: VoxelGrid,
    analyzer: Analyzer,
    /// The terrain memory; `None` when `[memory] enabled = false`.
    memory: Option<TerrainMemory>,
    verdict: Verdict,
    min_mm: u16,
    max_mm: u16,
    mixed: MixedPixels,
    leveled: bool,
}

impl Pipeline {
    /// Build every table and buffer for `config` (already validated).
    pub fn new(config: Config) -> Result<Self, Error> {
        config.validate().map_err(|(key, why)| Error::Config {
            message: format!("{key}: {why}"),
        })?;
        let (w, h) = (config.camera.width as usize, config.camera.height as usize);
        let projector = Projector::new(&config, w, h);
        let spec = GridSpec::from_config(&config);
        let grid = VoxelGrid::new(spec, w * h);
        let mixed = MixedPixels::new(&projector, config.analysis.mixed_pixel_angle_deg);
        let analyzer = Analyzer::new(&config, spec, &projector)?;
        let memory = config.memory.enabled.then(|| {
            let mut m = TerrainMemory::new(&config, spec);
            m.set_view(analyzer.expected(), analyzer.regions());
            m
        });
        let min_mm = (config.camera.min_range_m * 1000.0)
            .ceil()
            .clamp(1.0, 65535.0) as u16;
        let max_mm = (config.camera.max_range_m * 1000.0)
            .floor()
            .clamp(1.0, 65535.0) as u16;
        Ok(Pipeline {
            config,
            projector,
            grid,
            analyzer,
            memory,
            verdict: Verdict::default(),
            min_mm,
            max_mm,
            mixed,
            leveled: false,
        })
    }

    /// Analyse from now on with the camera at this attitude (auto-level): rebuilds the
    /// ray tables and the analysis state for the new mount. Allocates; called only
    /// when the attitude changes, not per frame. Yaw and position stay configured.
    pub fn set_attitude(&mut self, a: crate::level::Attitude) -> Result<(), Error> {
        let mut config = self.config.clone();
        config.mount.pitch_deg = a.pitch_deg;
        config.mount.roll_deg = a.roll_deg;
        config.validate().map_err(|(key, why)| {
            Error::Setup(format!(
                "auto-level to pitch {:.1}°, roll {:.1}°: {key}: {why}",
                a.pitch_deg, a.roll_deg
            ))
        })?;
        let projector = Projector::new(&config, self.projector.width(), self.projector.height());
        let analyzer = Analyzer::new(&config, GridSpec::from_config(&config), &projector)?;
        // The view changed: what was out of view is not what is now.
        if let Some(m) = &mut self.memory {
            m.clear();
            m.set_view(analyzer.expected(), analyzer.regions());
        }
        self.projector = projector;
        self.analyzer = analyzer;
        self.config = config;
        self.leveled = true;
        Ok(())
    }

    /// The configuration in force.
    pub fn config(&self) -> &Config {
        &self.config
    }

    /// The verdict of the last frame processed.
    pub fn verdict(&self) -> &Verdict {
        &self.verdict
    }

    /// The voxel grid of the last frame (voxels and ground cells).
    pub fn grid(&self) -> &VoxelGrid {
        &self.grid
    }

    /// The analysis state (regions, expected cells).
    pub fn analyzer(&self) -> &Analyzer {
        &self.analyzer
    }

    /// The projector (ray tables and mount).
    pub fn projector(&self) -> &Projector {
        &self.projector
    }

    /// The ground cells the last frame was analysed on: the terrain memory's fused
    /// cells when the frame was fused, else the grid's.
    pub fn analysed_cells(&self) -> &[crate::grid::Cell] {
        match &self.memory {
            Some(m) if self.verdict.memory.state == MemoryState::Fused => m.cells(),
            _ => self.grid.cells(),
        }
    }

    /// The terrain memory, when enabled.
    pub fn memory(&self) -> Option<&TerrainMemory> {
        self.memory.as_ref()
    }

    /// Analyse one frame on its own (no odometry: the terrain memory, if enabled,
    /// starts again from this frame). A frame whose size is not the configured one is
    /// rejected, never analysed.
    pub fn process(&mut self, frame: &DepthFrame) -> Result<&Verdict, Error> {
        self.process_moved(frame, Err(Untrusted::NoOdometry))
    }

    /// Analyse one frame, the rover having moved by `motion` since the previous one:
    /// with the memory enabled and the motion trusted, the frame is fused with the
    /// remembered map and the analysis runs on the fused cells; otherwise the map
    /// starts again from this frame and the verdict is the frame's alone, saying why.
    pub fn process_moved(
        &mut self,
        frame: &DepthFrame,
        motion: Result<Motion, Untrusted>,
    ) -> Result<&Verdict, Error> {
        let t0 = Instant::now();
        if frame.width() != self.projector.width() || frame.height() != self.projector.height() {
            return Err(Error::FrameSize {
                seq: frame.seq,
                got_w: frame.width(),
                got_h: frame.height(),
                want_w: self.projector.width(),
                want_h: self.projector.height(),
            });
        }
        let v = &mut self.verdict;
        v.frame = frame.seq;
        v.mount = crate::verdict::MountUsed {
            pitch_deg: self.config.mount.pitch_deg as f32,
            roll_deg: self.config.mount.roll_deg as f32,
            from_accelerometer: self.leveled,
        };
        let stats = self.grid.bin(
            &self.projector,
            frame.pixels(),
            self.min_mm,
            self.max_mm,
            &self.mixed,
        );
        let t1 = Instant::now();
        self.grid.emit();
        let t2 = Instant::now();
        v.points_in = stats.points_in;
        v.points_binned = stats.points_binned;
        v.voxels = self.grid.voxels().len() as u32;
        v.timing_us.bin = (t1 - t0).as_secs_f32() * 1e6;
        v.timing_us.voxels = (t2 - t1).as_secs_f32() * 1e6;
        let (cells, remembered) = match &mut self.memory {
            None => {
                v.memory = crate::verdict::MemoryUse::default();
                (self.grid.cells(), None)
            }
            Some(memory) => match motion {
                Ok(m) => {
                    memory.advance(&m);
                    let remembered =
                        memory.fuse(self.grid.cells(), self.analyzer.expected(), self.grid.cut());
                    v.memory = crate::verdict::MemoryUse {
                        state: MemoryState::Fused,
                        reason: None,
                        remembered_cells: remembered,
                        remembered_confidence: memory.mean_confidence(),
                        remembered_hazards: 0,
                    };
                    (memory.cells(), Some(memory.confidence()))
                }
                Err(why) => {
                    // The frame alone; the map starts again from it.
                    memory.restart(self.grid.cells(), self.grid.cut());
                    v.memory = crate::verdict::MemoryUse {
                        state: MemoryState::SingleFrame,
                        reason: Some(why.as_str()),
                        ..Default::default()
                    };
                    (self.grid.cells(), None)
                }
            },
        };
        v.timing_us.memory = t2.elapsed().as_secs_f32() * 1e6;
        let view_end = (self.grid.cut(), self.grid.range_cut());
        self.analyzer.analyze(cells, remembered, view_end, v);
        if let Some(memory) = &mut self.memory {
            v.memory.remembered_hazards = memory.carry_hazards(v);
        }
        v.timing_us.total = t0.elapsed().as_secs_f32() * 1e6;
        Ok(&self.verdict)
    }
}
