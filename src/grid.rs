//! The dense voxel grid over the corridor and the ground cells (columns) under it.
//!
//! The grid covers `x ∈ [0, corridor_length)`, `y ∈ [−track_outer, track_outer)`,
//! `z ∈ [z_min, z_max)` in the rover frame. Its accumulators are allocated once; a
//! frame touches only the voxels its points land in, and only those are reset before
//! the next frame. Each occupied voxel yields exactly one point, the centroid of its
//! points, with their count (exact: no hashing, no duplicates).
//!
//! Projection, transform and binning are fused into [`VoxelGrid::bin`]: one pass over
//! the depth image with the [`Projector`]'s tables, no intermediate cloud.

use std::ops::Range;

use wide::{f32x4, i32x4, CmpEq};

use crate::config::Config;
use crate::mixed_pixels::MixedPixels;
use crate::projection::Projector;

/// The grid's geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridSpec {
    /// Voxel edge, metres.
    pub voxel_m: f32,
    /// Cells along x (forward).
    pub nx: usize,
    /// Cells along y (lateral).
    pub ny: usize,
    /// Cells along z (up).
    pub nz: usize,
    /// Rover-frame corner of voxel (0, 0, 0), metres.
    pub origin: [f32; 3],
}

impl GridSpec {
    /// The grid the config asks for.
    pub fn from_config(config: &Config) -> Self {
        let a = &config.analysis;
        let w = config.rover.track_outer_m;
        let cells = |len: f64| ((len / a.voxel_m) - 1e-9).ceil().max(1.0) as usize;
        GridSpec {
            voxel_m: a.voxel_m as f32,
            nx: cells(a.corridor_length_m),
            ny: cells(2.0 * w),
            nz: cells(a.z_max_m - a.z_min_m),
            origin: [0.0, -w as f32, a.z_min_m as f32],
        }
    }

    /// Number of voxels.
    pub fn voxel_count(&self) -> usize {
        self.nx * self.ny * self.nz
    }

    /// Number of ground cells (columns).
    pub fn cell_count(&self) -> usize {
        self.nx * self.ny
    }

    /// Index of ground cell (ix, iy).
    #[inline]
    pub fn cell(&self, ix: usize, iy: usize) -> usize {
        ix * self.ny + iy
    }

    /// The strip (iy) of ground cell index `c`, the inverse of [`GridSpec::cell`]'s.
    #[inline]
    pub fn strip_of(&self, c: usize) -> usize {
        c % self.ny
    }

    /// Centre x of cells in row ix, metres.
    #[inline]
    pub fn x_centre(&self, ix: usize) -> f32 {
        self.origin[0] + (ix as f32 + 0.5) * self.voxel_m
    }

    /// Centre y of cells in strip iy, metres.
    #[inline]
    pub fn y_centre(&self, iy: usize) -> f32 {
        self.origin[1] + (iy as f32 + 0.5) * self.voxel_m
    }

    /// The cell containing rover-frame (x, y), if inside the grid.
    #[inline]
    pub fn cell_at(&self, x: f32, y: f32) -> Option<(usize, usize)> {
        let fx = (x - self.origin[0]) / self.voxel_m;
        let fy = (y - self.origin[1]) / self.voxel_m;
        if fx >= 0.0 && fy >= 0.0 && fx < self.nx as f32 && fy < self.ny as f32 {
            Some((fx as usize, fy as usize))
        } else {
            None
        }
    }
}

#[derive(Debug, Clone, Copy, Default)]
struct Acc {
    // Sums in voxel units relative to the grid origin (keeps f32 precise).
    sx: f32,
    sy: f32,
    sz: f32,
    n: u32,
}

/// A voxel's (or a run's) highest z in each of [`LANES`] lanes, voxel units, before any
/// point. Kept lane by lane beside the sums and folded once per voxel, in `emit`, not
/// once per run (valgrind counts six times the instructions that way).
const NO_POINT: f32x4 = f32x4::new([f32::NEG_INFINITY; LANES]);

/// One occupied voxel: the centroid of its points and their count.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Voxel {
    /// Centroid x (forward), metres, rover frame.
    pub x: f32,
    /// Centroid y (left), metres, rover frame.
    pub y: f32,
    /// Centroid z (up), metres, rover frame.
    pub z: f32,
    /// Height of the voxel's highest point, metres, rover frame.
    pub z_max: f32,
    /// Number of points in the voxel.
    pub count: u32,
}

/// Counts from one binning pass.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BinStats {
    /// Pixels with a depth inside the range limits.
    pub points_in: u32,
    /// Of those, the points that fell inside the grid.
    pub points_binned: u32,
    /// Points inside the grid dropped as mixed pixels at a depth edge
    /// ([`MixedPixels`]); not in `points_binned`.
    pub points_mixed: u32,
}

/// One ground cell: the points of every voxel in a column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    /// Points in the column.
    pub n: u32,
    /// Mean x of the points, metres.
    pub x: f32,
    /// Mean y of the points, metres.
    pub y: f32,
    /// Mean z of the points, metres.
    pub z: f32,
    /// Highest voxel centroid with at least [`TOP_MIN_POINTS`] points, metres.
    pub top: f32,
    /// The highest point of that voxel, metres (`top` when no voxel has
    /// [`TOP_MIN_POINTS`]). Over a sharp apex the voxel's centroid lies up to two
    /// thirds of a voxel under it.
    pub peak: f32,
    /// That voxel's centroid (x, y), metres: which side of the cell a face's top runs
    /// along. The mean (x, y) when no voxel has [`TOP_MIN_POINTS`].
    pub top_xy: [f32; 2],
    /// Lowest voxel centroid with at least [`TOP_MIN_POINTS`] points, metres. Far
    /// below `top` when the cell holds a vertical face: two surfaces, the face's foot
    /// and its crest.
    pub low: f32,
    /// Mean height of the points within [`SURFACE_BAND`] voxels of `top`: the upper
    /// surface of the cell, without the points of a face below it, metres. Equal to
    /// `z` when the cell's points span no more than that band; `foot` when the band
    /// holds less than [`SURFACE_MIN_SHARE`] of the points. Stray points (voxels
    /// under [`TOP_MIN_POINTS`]) above `top` take no part.
    pub crest: f32,
    /// Mean height of the points within [`SURFACE_BAND`] voxels of `low`: the lower
    /// surface of the cell, without the points of a face above it, metres; `crest`
    /// when the band holds less than [`SURFACE_MIN_SHARE`] of the points. Stray
    /// points below `low` take no part.
    pub foot: f32,
    /// Mean (x, y) of the points `crest` is the mean height of, metres. A face along
    /// a strip hugs one side of its cells; a face across it, their far or near part.
    pub crest_xy: [f32; 2],
    /// Mean (x, y) of the points `foot` is the mean height of, metres.
    pub foot_xy: [f32; 2],
}

/// Least share of a cell's points that makes its upper or lower band a surface; a
/// band with fewer is the fringe of a face seen edge-on, and the other band stands
/// for both.
pub const SURFACE_MIN_SHARE: f32 = 0.25;

/// How many voxels below a cell's top (above its low) count as its upper (lower)
/// surface: two voxel layers, all that one sloped or noisy surface spans in a cell.
pub const SURFACE_BAND: f32 = 1.5;

impl Cell {
    /// A cell with no points.
    pub const EMPTY: Cell = Cell {
        n: 0,
        x: 0.0,
        y: 0.0,
        z: 0.0,
        top: f32::NEG_INFINITY,
        peak: f32::NEG_INFINITY,
        top_xy: [0.0; 2],
        low: f32::INFINITY,
        crest: 0.0,
        foot: 0.0,
        crest_xy: [0.0; 2],
        foot_xy: [0.0; 2],
    };
}

/// Image rows, from the top, whose points mark the cells where the view is cut
/// ([`VoxelGrid::cut`]); two, so that one dropped pixel does not hide a cut.
pub const CUT_ROWS: usize = 2;

