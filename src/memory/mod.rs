//! Terrain memory: a rover-centred map of ground cells that moves with the rover's
//! odometry, so that what the camera saw stays known as it passes into the blind zone
//! before the wheels (or out of the field of view to the side).
//!
//! - [`odometry::Tracker`] turns the controller's wrapping odometry counters into the
//!   motion between two frames, and refuses motion it cannot trust (none for too
//!   long, or a jump faster than the rover can go).
//! - [`TerrainMemory`] holds the map: the analysis grid's cells plus rows behind the
//!   rover origin and columns beside the corridor, allocated once. Each frame it is
//!   moved by the motion (every remembered cell keeps its points' centroid, moved
//!   exactly, and lands in the cell that centroid now falls in: no drift however
//!   small the steps), the new frame's seen cells replace what was remembered there,
//!   and the cells the camera cannot see now (outside its view) are filled from
//!   memory when they were seen by at least `min_frames` frames at a consistent
//!   height, within `max_travel_m` of travel and `max_age_s`.
//!
//! What the camera sees now always wins: a cell seen now is the frame's, and a cell
//! the camera should see now but does not is not filled (a hole, a shadow or a gap is
//! judged from the frame). The memory never invents ground it has not seen, and it
//! only remembers ground seen more than once. A hazard several verdicts in a row
//! reported is not lost to the first frames that miss it in view: it is kept until as
//! many have, and a rover standing where a verdict reported one holds it for a second
//! after ([`TerrainMemory::carry_hazards`]).

pub mod odometry;

use crate::analysis::Region;
use crate::config::Config;
use crate::grid::{Cell, GridSpec};
pub use crate::verdict::MemoryState;
use crate::verdict::{Decision, Hazard, HazardKind, Side, Verdict, MAX_HAZARDS};

/// The rover's motion between two frames, in the earlier frame's rover coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Motion {
    /// Travel along the rover's x axis, metres.
    pub forward_m: f32,
    /// Travel along its y axis (left positive), metres.
    pub lateral_m: f32,
    /// Heading change, radians, counter-clockwise positive.
    pub dheading_rad: f32,
    /// Time between the two frames, seconds.
    pub dt_s: f32,
}

impl Motion {
    /// Where a point at `p` (earlier rover frame) lies in the later rover frame,
    /// metres: the rover moved by (forward, lateral), then turned by the heading
    /// change.
    pub fn apply(&self, p: [f32; 2]) -> [f32; 2] {
        Rigid::of(self).apply(p)
    }

    /// The inverse of [`Motion::apply`]: where a point of the later frame was in the
    /// earlier one.
    pub fn unapply(&self, q: [f32; 2]) -> [f32; 2] {
        Rigid::of(self).unapply(q)
    }
}

/// A motion's rigid transform with its sine and cosine worked out once (the map
/// moves thousands of points per frame).
#[derive(Debug, Clone, Copy)]
struct Rigid {
    s: f32,
    c: f32,
    t: [f32; 2],
}

impl Rigid {
    fn of(m: &Motion) -> Self {
        let (s, c) = m.dheading_rad.sin_cos();
        Rigid {
            s,
            c,
            t: [m.forward_m, m.lateral_m],
        }
    }

    fn apply(&self, p: [f32; 2]) -> [f32; 2] {
        let (dx, dy) = (p[0] - self.t[0], p[1] - self.t[1]);
        [self.c * dx + self.s * dy, -self.s * dx + self.c * dy]
    }

    fn unapply(&self, q: [f32; 2]) -> [f32; 2] {
        [
            self.c * q[0] - self.s * q[1] + self.t[0],
            self.s * q[0] + self.c * q[1] + self.t[1],
        ]
    }
}

/// One remembered map cell.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Remembered {
    /// The cell's statistics; `n == 0` when nothing is remembered.
    cell: Cell,
    /// Frames that saw it at a consistent height, in a row.
    frames: u16,
    /// The points behind the blended statistics (capped: older frames fade).
    weight: f32,
    /// Travel since it was last seen, metres.
    travel_m: f32,
    /// Time since it was last seen, seconds.
    age_s: f32,
    /// The camera's distance from its points when last seen, metres.
    range_m: f32,
    /// A copy of a neighbour filling a hole the motion left: used this frame, never
    /// moved on (the original is, and copies again where a hole is left).
    copy: bool,
    /// The ground bent within reach of the cell when last seen (see [`bent`]).
    bent: bool,
}

impl Remembered {
    const EMPTY: Remembered = Remembered {
        cell: Cell::EMPTY,
        frames: 0,
        weight: 0.0,
        travel_m: 0.0,
        age_s: 0.0,
        range_m: 0.0,
        copy: false,
        bent: false,
    };

    fn is_empty(&self) -> bool {
        self.cell.n == 0
    }
}

/// A hazard a verdict reported, carried with the rover's motion so that it is still
/// reported once it is out of the camera's view (a drop-off's edge, whose far side
/// was never seen, leaves no cells to find it from).
#[derive(Debug, Clone, Copy, PartialEq)]
struct CarriedHazard {
    kind: HazardKind,
    side: Side,
    /// Where it is, rover frame, metres (x: its distance; y: its side's centre).
    at: [f32; 2],
    /// Consecutive verdicts that reported it there.
    frames: u16,
    /// Consecutive verdicts since, with its place in view, that did not report it.
    missed: u16,
    travel_m: f32,
    age_s: f32,
}

/// A hazard in a new verdict within this of a carried one (same kind and side) is the
/// same hazard, metres.
const SAME_HAZARD_M: f32 = 0.15;

/// A carried hazard's place is the mean of about this many frames' views of it.
const CARRY_FRAMES: u16 = 4;

/// Most verdicts in a row that may miss a carried hazard in view before it is dropped
/// (however many reported it): a second at 30 frames a second. A stop a parked rover
/// holds against its own view of the place ends within that. A 16.1 cm cone found a
/// `step` by eleven frames of a drive up to it (its foot 2.5 m to 1.5 m out) was read
/// climbable by the next seven (its apex 1.6 m to 1.0 m out, 12.7 cm over the ground
/// before it: lumpy ground dips under it), and the drive went there
/// (`sweep -- natural 100 9202 random` #95, driven up to from 1.2 m back in 0.1 m
/// steps); kept, the drive stops in every frame.
const MISSED_MAX_FRAMES: u16 = 30;

/// A carried hazard is held in view, reported or not, while the rover has moved less
/// than this since a verdict last reported it (and for under `[memory]
/// standing_hold_s`, 1 s by default: as long as a parked rover's view takes to clear a
/// hazard many verdicts reported, [`MISSED_MAX_FRAMES`] at 30 frames a second),
/// metres: a rover standing, or all but. A view from the same place is no better than
/// the one that found it; another frame of it rolls the sensor's noise again, and
/// cannot clear it. A rover moving on (2 cm a frame is 0.4 m/s at 20 frames a second)
/// sees anew, and one frame's glitch is gone at the next frame that misses it
/// (`an_obstacle_in_one_frame_only_is_gone_at_once`).
/// A rover that stopped for an `unknown` at a threshold (the image's top edge on 4.8
/// cm of a 0.56 m belly block's face, `sweep -- hazards 100 3304 random` #32, noisy)
/// otherwise went again in 7 of 10 frames held there, each a go that sets it moving.
const STILL_M: f32 = 0.01;

