//! `side.png`: height against forward distance, per wheel track and the belly band.

use super::canvas::{rgb, Canvas, BODY, SMALL};
use super::Scene;
use crate::verdict::Side;

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

/// Draw the side profile of `scene`.
pub fn draw(scene: &Scene<'_>) -> Canvas {
    let s = scene.spec;
    let mut c = Canvas::new(WIDTH, HEIGHT, rgb(255, 255, 255));
    let bands = [
        (Side::Left, "left track", rgb(30, 90, 220)),
        (Side::Centre, "belly band", rgb(0, 150, 0)),
        (Side::Right, "right track", rgb(230, 120, 0)),
    ];
    let profiles: Vec<Vec<Option<f32>>> = bands
        .iter()
        .map(|(side, _, _)| (0..s.nx).map(|ix| band_height(scene, *side, ix)).collect())
        .collect();
    let r = &scene.config.rover;
    let (mut lo, mut hi) = (-0.2f32, (r.belly_clearance_m as f32 + 0.1).max(0.5));
    for z in profiles.iter().flatten().flatten() {
        lo = lo.min(z - 0.05);
        hi = hi.max(z + 0.05);
    }
    let len = s.nx as f32 * s.voxel_m;
    let (pw, ph) = (
        (WIDTH as i32 - LEFT - RIGHT) as f32,
        (HEIGHT as i32 - TOP - BOTTOM) as f32,
    );
    let px = |x: f32| LEFT + (x / len * pw).round() as i32;
    let py = |z: f32| TOP + ((hi - z) / (hi - lo) * ph).round() as i32;

    // Axes and ticks.
    c.outline(LEFT, TOP, pw as u32 + 1, ph as u32 + 1, rgb(0, 0, 0), 1);
    let mut x = 0.0f32;
    while x <= len + 1e-3 {
        c.line(
            (px(x), TOP),
            (px(x), TOP + ph as i32),
            rgb(225, 225, 225),
            1,
        );
        c.text(
            &format!("{x:.1}"),
            px(x) - 9,
            TOP + ph as i32 + 6,
            SMALL,
            rgb(0, 0, 0),
        );
        x += 0.5;
    }
    let step = if hi - lo > 1.2 { 0.2 } else { 0.1 };
    let mut z = (lo / step).ceil() * step;
    while z <= hi {
        c.line(
            (LEFT, py(z)),
            (LEFT + pw as i32, py(z)),
            rgb(225, 225, 225),
            1,
        );
        c.text(
            &format!("{z:+.1}"),
            LEFT - 34,
            py(z) - 5,
            SMALL,
            rgb(0, 0, 0),
        );
        z += step;
    }
    c.text(
        "forward distance x, m (rover frame)",
        LEFT + pw as i32 / 2 - 120,
        HEIGHT as i32 - 22,
        BODY,
        rgb(0, 0, 0),
    );
    c.text(
        "height z, m (highest point per band)",
        6,
        4,
        SMALL,
        rgb(0, 0, 0),
    );
    // Reference heights.
    for (zref, label) in [
        (0.0f32, "ground"),
        (r.wheel_radius_m as f32, "wheel radius"),
        (r.belly_clearance_m as f32, "belly clearance"),
    ] {
        if zref >= lo && zref <= hi {
            let y = py(zref);
            let mut xx = LEFT;
            while xx < LEFT + pw as i32 {
                c.line(
                    (xx, y),
                    ((xx + 6).min(LEFT + pw as i32), y),
                    rgb(120, 120, 120),
                    1,
                );
                xx += 12;
            }
            c.text(
                label,
                LEFT + pw as i32 - label.len() as i32 * 6 - 4,
                y - 12,
                SMALL,
                rgb(90, 90, 90),
            );
        }
    }
    // Hazards.
    for h in &scene.verdict.hazards {
        let x = px(h.distance_m);
        c.line((x, TOP), (x, TOP + ph as i32), rgb(230, 30, 30), 2);
        let name = format!("{:?} {:?}", h.kind, h.side).to_lowercase();
        c.text(&name, x + 4, TOP + 4, SMALL, rgb(200, 0, 0));
    }
    // The profiles.
    for ((_, _, colour), prof) in bands.iter().zip(&profiles) {
        let mut last: Option<(i32, i32)> = None;
        for (ix, z) in prof.iter().enumerate() {
            match z {
                Some(z) => {
                    let p = (px(s.x_centre(ix)), py(*z));
                    if let Some(q) = last {
                        c.line(q, p, *colour, 2);
                    }
                    c.fill(p.0 - 2, p.1 - 2, 5, 5, *colour);
                    last = Some(p);
                }
                None => last = None,
            }
        }
    }
    // Legend.
    let mut lx = LEFT + 280;
    for (_, name, colour) in bands {
        c.fill(lx, 22, 18, 4, colour);
        c.text(name, lx + 24, 17, BODY, rgb(0, 0, 0));
        lx += 150;
    }
    c
}