/// Depth band below the camera's far range limit whose points, like the top
/// [`CUT_ROWS`] rows', mark the cells where the view is cut ([`VoxelGrid::cut`]),
/// millimetres: about one 5 cm cell of ground, more than depth noise and a Kinect's
/// disparity step at 3 m (1-3 cm). A surface reaching the far limit leaves the
/// sensor's range there, as one reaching the image's top edge leaves its view.
pub const RANGE_CUT_MM: u16 = 50;

/// How near the far range limit an image column's topmost depth in range must lie
/// to mark its cell as cut ([`VoxelGrid::cut`]), millimetres. Ground met at a grazing
/// angle 3 m out steps 4-7 cm in depth from one pixel row to the next (a 320×240
/// camera's rows, a 10-14° descent): its last row in range may lie that far short
/// of the limit, and no point of its strip in [`RANGE_CUT_MM`].
pub const TOPMOST_CUT_MM: u16 = 150;

/// Voxels with fewer points than this do not count for a column's top (one stray
/// point must not raise a rock).
pub const TOP_MIN_POINTS: u32 = 2;

/// Add a run of points (its sums, `run`, and its highest z per lane, `zmax`) to voxel
/// `i` (`u32::MAX`: nothing). Returns the points added.
#[inline]
fn flush(acc: &mut Accumulators, i: u32, run: &Acc, zmax: f32x4) -> u32 {
    if i == u32::MAX || run.n == 0 {
        return 0;
    }
    match (acc.sums.get_mut(i as usize), acc.zmax.get_mut(i as usize)) {
        (Some(a), Some(top)) => {
            if a.n == 0 {
                // Capacity is the voxel count (or the pixel count): never reallocates.
                acc.touched.push(i);
            }
            *top = top.fast_max(zmax);
            a.n += run.n;
            a.sx += run.sx;
            a.sy += run.sy;
            a.sz += run.sz;
            run.n
        }
        _ => 0,
    }
}

/// Per-voxel accumulators ([`Acc`] and highest z per lane), and the voxels touched.
#[derive(Debug, Clone)]
struct Accumulators {
    sums: Vec<Acc>,
    zmax: Vec<f32x4>,
    touched: Vec<u32>,
}

/// Pixels [`merge_row`] takes at a time: pixel k of a row adds to lane k % LANES.
const LANES: usize = 4;

/// Lane l's bit, 1 << l.
const LANE_BIT: i32x4 = i32x4::new([1, 2, 4, 8]);

/// A run's position sums, in [`LANES`] lanes (voxel units), its highest z per lane,
/// and its points.
#[derive(Clone, Copy)]
struct LaneSums {
    x: f32x4,
    y: f32x4,
    z: f32x4,
    zmax: f32x4,
    n: u32,
}

impl LaneSums {
    const ZERO: LaneSums = LaneSums {
        x: f32x4::ZERO,
        y: f32x4::ZERO,
        z: f32x4::ZERO,
        zmax: NO_POINT,
        n: 0,
    };

    /// Add the lanes whose bit is set in `on` (a mask, not a product: the others'
    /// positions may be NaN).
    #[inline(always)]
    fn add(&mut self, on: u32, q: &[f32x4; 3]) {
        let bits = i32x4::splat(on as i32) & LANE_BIT;
        let keep: f32x4 = bytemuck::cast(bits.cmp_eq(LANE_BIT));
        self.x += q[0] & keep;
        self.y += q[1] & keep;
        self.z += q[2] & keep;
        // `fast_max`: no lane is NaN (those not kept are −∞).
        self.zmax = self.zmax.fast_max(keep.blend(q[2], NO_POINT));
        self.n += on.count_ones();
    }

    /// Add all lanes.
    #[inline(always)]
    fn add_all(&mut self, q: &[f32x4; 3]) {
        self.x += q[0];
        self.y += q[1];
        self.z += q[2];
        self.zmax = self.zmax.fast_max(q[2]);
        self.n += LANES as u32;
    }

    /// The run's sums: its lanes added pairwise in a fixed order.
    #[inline(always)]
    fn total(&self) -> Acc {
        let sum = |v: f32x4| {
            let v = v.to_array();
            (v[0] + v[2]) + (v[1] + v[3])
        };
        Acc {
            sx: sum(self.x),
            sy: sum(self.y),
            sz: sum(self.z),
            n: self.n,
        }
    }
}

/// The run [`merge_row`] is adding up: its voxel (`u32::MAX`: none yet) and sums.
struct Merge<'a> {
    acc: &'a mut Accumulators,
    cur: u32,
    run: LaneSums,
    binned: u32,
}

impl Merge<'_> {
    /// Take [`LANES`] pixels: voxel indices (`u32::MAX`: not binned) and positions.
    #[inline(always)]
    fn take(&mut self, ids: i32x4, q: &[f32x4; 3]) {
        let same_as = |cur: u32| ids.cmp_eq(i32x4::splat(cur as i32)).move_mask() as u32;
        let mut same = same_as(self.cur);
        if same == (1 << LANES) - 1 {
            // Inside a run: the common case.
            self.run.add_all(q);
            return;
        }
        let mut pending = !same_as(u32::MAX) & ((1 << LANES) - 1);
        loop {
            let fresh = pending & !same;
            if fresh == 0 {
                if pending != 0 {
                    self.run.add(pending, q);
                }
                return;
            }
            // Lanes before the first pixel of another voxel end this run.
            let p = fresh.trailing_zeros();
            let before = (1u32 << p) - 1;
            if pending & before != 0 {
                self.run.add(pending & before, q);
            }
            self.binned += flush(self.acc, self.cur, &self.run.total(), self.run.zmax);
            self.run = LaneSums::ZERO;
            self.cur = ids.to_array()[p as usize] as u32;
            pending &= !before;
            same = same_as(self.cur);
        }
    }
}

/// The second half of binning one row: add runs of neighbouring pixels that share
/// a voxel (pixels not binned between them do not end a run) and touch the
/// accumulators once per run. A run is summed in [`LANES`] lanes (pixel k in lane
/// k % LANES) with the `wide` crate's portable vectors, so that a stretch of one
/// voxel's pixels is a few vector additions, not a chain of scalar ones (each waiting
/// on the last: that chain was most of binning's time); the lanes are added in a
/// fixed order, so the sums do not depend on the instruction set. Only the columns
/// `span` are read (the others hold no binned pixel); it starts on a whole number of
/// lanes, so that each pixel keeps its lane and the sums are those of the whole row.
/// Returns the points added.
#[multiversion::multiversion(targets("x86_64+avx2", "x86_64+sse4.1", "aarch64+neon"))]
fn merge_row(rb: &RowBuffers, span: Range<usize>, acc: &mut Accumulators) -> u32 {
    let n = rb
        .idx
        .len()
        .min(rb.qx.len())
        .min(rb.qy.len())
        .min(rb.qz.len());
    debug_assert_eq!(span.start % LANES, 0, "a span starts on a lane boundary");
    let hi = span.end.min(n);
    let lo = span.start.min(hi);
    let (idx, qx, qy, qz) = (
        &rb.idx[lo..hi],
        &rb.qx[lo..hi],
        &rb.qy[lo..hi],
        &rb.qz[lo..hi],
    );
    let n = hi - lo;
    let mut m = Merge {
        acc,
        cur: u32::MAX,
        run: LaneSums::ZERO,
        binned: 0,
    };
    let whole = n - n % LANES;
    fn chunks(s: &[f32], whole: usize) -> &[[f32; LANES]] {
        bytemuck::cast_slice(&s[..whole])
    }
    let ids: &[[u32; LANES]] = bytemuck::cast_slice(&idx[..whole]);
    for (((i, x), y), z) in ids
        .iter()
        .zip(chunks(qx, whole))
        .zip(chunks(qy, whole))
        .zip(chunks(qz, whole))
    {
        m.take(
            bytemuck::cast(*i),
            &[f32x4::from(*x), f32x4::from(*y), f32x4::from(*z)],
        );
    }
    if whole < n {
        // The row's last pixels, padded with pixels not binned.
        let r = n - whole;
        let mut ids = [u32::MAX; LANES];
        ids[..r].copy_from_slice(&idx[whole..n]);
        let pad = |s: &[f32]| {
            let mut a = [0.0f32; LANES];
            a[..r].copy_from_slice(&s[whole..n]);
            f32x4::from(a)
        };
        m.take(bytemuck::cast(ids), &[pad(qx), pad(qy), pad(qz)]);
    }
    let (cur, run, zmax) = (m.cur, m.run.total(), m.run.zmax);
    m.binned + flush(m.acc, cur, &run, zmax)
}