/// Heights of one cell in two frames within this of each other count as the same
/// ground, metres: a frame that disagrees starts the cell's count again.
const CONSISTENT_M: f32 = 0.04;

/// The rover-centred terrain map and the fused cells of the last frame.
#[derive(Debug, Clone)]
pub struct TerrainMemory {
    spec: GridSpec,
    /// Map rows behind the analysis grid and columns on each side of it.
    behind: usize,
    side: usize,
    nx: usize,
    ny: usize,
    map: Vec<Remembered>,
    next: Vec<Remembered>,
    /// Which map cell each cell of `next` came from ([`NONE`]: none yet).
    source: Vec<u32>,
    /// The map cells that landed in no cell of `next` in the first pass (outside the
    /// map, or lost a collision), capacity one per map cell.
    unplaced: Vec<u32>,
    fused: Vec<Cell>,
    /// Per fused cell, the confidence of the remembered cell it came from (0: the
    /// frame's own).
    confidence: Vec<f32>,
    /// Where the camera is, rover frame, metres.
    camera: [f32; 3],
    hazards: heapless::Vec<CarriedHazard, MAX_HAZARDS>,
    /// Where the camera's whole-cell view starts on the left track, the belly band
    /// and the right track, metres (nearer is out of view).
    view_start: [f32; 3],
    /// Lateral centre of each side, metres.
    side_y: [f32; 3],
    min_points: u32,
    min_frames: u16,
    max_travel_m: f32,
    max_age_s: f32,
    /// `[memory] standing_hold_s`, seconds ([`STILL_M`]).
    standing_hold_s: f32,
    /// Map cells per metre (the voxel size's inverse, worked out once).
    per_voxel: f32,
    remembered: u32,
    /// The sum of the remembered cells' confidence in the last fuse.
    confidence_sum: f32,
}

/// Range up to which a cell is seen as well as the camera sees anything, metres: a
/// depth camera's noise grows with the square of the range (σ = 1.425e-3 m⁻¹ · Z² for
/// a Kinect v1: 3 mm here), so a cell last seen from twice as far counts a quarter.
pub const CLEAR_RANGE_M: f32 = 1.5;

/// No map cell (in [`TerrainMemory`]'s `source`).
const NONE: u32 = u32::MAX;

/// Width of the map beyond the corridor on each side, metres.
const SIDE_MARGIN_M: f64 = 0.2;

impl TerrainMemory {
    /// An empty map for the analysis grid `spec`, sized and allocated once.
    pub fn new(config: &Config, spec: GridSpec) -> Self {
        let m = &config.memory;
        let vs = f64::from(spec.voxel_m);
        let behind = (m.behind_m / vs).ceil() as usize;
        let side = (SIDE_MARGIN_M / vs).ceil() as usize;
        let (nx, ny) = (spec.nx + behind, spec.ny + 2 * side);
        TerrainMemory {
            spec,
            behind,
            side,
            nx,
            ny,
            map: vec![Remembered::EMPTY; nx * ny],
            next: vec![Remembered::EMPTY; nx * ny],
            source: vec![NONE; nx * ny],
            unplaced: Vec::with_capacity(nx * ny),
            fused: vec![Cell::EMPTY; spec.cell_count()],
            confidence: vec![0.0; spec.cell_count()],
            camera: [
                config.mount.x_m as f32,
                config.mount.y_m as f32,
                config.mount.z_m as f32,
            ],
            hazards: heapless::Vec::new(),
            view_start: [0.0; 3],
            side_y: {
                let mid = config.rover.track_centre_m() as f32;
                [mid, 0.0, -mid]
            },
            min_points: config.analysis.min_points_per_cell,
            min_frames: m.min_frames.min(u32::from(u16::MAX)) as u16,
            max_travel_m: m.max_travel_m as f32,
            max_age_s: m.max_age_s as f32,
            standing_hold_s: m.standing_hold_s as f32,
            per_voxel: 1.0 / spec.voxel_m,
            remembered: 0,
            confidence_sum: 0.0,
        }
    }

    /// How much a remembered cell is worth against one seen now, 0..=1: its
    /// remaining life (the larger of the travel and the time since it was seen, as
    /// parts of `max_travel_m` and `max_age_s`) times `(CLEAR_RANGE_M / range)²` for
    /// a cell last seen from farther than [`CLEAR_RANGE_M`].
    fn confidence_of(&self, r: &Remembered) -> f32 {
        let spent = (r.travel_m / self.max_travel_m).max(r.age_s / self.max_age_s);
        let range = (CLEAR_RANGE_M / r.range_m.max(CLEAR_RANGE_M)).powi(2);
        ((1.0 - spent) * range).clamp(0.0, 1.0)
    }

    /// Forget everything (odometry lost: the map can no longer be placed).
    pub fn clear(&mut self) {
        self.map.fill(Remembered::EMPTY);
        self.hazards.clear();
    }

    /// Learn where the camera's view starts on each side: the nearest cell it sees
    /// whole (`expected`) in each region's strips (`regions`, one per strip).
    pub fn set_view(&mut self, expected: &[bool], regions: &[Region]) {
        let s = self.spec;
        let mut start = [f32::INFINITY; 3];
        for iy in 0..s.ny {
            let k = side_index(regions[iy].side());
            if let Some(ix) = (0..s.nx).find(|&ix| expected[s.cell(ix, iy)]) {
                start[k] = start[k].min(s.origin[0] + ix as f32 * s.voxel_m);
            }
        }
        self.view_start = start;
    }

    /// The map cell under analysis grid cell (`ix`, `iy`).
    fn map_index(&self, ix: usize, iy: usize) -> usize {
        (ix + self.behind) * self.ny + iy + self.side
    }

    /// The map cell (mx, my) containing the point (x, y), rover frame, metres.
    fn map_xy(&self, p: [f32; 2]) -> Option<(usize, usize)> {
        let fx = (p[0] - self.spec.origin[0]) * self.per_voxel + self.behind as f32;
        let fy = (p[1] - self.spec.origin[1]) * self.per_voxel + self.side as f32;
        (fx >= 0.0 && fy >= 0.0 && fx < self.nx as f32 && fy < self.ny as f32)
            .then_some((fx as usize, fy as usize))
    }

    /// The index of the map cell containing the point (x, y), rover frame, metres.
    fn map_cell_at(&self, p: [f32; 2]) -> Option<usize> {
        self.map_xy(p).map(|(mx, my)| mx * self.ny + my)
    }

    /// The centre of map cell (`mx`, `my`), rover frame, metres.
    fn map_centre(&self, mx: usize, my: usize) -> [f32; 2] {
        let vs = self.spec.voxel_m;
        [
            self.spec.origin[0] + (mx as f32 - self.behind as f32 + 0.5) * vs,
            self.spec.origin[1] + (my as f32 - self.side as f32 + 0.5) * vs,
        ]
    }

