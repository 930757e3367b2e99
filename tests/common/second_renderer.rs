//! A second renderer, written from the README's conventions alone: its own rays (FOV
//! model, pinhole, URDF rpy, depth along the optical axis) and exact intersection of
//! planar terrain with vertical faces. `tests/second_renderer.rs` checks the sim's
//! renderer and the analysis with it; `EXACT=1` makes the `sweep` example draw with it.
//!
//! The terrain is the sim's `Element`s, read from their documentation by [`planar`]
//! (ramps, capped or not, steps, drop-offs, blocks and rocks over regions that do not
//! overlap), not through the sim's height field.
#![allow(dead_code)]

use rand::Rng;
use rover_terrain::sim::{Element, Extent, Terrain};
use rover_terrain::Config;
use rover_terrain_drivers::DepthFrame;

/// The camera: image size and intrinsics, pixels and degrees.
#[derive(Debug, Clone, Copy)]
pub enum Lens {
    /// The paper's model: X = (u/W − 0.5)·Z·2·tan(hfov/2), Y = (0.5 − v/H)·Z·2·tan(vfov/2).
    Fov { hfov: f64, vfov: f64 },
    /// X = (u − cx)/fx·Z, Y = −(v − cy)/fy·Z.
    Pinhole { fx: f64, fy: f64, cx: f64, cy: f64 },
}

/// A camera on a mount: position in the rover frame (metres) and roll, pitch, yaw
/// (degrees, as the config means them).
#[derive(Debug, Clone, Copy)]
pub struct Rig {
    /// Image width, pixels.
    pub width: usize,
    /// Image height, pixels.
    pub height: usize,
    /// Intrinsics.
    pub lens: Lens,
    /// Camera position in the rover frame, metres.
    pub at: [f64; 3],
    /// Roll, pitch, yaw, degrees.
    pub rpy: [f64; 3],
    /// Nearest depth kept, metres.
    pub min_range: f64,
}

impl Rig {
    /// A random mount and camera over the ranges, `scale` times the size.
    pub fn random(rng: &mut impl Rng, scale: f64) -> Rig {
        let (w, h, lens) = match rng.gen_range(0..4) {
            0 => (640.0, 480.0, None),
            1 => (512.0, 424.0, Some((70.6, 60.0))),
            2 => (320.0, 240.0, None),
            _ => (848.0, 480.0, Some((0.0, 0.0))),
        };
        let (width, height) = ((w * scale).round(), (h * scale).round());
        let lens = match lens {
            None => Lens::Fov {
                hfov: 57.0,
                vfov: 43.0,
            },
            Some((hfov, vfov)) if hfov > 0.0 => Lens::Fov { hfov, vfov },
            // D435-like: fx ≈ fy ≈ 425 at 848 × 480, the principal point off centre.
            _ => Lens::Pinhole {
                fx: rng.gen_range(415.0..435.0) * scale,
                fy: rng.gen_range(415.0..435.0) * scale,
                cx: (424.0 + rng.gen_range(-12.0..12.0)) * scale,
                cy: (240.0 + rng.gen_range(-10.0..10.0)) * scale,
            },
        };
        Rig {
            width: width as usize,
            height: height as usize,
            lens,
            at: [
                rng.gen_range(-0.2..0.2),
                rng.gen_range(-0.1..0.1),
                rng.gen_range(0.5..1.2),
            ],
            rpy: [
                rng.gen_range(-10.0..10.0),
                rng.gen_range(15.0..45.0),
                rng.gen_range(-10.0..10.0),
            ],
            min_range: rng.gen_range(0.3..0.5),
        }
    }

    /// The rig as the library's config.
    pub fn config(&self) -> Config {
        let mut c = Config::default();
        c.camera.width = self.width as u32;
        c.camera.height = self.height as u32;
        c.camera.min_range_m = self.min_range;
        match self.lens {
            Lens::Fov { hfov, vfov } => {
                c.camera.hfov_deg = hfov;
                c.camera.vfov_deg = vfov;
            }
            Lens::Pinhole { fx, fy, cx, cy } => {
                (c.camera.fx, c.camera.fy) = (Some(fx), Some(fy));
                (c.camera.cx, c.camera.cy) = (Some(cx), Some(cy));
            }
        }
        [c.mount.x_m, c.mount.y_m, c.mount.z_m] = self.at;
        [c.mount.roll_deg, c.mount.pitch_deg, c.mount.yaw_deg] = self.rpy;
        c
    }