/// What [`index_row`] needs about the row and the grid, in voxel units.
#[derive(Clone, Copy)]
struct RowParams {
    /// The row's ray part, voxel units per metre of depth.
    r: [f32; 3],
    t: [f32; 3],
    n: [f32; 3],
    strides: [i32; 2],
    min_mm: u16,
    max_mm: u16,
}

impl RowParams {
    /// What every row of a frame shares: a camera at `origin` (rover frame, metres),
    /// binned into grid `s`, depths in `[min_mm, max_mm]`. Its ray part is zero until
    /// [`RowParams::row`] sets a row's.
    fn new(s: &GridSpec, origin: [f32; 3], (min_mm, max_mm): (u16, u16)) -> Self {
        let inv = 1.0 / s.voxel_m;
        RowParams {
            r: [0.0; 3],
            // The camera's position in voxel units relative to the grid's origin.
            t: [0, 1, 2].map(|k| (origin[k] - s.origin[k]) * inv),
            n: [s.nx as f32, s.ny as f32, s.nz as f32],
            strides: [(s.ny * s.nz) as i32, s.nz as i32],
            min_mm,
            max_mm,
        }
    }

    /// These parameters for the row whose ray part is `row` (the projector's row
    /// table: rover frame, per metre of depth) in grid `s`.
    fn row(self, s: &GridSpec, row: [f32; 3]) -> Self {
        let inv = 1.0 / s.voxel_m;
        RowParams {
            r: row.map(|v| v * inv),
            ..self
        }
    }
}

/// Mark in `cand` the pixels of `row` that may be mixed ([`MixedPixels`]):
/// returned, with a returned neighbour (along the row, or in `above` and `below`, all
/// as wide) more than the least jump at the pixel's depth away (`jump`: per mm of
/// depth, the lesser of the row's and the column's, 16.16 fixed point, rounded down:
/// never more). A mixed pixel always is one; [`MixedPixels::is_mixed`] decides.
/// Returns whether any is. Branch-free in 16-bit lanes, so that it vectorises like
/// [`index_row`].
#[multiversion::multiversion(targets("x86_64+avx2", "x86_64+sse4.1", "aarch64+neon"))]
fn mark_candidates(above: &[u16], row: &[u16], below: &[u16], jump: u16, cand: &mut [u16]) -> bool {
    let n = row.len().min(above.len()).min(below.len()).min(cand.len());
    if n < 2 {
        cand[..n].fill(0);
        return false;
    }
    // Pixel `d` with neighbours `x` (0: none): 1 when one lies more than the jump off.
    let candidate = |d: u16, x: [u16; 4]| {
        let t = ((u32::from(d) * u32::from(jump)) >> 16) as u16;
        let far = x[0].max(x[1]).max(x[2]).max(x[3]);
        // The nearest returned one, less 1 (0 wraps to the top and never wins).
        let z = |v: u16| v.wrapping_sub(1);
        let near_1 = z(x[0]).min(z(x[1])).min(z(x[2])).min(z(x[3]));
        let off = far.saturating_sub(d).max(z(d).saturating_sub(near_1));
        // 1 when off > t and d returned (min and saturation instead of compares).
        off.saturating_sub(t).min(1) & d.min(1)
    };
    // The ends of the row have one neighbour along it.
    cand[0] = candidate(row[0], [0, row[1], above[0], below[0]]);
    let last = n - 1;
    cand[last] = candidate(row[last], [row[last - 1], 0, above[last], below[last]]);
    let mut any = cand[0] | cand[last];
    let (left, mid, right) = (&row[..n - 2], &row[1..last], &row[2..n]);
    let (up, down, out) = (&above[1..last], &below[1..last], &mut cand[1..last]);
    for k in 0..n - 2 {
        let c = candidate(mid[k], [left[k], right[k], up[k], down[k]]);
        out[k] = c;
        any |= c;
    }
    any != 0
}

/// Unmark (`u32::MAX`) the binned pixels of image row `v` of `depth` (`width`
/// wide) that `mixed` finds mixed; `jump` is [`mark_candidates`]'s. Only the
/// columns `span` hold binned pixels: the candidates are marked there (with their
/// neighbours along the row, as over the whole row). Returns how many.
fn drop_mixed(
    mixed: &MixedPixels,
    jump: u16,
    (depth, width): (&[u16], usize),
    (v, span): (usize, Range<usize>),
    rb: &mut RowBuffers,
) -> u32 {
    let rows = depth.len() / width.max(1);
    let line = |r: usize| &depth[r * width..(r + 1) * width];
    let pixels = line(v);
    // Past the image's top or bottom: the pixel itself, no jump.
    let above = if v > 0 { line(v - 1) } else { pixels };
    let below = if v + 1 < rows { line(v + 1) } else { pixels };
    let hi = span.end.min(width);
    let lo = span.start.min(hi);
    // One column more each side, for the neighbours along the row.
    let wide = lo.saturating_sub(1)..(hi + 1).min(width);
    if !mark_candidates(
        &above[wide.clone()],
        &pixels[wide.clone()],
        &below[wide.clone()],
        jump,
        &mut rb.cand[wide.clone()],
    ) {
        return 0;
    }
    let mut dropped = 0;
    for (u, (&c, i)) in rb
        .cand
        .iter()
        .zip(rb.idx.iter_mut())
        .enumerate()
        .take(hi)
        .skip(lo)
    {
        if c != 0 && *i != u32::MAX && mixed.is_mixed(depth, width, u, v) {
            *i = u32::MAX;
            dropped += 1;
        }
    }
    dropped
}

/// How many of a row's depths (mm) lie in `[min_mm, max_mm]`, the least of them
/// (`u16::MAX` when none), and how many lie in `[far_mm, max_mm]`. Vectorises (a
/// running maximum beside the minimum did not: binning flat.png took 1.7× as long).
#[multiversion::multiversion(targets("x86_64+avx2", "x86_64+sse4.1", "aarch64+neon"))]
fn depths_in_range(pixels: &[u16], min_mm: u16, max_mm: u16, far_mm: u16) -> (u32, u16, u32) {
    let (mut n, mut nearest, mut n_far) = (0u32, u16::MAX, 0u32);
    // Counted in 16-bit lanes, as wide as the depths: a whole row is one chunk.
    for chunk in pixels.chunks(usize::from(u16::MAX)) {
        let (mut count, mut far) = (0u16, 0u16);
        for &d in chunk {
            let in_range = (d >= min_mm) & (d <= max_mm);
            count += u16::from(in_range);
            far += u16::from((d >= far_mm) & (d <= max_mm));
            nearest = nearest.min(if in_range { d } else { u16::MAX });
        }
        n += u32::from(count);
        n_far += u32::from(far);
    }
    (n, nearest, n_far)
}

/// Mark the columns of a row whose depth lies in `[min_mm, max_mm]` as having had
/// their topmost such depth (`col_seen`), and take those not marked before off
/// `left`, the columns whose topmost depth in range is still to come. Most frames
/// mark every column in their first rows in range; then it returns at once.
fn see_columns(
    col_seen: &mut [bool],
    pixels: &[u16],
    (min_mm, max_mm): (u16, u16),
    left: &mut usize,
) {
    if *left == 0 {
        return;
    }
    let mut newly = 0;
    for (seen, &d) in col_seen.iter_mut().zip(pixels) {
        let now = !*seen && d >= min_mm && d <= max_mm;
        newly += usize::from(now);
        *seen |= now;
    }
    *left -= newly;
}