    /// Move the map by the rover's motion since the last frame, and age it.
    pub fn advance(&mut self, motion: &Motion) {
        let step = motion.forward_m.hypot(motion.lateral_m);
        let dt = motion.dt_s;
        let motion = &Rigid::of(motion);
        self.source.fill(NONE);
        self.unplaced.clear();
        // Every remembered cell to where its centroid is now; when two land in one
        // cell, the one seen more recently stays.
        let (max_travel, max_age) = (self.max_travel_m, self.max_age_s);
        let carried = |r: &Remembered| {
            !r.is_empty() && !r.copy && r.travel_m + step <= max_travel && r.age_s + dt <= max_age
        };
        for i in 0..self.map.len() {
            let r = &self.map[i];
            if !carried(r) {
                continue;
            }
            let moved = moved(r, motion, step, dt);
            let Some(j) = self.map_cell_at([moved.cell.x, moved.cell.y]) else {
                self.unplaced.push(i as u32);
                continue;
            };
            let was = self.source[j];
            if was == NONE || moved.travel_m < self.next[j].travel_m {
                self.next[j] = moved;
                if was != NONE {
                    self.unplaced.push(was);
                }
                self.source[j] = i as u32;
            } else {
                self.unplaced.push(i as u32);
            }
        }
        // Two centroids in one cell leave a cell that none lands in (a turn does this
        // often, small steps now and then). The one that lost goes to the empty cell
        // beside where it landed nearest its centroid, in map order...
        self.unplaced.sort_unstable();
        let vs = self.spec.voxel_m;
        for k in 0..self.unplaced.len() {
            let i = self.unplaced[k] as usize;
            let moved = moved(&self.map[i], motion, step, dt);
            let p = [moved.cell.x, moved.cell.y];
            let free = [[-vs, 0.0], [vs, 0.0], [0.0, -vs], [0.0, vs]]
                .into_iter()
                .filter_map(|[dx, dy]| self.map_xy([p[0] + dx, p[1] + dy]))
                .filter(|&(mx, my)| self.source[mx * self.ny + my] == NONE)
                .map(|(mx, my)| {
                    let c = self.map_centre(mx, my);
                    (
                        mx * self.ny + my,
                        (c[0] - p[0]).powi(2) + (c[1] - p[1]).powi(2),
                    )
                })
                .min_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((j, _)) = free {
                self.next[j] = moved;
                self.source[j] = i as u32;
            }
        }
        // ...and a cell still empty takes a copy of the cell that was under its centre
        // when that one's centroid now lies within a cell of it: a remembered surface
        // has no holes that the motion made.
        for j in 0..self.next.len() {
            if self.source[j] != NONE {
                continue;
            }
            let centre = self.map_centre(j / self.ny, j % self.ny);
            let copy = self
                .map_cell_at(motion.unapply(centre))
                .map(|i| &self.map[i])
                .filter(|r| carried(r))
                .map(|r| moved(r, motion, step, dt))
                .filter(|m| {
                    (m.cell.x - centre[0]).abs() <= vs && (m.cell.y - centre[1]).abs() <= vs
                });
            self.next[j] = match copy {
                Some(m) => Remembered { copy: true, ..m },
                None => Remembered::EMPTY,
            };
        }
        std::mem::swap(&mut self.map, &mut self.next);
        // Carried hazards move too; one under or behind the front axle is passed.
        for h in self.hazards.iter_mut() {
            h.at = motion.apply(h.at);
            h.travel_m += step;
            h.age_s += dt;
        }
        self.hazards
            .retain(|h| h.at[0] >= 0.0 && h.travel_m <= max_travel && h.age_s <= max_age);
    }

    /// After the analysis of the fused cells: report the carried hazards that are out
    /// of the camera's view now (seen by `min_frames` verdicts alike), re-deciding the
    /// verdict when one is added; then carry on what the verdict reports. A hazard in
    /// view is the frame's to find, but one that `min_frames` verdicts in a row
    /// reported is dropped only once as many verdicts in a row as reported it (up to
    /// 30, `MISSED_MAX_FRAMES`) see its place and do not: until then it is reported where
    /// the motion carried it. A hazard one frame reported is gone the next that misses
    /// it, unless the rover has not moved since (under 1 cm): a standing rover holds
    /// any hazard a verdict reported for a second after the last that did.
    /// Returns how many hazards came from memory.
    pub fn carry_hazards(&mut self, verdict: &mut Verdict) -> u32 {
        let mut added = 0u32;
        for h in &self.hazards {
            if self.out_of_view(h.at[0], h.side) && h.frames >= self.min_frames {
                verdict.add_hazard(Hazard {
                    kind: h.kind,
                    side: h.side,
                    distance_m: h.at[0],
                });
                added += 1;
            }
        }
        if added > 0 {
            redecide(verdict);
        }
        let old = self.hazards.clone();
        self.hazards.clear();
        let mut moved = false;
        // Which carried hazards a verdict hazard matched, by index in `old`.
        let mut found = 0u32;
        for h in verdict.hazards.iter_mut() {
            let k = side_index(h.side);
            let prev = old.iter().enumerate().find(|(_, c)| {
                c.kind == h.kind
                    && c.side == h.side
                    && (c.at[0] - h.distance_m).abs() <= SAME_HAZARD_M
            });
            found |= prev.map_or(0, |(i, _)| 1 << i);
            let prev = prev.map(|(_, c)| c);
            let carried = match prev {
                // Out of view: the carried one itself, where the motion put it.
                Some(p) if self.out_of_view(h.distance_m, h.side) => *p,
                // In view again: where it was carried to, averaged with where the
                // frame finds it (a frame's distance is quantised by the grid; the
                // carried one is the mean of the last frames', moved exactly).
                Some(p) => {
                    let w = 1.0 / f32::from(p.frames.saturating_add(1).min(CARRY_FRAMES));
                    CarriedHazard {
                        at: [p.at[0] + w * (h.distance_m - p.at[0]), self.side_y[k]],
                        frames: p.frames.saturating_add(1),
                        missed: 0,
                        travel_m: 0.0,
                        age_s: 0.0,
                        ..*p
                    }
                }
                None => CarriedHazard {
                    kind: h.kind,
                    side: h.side,
                    at: [h.distance_m, self.side_y[k]],
                    frames: 1,
                    missed: 0,
                    travel_m: 0.0,
                    age_s: 0.0,
                },
            };
            // A hazard seen again in view is reported where the frames' views of it,
            // carried exactly, put it on average.
            if prev.is_some() && h.distance_m != carried.at[0] {
                h.distance_m = carried.at[0].max(0.0);
                moved = true;
            }
            let _ = self.hazards.push(carried);
        }
        if moved {
            verdict
                .hazards
                .sort_unstable_by(|a, b| a.distance_m.total_cmp(&b.distance_m));
        }
        let kept = self.keep_missed(&old, found, verdict);
        if kept > 0 {
            redecide(verdict);
        }
        added + kept
    }

    /// Whether a hazard `x` metres out on `side` is out of the camera's view now:
    /// nearer than that side's nearest wholly seen cell.
    fn out_of_view(&self, x: f32, side: Side) -> bool {
        x < self.view_start[side_index(side)]
    }

