use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

/// Which part of the width an element covers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Extent {
    /// The whole width.
    Full,
    /// Only y ≥ 0 (the left half).
    Left,
    /// Only y ≤ 0 (the right half).
    Right,
    /// Only `from_m ≤ y ≤ to_m`, metres: an element with vertical side faces along
    /// those lines (a ramp under one wheel track, ground falling away beside it).
    Band {
        /// Right edge (smaller y), metres.
        from_m: f64,
        /// Left edge (larger y), metres.
        to_m: f64,
    },
    /// Like [`Extent::Band`], but its sides slope where the band's stand vertical:
    /// the element's height fades linearly to nothing over `side_m` centred on each
    /// edge, as a renderer that samples the ground on a grid `side_m` apart and
    /// interpolates between the samples draws a vertical side face.
    Bevelled {
        /// Right edge (smaller y), the middle of its slope, metres.
        from_m: f64,
        /// Left edge (larger y), the middle of its slope, metres.
        to_m: f64,
        /// Width of each side's slope, metres (not positive: vertical, a band).
        side_m: f64,
    },
}

impl Extent {
    /// Whether lateral position `y` (metres) is covered.
    pub fn covers(self, y: f64) -> bool {
        match self {
            Extent::Full => true,
            Extent::Left => y >= 0.0,
            Extent::Right => y <= 0.0,
            Extent::Band { from_m, to_m } => (from_m..=to_m).contains(&y),
            Extent::Bevelled { .. } => self.share(y) > 0.0,
        }
    }

    /// The extent with vertical sides: a [`Extent::Bevelled`] band as the
    /// [`Extent::Band`] it fades from; any other extent as it is.
    pub fn sharp(self) -> Extent {
        match self {
            Extent::Bevelled { from_m, to_m, .. } => Extent::Band { from_m, to_m },
            other => other,
        }
    }

    /// How much of an element's height stands at lateral position `y` (metres): 1
    /// where it is covered, 0 where not, in between across a bevelled side.
    pub fn share(self, y: f64) -> f64 {
        match self {
            Extent::Bevelled {
                from_m,
                to_m,
                side_m,
            } if side_m > 0.0 => {
                let rise = (y - from_m) / side_m + 0.5;
                let fall = (to_m - y) / side_m + 0.5;
                rise.min(fall).clamp(0.0, 1.0)
            }
            Extent::Bevelled { .. } => self.sharp().share(y),
            _ => {
                if self.covers(y) {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }
}

/// One terrain element; heights add up over flat ground at z = 0.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum Element {
    /// A planar face from a straight toe line: it rises (gradient > 0) or falls
    /// (gradient < 0) across the line, up to `cap_m` in height if given.
    Ramp {
        /// Forward distance of the toe line at `ref_y_m`, metres.
        toe_x_m: f64,
        /// Lateral position where `toe_x_m` is measured, metres.
        ref_y_m: f64,
        /// Steepest slope across the toe line, degrees, negative downhill.
        gradient_deg: f64,
        /// Angle of the toe line to the lateral axis, degrees, positive when its
        /// left end is nearer.
        alpha_deg: f64,
        /// Which part of the width the face covers.
        extent: Extent,
        /// Largest height change of the face, metres (a plateau beyond).
        cap_m: Option<f64>,
        /// Length across the toe line over which the toe is rounded, metres: a
        /// parabola centred on the toe line, tangent to the ground before it and to
        /// the face after it, so the two planes still meet at the toe line
        /// ([`crate::sim::toe_rounding`]). `None` (or 0): a sharp toe. The plateau's
        /// edge stays sharp.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        round_m: Option<f64>,
    },
    /// A vertical step up (height > 0) or down at `x_m`.
    Step {
        /// Forward distance of the step, metres.
        x_m: f64,
        /// Height change, metres.
        height_m: f64,
        /// Which part of the width it covers.
        extent: Extent,
    },
    /// A box standing on the ground.
    Block {
        /// Near edge, metres forward.
        x_m: f64,
        /// Centre, metres left.
        y_m: f64,
        /// Length along x, metres.
        length_m: f64,
        /// Width along y, metres.
        width_m: f64,
        /// Height, metres.
        height_m: f64,
    },
    /// A rock: a half-ellipsoid on the ground.
    Rock {
        /// Centre, metres forward.
        x_m: f64,
        /// Centre, metres left.
        y_m: f64,
        /// Radius on the ground, metres.
        radius_m: f64,
        /// Height, metres.
        height_m: f64,
    },
    /// The ground ends at `x_m` and continues `depth_m` lower.
    DropOff {
        /// Forward distance of the edge, metres.
        x_m: f64,
        /// How far the ground falls, metres.
        depth_m: f64,
    },
    /// Rough natural ground: a smooth random height field (a sum of
    /// [`ROUGH_WAVES`] plane waves with Gaussian-distributed wave vectors, which gives
    /// a Gaussian correlation of length `correlation_m`), standard deviation
    /// `amplitude_m / 2`, clipped to `±amplitude_m`. Deterministic for `seed`.
    Rough {
        /// Largest height change either way, metres.
        amplitude_m: f64,
        /// Correlation length, metres.
        correlation_m: f64,
        /// Random seed of the field.
        seed: u64,
    },
    /// Rough natural ground drawn another way than [`Element::Rough`]: value noise,
    /// heights uniform within `±amplitude_m` on a square lattice of `spacing_m`,
    /// blended between lattice points with a smoothstep (continuous slope).
    /// Deterministic for `seed`.
    Lumpy {
        /// Largest height change either way, metres.
        amplitude_m: f64,
        /// Lattice spacing, metres.
        spacing_m: f64,
        /// Random seed of the field.
        seed: u64,
    },
    /// A stone of another shape than [`Element::Rock`]'s half-ellipsoid, on the
    /// same round footprint.
    Stone {
        /// Centre, metres forward.
        x_m: f64,
        /// Centre, metres left.
        y_m: f64,
        /// Radius on the ground, metres.
        radius_m: f64,
        /// Height, metres.
        height_m: f64,
        /// Its profile.
        shape: StoneShape,
    },
}

/// The profile of an [`Element::Stone`], as height over distance from its centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StoneShape {
    /// A cone: straight flanks to a point.
    Cone,
    /// A spherical cap: the part of a sphere above the ground.
    Cap,
    /// A Gaussian mound (σ a third of the radius), cut at the footprint.
    Mound,
    /// A superellipsoid of exponent 4: steep flanks and a broad, flat-ish top.
    Boulder,
}

impl StoneShape {
    /// Every shape.
    pub const ALL: [StoneShape; 4] = [
        StoneShape::Cone,
        StoneShape::Cap,
        StoneShape::Mound,
        StoneShape::Boulder,
    ];