/// The columns of a row (`p`) that can hold a point inside the grid. Every depth in
/// range in the row lies in `[near_mm, p.max_mm]`, and a pixel's x (and y) moves
/// monotonically with its depth, in floating point too (the same products and sums as
/// [`index_row`]'s, each rounded monotonically): a column whose x (or y) lies on the
/// same side outside the grid at both ends lies there at every depth between. Along the row, a pinhole's ray tables run
/// monotonically too ([`ColumnRays::order`]), so the columns outside that way on the
/// row's one side are a prefix, those on the other a suffix. Each end is found by
/// walking from `guess`'s (the row before's: neighbouring rows' ends lie a few
/// columns apart; a bisection's mispredicted branches cost binning flat.png 4 %). A
/// row looking past the corridor's sides (far rows: at 3 m a VGA Kinect's row spans
/// 2.2 times the corridor's width) bins only its middle. The whole row when the
/// tables are not monotonic; an empty range when no column can hold a point.
fn grid_columns(
    cols: &ColumnRays,
    p: &RowParams,
    near_mm: u16,
    guess: Range<usize>,
) -> Range<usize> {
    let n = cols.x.len().min(cols.y.len());
    let Some(ascending) = cols.order else {
        return 0..n;
    };
    let (near, far) = (f32::from(near_mm) * 0.001, f32::from(p.max_mm) * 0.001);
    // Whether column k's axis a lies below the grid at both depths, and at or past its
    // end at both: at every depth between.
    let off = |k: usize, a: usize| {
        let ray = [cols.x[k], cols.y[k]][a];
        let (t, r, end) = (p.t[a], p.r[a], p.n[a]);
        let (u, w) = (t + near * (ray + r), t + far * (ray + r));
        (u < 0.0 && w < 0.0, u >= end && w >= end)
    };
    // Outside on the row's start side (`start`): below the grid on an ascending axis,
    // past it on a descending one; on its end side the other way round.
    let out = |k: usize, start: bool| {
        (0..2).any(|a| {
            let (below, past) = off(k, a);
            if ascending[a] == start {
                below
            } else {
                past
            }
        })
    };
    let lo = partition_from(n, guess.start, |k| out(k, true));
    let hi = partition_from(n, guess.end, |k| !out(k, false)).max(lo);
    lo..hi
}

/// `span` rounded out to whole [`LANES`], within `0..n`.
fn whole_lanes(span: Range<usize>, n: usize) -> Range<usize> {
    span.start / LANES * LANES..span.end.next_multiple_of(LANES).min(n)
}

/// The first of `0..n` for which `pred` is false (`n` when none is), `pred` being true
/// on a prefix; found by walking from `guess`.
fn partition_from(n: usize, guess: usize, pred: impl Fn(usize) -> bool) -> usize {
    let mut k = guess.min(n);
    if k < n && pred(k) {
        k += 1;
        while k < n && pred(k) {
            k += 1;
        }
    } else {
        while k > 0 && !pred(k - 1) {
            k -= 1;
        }
    }
    k
}

/// The branch-free half of binning one row: every pixel's voxel index (`u32::MAX`
/// when out of range or outside the grid, and for every pixel outside the columns
/// `span`, which [`grid_columns`] found can hold none inside) and, in `span`,
/// position in voxel units. Returns how many of the span's pixels are in range and
/// how many of them fall inside the grid. Written as
/// plain indexed arithmetic so that it vectorises; compiled for several instruction
/// sets and picked at run time (same results on each: Rust never fuses multiply-adds
/// on its own). [`depths_in_range`] counted the pixels in range already; counted
/// again here, they cost nothing, and without the count the compiler laid the loop
/// out so that binning flat.png took 6 % longer (rustc 1.95, `bench`).
#[multiversion::multiversion(targets("x86_64+avx2", "x86_64+sse4.1", "aarch64+neon"))]
fn index_row(
    cols: &ColumnRays,
    pixels: &[u16],
    p: RowParams,
    span: Range<usize>,
    rb: &mut RowBuffers,
) -> [u32; 2] {
    let n = cols.x.len().min(pixels.len()).min(rb.idx.len());
    let (lo, hi) = (span.start.min(n), span.end.min(n));
    let lo = lo.min(hi);
    rb.idx[..lo].fill(u32::MAX);
    rb.idx[hi..].fill(u32::MAX);
    let (cx_t, cy_t, cz_t, pixels) = (
        &cols.x[lo..hi],
        &cols.y[lo..hi],
        &cols.z[lo..hi],
        &pixels[lo..hi],
    );
    let (idx, qx, qy, qz) = (
        &mut rb.idx[lo..hi],
        &mut rb.qx[lo..hi],
        &mut rb.qy[lo..hi],
        &mut rb.qz[lo..hi],
    );
    let n = hi - lo;
    let (mut valid, mut in_grid) = (0u32, 0u32);
    for k in 0..n {
        let d = pixels[k];
        let in_range = (d >= p.min_mm) & (d <= p.max_mm);
        valid += u32::from(in_range);
        let z = f32::from(d) * 0.001;
        let x = p.t[0] + z * (cx_t[k] + p.r[0]);
        let y = p.t[1] + z * (cy_t[k] + p.r[1]);
        let h = p.t[2] + z * (cz_t[k] + p.r[2]);
        let inside = in_range
            & (x >= 0.0)
            & (y >= 0.0)
            & (h >= 0.0)
            & (x < p.n[0])
            & (y < p.n[1])
            & (h < p.n[2]);
        // Clamp into the grid so the conversion below is always in range (points
        // outside are discarded by `inside` anyway); `f32::max`/`min` also map NaN
        // to a bound.
        let (cx, cy, ch) = (
            x.max(0.0).min(p.n[0] - 1.0),
            y.max(0.0).min(p.n[1] - 1.0),
            h.max(0.0).min(p.n[2] - 1.0),
        );
        // Safety: cx, cy, ch are finite and within [0, n - 1] ⊂ i32's range, which is
        // all `to_int_unchecked` requires; it truncates toward zero, i.e. floors these
        // non-negative values. (The saturating `as` cast does not vectorise.)
        let (ix, iy, iz) = unsafe {
            (
                cx.to_int_unchecked::<i32>(),
                cy.to_int_unchecked::<i32>(),
                ch.to_int_unchecked::<i32>(),
            )
        };
        let i = ix * p.strides[0] + iy * p.strides[1] + iz;
        in_grid += u32::from(inside);
        idx[k] = if inside { i as u32 } else { u32::MAX };
        qx[k] = x;
        qy[k] = y;
        qz[k] = h;
    }
    [valid, in_grid]
}

/// The projector's per-column rays in voxel units, as three arrays (vectorises).
#[derive(Debug, Clone, Default)]
struct ColumnRays {
    /// The projector's column table these were made from (rover frame, per metre).
    source: Vec<[f32; 3]>,
    x: Vec<f32>,
    y: Vec<f32>,
    z: Vec<f32>,
    /// The least of `x`.
    x_min: f32,
    /// Whether `x` and `y` each run monotonically along the row, and which way
    /// (`true`: not decreasing); `None` when one does not. A pinhole's tables do:
    /// each is a fixed vector times the column's increasing ray slope, rounded
    /// monotonically. [`grid_columns`] needs it.
    order: Option<[bool; 2]>,
}

