//! `side.png`: height against forward distance, per wheel track and the belly band.

use super::canvas::{rgb, Canvas, BODY, SMALL};
use super::Scene;
use crate::config::RoverConfig;
use crate::verdict::Side;
use embedded_graphics::pixelcolor::Rgb888;

/// Width of the picture, pixels.
pub const WIDTH: u32 = 900;
/// Height of the picture, pixels.
pub const HEIGHT: u32 = 420;
const LEFT: i32 = 64;
const RIGHT: i32 = 24;
const TOP: i32 = 44;
const BOTTOM: i32 = 52;

/// The highest ground-cell top among the seen cells of `side`'s band in row `ix`,
/// metres (what a wheel or the belly would meet there).
pub fn band_height(scene: &Scene<'_>, side: Side, ix: usize) -> Option<f32> {
    let s = scene.spec;
    (0..s.ny)
        .filter(|&iy| scene.side_of(s.y_centre(iy)) == side)
        .map(|iy| s.cell(ix, iy))
        .filter(|&i| scene.seen(i))
        .map(|i| scene.cells[i].top)
        .reduce(f32::max)
}

/// The three bands drawn, with their legend names and colours.
const BANDS: [(Side, &str, Rgb888); 3] = [
    (Side::Left, "left track", Rgb888::new(30, 90, 220)),
    (Side::Centre, "belly band", Rgb888::new(0, 150, 0)),
    (Side::Right, "right track", Rgb888::new(230, 120, 0)),
];

/// Draw the side profile of `scene`.
pub fn draw(scene: &Scene<'_>) -> Canvas {
    let s = scene.spec;
    let mut c = Canvas::new(WIDTH, HEIGHT, rgb(255, 255, 255));
    let profiles: Vec<Vec<Option<f32>>> = (BANDS.iter())
        .map(|&(side, _, _)| (0..s.nx).map(|ix| band_height(scene, side, ix)).collect())
        .collect();
    let r = &scene.config.rover;
    let plot = Plot::fit(
        s.nx as f32 * s.voxel_m,
        r.belly_clearance_m as f32,
        profiles.iter().flatten().flatten().copied(),
    );
    plot.axes(&mut c);
    plot.references(&mut c, r);
    // Hazards.
    for h in &scene.verdict.hazards {
        let x = plot.px(h.distance_m);
        c.line((x, TOP), (x, TOP + plot.ph as i32), rgb(230, 30, 30), 2);
        let name = format!("{:?} {:?}", h.kind, h.side).to_lowercase();
        c.text(&name, x + 4, TOP + 4, SMALL, rgb(200, 0, 0));
    }
    for ((_, _, colour), prof) in BANDS.iter().zip(&profiles) {
        let points = (prof.iter().enumerate())
            .map(|(ix, z)| z.map(|z| (plot.px(s.x_centre(ix)), plot.py(z))));
        profile(&mut c, points, *colour);
    }
    // Legend.
    let mut lx = LEFT + 280;
    for (_, name, colour) in BANDS {
        c.fill(lx, 22, 18, 4, colour);
        c.text(name, lx + 24, 17, BODY, rgb(0, 0, 0));
        lx += 150;
    }
    c
}

/// The plot area: forward distance 0..`len` across, heights `lo`..`hi` up, metres.
struct Plot {
    len: f32,
    lo: f32,
    hi: f32,
    /// Width and height of the plot area, pixels.
    pw: f32,
    ph: f32,
}

impl Plot {
    /// From -0.2 m (or the lowest height less 5 cm) to 0.5 m or 10 cm over the belly
    /// clearance (or the highest height plus 5 cm).
    fn fit(len: f32, clearance: f32, heights: impl Iterator<Item = f32>) -> Self {
        let (mut lo, mut hi) = (-0.2f32, (clearance + 0.1).max(0.5));
        for z in heights {
            lo = lo.min(z - 0.05);
            hi = hi.max(z + 0.05);
        }
        Self {
            len,
            lo,
            hi,
            pw: (WIDTH as i32 - LEFT - RIGHT) as f32,
            ph: (HEIGHT as i32 - TOP - BOTTOM) as f32,
        }
    }

    /// Pixel column of forward distance `x`, metres.
    fn px(&self, x: f32) -> i32 {
        LEFT + (x / self.len * self.pw).round() as i32
    }

    /// Pixel row of height `z`, metres.
    fn py(&self, z: f32) -> i32 {
        TOP + ((self.hi - z) / (self.hi - self.lo) * self.ph).round() as i32
    }

    /// The frame, a grid line every 0.5 m and every 0.1 m (0.2 m over a tall range)
    /// with their labels, and the axis titles.
    fn axes(&self, c: &mut Canvas) {
        let (pw, ph) = (self.pw as i32, self.ph as i32);
        let grid = rgb(225, 225, 225);
        c.outline(LEFT, TOP, pw as u32 + 1, ph as u32 + 1, rgb(0, 0, 0), 1);
        let mut x = 0.0f32;
        while x <= self.len + 1e-3 {
            c.line((self.px(x), TOP), (self.px(x), TOP + ph), grid, 1);
            let label = format!("{x:.1}");
            c.text(&label, self.px(x) - 9, TOP + ph + 6, SMALL, rgb(0, 0, 0));
            x += 0.5;
        }
        let step = if self.hi - self.lo > 1.2 { 0.2 } else { 0.1 };
        let mut z = (self.lo / step).ceil() * step;
        while z <= self.hi {
            c.line((LEFT, self.py(z)), (LEFT + pw, self.py(z)), grid, 1);
            let label = format!("{z:+.1}");
            c.text(&label, LEFT - 34, self.py(z) - 5, SMALL, rgb(0, 0, 0));
            z += step;
        }
        let x_title = "forward distance x, m (rover frame)";
        c.text(
            x_title,
            LEFT + pw / 2 - 120,
            HEIGHT as i32 - 22,
            BODY,
            rgb(0, 0, 0),
        );
        let z_title = "height z, m (highest point per band)";
        c.text(z_title, 6, 4, SMALL, rgb(0, 0, 0));
    }

    /// Dashed lines at the ground, the wheel radius and the belly clearance, labelled.
    fn references(&self, c: &mut Canvas, r: &RoverConfig) {
        let right = LEFT + self.pw as i32;
        for (zref, label) in [
            (0.0f32, "ground"),
            (r.wheel_radius_m as f32, "wheel radius"),
            (r.belly_clearance_m as f32, "belly clearance"),
        ] {
            if zref < self.lo || zref > self.hi {
                continue;
            }
            let y = self.py(zref);
            for xx in (LEFT..right).step_by(12) {
                c.line((xx, y), ((xx + 6).min(right), y), rgb(120, 120, 120), 1);
            }
            let x = right - label.len() as i32 * 6 - 4;
            c.text(label, x, y - 12, SMALL, rgb(90, 90, 90));
        }
    }
}

/// One band's profile: its points (pixels; `None` where nothing was seen) as dots,
/// joined where consecutive.
fn profile(c: &mut Canvas, points: impl Iterator<Item = Option<(i32, i32)>>, colour: Rgb888) {
    let mut last: Option<(i32, i32)> = None;
    for p in points {
        if let (Some(p), Some(q)) = (p, last) {
            c.line(q, p, colour, 2);
        }
        if let Some(p) = p {
            c.fill(p.0 - 2, p.1 - 2, 5, 5, colour);
        }
        last = p;
    }
}
