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
}

impl Extent {
    /// Whether lateral position `y` (metres) is covered.
    pub fn covers(self, y: f64) -> bool {
        match self {
            Extent::Full => true,
            Extent::Left => y >= 0.0,
            Extent::Right => y <= 0.0,
            Extent::Band { from_m, to_m } => (from_m..=to_m).contains(&y),
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
        }
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
            } => {
                if !extent.covers(y) {
                    return 0.0;
                }
                let a = alpha_deg.to_radians();
                let across = (x - toe_x_m) * a.cos() + (y - ref_y_m) * a.sin();
                if across <= 0.0 {
                    return 0.0;
                }
                let h = across * gradient_deg.to_radians().tan();
                match cap_m {
                    Some(cap) => h.clamp(-cap, cap),
                    None => h,
                }
            }
            Element::Step {
                x_m,
                height_m,
                extent,
            } => {
                if extent.covers(y) && x >= x_m {
                    height_m
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
                let r = (x - x_m).hypot(y - y_m) / radius_m;
                height_m * shape.profile(r, height_m, radius_m)
            }
            Element::Rough { .. } => unreachable!("rough fields are evaluated by Terrain"),
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

/// A height field: flat ground at z = 0 plus elements.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Terrain {
    /// The elements, heights added.
    pub elements: Vec<Element>,
}

/// A terrain prepared for many height queries: each rough field's waves drawn once
/// and tabulated on a [`ROUGH_GRID_M`] grid over the region a camera on the rover
/// sees ([`ROUGH_TABLE_X`], [`ROUGH_TABLE_Y`]), interpolated bilinearly there (an
/// error far below a millimetre for correlation lengths of centimetres and more) and
/// summed directly elsewhere.
#[derive(Debug, Clone)]
pub struct HeightField<'a> {
    terrain: &'a Terrain,
    waves: Vec<Option<RoughTable>>,
}

/// Spacing of a rough field's table, metres.
pub const ROUGH_GRID_M: f64 = 0.01;
/// Forward extent of a rough field's table, metres.
pub const ROUGH_TABLE_X: (f64, f64) = (-0.5, 6.0);
/// Lateral extent of a rough field's table, metres.
pub const ROUGH_TABLE_Y: (f64, f64) = (-3.0, 3.0);

#[derive(Debug, Clone)]
struct RoughTable {
    amplitude: f64,
    scale: f64,
    waves: [(f64, f64, f64); ROUGH_WAVES],
    nx: usize,
    ny: usize,
    table: Vec<f32>,
}

impl RoughTable {
    fn new(amplitude: f64, correlation: f64, seed: u64) -> Self {
        // σ = amplitude / 2: each wave contributes σ·√(2/N)·cos(…).
        let scale = 0.5 * amplitude * (2.0 / ROUGH_WAVES as f64).sqrt();
        let waves = rough_waves(correlation, seed);
        let nx = ((ROUGH_TABLE_X.1 - ROUGH_TABLE_X.0) / ROUGH_GRID_M).round() as usize + 1;
        let ny = ((ROUGH_TABLE_Y.1 - ROUGH_TABLE_Y.0) / ROUGH_GRID_M).round() as usize + 1;
        let mut t = RoughTable {
            amplitude,
            scale,
            waves,
            nx,
            ny,
            table: Vec::new(),
        };
        t.table = (0..nx * ny)
            .map(|k| {
                let x = ROUGH_TABLE_X.0 + (k / ny) as f64 * ROUGH_GRID_M;
                let y = ROUGH_TABLE_Y.0 + (k % ny) as f64 * ROUGH_GRID_M;
                t.direct(x, y) as f32
            })
            .collect();
        t
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

    fn height(&self, x: f64, y: f64) -> f64 {
        let fx = (x - ROUGH_TABLE_X.0) / ROUGH_GRID_M;
        let fy = (y - ROUGH_TABLE_Y.0) / ROUGH_GRID_M;
        let h = if fx >= 0.0 && fy >= 0.0 && fx < (self.nx - 1) as f64 && fy < (self.ny - 1) as f64
        {
            let (i, j) = (fx as usize, fy as usize);
            let (a, b) = (fx - i as f64, fy - j as f64);
            let at = |i: usize, j: usize| f64::from(self.table[i * self.ny + j]);
            (1.0 - a) * ((1.0 - b) * at(i, j) + b * at(i, j + 1))
                + a * ((1.0 - b) * at(i + 1, j) + b * at(i + 1, j + 1))
        } else {
            self.direct(x, y)
        };
        h.clamp(-self.amplitude, self.amplitude)
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
        for (e, w) in self.terrain.elements.iter().zip(&self.waves) {
            h += match w {
                Some(table) => table.height(x, y),
                None => e.height(x, y),
            };
        }
        h
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
        let waves = self
            .elements
            .iter()
            .map(|e| match *e {
                Element::Rough {
                    amplitude_m,
                    correlation_m,
                    seed,
                } => Some(RoughTable::new(amplitude_m, correlation_m, seed)),
                _ => None,
            })
            .collect();
        HeightField {
            terrain: self,
            waves,
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