impl ColumnRays {
    /// `projector`'s column rays in the voxel units of grid `s`.
    fn new(projector: &Projector, s: &GridSpec) -> Self {
        let inv = 1.0 / s.voxel_m;
        let c = projector.col_table();
        let axis = |k: usize| c.iter().map(|c| c[k] * inv).collect::<Vec<f32>>();
        let (x, y, z) = (axis(0), axis(1), axis(2));
        ColumnRays {
            source: c.to_vec(),
            x_min: x.iter().copied().fold(f32::INFINITY, f32::min),
            order: monotonic(&x).zip(monotonic(&y)).map(|(x, y)| [x, y]),
            x,
            y,
            z,
        }
    }
}

/// The depth bounds that decide which of a row's points mark a cut cell (mm).
#[derive(Debug, Clone, Copy)]
struct CutLimits {
    /// The sensor's range, `[min_mm, max_mm]`.
    min_mm: u16,
    max_mm: u16,
    /// Points at or past this mark their cell cut by range ([`RANGE_CUT_MM`]).
    range_mm: u16,
    /// An image column's topmost point in range at or past this marks its cell cut by
    /// range ([`TOPMOST_CUT_MM`]).
    topmost_mm: u16,
}

/// The ground cells where the view is cut in the current frame ([`VoxelGrid::cut`],
/// [`VoxelGrid::range_cut`]), with the list of those marked so that clearing them
/// costs what marking did.
#[derive(Debug, Clone)]
struct ViewCut {
    cut: Vec<bool>,
    by_range: Vec<bool>,
    touched: Vec<u32>,
}

impl ViewCut {
    fn new(cells: usize) -> Self {
        ViewCut {
            cut: vec![false; cells],
            by_range: vec![false; cells],
            touched: Vec::with_capacity(cells),
        }
    }

    /// Unmark every cell the last frame marked.
    fn clear(&mut self) {
        for &c in &self.touched {
            self.cut[c as usize] = false;
            self.by_range[c as usize] = false;
        }
        self.touched.clear();
    }

    /// Mark the cells one indexed row's points (`idx`, `pixels`) cut: every point's
    /// when the row is one of the top [`CUT_ROWS`] (`top`); otherwise those within
    /// [`RANGE_CUT_MM`] of the far range limit, and a column's topmost point in range
    /// (`col_seen`: the columns that had one in a row above) within
    /// [`TOPMOST_CUT_MM`] of it (a surface met at a grazing angle leaves the band
    /// between two rows); past them the surface leaves the sensor's range. `nz` is the
    /// grid's column height in voxels.
    fn mark_row(
        &mut self,
        (idx, col_seen): (&[u32], &[bool]),
        pixels: &[u16],
        limits: CutLimits,
        top: bool,
        nz: usize,
    ) {
        for ((&i, &d), &seen) in idx.iter().zip(pixels).zip(col_seen) {
            let in_range = d >= limits.min_mm && d <= limits.max_mm;
            let topmost = in_range && !seen;
            let by_range =
                in_range && (d >= limits.range_mm || (topmost && d >= limits.topmost_mm));
            if i == u32::MAX || !(top || by_range) {
                continue;
            }
            let c = (i / nz as u32) as usize;
            if !self.cut[c] {
                self.cut[c] = true;
                // Capacity is the cell count: never reallocates.
                self.touched.push(c as u32);
            }
            self.by_range[c] |= by_range;
        }
    }
}

/// Whether `v` runs monotonically: `Some(true)` not decreasing, `Some(false)` not
/// increasing (a constant run is both: `true`), `None` neither.
fn monotonic(v: &[f32]) -> Option<bool> {
    if v.windows(2).all(|w| w[0] <= w[1]) {
        Some(true)
    } else if v.windows(2).all(|w| w[0] >= w[1]) {
        Some(false)
    } else {
        None
    }
}

/// One image row's per-pixel voxel indices and positions (voxel units).
#[derive(Debug, Clone, Default)]
struct RowBuffers {
    idx: Vec<u32>,
    /// 1 where the pixel may be mixed (`mark_candidates`).
    cand: Vec<u16>,
    qx: Vec<f32>,
    qy: Vec<f32>,
    qz: Vec<f32>,
    /// Per image column: whether a row above (binned, or the one being) held a
    /// depth in range, so that the column's topmost one is behind.
    col_seen: Vec<bool>,
}

impl RowBuffers {
    fn resize(&mut self, width: usize) {
        // Allocates only when the width grows (the first frame).
        self.col_seen.resize(width, false);
        self.idx.resize(width, u32::MAX);
        self.cand.resize(width, 0);
        self.qx.resize(width, 0.0);
        self.qy.resize(width, 0.0);
        self.qz.resize(width, 0.0);
    }
}

/// The voxel grid with its preallocated accumulators, outputs and ground cells.
#[derive(Debug, Clone)]
pub struct VoxelGrid {
    spec: GridSpec,
    acc: Accumulators,
    voxels: Vec<Voxel>,
    cells: Vec<Cell>,
    touched_cells: Vec<u32>,
    surface_n: Vec<[f32; 2]>,
    view_cut: ViewCut,
    row: RowBuffers,
    cols: ColumnRays,
}

impl VoxelGrid {
    /// Allocate everything for `spec`. `max_points` bounds how many voxels one frame
    /// can touch (the pixel count).
    pub fn new(spec: GridSpec, max_points: usize) -> Self {
        let cap = spec.voxel_count().min(max_points);
        VoxelGrid {
            spec,
            acc: Accumulators {
                sums: vec![Acc::default(); spec.voxel_count()],
                zmax: vec![NO_POINT; spec.voxel_count()],
                touched: Vec::with_capacity(cap),
            },
            voxels: Vec::with_capacity(cap),
            cells: vec![Cell::EMPTY; spec.cell_count()],
            touched_cells: Vec::with_capacity(spec.cell_count()),
            surface_n: vec![[0.0; 2]; spec.cell_count()],
            view_cut: ViewCut::new(spec.cell_count()),
            row: RowBuffers::default(),
            cols: ColumnRays::default(),
        }
    }

    /// The grid geometry.
    pub fn spec(&self) -> &GridSpec {
        &self.spec
    }

    /// The occupied voxels of the last frame.
    pub fn voxels(&self) -> &[Voxel] {
        &self.voxels
    }

    /// The ground cells of the last frame, indexed by [`GridSpec::cell`].
    pub fn cells(&self) -> &[Cell] {
        &self.cells
    }

    /// Ground cells the view's end cuts through in the last frame, indexed by
    /// [`GridSpec::cell`]: those the points of the top [`CUT_ROWS`] rows fall in, and
    /// those of the points within [`RANGE_CUT_MM`] of the far range limit or of an
    /// image column's topmost point in range within [`TOPMOST_CUT_MM`] of it. There the
    /// surface leaves the field of view (or the range), so what the cell holds is only
    /// part of what stands there (under the image's top edge, its lower part: its
    /// height is a lower bound), and the ground beyond it along the line of sight is
    /// beyond view.
    pub fn cut(&self) -> &[bool] {
        &self.view_cut.cut
    }

    /// The cells of [`VoxelGrid::cut`] that the far range limit cuts ([`RANGE_CUT_MM`],
    /// [`TOPMOST_CUT_MM`]), indexed by [`GridSpec::cell`]: the surface leaves the
    /// sensor's range there. A camera pitched down sees the nearer, upper part of such
    /// a cell (its farther, lower points lie past the limit): its height proves
    /// nothing either way.
    pub fn range_cut(&self) -> &[bool] {
        &self.view_cut.by_range
    }