    /// The carried hazards of `old` that no verdict hazard matched (`found`, a bit per
    /// index) while in view, kept and reported where the motion carried them when
    /// `min_frames` verdicts in a row reported them and fewer in a row (up to
    /// [`MISSED_MAX_FRAMES`]) have missed them since, or when the rover has not moved
    /// since one last reported them ([`STILL_M`], `[memory] standing_hold_s`). Returns
    /// how many.
    fn keep_missed(&mut self, old: &[CarriedHazard], found: u32, verdict: &mut Verdict) -> u32 {
        let mut kept = 0u32;
        for (i, p) in old.iter().enumerate() {
            let missed = p.missed.saturating_add(1);
            let still = p.travel_m < STILL_M && p.age_s < self.standing_hold_s;
            let dropped = p.frames < self.min_frames || missed >= p.frames.min(MISSED_MAX_FRAMES);
            if found & (1 << i) != 0 || self.out_of_view(p.at[0], p.side) || (dropped && !still) {
                continue;
            }
            verdict.add_hazard(Hazard {
                kind: p.kind,
                side: p.side,
                distance_m: p.at[0].max(0.0),
            });
            let _ = self.hazards.push(CarriedHazard { missed, ..*p });
            kept += 1;
        }
        kept
    }

    /// Fuse a frame's cells into the map and build the cells the analysis sees:
    ///
    /// - a cell wholly in the camera's view now (`expected`) is the frame's, seen or
    ///   not, and when seen it replaces what was remembered there;
    /// - a cell outside it, or only partly in it (the image's edges), is the
    ///   remembered one when that is trusted (seen whole by `min_frames` frames at a
    ///   consistent height): a partial view of a cell is a biased one. Otherwise it
    ///   is the frame's, and the frame's view is remembered.
    ///
    /// A cell the image's top edge cuts now (`cut`; empty: none) holds only the
    /// lower part of what stands there: it is the frame's alone, and it is not
    /// averaged into the next frame's view of that cell either. Nor is a cell over a
    /// bend in the ground, now or when last seen (`bent`).
    ///
    /// Returns how many cells came from memory.
    pub fn fuse(&mut self, frame: &[Cell], expected: &[bool], cut: &[bool]) -> u32 {
        let s = self.spec;
        let mut remembered = 0u32;
        let mut confidence_sum = 0.0f32;
        for ix in 0..s.nx {
            for iy in 0..s.ny {
                let c = s.cell(ix, iy);
                let m = self.map_index(ix, iy);
                let now = frame[c];
                let seen = now.n >= self.min_points;
                let r = &mut self.map[m];
                let same = !r.is_empty() && (r.cell.z - now.z).abs() <= CONSISTENT_M;
                let trusted = r.frames >= self.min_frames && r.cell.n >= self.min_points;
                if !expected[c] && trusted {
                    if seen && same {
                        r.travel_m = 0.0;
                        r.age_s = 0.0;
                    }
                    let r = *r;
                    let k = self.confidence_of(&r);
                    self.fused[c] = r.cell;
                    self.confidence[c] = k;
                    confidence_sum += k;
                    remembered += 1;
                    continue;
                }
                self.confidence[c] = 0.0;
                if seen {
                    // Frames that agree are averaged, weighted by the inverse
                    // variance of their view ([`view_weight`]): noise falls as the
                    // rover drives on. A cell that changed (a face appeared, a rock
                    // went), or over a bend ([`bent`]), is the frame's alone.
                    let partial = cut.get(c) == Some(&true);
                    let bent_now = bent(frame, &s, ix, iy, self.min_points);
                    let agree = same
                        && (r.cell.top - now.top).abs() <= CONSISTENT_M
                        && !bent_now
                        && !r.bent;
                    let range = range_from(self.camera, &now);
                    let w_now = view_weight(now.n, range);
                    let w_old = if agree && !partial {
                        r.weight.min(BLEND_FRAMES * w_now)
                    } else {
                        0.0
                    };
                    let cell = blend(&r.cell, w_old, &now, w_now);
                    let frames = if same { r.frames.saturating_add(1) } else { 1 };
                    *r = seen_now(cell, frames, w_old + w_now, range, partial);
                    r.bent = bent_now;
                    self.fused[c] = cell;
                } else {
                    self.fused[c] = now;
                }
            }
        }
        self.remembered = remembered;
        self.confidence_sum = confidence_sum;
        remembered
    }

    /// Start the map again from one frame (no trusted odometry: it can no longer be
    /// placed): forget everything, then remember the frame's seen cells as seen once,
    /// as [`clear`](Self::clear) and [`fuse`](Self::fuse) would, but without copying
    /// the frame into the fused cells: the frame's analysis is its own
    /// ([`Pipeline`](crate::Pipeline) hands it the grid's cells), and the next fuse
    /// starts from this map. The confidences are 0 (nothing comes from memory).
    pub fn restart(&mut self, frame: &[Cell], cut: &[bool]) {
        self.clear();
        self.confidence.fill(0.0);
        self.remembered = 0;
        self.confidence_sum = 0.0;
        let s = self.spec;
        for ix in 0..s.nx {
            for iy in 0..s.ny {
                let c = s.cell(ix, iy);
                let now = &frame[c];
                if now.n >= self.min_points {
                    let partial = cut.get(c) == Some(&true);
                    let m = self.map_index(ix, iy);
                    let range = range_from(self.camera, now);
                    self.map[m] = seen_now(*now, 1, view_weight(now.n, range), range, partial);
                }
            }
        }
    }

    /// Per cell of the last fuse (analysis grid layout), the confidence of the
    /// remembered cell it came from, 0..=1 (0: the frame's own).
    pub fn confidence(&self) -> &[f32] {
        &self.confidence
    }

    /// The mean confidence of the cells the last fuse took from memory (0 when none).
    pub fn mean_confidence(&self) -> f32 {
        if self.remembered == 0 {
            0.0
        } else {
            self.confidence_sum / self.remembered as f32
        }
    }

    /// The cells of the last [`TerrainMemory::fuse`], analysis grid layout.
    pub fn cells(&self) -> &[Cell] {
        &self.fused
    }

    /// Cells the last fuse took from memory.
    pub fn remembered(&self) -> u32 {
        self.remembered
    }

    /// How long ago and how far back each analysis-grid cell was last seen
    /// (`None`: nothing remembered there), for the pictures: (seconds, metres).
    pub fn age_at(&self, ix: usize, iy: usize) -> Option<(f32, f32)> {
        let r = self.map.get(self.map_index(ix, iy))?;
        (!r.is_empty()).then_some((r.age_s, r.travel_m))
    }
}

fn side_index(s: Side) -> usize {
    match s {
        Side::Left => 0,
        Side::Centre => 1,
        Side::Right => 2,
    }
}

/// The decision again after hazards were added: stop for any but unknown ground,
/// unknown for unknown ground; a go loses its feature. Hazards nearest first, in a
/// stop the ones that stop the rover first ([`Verdict::order_hazards`]).
fn redecide(v: &mut Verdict) {
    let decision = v.hazards_decision().unwrap_or(v.decision);
    if decision != Decision::Go {
        v.feature = None;
    }
    v.decision = decision;
    v.order_hazards();
}