    /// The rig as a user writes it in the config file.
    pub fn toml(&self) -> String {
        let lens = match self.lens {
            Lens::Fov { hfov, vfov } => format!("hfov_deg = {hfov}\nvfov_deg = {vfov}\n"),
            Lens::Pinhole { fx, fy, cx, cy } => {
                format!("fx = {fx}\nfy = {fy}\ncx = {cx}\ncy = {cy}\n")
            }
        };
        format!(
            "[camera]\nwidth = {}\nheight = {}\nmin_range_m = {}\n{lens}\n[mount]\nx_m = {}\n\
             y_m = {}\nz_m = {}\nroll_deg = {}\npitch_deg = {}\nyaw_deg = {}\n",
            self.width,
            self.height,
            self.min_range,
            self.at[0],
            self.at[1],
            self.at[2],
            self.rpy[0],
            self.rpy[1],
            self.rpy[2]
        )
    }

    /// Pixel (u, v)'s ray in the rover frame, scaled so that its optical Z is 1: the
    /// ray parameter is the optical depth.
    pub fn ray(&self, u: usize, v: usize) -> [f64; 3] {
        let (u, v) = (u as f64, v as f64);
        let (kx, ky) = match self.lens {
            Lens::Fov { hfov, vfov } => (
                (u / self.width as f64 - 0.5) * 2.0 * (hfov.to_radians() / 2.0).tan(),
                (0.5 - v / self.height as f64) * 2.0 * (vfov.to_radians() / 2.0).tan(),
            ),
            Lens::Pinhole { fx, fy, cx, cy } => ((u - cx) / fx, -(v - cy) / fy),
        };
        // Optical (X right, Y up, Z forward) to body axes (x forward, y left, z up).
        let d = [1.0, -kx, ky];
        let [r, p, y] = self.rpy.map(f64::to_radians);
        let rx = [
            [1.0, 0.0, 0.0],
            [0.0, r.cos(), -r.sin()],
            [0.0, r.sin(), r.cos()],
        ];
        let ry = [
            [p.cos(), 0.0, p.sin()],
            [0.0, 1.0, 0.0],
            [-p.sin(), 0.0, p.cos()],
        ];
        let rz = [
            [y.cos(), -y.sin(), 0.0],
            [y.sin(), y.cos(), 0.0],
            [0.0, 0.0, 1.0],
        ];
        let turn = |m: [[f64; 3]; 3], a: [f64; 3]| {
            [0, 1, 2].map(|i| m[i][0] * a[0] + m[i][1] * a[1] + m[i][2] * a[2])
        };
        turn(rz, turn(ry, turn(rx, d)))
    }
}

/// Whether a point (x, y), metres, lies in a piece's region.
pub type Region = Box<dyn Fn(f64, f64) -> bool>;

/// Ground made of planar pieces, z = a + b·x + c·y (metres), each over a region of the
/// plane (the first piece whose region holds a point is the ground there; the last one
/// holds everything), vertical faces n·(x, y) = k wherever the height jumps, and rocks
/// standing on flat ground.
pub struct Ground {
    pieces: Vec<(Region, [f64; 3])>,
    faces: Vec<([f64; 2], f64)>,
    /// Half-ellipsoids on z = 0: centre x, y, radius, height, metres.
    rocks: Vec<[f64; 4]>,
}

impl Ground {
    pub fn flat() -> Ground {
        Ground {
            pieces: vec![(Box::new(|_, _| true), [0.0; 3])],
            faces: Vec::new(),
            rocks: Vec::new(),
        }
    }

    /// Adds a piece before the ones there (it covers them where its region holds).
    pub fn with(mut self, inside: impl Fn(f64, f64) -> bool + 'static, plane: [f64; 3]) -> Ground {
        self.pieces.insert(0, (Box::new(inside), plane));
        self
    }