    /// Height as a fraction of the stone's at `r`, the distance from its centre as a
    /// fraction of its radius (0 at and past the rim), for a stone `h` high and
    /// `radius` wide (the cap's curvature depends on both).
    fn profile(self, r: f64, h: f64, radius: f64) -> f64 {
        if r >= 1.0 {
            return 0.0;
        }
        match self {
            StoneShape::Cone => 1.0 - r,
            StoneShape::Cap => {
                // The sphere through the rim and the top: ρ = (R² + h²) / 2h.
                let rho = (radius * radius + h * h) / (2.0 * h);
                let d = r * radius;
                ((rho * rho - d * d).sqrt() - (rho - h)) / h
            }
            StoneShape::Mound => (-4.5 * r * r).exp(),
            StoneShape::Boulder => (1.0 - r.powi(4)).powf(0.25),
        }
    }
}

/// Whether the offset (dx, dy) from a round element's centre lies outside the square
/// about its `radius` (metres), where it adds nothing: no root to take there.
fn outside_square(dx: f64, dy: f64, radius: f64) -> bool {
    dx.abs() >= radius || dy.abs() >= radius
}

/// A uniform number in [−1, 1] for lattice point (i, j) of field `seed`
/// (SplitMix64 of the three).
fn lattice_value(i: i64, j: i64, seed: u64) -> f64 {
    let mut z = seed
        ^ (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (j as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

/// Plane waves summed by [`Element::Rough`].
pub const ROUGH_WAVES: usize = 48;

/// One plane wave of a rough field: wave vector (rad/m) and phase (rad).
fn rough_waves(correlation_m: f64, seed: u64) -> [(f64, f64, f64); ROUGH_WAVES] {
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    // A Gaussian covariance exp(-r²/(2ℓ²)) has a Gaussian spectrum with σ_k = 1/ℓ.
    let k = Normal::new(0.0, 1.0 / correlation_m.max(1e-3)).expect("finite σ");
    let mut out = [(0.0, 0.0, 0.0); ROUGH_WAVES];
    for w in &mut out {
        *w = (
            k.sample(&mut rng),
            k.sample(&mut rng),
            rand::Rng::gen_range(&mut rng, 0.0..std::f64::consts::TAU),
        );
    }
    out
}

impl Element {
    /// A [`Element::Ramp`] with no plateau: toe line at `toe_x_m` (measured at
    /// `ref_y_m`), gradient and toe-line angle in degrees, over `extent`.
    pub fn ramp(
        toe_x_m: f64,
        ref_y_m: f64,
        gradient_deg: f64,
        alpha_deg: f64,
        extent: Extent,
    ) -> Element {
        Element::Ramp {
            toe_x_m,
            ref_y_m,
            gradient_deg,
            alpha_deg,
            extent,
            cap_m: None,
            round_m: None,
        }
    }

    /// A [`Element::Stone`] of `shape`, `height_m` high and `radius_m` in radius, centred
    /// at (`x_m`, `y_m`); metres.
    pub fn stone(x_m: f64, y_m: f64, radius_m: f64, height_m: f64, shape: StoneShape) -> Element {
        Element::Stone {
            x_m,
            y_m,
            radius_m,
            height_m,
            shape,
        }
    }

    /// This ramp with its toe rounded over `round` metres across the toe line
    /// ([`crate::sim::toe_rounding`]; `None` or 0: sharp); other elements are
    /// returned unchanged.
    pub fn toe_rounded(mut self, round: Option<f64>) -> Element {
        if let Element::Ramp { round_m, .. } = &mut self {
            *round_m = round;
        }
        self
    }

    /// This ramp with a plateau `cap_m` metres above (or below) its toe; other
    /// elements are returned unchanged.
    pub fn capped(mut self, cap: Option<f64>) -> Element {
        if let Element::Ramp { cap_m, .. } = &mut self {
            *cap_m = cap;
        }
        self
    }

    fn height(&self, x: f64, y: f64) -> f64 {
        match *self {
            Element::Ramp {
                toe_x_m,
                ref_y_m,
                gradient_deg,
                alpha_deg,
                extent,
                cap_m,
                round_m,
            } => {
                let trig = RampTrig::new(alpha_deg, gradient_deg, round_m);
                trig.height(x, y, toe_x_m, ref_y_m, extent, cap_m)
            }
            Element::Step {
                x_m,
                height_m,
                extent,
            } => {
                if x >= x_m {
                    height_m * extent.share(y)
                } else {
                    0.0
                }
            }
            Element::Block {
                x_m,
                y_m,
                length_m,
                width_m,
                height_m,
            } => {
                if x >= x_m && x <= x_m + length_m && (y - y_m).abs() <= width_m / 2.0 {
                    height_m
                } else {
                    0.0
                }
            }
            Element::Rock {
                x_m,
                y_m,
                radius_m,
                height_m,
            } => {
                if outside_square(x - x_m, y - y_m, radius_m) {
                    return 0.0;
                }
                let r = (x - x_m).hypot(y - y_m) / radius_m;
                if r < 1.0 {
                    height_m * (1.0 - r * r).sqrt()
                } else {
                    0.0
                }
            }
            Element::DropOff { x_m, depth_m } => {
                if x >= x_m {
                    -depth_m
                } else {
                    0.0
                }
            }
            Element::Lumpy {
                amplitude_m,
                spacing_m,
                seed,
            } => {
                let (fx, fy) = (x / spacing_m, y / spacing_m);
                let (i, j) = (fx.floor(), fy.floor());
                let smooth = |t: f64| t * t * (3.0 - 2.0 * t);
                let (a, b) = (smooth(fx - i), smooth(fy - j));
                let (i, j) = (i as i64, j as i64);
                let at = |di: i64, dj: i64| lattice_value(i + di, j + dj, seed);
                amplitude_m
                    * ((1.0 - a) * ((1.0 - b) * at(0, 0) + b * at(0, 1))
                        + a * ((1.0 - b) * at(1, 0) + b * at(1, 1)))
            }
            Element::Stone {
                x_m,
                y_m,
                radius_m,
                height_m,
                shape,
            } => {
                if outside_square(x - x_m, y - y_m, radius_m) {
                    return 0.0;
                }
                let r = (x - x_m).hypot(y - y_m) / radius_m;
                height_m * shape.profile(r, height_m, radius_m)
            }
            Element::Rough { .. } => unreachable!("rough fields are evaluated by Terrain"),
        }
    }

    /// The square (x, y ranges, metres) outside which a block, rock or stone adds
    /// nothing; `None` for the elements that reach everywhere or across a half-plane.
    fn footprint(&self) -> Option<([f64; 2], [f64; 2])> {
        match *self {
            Element::Block {
                x_m,
                y_m,
                length_m,
                width_m,
                ..
            } => Some((
                [x_m, x_m + length_m],
                [y_m - width_m / 2.0, y_m + width_m / 2.0],
            )),
            Element::Rock {
                x_m, y_m, radius_m, ..
            }
            | Element::Stone {
                x_m, y_m, radius_m, ..
            } => Some((
                [x_m - radius_m, x_m + radius_m],
                [y_m - radius_m, y_m + radius_m],
            )),
            _ => None,
        }
    }

    /// (lowest, highest) contribution, metres (unbounded ramps: what a 10 m run gives).
    fn bounds(&self) -> (f64, f64) {
        let h = match *self {
            Element::Ramp {
                gradient_deg,
                cap_m,
                ..
            } => {
                let run = 10.0 * gradient_deg.to_radians().tan();
                match cap_m {
                    Some(cap) => run.clamp(-cap, cap),
                    None => run,
                }
            }
            Element::Step { height_m, .. } => height_m,
            Element::Block { height_m, .. }
            | Element::Rock { height_m, .. }
            | Element::Stone { height_m, .. } => height_m,
            Element::DropOff { depth_m, .. } => -depth_m,
            Element::Rough { amplitude_m, .. } | Element::Lumpy { amplitude_m, .. } => {
                return (-amplitude_m, amplitude_m)
            }
        };
        (h.min(0.0), h.max(0.0))
    }
}

/// How far past the toe line a ramp's face stands, per unit of its tangent, at
/// `across` metres past it (negative before it), with its toe rounded over `round`
/// metres: `across` past `round / 2`, nothing before `−round / 2`, and between
/// them the parabola (across + round / 2)² / (2 round), which meets both with their
/// slope. It lies over both lines, by at most `round / 8` at the toe line.
pub fn toe_rounding(across: f64, round: f64) -> f64 {
    let half = 0.5 * round;
    if across >= half {
        across
    } else if across <= -half {
        0.0
    } else {
        (across + half).powi(2) / (2.0 * round)
    }
}

/// A ramp's trigonometry, which a [`HeightField`] computes once and not per query.
#[derive(Debug, Clone, Copy)]
struct RampTrig {
    /// cos and sin of the toe line's angle.
    cos: f64,
    sin: f64,
    /// Tangent of the gradient.
    tan: f64,
    /// Length of the toe's rounding, metres (0: sharp).
    round: f64,
}

impl RampTrig {
    fn new(alpha_deg: f64, gradient_deg: f64, round_m: Option<f64>) -> Self {
        let a = alpha_deg.to_radians();
        RampTrig {
            cos: a.cos(),
            sin: a.sin(),
            tan: gradient_deg.to_radians().tan(),
            round: round_m.unwrap_or(0.0).max(0.0),
        }
    }

    /// How far (x, y) lies past the toe line at `toe_x` (measured at `ref_y`), across
    /// it, metres.
    fn across(self, x: f64, y: f64, toe_x: f64, ref_y: f64) -> f64 {
        (x - toe_x) * self.cos + (y - ref_y) * self.sin
    }

    /// Height of the ramp with toe line at `toe_x` (measured at `ref_y`) over
    /// `extent`, capped at `cap`, at (x, y), metres.
    fn height(
        self,
        x: f64,
        y: f64,
        toe_x: f64,
        ref_y: f64,
        extent: Extent,
        cap: Option<f64>,
    ) -> f64 {
        let share = extent.share(y);
        if share == 0.0 {
            return 0.0;
        }
        let across = self.across(x, y, toe_x, ref_y);
        if across <= -0.5 * self.round {
            return 0.0;
        }
        let h = toe_rounding(across, self.round) * self.tan;
        share
            * match cap {
                Some(cap) => h.clamp(-cap, cap),
                None => h,
            }
    }
}

/// What a [`HeightField`] prepares for one element.
#[derive(Debug, Clone)]
enum Prepared {
    /// A rough field's table.
    Rough(Box<RoughTable>),
    /// A ramp's trigonometry.
    Ramp(RampTrig),
    /// Nothing: the element is evaluated as it is.
    Plain,
}

/// A height field: flat ground at z = 0 plus elements.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Terrain {
    /// The elements, heights added.
    pub elements: Vec<Element>,
}

/// A terrain prepared for many height queries: each rough field's waves drawn once
/// and tabulated on a `ROUGH_GRID_M` grid over the region a camera on the rover
/// can see (`ROUGH_TABLE_X`, `ROUGH_TABLE_Y`), a tile at a time as queries need
/// it, interpolated bilinearly there (an error far below a millimetre for
/// correlation lengths of centimetres and more) and summed directly elsewhere; each
/// ramp's trigonometry computed once (the same values as per query, so the same
/// heights to the bit).
#[derive(Debug, Clone)]
pub struct HeightField<'a> {
    terrain: &'a Terrain,
    prepared: Vec<Prepared>,
}

/// Spacing of a rough field's table, metres.
pub const ROUGH_GRID_M: f64 = 0.01;
/// Forward extent of a rough field's table, metres: from behind the rover to past
/// the renderer's farthest ray ([`super::FAR_M`]).
pub const ROUGH_TABLE_X: (f64, f64) = (-0.5, 12.0);
/// Lateral extent of a rough field's table, metres.
pub const ROUGH_TABLE_Y: (f64, f64) = (-12.0, 12.0);
/// Where the table's lattice starts: (x, y) of grid point (0, 0), metres. Points at
/// negative indices down to [`ROUGH_TABLE_X`]`.0`, [`ROUGH_TABLE_Y`]`.0` are in the
/// table too; the origin fixes where the lattice lies.
const ROUGH_ORIGIN: (f64, f64) = (-0.5, -3.0);
/// Side of a tile of a rough field's table, grid steps. The table is computed a
/// tile at a time, when a query first needs it: a frame touches a small part of it.
const ROUGH_TILE: usize = 64;

#[derive(Debug)]
struct RoughTable {
    amplitude: f64,
    scale: f64,
    waves: [(f64, f64, f64); ROUGH_WAVES],
    /// Lattice index of the table's first grid point, (i, j).
    first: (i64, i64),
    /// Tiles along x and along y.
    tiles: (usize, usize),
    /// The tiles, x-major, each [`ROUGH_TILE`]² heights (x-major), filled on first
    /// use.
    table: Vec<OnceLock<Box<[f32]>>>,
}

impl Clone for RoughTable {
    fn clone(&self) -> Self {
        RoughTable::new_like(self)
    }
}

impl RoughTable {
    fn new(amplitude: f64, correlation: f64, seed: u64) -> Self {
        // σ = amplitude / 2: each wave contributes σ·√(2/N)·cos(…).
        let scale = 0.5 * amplitude * (2.0 / ROUGH_WAVES as f64).sqrt();
        let index = |v: f64, origin: f64| ((v - origin) / ROUGH_GRID_M).floor() as i64;
        let first = (
            index(ROUGH_TABLE_X.0, ROUGH_ORIGIN.0),
            index(ROUGH_TABLE_Y.0, ROUGH_ORIGIN.1),
        );
        let last = (
            index(ROUGH_TABLE_X.1, ROUGH_ORIGIN.0),
            index(ROUGH_TABLE_Y.1, ROUGH_ORIGIN.1),
        );
        let count = |a: i64, b: i64| ((b - a + 1) as usize).div_ceil(ROUGH_TILE);
        let tiles = (count(first.0, last.0), count(first.1, last.1));
        RoughTable {
            amplitude,
            scale,
            waves: rough_waves(correlation, seed),
            first,
            tiles,
            table: (0..tiles.0 * tiles.1).map(|_| OnceLock::new()).collect(),
        }
    }

    /// A table of the same field, its tiles not yet computed.
    fn new_like(&self) -> Self {
        RoughTable {
            table: (0..self.table.len()).map(|_| OnceLock::new()).collect(),
            ..*self
        }
    }

    /// The field summed directly, unclipped.
    fn direct(&self, x: f64, y: f64) -> f64 {
        let s: f64 = self
            .waves
            .iter()
            .map(|&(kx, ky, p)| (kx * x + ky * y + p).cos())
            .sum();
        self.scale * s
    }

    /// The tabulated value at lattice point (i, j), if the table holds it.
    fn at(&self, i: i64, j: i64) -> Option<f64> {
        let (ti, tj) = (i - self.first.0, j - self.first.1);
        if ti < 0 || tj < 0 {
            return None;
        }
        let (ti, tj) = (ti as usize, tj as usize);
        let (tx, ty) = (ti / ROUGH_TILE, tj / ROUGH_TILE);
        if tx >= self.tiles.0 || ty >= self.tiles.1 {
            return None;
        }
        let tile = self.table[tx * self.tiles.1 + ty].get_or_init(|| {
            let (i0, j0) = (
                self.first.0 + (tx * ROUGH_TILE) as i64,
                self.first.1 + (ty * ROUGH_TILE) as i64,
            );
            (0..ROUGH_TILE * ROUGH_TILE)
                .map(|k| {
                    let x = ROUGH_ORIGIN.0 + (i0 + (k / ROUGH_TILE) as i64) as f64 * ROUGH_GRID_M;
                    let y = ROUGH_ORIGIN.1 + (j0 + (k % ROUGH_TILE) as i64) as f64 * ROUGH_GRID_M;
                    self.direct(x, y) as f32
                })
                .collect()
        });
        Some(f64::from(
            tile[(ti % ROUGH_TILE) * ROUGH_TILE + tj % ROUGH_TILE],
        ))
    }

    /// The field at (x, y), metres: interpolated bilinearly in the table, summed
    /// directly outside it; clipped to the amplitude.
    fn height(&self, x: f64, y: f64) -> f64 {
        let fx = (x - ROUGH_ORIGIN.0) / ROUGH_GRID_M;
        let fy = (y - ROUGH_ORIGIN.1) / ROUGH_GRID_M;
        let (i, j) = (floor(fx), floor(fy));
        let (a, b) = (fx - i as f64, fy - j as f64);
        let corners = (|| {
            Some([
                self.at(i, j)?,
                self.at(i, j + 1)?,
                self.at(i + 1, j)?,
                self.at(i + 1, j + 1)?,
            ])
        })();
        let h = match corners {
            Some([c00, c01, c10, c11]) => {
                (1.0 - a) * ((1.0 - b) * c00 + b * c01) + a * ((1.0 - b) * c10 + b * c11)
            }
            None => self.direct(x, y),
        };
        h.clamp(-self.amplitude, self.amplitude)
    }
}

/// `v.floor()` as an integer, without a call to libm's `floor` (which the baseline
/// x86-64 target makes for every `f64::floor`, a tenth of a frame's rendering).
fn floor(v: f64) -> i64 {
    let i = v as i64;
    if (i as f64) > v {
        i - 1
    } else {
        i
    }
}

impl HeightField<'_> {
    /// Bounds on the height anywhere, metres.
    pub fn bounds(&self) -> (f64, f64) {
        self.terrain.bounds()
    }

    /// Ground height at (x, y), metres, rover frame.
    pub fn height(&self, x: f64, y: f64) -> f64 {
        let mut h = 0.0;
        for (e, p) in self.terrain.elements.iter().zip(&self.prepared) {
            h += match (p, e) {
                (Prepared::Rough(table), _) => table.height(x, y),
                (
                    Prepared::Ramp(trig),
                    &Element::Ramp {
                        toe_x_m,
                        ref_y_m,
                        extent,
                        cap_m,
                        ..
                    },
                ) => trig.height(x, y, toe_x_m, ref_y_m, extent, cap_m),
                _ => e.height(x, y),
            };
        }
        h
    }
}

/// How one element bounds the height from above ([`HeightField::reach`]), metres.
enum Upper {
    /// A rising ramp: the half-plane past its toe line (at x, measured at y) at its
    /// slope, up to its cap.
    Ramp(RampTrig, [f64; 2], Option<f64>),
    /// A step up: its height past its edge.
    Step { x: f64, height: f64 },
    /// A block, rock or stone: its height over the square about it.
    Square {
        x: [f64; 2],
        y: [f64; 2],
        height: f64,
    },
    /// Anything else: its highest point, everywhere (nothing for a descent).
    Everywhere(f64),
}

impl Upper {
    fn of(e: &Element, p: &Prepared) -> Upper {
        match (e, p) {
            (
                &Element::Ramp {
                    toe_x_m,
                    ref_y_m,
                    cap_m,
                    ..
                },
                &Prepared::Ramp(trig),
            ) if trig.tan > 0.0 => Upper::Ramp(trig, [toe_x_m, ref_y_m], cap_m),
            (&Element::Step { x_m, height_m, .. }, _) if height_m > 0.0 => Upper::Step {
                x: x_m,
                height: height_m,
            },
            _ => match e.footprint() {
                Some((x, y)) => Upper::Square {
                    x,
                    y,
                    height: e.bounds().1,
                },
                None => Upper::Everywhere(e.bounds().1),
            },
        }
    }