/// How far a cell's mean height may lie off the line through its two neighbours'
/// (along its strip or across it) for the ground under it to count as plane, metres.
const BEND_M: f32 = 0.003;

/// Whether the ground bends within reach of frame cell (`ix`, `iy`): its mean point
/// lies more than [`BEND_M`] off the line through its seen neighbours' mean points,
/// along the strip or across it. Over a bend (a ramp's toe, a crest) a cell's mean
/// point depends on which part of the cell its points cover, and the views the memory
/// re-bins cover different parts: averaging them mixes different chords. On a plane
/// every part gives a point on it.
fn bent(frame: &[Cell], s: &GridSpec, ix: usize, iy: usize, min_points: u32) -> bool {
    let c = &frame[s.cell(ix, iy)];
    let off = |a: &Cell, b: &Cell, along_x: bool| {
        if a.n < min_points || b.n < min_points {
            return 0.0;
        }
        let (pa, pb, pc) = if along_x {
            (a.x, b.x, c.x)
        } else {
            (a.y, b.y, c.y)
        };
        let span = pb - pa;
        if span.abs() < 1e-4 {
            return 0.0;
        }
        (c.z - (a.z + (b.z - a.z) * (pc - pa) / span)).abs()
    };
    let along = ix > 0 && ix + 1 < s.nx && {
        off(&frame[s.cell(ix - 1, iy)], &frame[s.cell(ix + 1, iy)], true) > BEND_M
    };
    let across = iy > 0 && iy + 1 < s.ny && {
        off(
            &frame[s.cell(ix, iy - 1)],
            &frame[s.cell(ix, iy + 1)],
            false,
        ) > BEND_M
    };
    along || across
}

/// How many of the current frame's weight the remembered statistics of a cell may
/// carry when a frame agrees with them: about the last five frames count.
const BLEND_FRAMES: f32 = 4.0;

/// The weighted mean of two views of one cell (`old` weighing `w_old`, `now` its
/// points); the point count is the frame's (the analysis's "seen" threshold).
fn blend(old: &Cell, w_old: f32, now: &Cell, w_now: f32) -> Cell {
    if w_old <= 0.0 {
        return *now;
    }
    let k = w_old / (w_old + w_now);
    let mix = |a: f32, b: f32| b + k * (a - b);
    let mix2 = |a: [f32; 2], b: [f32; 2]| [mix(a[0], b[0]), mix(a[1], b[1])];
    Cell {
        n: now.n,
        x: mix(old.x, now.x),
        y: mix(old.y, now.y),
        z: mix(old.z, now.z),
        top: mix(old.top, now.top),
        peak: mix(old.peak, now.peak),
        top_xy: mix2(old.top_xy, now.top_xy),
        low: mix(old.low, now.low),
        crest: mix(old.crest, now.crest),
        foot: mix(old.foot, now.foot),
        crest_xy: mix2(old.crest_xy, now.crest_xy),
        foot_xy: mix2(old.foot_xy, now.foot_xy),
    }
}