    pub fn with_face(mut self, n: [f64; 2], k: f64) -> Ground {
        self.faces.push((n, k));
        self
    }

    /// Which piece is the ground at (x, y).
    pub fn piece(&self, x: f64, y: f64) -> usize {
        self.pieces
            .iter()
            .position(|(inside, _)| inside(x, y))
            .unwrap()
    }

    pub fn height(&self, x: f64, y: f64) -> f64 {
        let [a, b, c] = self.pieces[self.piece(x, y)].1;
        a + b * x + c * y
    }

    /// Optical depth (mm) at which the ray o + t·d first meets the ground, 0 for none
    /// within 10 m, as the sim renders.
    pub fn depth_mm(&self, o: [f64; 3], d: [f64; 3]) -> u16 {
        let at = |t: f64| [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]];
        let mut best = f64::INFINITY;
        for (i, (_, [a, b, c])) in self.pieces.iter().enumerate() {
            let t = (a + b * o[0] + c * o[1] - o[2]) / (d[2] - b * d[0] - c * d[1]);
            let p = at(t);
            if t > 0.0 && t < best && self.piece(p[0], p[1]) == i {
                best = t;
            }
        }
        for &([nx, ny], k) in &self.faces {
            let t = (k - nx * o[0] - ny * o[1]) / (nx * d[0] + ny * d[1]);
            let p = at(t);
            let e = 1e-9;
            let h0 = self.height(p[0] - e * nx, p[1] - e * ny);
            let h1 = self.height(p[0] + e * nx, p[1] + e * ny);
            if t > 0.0 && t < best && p[2] >= h0.min(h1) && p[2] <= h0.max(h1) {
                best = t;
            }
        }
        for &[cx, cy, r, h] in &self.rocks {
            // In units of the rock's radii it is the upper half of the unit sphere:
            // |q + t·e|² = 1 with q, e the ray's origin and direction so scaled.
            let q = [(o[0] - cx) / r, (o[1] - cy) / r, o[2] / h];
            let e = [d[0] / r, d[1] / r, d[2] / h];
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let (a, b, c) = (dot(e, e), dot(q, e), dot(q, q) - 1.0);
            let disc = b * b - a * c;
            if disc < 0.0 {
                continue;
            }
            let t = (-b - disc.sqrt()) / a;
            if t > 0.0 && t < best && at(t)[2] >= 0.0 {
                best = t;
            }
        }
        let mm = (best * 1000.0).round();
        if best <= 10.0 && (1.0..=65535.0).contains(&mm) {
            mm as u16
        } else {
            0
        }
    }

    pub fn render(&self, rig: &Rig) -> Vec<u16> {
        let mut out = Vec::with_capacity(rig.width * rig.height);
        for v in 0..rig.height {
            for u in 0..rig.width {
                out.push(self.depth_mm(rig.at, rig.ray(u, v)));
            }
        }
        out
    }
}