    /// The bound at (x, y), metres.
    fn at(&self, x: f64, y: f64) -> f64 {
        match *self {
            Upper::Ramp(trig, [toe_x, ref_y], cap) => {
                // A rounded toe lies under the face's line moved back by half its
                // rounding (`toe_rounding`).
                let past = trig.across(x, y, toe_x, ref_y) + 0.5 * trig.round;
                let h = (past * trig.tan).max(0.0);
                cap.map_or(h, |cap| h.min(cap))
            }
            Upper::Step { x: edge, height } => {
                if x >= edge {
                    height
                } else {
                    0.0
                }
            }
            Upper::Square {
                x: [x0, x1],
                y: [y0, y1],
                height,
            } => {
                if (x0..=x1).contains(&x) && (y0..=y1).contains(&y) {
                    height
                } else {
                    0.0
                }
            }
            Upper::Everywhere(height) => height,
        }
    }

    /// Where the bound changes its slope or value along the ray `origin + t·dir`
    /// (x and y, metres): each `t` is given to `push`, which says whether it kept it.
    fn breaks(&self, origin: [f64; 3], dir: [f64; 3], mut push: impl FnMut(f64) -> bool) -> bool {
        let at = |o: f64, d: f64, v: f64| (d != 0.0).then(|| (v - o) / d);
        let mut kept = true;
        let mut put = |t: Option<f64>| kept &= t.is_none_or(&mut push);
        match *self {
            Upper::Ramp(trig, [toe_x, ref_y], cap) => {
                // The distance past the bound's toe line, a + b·t.
                let a = trig.across(origin[0], origin[1], toe_x, ref_y) + 0.5 * trig.round;
                let b = dir[0] * trig.cos + dir[1] * trig.sin;
                put(at(a, b, 0.0));
                if let Some(cap) = cap {
                    put(at(a, b, cap / trig.tan));
                }
            }
            Upper::Step { x, .. } => put(at(origin[0], dir[0], x)),
            Upper::Square { x, y, .. } => {
                for (k, [lo, hi]) in [(0, x), (1, y)] {
                    put(at(origin[k], dir[k], lo));
                    put(at(origin[k], dir[k], hi));
                }
            }
            Upper::Everywhere(_) => {}
        }
        kept
    }
}

impl HeightField<'_> {
    /// The least `t` in `[t0, t1]` at which the ray `origin + t·dir` (terrain frame,
    /// metres) may meet the ground: before it the ray stays above an upper bound on
    /// the height, in which a rising ramp is the half-plane past its toe line (its
    /// extent aside; a rounded toe's line moved back by half its rounding), a step up
    /// the half-plane past its edge, a block, rock or stone
    /// the square about it, and any other element its highest point everywhere. `t1`
    /// when it never comes down to that bound. The bound is piecewise linear along
    /// the ray, so the answer is exact up to rounding: [`super::render`] only skips
    /// the height queries before it.
    pub fn reach(&self, origin: [f64; 3], dir: [f64; 3], t0: f64, t1: f64) -> f64 {
        let uppers = || {
            self.terrain
                .elements
                .iter()
                .zip(&self.prepared)
                .map(|(e, p)| Upper::of(e, p))
        };
        // Where the bound's slope or value changes along the ray (more than it holds:
        // no bound, the march asks everywhere).
        let mut breaks = heapless::Vec::<f64, 48>::new();
        let mut room = true;
        for u in uppers() {
            room &= u.breaks(origin, dir, |t| {
                !(t > t0 && t < t1) || breaks.push(t).is_ok()
            });
        }
        if !room {
            return t0;
        }
        let upper = |t: f64| {
            let (x, y) = (origin[0] + t * dir[0], origin[1] + t * dir[1]);
            uppers().map(|u| u.at(x, y)).sum::<f64>()
        };
        breaks.sort_unstable_by(f64::total_cmp);
        let mut a = t0;
        for b in breaks.iter().copied().chain([t1]) {
            let w = b - a;
            if w > 0.0 {
                // The bound is linear inside the piece: its line through two inner
                // points, carried to the ends.
                let (p, q) = (a + 0.25 * w, a + 0.75 * w);
                let (up, uq) = (upper(p), upper(q));
                let slope = (uq - up) / (q - p);
                let ga = origin[2] + a * dir[2] - (up - slope * (p - a));
                let gb = origin[2] + b * dir[2] - (uq + slope * (b - q));
                if ga <= 0.0 {
                    return a;
                }
                if gb <= 0.0 {
                    return a + w * ga / (ga - gb);
                }
            }
            a = b;
        }
        t1
    }
}