    /// Project, transform and bin one depth image (`projector`'s size) in one pass.
    /// Depths outside `[min_mm, max_mm]` are skipped (`min_mm ≥ 1`, so 0 = no return
    /// is always skipped), and so are the pixels `mixed` finds mixed at a depth edge.
    ///
    /// Each row is done in two steps: a branch-free pass that the compiler vectorises
    /// computes every pixel's voxel index (or `u32::MAX`) and its position in voxel
    /// units; a second pass (`merge_row`) then adds runs of neighbouring pixels
    /// that share a voxel in registers and touches memory once per run.
    pub fn bin(
        &mut self,
        projector: &Projector,
        depth: &[u16],
        min_mm: u16,
        max_mm: u16,
        mixed: &MixedPixels,
    ) -> BinStats {
        let acc = &mut self.acc;
        for &i in &acc.touched {
            (acc.sums[i as usize], acc.zmax[i as usize]) = (Acc::default(), NO_POINT);
        }
        acc.touched.clear();
        self.view_cut.clear();
        let s = self.spec;
        let nx = s.nx as f32;
        let width = projector.width();
        self.row.resize(width);
        // The least jump per mm of depth in 16.16 fixed point (≤ 1: never more).
        let [ju, jv] = mixed.per_mm();
        let jump = (ju.min(jv) * 65536.0).clamp(0.0, 65535.0) as u16;
        if self.cols.source != projector.col_table() {
            // First frame, or a new projector (size or mount: auto-level): allocate.
            self.cols = ColumnRays::new(projector, &s);
        }
        let mut stats = BinStats::default();
        let min_mm = min_mm.max(1);
        let limits = CutLimits {
            min_mm,
            max_mm,
            range_mm: max_mm.saturating_sub(RANGE_CUT_MM),
            topmost_mm: max_mm.saturating_sub(TOPMOST_CUT_MM),
        };
        let range = (min_mm, max_mm);
        self.row.col_seen.fill(false);
        // Image columns whose topmost depth in range is still to come.
        let mut columns_left = width;
        // The last row's columns that can hold a point in the grid.
        let mut guess = 0..width;
        let frame = RowParams::new(&s, projector.origin(), (min_mm, max_mm));
        for (v, (row, pixels)) in projector
            .row_table()
            .iter()
            .zip(depth.chunks_exact(width))
            .enumerate()
        {
            let p = frame.row(&s, *row);
            let (r, t) = (p.r, p.t);
            // A row whose every ray runs forward and whose nearest point lies past the
            // corridor's far end (a voxel's margin for rounding) bins nothing: the
            // upper rows of a camera pitched down at ground beyond the corridor.
            let (valid, nearest_mm, near_limit) =
                depths_in_range(pixels, min_mm, max_mm, limits.topmost_mm);
            let forward = self.cols.x_min + r[0];
            if valid == 0
                || (forward > 0.0 && t[0] + f32::from(nearest_mm) * 0.001 * forward >= nx + 1.0)
            {
                stats.points_in += valid;
                if valid > 0 {
                    see_columns(&mut self.row.col_seen, pixels, range, &mut columns_left);
                }
                continue;
            }
            let rb = &mut self.row;
            let exact = grid_columns(&self.cols, &p, nearest_mm, guess);
            guess = exact.clone();
            let span = whole_lanes(exact, width);
            let [_, in_grid] = index_row(&self.cols, pixels, p, span.clone(), rb);
            stats.points_in += valid;
            if in_grid == 0 {
                // Nothing to bin (a row looking past the corridor): nor to filter.
                see_columns(&mut rb.col_seen, pixels, range, &mut columns_left);
                continue;
            }
            if mixed.is_on() {
                stats.points_mixed +=
                    drop_mixed(mixed, jump, (depth, width), (v, span.clone()), rb);
            }
            if v < CUT_ROWS || near_limit > 0 {
                let seen = (rb.idx.as_slice(), rb.col_seen.as_slice());
                self.view_cut
                    .mark_row(seen, pixels, limits, v < CUT_ROWS, s.nz);
            }
            // The columns in range here have their topmost point behind them from now.
            see_columns(&mut rb.col_seen, pixels, range, &mut columns_left);
            stats.points_binned += merge_row(&self.row, span, &mut self.acc);
        }
        stats
    }