/// The sim's terrain as planar pieces and rocks, where it is made only of ramps (capped
/// or not), steps, drop-offs, blocks and rocks (half-ellipsoids) over regions that do
/// not overlap, with vertical sides; `None` otherwise.
pub fn planar(terrain: &Terrain) -> Option<Ground> {
    let span = |e: Extent| match e {
        Extent::Full => Some((f64::NEG_INFINITY, f64::INFINITY)),
        Extent::Left => Some((0.0, f64::INFINITY)),
        Extent::Right => Some((f64::NEG_INFINITY, 0.0)),
        Extent::Band { from_m, to_m } => Some((from_m, to_m)),
        Extent::Bevelled { .. } => None,
    };
    let mut ground = Ground::flat();
    // Rocks stand on flat ground: apart from each other and from every other element.
    for e in &terrain.elements {
        if let Element::Rock {
            x_m,
            y_m,
            radius_m,
            height_m,
        } = *e
        {
            let apart = ground
                .rocks
                .iter()
                .all(|&[x, y, r, _]| (x - x_m).hypot(y - y_m) >= r + radius_m);
            if !apart {
                return None;
            }
            ground.rocks.push([x_m, y_m, radius_m, height_m]);
        }
    }
    let mut taken: Vec<(f64, f64)> = ground
        .rocks
        .iter()
        .map(|&[_, y, r, _]| (y - r, y + r))
        .collect();
    for e in &terrain.elements {
        let (from, to) = match *e {
            Element::Rock { .. } => continue,
            Element::Ramp { extent, .. } | Element::Step { extent, .. } => span(extent)?,
            Element::DropOff { .. } => span(Extent::Full)?,
            Element::Block { y_m, width_m, .. } => (y_m - width_m / 2.0, y_m + width_m / 2.0),
            _ => return None,
        };
        if taken.iter().any(|&(a, b)| from < b && a < to) {
            return None;
        }
        taken.push((from, to));
        let band = move |y: f64| (from..=to).contains(&y);
        ground = match *e {
            Element::Ramp {
                toe_x_m: toe,
                ref_y_m: y0,
                gradient_deg,
                alpha_deg,
                cap_m,
                round_m,
                ..
            } => {
                // Planes only: a rounded toe is no plane.
                if round_m.is_some_and(|r| r > 0.0) {
                    return None;
                }
                let (tg, (sa, ca)) = (
                    gradient_deg.to_radians().tan(),
                    alpha_deg.to_radians().sin_cos(),
                );
                let across = move |x: f64, y: f64| (x - toe) * ca + (y - y0) * sa;
                // Where the face reaches its cap, and the plateau's height.
                let (end, cap) =
                    cap_m.map_or((f64::INFINITY, 0.0), |c| (c / tg.abs(), c * tg.signum()));
                let ground = ground.with(
                    move |x, y| band(y) && across(x, y) > 0.0 && across(x, y) < end,
                    [-tg * (toe * ca + y0 * sa), tg * ca, tg * sa],
                );
                if cap_m.is_some() {
                    ground.with(move |x, y| band(y) && across(x, y) >= end, [cap, 0.0, 0.0])
                } else {
                    ground
                }
            }
            Element::Step { x_m, height_m, .. } => ground
                .with(move |x, y| band(y) && x >= x_m, [height_m, 0.0, 0.0])
                .with_face([1.0, 0.0], x_m),
            Element::DropOff { x_m, depth_m } => ground
                .with(move |x, _| x >= x_m, [-depth_m, 0.0, 0.0])
                .with_face([1.0, 0.0], x_m),
            Element::Block {
                x_m,
                length_m,
                height_m,
                ..
            } => ground
                .with(
                    move |x, y| band(y) && (x_m..=x_m + length_m).contains(&x),
                    [height_m, 0.0, 0.0],
                )
                .with_face([1.0, 0.0], x_m)
                .with_face([1.0, 0.0], x_m + length_m),
            _ => unreachable!(),
        };
        for edge in [from, to].into_iter().filter(|y| y.is_finite()) {
            ground = ground.with_face([0.0, 1.0], edge);
        }
    }
    Some(ground)
}

/// The frame `config`'s camera sees of `terrain`, drawn by this renderer; `None` where
/// [`planar`] cannot draw the terrain.
pub fn frame(terrain: &Terrain, config: &Config) -> Option<DepthFrame> {
    let rig = rig_of(config);
    let ground = planar(terrain)?;
    Some(DepthFrame::from_pixels(
        rig.width,
        rig.height,
        ground.render(&rig),
    ))
}

/// The rig a config describes, read field by field.
pub fn rig_of(c: &Config) -> Rig {
    let k = &c.camera;
    Rig {
        width: k.width as usize,
        height: k.height as usize,
        lens: match (k.fx, k.fy, k.cx, k.cy) {
            (Some(fx), Some(fy), Some(cx), Some(cy)) => Lens::Pinhole { fx, fy, cx, cy },
            _ => Lens::Fov {
                hfov: k.hfov_deg,
                vfov: k.vfov_deg,
            },
        },
        at: [c.mount.x_m, c.mount.y_m, c.mount.z_m],
        rpy: [c.mount.roll_deg, c.mount.pitch_deg, c.mount.yaw_deg],
        min_range: k.min_range_m,
    }
}