/// The camera's distance (at `camera`, rover frame) from a cell's mean point, metres.
fn range_from(camera: [f32; 3], cell: &Cell) -> f32 {
    let d = [cell.x - camera[0], cell.y - camera[1], cell.z - camera[2]];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

/// How much a view of a cell (`n` points, seen from `range_m` metres) weighs in the
/// blend: the inverse variance of its mean height, relative: its points over the
/// fourth power of its range (a depth camera's noise σ grows with the square of the
/// range), ranges under [`CLEAR_RANGE_M`] counting as that.
fn view_weight(n: u32, range_m: f32) -> f32 {
    n as f32 * (CLEAR_RANGE_M / range_m.max(CLEAR_RANGE_M)).powi(4)
}

/// A map cell as the frame sees it now: `cell` (the frame's view, or its blend with
/// the map's) seen `frames` frames in a row, carrying `weight` (the blend's, see
/// [`view_weight`]), its points seen from `range_m` metres. A view the image's top
/// edge cut (`partial`) is biased low: it carries no weight, and the next frame
/// starts anew.
fn seen_now(cell: Cell, frames: u16, weight: f32, range_m: f32, partial: bool) -> Remembered {
    Remembered {
        cell,
        frames,
        weight: if partial { 0.0 } else { weight },
        travel_m: 0.0,
        age_s: 0.0,
        range_m,
        copy: false,
        bent: false,
    }
}

/// A remembered cell moved by `motion` (its points' centroids carried exactly) and
/// aged by it.
fn moved(r: &Remembered, motion: &Rigid, step: f32, dt: f32) -> Remembered {
    let mut out = *r;
    let c = &mut out.cell;
    [c.x, c.y] = motion.apply([c.x, c.y]);
    c.top_xy = motion.apply(c.top_xy);
    c.crest_xy = motion.apply(c.crest_xy);
    c.foot_xy = motion.apply(c.foot_xy);
    out.travel_m += step;
    out.age_s += dt;
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup() -> (Config, GridSpec) {
        let c = Config::default();
        let spec = GridSpec::from_config(&c);
        (c, spec)
    }

    /// A frame with one cell seen at (x, y) and height z.
    fn frame_with(spec: &GridSpec, x: f32, y: f32, z: f32) -> Vec<Cell> {
        frame_of(spec, &[(x, y, z)])
    }

    /// A frame with a cell seen at each (x, y) and height z.
    fn frame_of(spec: &GridSpec, seen: &[(f32, f32, f32)]) -> Vec<Cell> {
        let mut cells = vec![Cell::EMPTY; spec.cell_count()];
        for &(x, y, z) in seen {
            let (ix, iy) = spec.cell_at(x, y).unwrap();
            cells[spec.cell(ix, iy)] = Cell {
                n: 20,
                x,
                y,
                z,
                top: z,
                peak: z,
                top_xy: [x, y],
                low: z,
                crest: z,
                foot: z,
                crest_xy: [x, y],
                foot_xy: [x, y],
            };
        }
        cells
    }

    #[test]
    fn a_moved_cell_carries_every_point_it_keeps_by_the_same_motion() {
        let motion = Motion {
            forward_m: 0.3,
            lateral_m: -0.05,
            dheading_rad: 0.2,
            dt_s: 0.1,
        };
        let cell = Cell {
            n: 20,
            x: 1.0,
            y: 0.6,
            z: -0.1,
            top: 0.0,
            peak: 0.0,
            top_xy: [1.01, 0.69],
            low: -0.2,
            crest: -0.02,
            foot: -0.2,
            crest_xy: [1.02, 0.68],
            foot_xy: [0.99, 0.62],
        };
        let r = seen_now(cell, 1, 1.0, 1.0, false);
        let out = moved(&r, &Rigid::of(&motion), 0.3, 0.1).cell;
        assert_eq!([out.x, out.y], motion.apply([cell.x, cell.y]));
        assert_eq!(out.top_xy, motion.apply(cell.top_xy));
        assert_eq!(out.crest_xy, motion.apply(cell.crest_xy));
        assert_eq!(out.foot_xy, motion.apply(cell.foot_xy));
        assert_eq!((out.top, out.z), (cell.top, cell.z));
    }

    fn seen_at(m: &TerrainMemory, spec: &GridSpec) -> Vec<(f32, f32)> {
        m.cells()
            .iter()
            .filter(|c| c.n > 0)
            .map(|c| (c.x, c.y))
            .inspect(|&(x, y)| assert!(spec.cell_at(x, y).is_some()))
            .collect()
    }

    #[test]
    fn a_restart_remembers_what_forgetting_and_fusing_the_frame_would() {
        let (cfg, spec) = setup();
        let blind = vec![false; spec.cell_count()];
        // A map with history: a cell seen twice, a hazard reported, both moved.
        let mut a = TerrainMemory::new(&cfg, spec);
        let old = frame_with(&spec, 1.5, -0.4, 0.05);
        a.fuse(&old, &blind, &[]);
        a.fuse(&old, &blind, &[]);
        let mut v = Verdict::default();
        v.add_hazard(Hazard {
            kind: HazardKind::Step,
            side: Side::Right,
            distance_m: 1.5,
        });
        a.carry_hazards(&mut v);
        a.advance(&Motion {
            forward_m: 0.1,
            dt_s: 0.1,
            ..Motion::default()
        });
        assert_eq!(a.hazards.len(), 1);
        let mut b = a.clone();
        // The new frame: two cells, one the image's top edge cuts.
        let mut now = frame_with(&spec, 1.012, 0.41, 0.15);
        let far = frame_with(&spec, 2.6, 0.0, 0.3);
        let (ix, iy) = spec.cell_at(2.6, 0.0).unwrap();
        now[spec.cell(ix, iy)] = far[spec.cell(ix, iy)];
        let mut cut = vec![false; spec.cell_count()];
        cut[spec.cell(ix, iy)] = true;
        a.clear();
        a.fuse(&now, &blind, &cut);
        b.restart(&now, &cut);
        assert_eq!(a.map, b.map);
        assert!(b.hazards.is_empty());
        assert!(b.confidence().iter().all(|&k| k == 0.0));
        assert_eq!((b.remembered(), b.mean_confidence()), (0, 0.0));
        assert_eq!(b.map.iter().filter(|r| !r.is_empty()).count(), 2);
    }

    #[test]
    fn small_steps_move_a_remembered_cell_exactly_without_drift() {
        let (cfg, spec) = setup();
        let mut m = TerrainMemory::new(&cfg, spec);
        let blind = vec![false; spec.cell_count()];
        let f = frame_with(&spec, 1.012, 0.41, 0.15);
        m.fuse(&f, &blind, &[]);
        m.fuse(&f, &blind, &[]); // seen twice: trusted
        let empty = vec![Cell::EMPTY; spec.cell_count()];
        // 90 steps of 1 cm (under half a cell each): the cell must still arrive.
        for _ in 0..90 {
            m.advance(&Motion {
                forward_m: 0.01,
                dt_s: 0.033,
                ..Motion::default()
            });
            m.fuse(&empty, &blind, &[]);
        }
        let at = seen_at(&m, &spec);
        assert_eq!(at.len(), 1, "{at:?}");
        assert!(
            (at[0].0 - 0.112).abs() < 1e-4 && (at[0].1 - 0.41).abs() < 1e-4,
            "{at:?}"
        );
    }

    #[test]
    fn a_turn_carries_cells_round_the_rover() {
        let (cfg, spec) = setup();
        let mut m = TerrainMemory::new(&cfg, spec);
        let blind = vec![false; spec.cell_count()];
        let f = frame_with(&spec, 1.0, 0.5, 0.1);
        m.fuse(&f, &blind, &[]);
        m.fuse(&f, &blind, &[]);
        let empty = vec![Cell::EMPTY; spec.cell_count()];
        // Turn 20° left on the spot in 1° steps: the cell swings right, about the origin.
        for _ in 0..20 {
            m.advance(&Motion {
                dheading_rad: 1f32.to_radians(),
                dt_s: 0.033,
                ..Motion::default()
            });
            m.fuse(&empty, &blind, &[]);
        }
        let a = -20f32.to_radians();
        let want = [a.cos() - 0.5 * a.sin(), a.sin() + 0.5 * a.cos()];
        let at = seen_at(&m, &spec);
        assert!(!at.is_empty());
        assert!(
            at.iter()
                .all(|p| (p.0 - want[0]).abs() < 1e-3 && (p.1 - want[1]).abs() < 1e-3),
            "{at:?}, want {want:?}"
        );
    }

    #[test]
    fn one_frame_is_not_remembered_and_old_cells_are_forgotten() {
        let (cfg, spec) = setup();
        let blind = vec![false; spec.cell_count()];
        let empty = vec![Cell::EMPTY; spec.cell_count()];
        let f = frame_with(&spec, 1.0, 0.4, 0.2);
        let step = Motion {
            forward_m: 0.05,
            dt_s: 0.1,
            ..Motion::default()
        };
        // Seen once: never used out of view.
        let mut m = TerrainMemory::new(&cfg, spec);
        m.fuse(&f, &blind, &[]);
        m.advance(&step);
        assert_eq!(m.fuse(&empty, &blind, &[]), 0);
        // Seen twice at different heights: still one consistent frame.
        let mut m = TerrainMemory::new(&cfg, spec);
        m.fuse(&f, &blind, &[]);
        m.fuse(&frame_with(&spec, 1.0, 0.4, 0.3), &blind, &[]);
        m.advance(&step);
        assert_eq!(m.fuse(&empty, &blind, &[]), 0);
        // Seen twice alike: remembered, until max_travel_m (1.5 m) of travel.
        let mut m = TerrainMemory::new(&cfg, spec);
        m.fuse(&f, &blind, &[]);
        m.fuse(&f, &blind, &[]);
        let mut kept = 0;
        for _ in 0..40 {
            m.advance(&Motion {
                forward_m: -0.05, // backwards: the cell stays in the grid
                dt_s: 0.1,
                ..Motion::default()
            });
            kept += m.fuse(&empty, &blind, &[]);
        }
        // (The cell at a boundary may be filled by a copy one frame longer.)
        assert!(
            (29..=31).contains(&kept),
            "kept for 1.5 m of 0.05 m steps: {kept}"
        );
        // Time alone ages it too (max_age_s = 30 s).
        let mut m = TerrainMemory::new(&cfg, spec);
        m.fuse(&f, &blind, &[]);
        m.fuse(&f, &blind, &[]);
        let still = Motion {
            dt_s: 10.0,
            ..Motion::default()
        };
        let kept: Vec<u32> = (0..4)
            .map(|_| {
                m.advance(&still);
                m.fuse(&empty, &blind, &[])
            })
            .collect();
        assert_eq!(kept, [1, 1, 1, 0]);
    }

    #[test]
    fn confidence_falls_with_travel_time_and_range() {
        let (cfg, spec) = setup();
        let blind = vec![false; spec.cell_count()];
        let empty = vec![Cell::EMPTY; spec.cell_count()];
        // The confidence of the one remembered cell after `moves`, seen at (x, y).
        let after = |x: f32, y: f32, moves: &[Motion]| {
            let mut m = TerrainMemory::new(&cfg, spec);
            let f = frame_with(&spec, x, y, 0.0);
            m.fuse(&f, &blind, &[]);
            m.fuse(&f, &blind, &[]);
            for mv in moves {
                m.advance(mv);
                m.fuse(&empty, &blind, &[]);
            }
            assert_eq!(m.remembered(), 1);
            let k: Vec<f32> = m
                .confidence()
                .iter()
                .copied()
                .filter(|&k| k > 0.0)
                .collect();
            assert_eq!(k.len(), 1);
            assert!((m.mean_confidence() - k[0]).abs() < 1e-6);
            k[0]
        };
        let back = |d: f32| Motion {
            forward_m: -d,
            ..Motion::default()
        };
        let wait = |t: f32| Motion {
            dt_s: t,
            ..Motion::default()
        };
        // Seen from near (about 1.2 m from the camera), just now: full confidence.
        assert!((after(1.0, 0.4, &[wait(0.0)]) - 1.0).abs() < 1e-6);
        // Half of max_travel_m (1.5 m) driven since, or half of max_age_s (30 s) gone:
        // half; both: still half (the larger share counts).
        assert!((after(1.0, 0.4, &[back(0.75)]) - 0.5).abs() < 1e-3);
        assert!((after(1.0, 0.4, &[wait(15.0)]) - 0.5).abs() < 1e-3);
        assert!((after(1.0, 0.4, &[back(0.3), wait(15.0)]) - 0.5).abs() < 1e-3);
        // Seen from twice CLEAR_RANGE_M: a quarter.
        let cam = [
            cfg.mount.x_m as f32,
            cfg.mount.y_m as f32,
            cfg.mount.z_m as f32,
        ];
        let ground = (2.0 * CLEAR_RANGE_M).powi(2) - cam[2].powi(2) - (0.4 - cam[1]).powi(2);
        let x = cam[0] + ground.sqrt();
        assert!((after(x, 0.4, &[wait(0.0)]) - 0.25).abs() < 1e-3);
    }

    #[test]
    fn agreeing_views_are_averaged_but_not_with_a_view_the_image_edge_cut() {
        let (cfg, spec) = setup();
        let view = vec![true; spec.cell_count()];
        let (x, y) = (2.5, 0.4);
        let (ix, iy) = spec.cell_at(x, y).unwrap();
        let mut cut = vec![false; spec.cell_count()];
        cut[spec.cell(ix, iy)] = true;
        let z_of = |m: &TerrainMemory| m.cells().iter().find(|c| c.n > 0).unwrap().z;
        // Two agreeing views: averaged, between the two.
        let mut m = TerrainMemory::new(&cfg, spec);
        m.fuse(&frame_with(&spec, x, y, 0.30), &view, &[]);
        m.fuse(&frame_with(&spec, x, y, 0.32), &view, &[]);
        let z = z_of(&m);
        assert!(z > 0.30 && z < 0.32, "{z}");
        // The same with the second view cut by the image's top edge: it is the frame's
        // alone (biased low: only the cell's lower part is seen)...
        let mut m = TerrainMemory::new(&cfg, spec);
        m.fuse(&frame_with(&spec, x, y, 0.32), &view, &[]);
        m.fuse(&frame_with(&spec, x, y, 0.30), &view, &cut);
        assert_eq!(z_of(&m), 0.30);
        // ...and the next whole view is not averaged with it.
        m.fuse(&frame_with(&spec, x, y, 0.32), &view, &[]);
        assert_eq!(z_of(&m), 0.32);
    }

    #[test]
    fn views_over_a_bend_are_not_averaged() {
        let (cfg, spec) = setup();
        let view = vec![true; spec.cell_count()];
        let (x, y) = (2.525, 0.425);
        let vs = spec.voxel_m;
        // Three cells along a strip: the middle one's height `mid`, its neighbours on
        // a 20 % slope (a ramp's face) or, with `bend`, the nearer one flat (its toe).
        let strip = |mid: f32, bend: bool| {
            let near = if bend { mid } else { mid - 0.2 * vs };
            frame_of(
                &spec,
                &[(x - vs, y, near), (x, y, mid), (x + vs, y, mid + 0.2 * vs)],
            )
        };
        let mid_of = |m: &TerrainMemory| {
            let (ix, iy) = spec.cell_at(x, y).unwrap();
            m.cells()[spec.cell(ix, iy)].z
        };
        // On a plane, agreeing views are averaged...
        let mut m = TerrainMemory::new(&cfg, spec);
        m.fuse(&strip(0.300, false), &view, &[]);
        m.fuse(&strip(0.302, false), &view, &[]);
        let z = mid_of(&m);
        assert!(z > 0.300 && z < 0.302, "{z}");
        // ...over a bend seen now, or seen before, the frame's view stands alone.
        for bends in [[false, true], [true, false]] {
            let mut m = TerrainMemory::new(&cfg, spec);
            m.fuse(&strip(0.300, bends[0]), &view, &[]);
            m.fuse(&strip(0.302, bends[1]), &view, &[]);
            assert_eq!(mid_of(&m), 0.302, "{bends:?}");
        }
    }

    #[test]
    fn what_the_camera_sees_now_wins_and_what_it_should_see_is_not_filled() {
        let (cfg, spec) = setup();
        let mut m = TerrainMemory::new(&cfg, spec);
        let blind = vec![false; spec.cell_count()];
        let rock = frame_with(&spec, 1.0, 0.4, 0.2);
        m.fuse(&rock, &blind, &[]);
        m.fuse(&rock, &blind, &[]);
        // Seen again lower, wholly in view: the frame's height.
        let view = vec![true; spec.cell_count()];
        let ground = frame_with(&spec, 1.0, 0.4, 0.0);
        m.fuse(&ground, &view, &[]);
        let c = m.cells().iter().find(|c| c.n > 0).unwrap();
        assert_eq!(c.z, 0.0);
        // Out of view (or partly), the trusted memory beats a partial view...
        let mut m = TerrainMemory::new(&cfg, spec);
        m.fuse(&rock, &view, &[]);
        m.fuse(&rock, &view, &[]);
        m.fuse(&ground, &blind, &[]);
        let c = m.cells().iter().find(|c| c.n > 0).unwrap();
        assert_eq!(c.z, 0.2);
        // ...and in view and unseen, nothing is filled from memory.
        let empty = vec![Cell::EMPTY; spec.cell_count()];
        assert_eq!(m.fuse(&empty, &view, &[]), 0);
        assert!(m.cells().iter().all(|c| c.n == 0));
    }

    /// A memory of the default set-up whose camera's view starts at 0.6 m everywhere.
    fn viewing_from_0_6_m() -> TerrainMemory {
        let (cfg, spec) = setup();
        let mut m = TerrainMemory::new(&cfg, spec);
        let regions: Vec<Region> = (0..spec.ny)
            .map(|iy| {
                let y = spec.y_centre(iy);
                if y >= 0.2 {
                    Region::Left
                } else if y <= -0.2 {
                    Region::Right
                } else {
                    Region::Belly
                }
            })
            .collect();
        let expected: Vec<bool> = (0..spec.cell_count())
            .map(|c| spec.x_centre(c / spec.ny) > 0.6)
            .collect();
        m.set_view(&expected, &regions);
        m
    }

    /// A frame's verdict through `m`'s hazard carrying: a left `kind` hazard at `seen`
    /// metres (a stop), or none (a go); and how many hazards came from memory.
    fn carried(m: &mut TerrainMemory, kind: HazardKind, seen: Option<f32>) -> (Verdict, u32) {
        let mut v = Verdict {
            decision: Decision::Go,
            ..Verdict::default()
        };
        if let Some(d) = seen {
            v.add_hazard(Hazard {
                kind,
                side: Side::Left,
                distance_m: d,
            });
            v.decision = Decision::Stop;
        }
        let added = m.carry_hazards(&mut v);
        (v, added)
    }

    #[test]
    fn a_hazard_in_view_is_dropped_only_once_as_many_frames_miss_it_as_found_it() {
        let step = Motion {
            forward_m: 0.1,
            dt_s: 0.1,
            ..Motion::default()
        };
        // Parked: no travel, a quarter of a second a frame (exact in binary).
        let parked = Motion {
            dt_s: 0.25,
            ..Motion::default()
        };
        // How many verdicts in a row after `found` frames that reported a step at
        // 1.5 m still report it, each where the motion put it, the rover moving so
        // between frames.
        let misses_kept = |found: usize, motion: Motion| {
            let mut m = viewing_from_0_6_m();
            for _ in 0..found {
                carried(&mut m, HazardKind::Step, Some(1.5));
            }
            let mut kept = 0;
            loop {
                m.advance(&motion);
                let (v, added) = carried(&mut m, HazardKind::Step, None);
                if v.hazards.is_empty() {
                    assert_eq!(v.decision, Decision::Go);
                    return kept;
                }
                let want = 1.5 - motion.forward_m * (kept + 1) as f32;
                assert_eq!((v.decision, added), (Decision::Stop, 1));
                assert!((v.hazards[0].distance_m - want).abs() < 1e-4, "{v:?}");
                kept += 1;
            }
        };
        // Moving, one frame's hazard is gone at the next that misses it. Reported by
        // two, it is kept through one miss; by five, through four, keeping its place
        // on the ground.
        assert_eq!(misses_kept(1, step), 0);
        assert_eq!(misses_kept(2, step), 1);
        assert_eq!(misses_kept(5, step), 4);
        // Parked, the same view cannot clear it for a second (three frames here, the
        // fourth a second after the report), however few reported it; reported by
        // five, four misses keep it as moving.
        assert_eq!(misses_kept(1, parked), 3);
        assert_eq!(misses_kept(2, parked), 3);
        assert_eq!(misses_kept(5, parked), 4);
        // Creeping under a centimetre in all is still standing; a centimetre on, the
        // view is a new one.
        let creep = Motion {
            forward_m: 0.003,
            ..parked
        };
        assert_eq!(misses_kept(1, creep), 3);
        let on = Motion {
            forward_m: 0.01,
            ..parked
        };
        assert_eq!(misses_kept(1, on), 0);
        // However many reported it, a parked rover's view of its place clears it
        // within a second at 30 frames a second.
        let parked_30 = Motion {
            dt_s: 1.0 / 30.0,
            ..Motion::default()
        };
        assert_eq!(
            misses_kept(100, parked_30),
            usize::from(MISSED_MAX_FRAMES) - 1
        );
        // Found again, its misses count from nothing.
        let mut m = viewing_from_0_6_m();
        for seen in [Some(1.5), Some(1.5), None, Some(1.5), None] {
            let (v, _) = carried(&mut m, HazardKind::Step, seen);
            assert_eq!(v.decision, Decision::Stop, "{seen:?}");
        }
    }

    #[test]
    fn a_standing_rover_holds_a_hazard_that_flickers_at_a_threshold() {
        // One verdict in three finds it (an `unknown` at a threshold, noise deciding),
        // never two in a row: a rover standing where it stopped stops in every frame,
        // at 30 frames a second. (Moving, one verdict's hazard is gone at the next
        // miss: `a_hazard_in_view_is_dropped_only_once_as_many_frames_miss_it_as_found_it`.)
        let standing = Motion {
            dt_s: 1.0 / 30.0,
            ..Motion::default()
        };
        let decisions = |hold_s: f32| {
            let mut m = viewing_from_0_6_m();
            m.standing_hold_s = hold_s;
            (0..30)
                .map(|k| {
                    m.advance(&standing);
                    let seen = (k % 3 == 0).then_some(1.5);
                    carried(&mut m, HazardKind::Unknown, seen).0.decision
                })
                .collect::<Vec<Decision>>()
        };
        let held = decisions(1.0);
        assert!(held.iter().all(|&d| d != Decision::Go), "{held:?}");
        // `[memory] standing_hold_s = 0`: off, every frame that misses it goes.
        let off = decisions(0.0);
        assert_eq!(
            off.iter().filter(|&&d| d == Decision::Go).count(),
            20,
            "{off:?}"
        );
    }

    #[test]
    fn hazards_are_carried_out_of_view_once_seen_twice_and_never_behind() {
        let mut m = viewing_from_0_6_m();
        let step = Motion {
            forward_m: 0.1,
            dt_s: 0.1,
            ..Motion::default()
        };
        let frame =
            |m: &mut TerrainMemory, seen: Option<f32>| carried(m, HazardKind::DropOff, seen);
        // Seen once at 0.68 m, then out of view: not carried (one verdict).
        frame(&mut m, Some(0.68));
        m.advance(&step);
        let (v, added) = frame(&mut m, None);
        assert_eq!((v.decision, added), (Decision::Go, 0));
        // Seen at 0.78 and 0.68 m: carried at 0.58, 0.48, ... down to the front axle.
        frame(&mut m, Some(0.78));
        m.advance(&step);
        frame(&mut m, Some(0.68));
        let mut got = Vec::new();
        for _ in 0..9 {
            m.advance(&step);
            let (v, _) = frame(&mut m, None);
            got.push(
                v.hazards
                    .first()
                    .map(|h| (h.distance_m * 100.0).round() as i32),
            );
            assert_eq!(
                v.decision,
                if v.hazards.is_empty() {
                    Decision::Go
                } else {
                    Decision::Stop
                }
            );
        }
        assert_eq!(
            got,
            [
                Some(58),
                Some(48),
                Some(38),
                Some(28),
                Some(18),
                Some(8),
                None,
                None,
                None
            ]
        );
    }

    #[test]
    fn motion_apply_and_unapply_are_inverse() {
        let m = Motion {
            forward_m: 0.3,
            lateral_m: -0.1,
            dheading_rad: 0.4,
            dt_s: 0.1,
        };
        let p = [1.2, 0.7];
        let q = m.unapply(m.apply(p));
        assert!((q[0] - p[0]).abs() < 1e-6 && (q[1] - p[1]).abs() < 1e-6);
        // Straight ahead by 0.3 m: a point 1.2 m ahead is 0.9 m ahead.
        let fwd = Motion {
            forward_m: 0.3,
            ..Motion::default()
        };
        let p = fwd.apply([1.2, 0.0]);
        assert!((p[0] - 0.9).abs() < 1e-6 && p[1] == 0.0, "{p:?}");
    }
}