impl Terrain {
    /// Flat ground.
    pub fn flat() -> Self {
        Terrain::default()
    }

    /// Ground with these elements.
    pub fn new(elements: Vec<Element>) -> Self {
        Terrain { elements }
    }

    /// This terrain prepared for many height queries.
    pub fn field(&self) -> HeightField<'_> {
        let prepared = self
            .elements
            .iter()
            .map(|e| match *e {
                Element::Rough {
                    amplitude_m,
                    correlation_m,
                    seed,
                } => Prepared::Rough(Box::new(RoughTable::new(amplitude_m, correlation_m, seed))),
                Element::Ramp {
                    gradient_deg,
                    alpha_deg,
                    round_m,
                    ..
                } => Prepared::Ramp(RampTrig::new(alpha_deg, gradient_deg, round_m)),
                _ => Prepared::Plain,
            })
            .collect();
        HeightField {
            terrain: self,
            prepared,
        }
    }

    /// Ground height at (x, y), metres, rover frame (prepares the field per call: use
    /// [`Terrain::field`] for many queries).
    pub fn height(&self, x: f64, y: f64) -> f64 {
        self.field().height(x, y)
    }

    /// Bounds on the height anywhere, metres.
    pub fn bounds(&self) -> (f64, f64) {
        self.elements.iter().fold((0.0, 0.0), |(lo, hi), e| {
            let (a, b) = e.bounds();
            (lo + a, hi + b)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the table must give at (x, y): the direct sums at the four lattice
    /// points around it, as stored (f32), blended bilinearly; clipped.
    fn by_hand(t: &RoughTable, x: f64, y: f64) -> f64 {
        let (fx, fy) = (
            (x - ROUGH_ORIGIN.0) / ROUGH_GRID_M,
            (y - ROUGH_ORIGIN.1) / ROUGH_GRID_M,
        );
        let (i, j) = (fx.floor(), fy.floor());
        let (a, b) = (fx - i, fy - j);
        let at = |di: f64, dj: f64| {
            let px = ROUGH_ORIGIN.0 + ((i + di) as i64) as f64 * ROUGH_GRID_M;
            let py = ROUGH_ORIGIN.1 + ((j + dj) as i64) as f64 * ROUGH_GRID_M;
            f64::from(t.direct(px, py) as f32)
        };
        let h = (1.0 - a) * ((1.0 - b) * at(0.0, 0.0) + b * at(0.0, 1.0))
            + a * ((1.0 - b) * at(1.0, 0.0) + b * at(1.0, 1.0));
        h.clamp(-t.amplitude, t.amplitude)
    }

    #[test]
    fn a_rounded_toe_is_the_parabola_tangent_to_both_planes() {
        // A 20° ramp whose toe line at x = 1.5 m is rounded over 0.4 m: flat to
        // x = 1.3, the face from x = 1.7, and between them tan 20° · (x − 1.3)² / 0.8,
        // which stands tan 20° · 0.4 / 8 = 1.820 cm over the toe line.
        let t = Terrain::new(vec![
            Element::ramp(1.5, 0.0, 20.0, 0.0, Extent::Full).toe_rounded(Some(0.4))
        ]);
        let tan = 20f64.to_radians().tan();
        for (x, want) in [
            (1.0, 0.0),
            (1.3, 0.0),
            (1.4, tan * 0.01 / 0.8),
            (1.5, tan * 0.05),
            (1.6, tan * 0.09 / 0.8),
            (1.7, tan * 0.2),
            (2.0, tan * 0.5),
        ] {
            let got = t.height(x, 0.3);
            assert!((got - want).abs() < 1e-12, "x {x}: {got} vs {want}");
        }
        assert!((t.height(1.5, 0.0) - 0.018199).abs() < 1e-6);
        // The slope is continuous: 0 at the start, tan 20° at the end.
        let slope = |x: f64| (t.height(x + 1e-6, 0.0) - t.height(x - 1e-6, 0.0)) / 2e-6;
        assert!(slope(1.3).abs() < 1e-5 && (slope(1.7) - tan).abs() < 1e-5);
        // The same through the height field (its prepared trigonometry), and a
        // descent's rounding lies under both its planes.
        let field = t.field();
        assert!((field.height(1.6, -0.2) - tan * 0.09 / 0.8).abs() < 1e-12);
        let down = Terrain::new(vec![
            Element::ramp(1.0, 0.0, -10.0, 0.0, Extent::Full).toe_rounded(Some(0.3))
        ]);
        let tan10 = 10f64.to_radians().tan();
        assert!((down.height(1.0, 0.0) + tan10 * 0.3 / 8.0).abs() < 1e-12);
        assert_eq!(down.height(0.85, 0.0), 0.0);
        // A sharp toe (no rounding, or 0) as before.
        let sharp = Terrain::new(vec![
            Element::ramp(1.5, 0.0, 20.0, 0.0, Extent::Full).toe_rounded(Some(0.0))
        ]);
        assert_eq!(sharp.height(1.5, 0.0), 0.0);
        assert!((sharp.height(1.6, 0.0) - tan * 0.1).abs() < 1e-12);
    }

    #[test]
    fn a_bevelled_band_fades_its_element_linearly_across_each_side() {
        // A 20° ramp from x = 1 m under the left track, its sides sloping over 10 cm
        // centred on y = 0.2 and 0.7 m; and a 15 cm step over the same band.
        let extent = Extent::Bevelled {
            from_m: 0.2,
            to_m: 0.7,
            side_m: 0.1,
        };
        let tan = 20f64.to_radians().tan();
        let ramp = Terrain::new(vec![Element::ramp(1.0, 0.45, 20.0, 0.0, extent)]);
        let step = Terrain::new(vec![Element::Step {
            x_m: 1.0,
            height_m: 0.15,
            extent,
        }]);
        let (ramp, step) = (ramp.field(), step.field());
        // (y, share of the height): none outside, half on each edge, all inside.
        for (y, share) in [
            (0.1, 0.0),
            (0.15, 0.0),
            (0.175, 0.25),
            (0.2, 0.5),
            (0.225, 0.75),
            (0.25, 1.0),
            (0.45, 1.0),
            (0.65, 1.0),
            (0.7, 0.5),
            (0.74, 0.1),
            (0.75, 0.0),
            (-0.45, 0.0),
        ] {
            for x in [0.5, 1.0, 1.5, 2.5] {
                let want = (x - 1.0f64).max(0.0) * tan * share;
                assert!(
                    (ramp.height(x, y) - want).abs() < 1e-12,
                    "ramp at ({x}, {y})"
                );
                let want = if x >= 1.0 { 0.15 * share } else { 0.0 };
                assert!(
                    (step.height(x, y) - want).abs() < 1e-12,
                    "step at ({x}, {y})"
                );
            }
        }
        // No slope: the band's vertical sides, the same heights bit for bit.
        let band = Extent::Band {
            from_m: 0.2,
            to_m: 0.7,
        };
        let sheer = Extent::Bevelled {
            from_m: 0.2,
            to_m: 0.7,
            side_m: 0.0,
        };
        let [a, b] =
            [band, sheer].map(|e| Terrain::new(vec![Element::ramp(1.0, 0.45, 20.0, 10.0, e)]));
        let (a, b) = (a.field(), b.field());
        for k in 0..200 {
            let (x, y) = (0.5 + 0.01 * f64::from(k), -0.1 + 0.0047 * f64::from(k));
            assert_eq!(
                a.height(x, y).to_bits(),
                b.height(x, y).to_bits(),
                "({x}, {y})"
            );
        }
    }

    #[test]
    fn the_tiled_table_gives_the_lattice_blend_everywhere_and_the_sum_outside() {
        let t = RoughTable::new(0.025, 0.1, 11);
        let tile = ROUGH_TILE as f64 * ROUGH_GRID_M;
        let mut points = vec![
            // Both sides of tile boundaries, and the lattice's origin.
            (ROUGH_ORIGIN.0 + tile - 0.003, ROUGH_ORIGIN.1 + tile - 0.004),
            (ROUGH_ORIGIN.0 + tile + 0.003, ROUGH_ORIGIN.1 - tile + 0.004),
            (ROUGH_ORIGIN.0, ROUGH_ORIGIN.1),
            // Far ahead and far to the side, where rays end.
            (9.87, -7.31),
            (11.95, 11.9),
            (-0.45, -11.95),
        ];
        // A spread over the table, not on the lattice.
        for k in 0..400 {
            let k = f64::from(k);
            points.push(((k * 0.3137) % 12.4 - 0.45, (k * 0.7311) % 23.9 - 11.95));
        }
        for &(x, y) in &points {
            assert_eq!(t.height(x, y), by_hand(&t, x, y), "at ({x}, {y})");
            // The table's own error against the sum it tabulates.
            let direct = t.direct(x, y).clamp(-0.025, 0.025);
            assert!((t.height(x, y) - direct).abs() < 2e-4, "at ({x}, {y})");
        }
        // Outside the table: the sum itself.
        for (x, y) in [(-0.6, 0.0), (12.5, 1.0), (3.0, 12.5), (3.0, -12.5)] {
            assert_eq!(t.height(x, y), t.direct(x, y).clamp(-0.025, 0.025));
        }
        // A clone starts empty and gives the same heights.
        let c = t.clone();
        assert!(c.table.iter().all(|tile| tile.get().is_none()));
        for &(x, y) in &points {
            assert_eq!(c.height(x, y), t.height(x, y));
        }
    }
}