    /// Turn the accumulators into voxel centroids and ground-cell statistics.
    pub fn emit(&mut self) {
        for &c in &self.touched_cells {
            self.cells[c as usize] = Cell::EMPTY;
        }
        self.touched_cells.clear();
        self.voxels.clear();
        let s = self.spec;
        let vs = s.voxel_m;
        // A voxel's cell is its index over the column height: divided in 32 bits,
        // several times quicker than in 64 on many x86 cores.
        let nz = s.nz as u32;
        for &i in &self.acc.touched {
            let a = self.acc.sums[i as usize];
            let [z0, z1, z2, z3] = self.acc.zmax[i as usize].to_array();
            let n = a.n as f32;
            let v = Voxel {
                x: s.origin[0] + a.sx / n * vs,
                y: s.origin[1] + a.sy / n * vs,
                z: s.origin[2] + a.sz / n * vs,
                z_max: s.origin[2] + z0.max(z2).max(z1.max(z3)) * vs,
                count: a.n,
            };
            self.voxels.push(v);
            let c = (i / nz) as usize;
            let cell = &mut self.cells[c];
            if cell.n == 0 {
                self.touched_cells.push(c as u32);
            }
            // Accumulate sums here; divided below.
            cell.n += a.n;
            cell.x += v.x * n;
            cell.y += v.y * n;
            cell.z += v.z * n;
            if a.n >= TOP_MIN_POINTS {
                if v.z > cell.top {
                    (cell.top, cell.top_xy, cell.peak) = (v.z, [v.x, v.y], v.z_max);
                }
                cell.low = cell.low.min(v.z);
            }
        }
        for &c in &self.touched_cells {
            let cell = &mut self.cells[c as usize];
            let n = cell.n as f32;
            cell.x /= n;
            cell.y /= n;
            cell.z /= n;
        }
        // The upper and lower surfaces: a second pass over the voxels, now that each
        // cell's top and low are known (point counts of the two bands in scratch). A
        // cell with no voxel of TOP_MIN_POINTS has none yet: its mean stands for both.
        let band = SURFACE_BAND * vs;
        for &c in &self.touched_cells {
            self.surface_n[c as usize] = [0.0; 2];
        }
        for (&i, v) in self.acc.touched.iter().zip(&self.voxels) {
            let c = (i / nz) as usize;
            let cell = &mut self.cells[c];
            let w = &mut self.surface_n[c];
            let n = v.count as f32;
            let from_voxels = cell.top != f32::NEG_INFINITY;
            let (top, low) = if from_voxels {
                (cell.top, cell.low)
            } else {
                (cell.z, cell.z)
            };
            // A stray point above the top or below the low (a voxel too sparse to
            // count for them) joins neither surface: one point off a face beside the
            // cell must not lift its crest or lower its foot.
            let stray = from_voxels && v.count < TOP_MIN_POINTS && (v.z > top || v.z < low);
            if stray {
                continue;
            }
            if v.z >= top - band {
                cell.crest += v.z * n;
                cell.crest_xy[0] += v.x * n;
                cell.crest_xy[1] += v.y * n;
                w[0] += n;
            }
            if v.z <= low + band {
                cell.foot += v.z * n;
                cell.foot_xy[0] += v.x * n;
                cell.foot_xy[1] += v.y * n;
                w[1] += n;
            }
        }
        for &c in &self.touched_cells {
            let cell = &mut self.cells[c as usize];
            if cell.top == f32::NEG_INFINITY {
                (cell.top, cell.top_xy) = (cell.z, [cell.x, cell.y]);
                (cell.low, cell.peak) = (cell.z, cell.z);
            }
            let [wc, wf] = self.surface_n[c as usize];
            // A band with few of the cell's points is a face's fringe, not a surface.
            let least = SURFACE_MIN_SHARE * cell.n as f32;
            let mean =
                |z: f32, xy: [f32; 2], w: f32| (w >= least).then(|| (z / w, xy.map(|v| v / w)));
            let crest = mean(cell.crest, cell.crest_xy, wc);
            let foot = mean(cell.foot, cell.foot_xy, wf);
            let whole = (cell.z, [cell.x, cell.y]);
            (cell.crest, cell.crest_xy) = crest.or(foot).unwrap_or(whole);
            (cell.foot, cell.foot_xy) = foot.or(crest).unwrap_or(whole);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spec_matches_config() {
        let s = GridSpec::from_config(&Config::default());
        assert_eq!((s.nx, s.ny, s.nz), (60, 28, 70));
        assert_eq!(s.cell_at(0.01, -0.69), Some((0, 0)));
        assert_eq!(s.cell_at(2.99, 0.69), Some((59, 27)));
        assert_eq!(s.cell_at(3.01, 0.0), None);
        assert!((s.y_centre(14) - 0.025).abs() < 1e-6);
        for (ix, iy) in [(0, 0), (0, 27), (59, 0), (31, 13)] {
            assert_eq!(s.strip_of(s.cell(ix, iy)), iy);
        }
    }

    #[test]
    fn merged_runs_add_each_binned_pixel_to_its_voxel() {
        // 23 pixels (not a whole number of lanes): pixels not binned (with NaN
        // positions) before, inside and between runs, runs across lane boundaries, a
        // voxel that comes back after another, and one index past the accumulators.
        const X: u32 = u32::MAX;
        let idx = [
            X, 5, 5, 5, X, 5, 7, 7, 7, 7, 7, 7, 7, 7, 7, 5, 5, X, X, 9, 9, 99, 3,
        ];
        let mut rb = RowBuffers::default();
        rb.resize(idx.len());
        rb.idx.copy_from_slice(&idx);
        for (k, &i) in idx.iter().enumerate() {
            let q = if i == X { f32::NAN } else { k as f32 + 0.25 };
            (rb.qx[k], rb.qy[k], rb.qz[k]) = (q, 2.0 * q, 3.0 - q);
        }
        let mut acc = Accumulators {
            sums: vec![Acc::default(); 16],
            zmax: vec![NO_POINT; 16],
            touched: Vec::with_capacity(16),
        };
        let binned = merge_row(&rb, 0..rb.idx.len(), &mut acc);
        let in_grid = idx
            .iter()
            .filter(|&&i| (i as usize) < acc.sums.len())
            .count();
        assert_eq!(
            binned as usize, in_grid,
            "every pixel with an index in the grid, once"
        );
        assert_eq!(in_grid, 18);
        assert_eq!(acc.touched, [5, 7, 9, 3], "first touched first, each once");
        for (v, (a, top)) in acc.sums.iter().zip(&acc.zmax).enumerate() {
            let ks: Vec<f32> = (0..idx.len())
                .filter(|&k| idx[k] == v as u32)
                .map(|k| k as f32 + 0.25)
                .collect();
            assert_eq!(a.n as usize, ks.len(), "voxel {v}");
            let sum: f32 = ks.iter().sum();
            assert!((a.sx - sum).abs() < 1e-4, "voxel {v}: {} {sum}", a.sx);
            assert!((a.sy - 2.0 * sum).abs() < 1e-4, "voxel {v}");
            assert!(
                (a.sz - (3.0 * ks.len() as f32 - sum)).abs() < 1e-4,
                "voxel {v}"
            );
            // The highest point: the voxel's first pixel (z = 3 − q falls along the
            // row), never a pixel not binned beside it (NaN) nor another voxel's.
            if let Some(first) = ks.first() {
                let top = top.to_array().into_iter().fold(f32::NEG_INFINITY, f32::max);
                assert_eq!(top, 3.0 - first, "voxel {v}");
            }
        }
    }

    #[test]
    fn centroids_are_exact_and_no_voxel_is_emitted_twice() {
        let mut c = Config::default();
        c.mount.pitch_deg = 30.0;
        let p = Projector::new(&c, 64, 48);
        let spec = GridSpec::from_config(&c);
        let mut g = VoxelGrid::new(spec, 64 * 48);
        // Flat ground at z = 0 seen by every pixel: depth from the ray.
        let depth: Vec<u16> = (0..48)
            .flat_map(|v| (0..64).map(move |u| (u, v)))
            .map(|(u, v)| {
                let r = p.ray(u, v);
                ((0.8 / -r.z) * 1000.0).round() as u16
            })
            .collect();
        let stats = g.bin(&p, &depth, 400, 4500, &MixedPixels::OFF);
        g.emit();
        assert!(stats.points_binned > 0 && stats.points_binned <= stats.points_in);
        let total: u32 = g.voxels().iter().map(|v| v.count).sum();
        assert_eq!(total, stats.points_binned);
        let mut seen = std::collections::HashSet::new();
        for v in g.voxels() {
            let key = spec.cell_at(v.x, v.y).unwrap();
            let iz = ((v.z - spec.origin[2]) / spec.voxel_m) as i32;
            assert!(seen.insert((key, iz)), "voxel emitted twice");
            assert!(v.z.abs() < 0.002, "ground centroid at z = {}", v.z);
        }
        // Rebinning the same frame gives the same result (reset works).
        let before = g.voxels().to_vec();
        g.bin(&p, &depth, 400, 4500, &MixedPixels::OFF);
        g.emit();
        assert_eq!(before, g.voxels());
        // An empty frame clears everything.
        g.bin(&p, &vec![0; 64 * 48], 400, 4500, &MixedPixels::OFF);
        g.emit();
        assert!(g.voxels().is_empty());
        assert!(g.cells().iter().all(|c| c.n == 0));
    }

    /// Flat ground at z = 0 as `p`'s camera sees it (640 × 480): each pixel's optical
    /// depth in mm, capped at 4.5 m; 0 for rays at or above the horizon.
    fn flat_ground_depth(p: &Projector) -> Vec<u16> {
        let o = p.origin();
        (0..480)
            .flat_map(|v| (0..640).map(move |u| (u, v)))
            .map(|(u, v)| {
                let r = p.ray(u, v);
                if r.z < -1e-6 {
                    ((-f64::from(o[2]) / r.z) * 1000.0).round().min(4500.0) as u16
                } else {
                    0
                }
            })
            .collect()
    }

    #[test]
    fn a_mixed_pixel_is_not_binned_and_the_surfaces_either_side_are() {
        // Flat ground seen by the default camera, and one pixel on it moved half way
        // to where the pixel beside it sees (as across an edge): with the filter the
        // moved pixel alone is dropped; without, it is binned.
        let c = Config::default();
        let p = Projector::new(&c, 640, 480);
        let spec = GridSpec::from_config(&c);
        let mut depth = flat_ground_depth(&p);
        // Columns 321.. are a far surface 0.6 m behind, pixel 320 is mixed between.
        let v = 400;
        for u in 321..640 {
            depth[v * 640 + u] = depth[v * 640 + 319] + 600;
        }
        depth[v * 640 + 320] = depth[v * 640 + 319] + 300;
        let mixed = MixedPixels::new(&p, c.analysis.mixed_pixel_angle_deg);
        let mut on = VoxelGrid::new(spec, 640 * 480);
        let with = on.bin(&p, &depth, 400, 4500, &mixed);
        let mut off = VoxelGrid::new(spec, 640 * 480);
        let without = off.bin(&p, &depth, 400, 4500, &MixedPixels::OFF);
        assert_eq!(with.points_mixed, 1);
        assert_eq!(without.points_mixed, 0);
        assert_eq!(with.points_in, without.points_in);
        assert_eq!(with.points_binned + 1, without.points_binned);
        assert!(mixed.is_mixed(&depth, 640, 320, v));
        // Its neighbours on either surface are kept.
        assert!(!mixed.is_mixed(&depth, 640, 319, v) && !mixed.is_mixed(&depth, 640, 321, v));
    }

    #[test]
    fn the_columns_a_row_trims_hold_no_point_inside_the_grid() {
        // Mounts pitched 0-45°, rolled, yawed and offset (behind the grid too), three
        // depth rows per image row, all past the row's nearest depth: at it, at the far
        // range limit, and drawn between them with no returns among them. Every pixel outside the row's span
        // falls outside the grid, and the far rows of most mounts are trimmed.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut unit = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (w, h) = (160, 120);
        let (mut trimmed, mut rows) = (0, 0);
        for _ in 0..16 {
            let mut c = Config::default();
            let m = &mut c.mount;
            m.pitch_deg = 45.0 * unit();
            m.roll_deg = 20.0 * unit() - 10.0;
            m.yaw_deg = 20.0 * unit() - 10.0;
            (m.x_m, m.y_m, m.z_m) = (0.7 * unit() - 0.4, 0.4 * unit() - 0.2, 0.5 + 0.7 * unit());
            let p = Projector::new(&c, w, h);
            let s = GridSpec::from_config(&c);
            let cols = ColumnRays::new(&p, &s);
            assert!(cols.order.is_some(), "a pinhole's tables run monotonically");
            let (min_mm, max_mm) = (400, 4500);
            let frame = RowParams::new(&s, p.origin(), (min_mm, max_mm));
            let mut rb = RowBuffers::default();
            rb.resize(w);
            for row in p.row_table() {
                let params = frame.row(&s, *row);
                let near = min_mm + (unit() * f64::from(max_mm - min_mm)) as u16;
                let start = (unit() * w as f64) as usize;
                let guess = start..start + (unit() * (w - start) as f64) as usize;
                let exact = grid_columns(&cols, &params, near, guess.clone());
                let all = 0..w;
                assert_eq!(grid_columns(&cols, &params, near, all.clone()), exact);
                assert_eq!(grid_columns(&cols, &params, near, exact.clone()), exact);
                let span = whole_lanes(exact, w);
                let between = |_: usize| match unit() {
                    u if u < 0.1 => 0,
                    u => near + (u * f64::from(max_mm - near)) as u16,
                };
                for pixels in [
                    vec![near; w],
                    vec![max_mm; w],
                    (0..w).map(between).collect(),
                ] {
                    index_row(&cols, &pixels, params, 0..w, &mut rb);
                    for (k, &i) in rb.idx.iter().enumerate() {
                        assert!(
                            span.contains(&k) || i == u32::MAX,
                            "column {k} outside {span:?} binned at depth {}: {:?}",
                            pixels[k],
                            c.mount
                        );
                    }
                }
                assert!(span.start % LANES == 0 && span.end <= w);
                trimmed += usize::from(span.len() < w);
                rows += 1;
            }
        }
        assert!(trimmed * 4 > rows, "{trimmed} of {rows} rows trimmed");
        // A level camera 0.5 m behind the grid: its middle row's points lie behind the
        // grid at 0.4 m, past it at 4.5 m, inside between. Nothing is trimmed.
        let mut c = Config::default();
        (c.mount.pitch_deg, c.mount.x_m) = (0.0, -0.5);
        let p = Projector::new(&c, w, h);
        let s = GridSpec::from_config(&c);
        let level = RowParams::new(&s, p.origin(), (400, 4500)).row(&s, p.row_table()[h / 2]);
        assert_eq!(
            grid_columns(&ColumnRays::new(&p, &s), &level, 400, 0..0),
            0..w
        );
        // Tables that do not run monotonically are not trimmed.
        let c = Config::default();
        let p = Projector::new(&c, w, h);
        let s = GridSpec::from_config(&c);
        let mut cols = ColumnRays::new(&p, &s);
        cols.y.swap(3, 90);
        cols.order = monotonic(&cols.x)
            .zip(monotonic(&cols.y))
            .map(|(x, y)| [x, y]);
        let far = RowParams::new(&s, p.origin(), (400, 4500)).row(&s, p.row_table()[0]);
        assert_eq!(grid_columns(&cols, &far, 2900, 5..9), 0..w);
    }

    #[test]
    fn rows_past_the_far_end_are_counted_and_a_point_just_inside_them_is_binned() {
        // Flat ground seen by the default camera: its top rows see ground past the
        // corridor's far end (3 m) and bin nothing. One pixel of row 20 sees a post's
        // face 3 cm inside the far end instead: that row is binned, that point alone.
        let c = Config::default();
        let p = Projector::new(&c, 640, 480);
        let spec = GridSpec::from_config(&c);
        let o = p.origin();
        let mut depth = flat_ground_depth(&p);
        let (u, v) = (320, 20);
        let r = p.ray(u, v);
        let ground_x = f64::from(o[0]) + r.x * f64::from(depth[v * 640 + u]) * 0.001;
        assert!(ground_x > 3.5, "row 20 sees ground at {ground_x} m");
        let mut grid = VoxelGrid::new(spec, 640 * 480);
        let without = grid.bin(&p, &depth, 400, 4500, &MixedPixels::OFF);
        let post_z = (2.97 - f64::from(o[0])) / r.x;
        depth[v * 640 + u] = (post_z * 1000.0).round() as u16;
        let with = grid.bin(&p, &depth, 400, 4500, &MixedPixels::OFF);
        grid.emit();
        let in_range = depth.iter().filter(|&&d| (400..=4500).contains(&d)).count();
        assert_eq!(with.points_in as usize, in_range, "skipped rows count too");
        assert_eq!(with.points_binned, without.points_binned + 1);
        let h = f64::from(o[2]) + r.z * post_z;
        assert!(
            grid.voxels().iter().any(|p| p.count == 1
                && (f64::from(p.x) - 2.97).abs() < 0.01
                && (f64::from(p.z) - h).abs() < 0.01),
            "the post's point at (2.97, {h})"
        );
    }

    #[test]
    fn a_stray_point_above_a_cells_top_lifts_neither_surface() {
        // Two points on ground 0.3 m down, one stray point at z = 0 (off a face
        // beside the cell) in the same cell: the stray is too sparse for the top, so
        // it must not lift the crest either (it did: the crest was their mean).
        let c = Config::default();
        let p = Projector::new(&c, 640, 480);
        let spec = GridSpec::from_config(&c);
        let mut g = VoxelGrid::new(spec, 640 * 480);
        let o = p.origin();
        let origin = nalgebra::Vector3::new(f64::from(o[0]), f64::from(o[1]), f64::from(o[2]));
        // Optical depth (mm) of pixel (u, v) where its ray meets height z.
        let depth_at = |u: usize, v: usize, z: f64| {
            let r = p.ray(u, v);
            let d = (z - origin.z) / r.z;
            (d * 1000.0).round() as u16
        };
        let point = |u: usize, v: usize, mm: u16| origin + p.ray(u, v) * (f64::from(mm) / 1000.0);
        let mut depth = vec![0u16; 640 * 480];
        let (u0, v0) = (300, 300); // off the centre line, a cell edge
        let low = [(u0, v0), (u0 + 1, v0)];
        for &(u, v) in &low {
            depth[v * 640 + u] = depth_at(u, v, -0.3);
        }
        let at = point(u0, v0, depth[v0 * 640 + u0]);
        let target = spec.cell_at(at.x as f32, at.y as f32).unwrap();
        let stray = (0..480)
            .flat_map(|v| (0..640).map(move |u| (u, v)))
            .find(|&(u, v)| {
                let q = point(u, v, depth_at(u, v, 0.0));
                // Clear of the cell's edges by a centimetre.
                [(-0.01, -0.01), (0.01, 0.01), (-0.01, 0.01), (0.01, -0.01)]
                    .iter()
                    .all(|(dx, dy)| {
                        spec.cell_at((q.x + dx) as f32, (q.y + dy) as f32) == Some(target)
                    })
            })
            .expect("a pixel sees the cell's ground at z = 0");
        depth[stray.1 * 640 + stray.0] = depth_at(stray.0, stray.1, 0.0);
        g.bin(&p, &depth, 400, 4500, &MixedPixels::OFF);
        g.emit();
        let cell = g.cells()[spec.cell(target.0, target.1)];
        assert_eq!(cell.n, 3);
        assert!((cell.z + 0.2).abs() < 0.01, "mean {}", cell.z);
        for (name, z) in [
            ("top", cell.top),
            ("crest", cell.crest),
            ("foot", cell.foot),
        ] {
            assert!((z + 0.3).abs() < 0.01, "{name} {z}");
        }
    }
}
