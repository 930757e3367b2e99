//! `topdown.png`: the corridor from above, forward up, the rover's left on the left.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use super::canvas::{rgb, turbo, Canvas, BODY, LARGE, SMALL};
use super::Scene;
use crate::grid::GridSpec;
use crate::verdict::{Decision, HazardKind, Side};

/// Left margin, pixels.
const LEFT: i32 = 56;
/// Top margin, pixels.
const TOP: i32 = 40;
/// Space under the map (rover mark, scale bar), pixels.
const BOTTOM: u32 = 70;
/// Gap and text panel to the right of the map, pixels.
const PANEL: u32 = 360;
/// Heights coloured, metres: this range spans the colour map.
pub const Z_RANGE_M: (f64, f64) = (-0.4, 0.6);

/// Pixels per grid cell: the corridor is drawn about 720 pixels long.
fn cell_px(nx: usize) -> u32 {
    (720 / nx.max(1) as u32).clamp(4, 16)
}

/// The picture's size for a grid of `nx` × `ny` cells, pixels (width, height).
/// The default configuration (60 × 28 cells) gives 752 × 830.
pub fn size(nx: usize, ny: usize) -> (u32, u32) {
    let cp = cell_px(nx);
    (
        LEFT as u32 + ny as u32 * cp + PANEL,
        (TOP as u32 + nx as u32 * cp + BOTTOM).max(560),
    )
}

/// Where the rover-frame point (x forward, y left, metres) is drawn, pixels.
pub fn to_pixel(spec: &GridSpec, x: f32, y: f32) -> (i32, i32) {
    let cp = cell_px(spec.nx) as f32;
    let (v, half_w, len) = (spec.voxel_m, -spec.origin[1], spec.nx as f32 * spec.voxel_m);
    (
        LEFT + ((half_w - y) / v * cp).round() as i32,
        TOP + ((len - x) / v * cp).round() as i32,
    )
}

/// Draw the top-down map of `scene`.
pub fn draw(scene: &Scene<'_>) -> Canvas {
    let s = scene.spec;
    let cp = cell_px(s.nx);
    let (w, h) = size(s.nx, s.ny);
    let mut c = Canvas::new(w, h, rgb(250, 250, 250));
    let len = s.nx as f32 * s.voxel_m;
    let map_w = s.ny as u32 * cp;
    for ix in 0..s.nx {
        for iy in 0..s.ny {
            cell(&mut c, scene, ix, iy, cp);
        }
    }
    // Distance grid every 0.5 m with labels.
    let mut d = 0.0f32;
    while d <= len + 1e-3 {
        let y = to_pixel(s, d, 0.0).1;
        c.line((LEFT, y), (LEFT + map_w as i32, y), rgb(255, 255, 255), 1);
        c.text(&format!("{d:.1} m"), 4, y - 5, SMALL, rgb(40, 40, 40));
        d += 0.5;
    }
    bands(&mut c, scene, s.nx as u32 * cp);
    // The toe line.
    let px = |y: f32| to_pixel(s, 0.0, y).0;
    let py = |x: f32| to_pixel(s, x, 0.0).1;
    if let Some(((lo, hi), toe)) = scene.toe_line() {
        let (ya, yb) = (hi, lo);
        let colour = rgb(200, 0, 200);
        c.line((px(ya), py(toe(ya))), (px(yb), py(toe(yb))), colour, 3);
        c.text("toe", px(ya) + 4, py(toe(ya)) - 14, BODY, colour);
    }
    for hz in &scene.verdict.hazards {
        hazard_mark(&mut c, scene, hz);
    }
    scale(&mut c, s, cp);
    panel(&mut c, scene, LEFT + map_w as i32 + 24);
    c
}

/// Cell (`ix`, `iy`) as a `cp`-pixel square: seen, coloured by height (faded and
/// dotted when remembered out of view); should be seen but is not, hatched; out of
/// view, dark grey.
fn cell(c: &mut Canvas, scene: &Scene<'_>, ix: usize, iy: usize, cp: u32) {
    let s = scene.spec;
    let v = s.voxel_m;
    let i = s.cell(ix, iy);
    let (x0, y0) = to_pixel(s, s.x_centre(ix) + v / 2.0, s.y_centre(iy) + v / 2.0);
    if scene.seen(i) {
        let z = f64::from(scene.cells[i].z);
        let t = (z - Z_RANGE_M.0) / (Z_RANGE_M.1 - Z_RANGE_M.0);
        let mut colour = turbo(t);
        // Remembered, out of view: faded toward grey as its confidence falls
        // (with the travel and time since it was seen, and the range it was
        // seen from; fully grey where it would be forgotten), dotted.
        let remembered = scene.remembered_confidence(ix, iy);
        if let Some(k) = remembered {
            colour = fade(colour, 0.3 + 0.6 * (1.0 - k));
        }
        c.fill(x0, y0, cp, cp, colour);
        if remembered.is_some() {
            c.set(x0 + cp as i32 / 2, y0 + cp as i32 / 2, rgb(40, 40, 40));
        }
    } else if scene.expected[i] {
        // Should be seen, is not: hatched.
        c.fill(x0, y0, cp, cp, rgb(215, 215, 215));
        for k in 0..cp as i32 {
            for j in 0..cp as i32 {
                if (k + j + x0 + y0) % 5 == 0 {
                    c.set(x0 + k, y0 + j, rgb(110, 110, 110));
                }
            }
        }
    } else {
        c.fill(x0, y0, cp, cp, rgb(70, 70, 70));
    }
}

/// The wheel tracks (outlined black) and the belly band (white) along the map's
/// `map_h` pixels, named above it.
fn bands(c: &mut Canvas, scene: &Scene<'_>, map_h: u32) {
    let px = |y: f32| to_pixel(scene.spec, 0.0, y).0;
    let r = &scene.config.rover;
    let (b, o) = (r.belly_half_width_m as f32, r.track_outer_m as f32);
    for (lo, hi) in [(b, o), (-o, -b)] {
        let (xa, xb) = (px(hi), px(lo));
        c.outline(xa, TOP, (xb - xa) as u32, map_h, rgb(0, 0, 0), 2);
    }
    let (xa, xb) = (px(b), px(-b));
    c.outline(xa, TOP, (xb - xa) as u32, map_h, rgb(255, 255, 255), 1);
    for (label, y) in [
        ("left track", (b + o) / 2.0),
        ("belly", 0.0),
        ("right track", -(b + o) / 2.0),
    ] {
        let x = px(y) - (label.len() as i32 * 6) / 2;
        c.text(label, x, TOP - 14, SMALL, rgb(40, 40, 40));
    }
}

/// A hazard where it is: a bar across its side and a marked, named dot.
fn hazard_mark(c: &mut Canvas, scene: &Scene<'_>, hz: &crate::Hazard) {
    let px = |y: f32| to_pixel(scene.spec, 0.0, y).0;
    let r = &scene.config.rover;
    let (b, o) = (r.belly_half_width_m as f32, r.track_outer_m as f32);
    let (lo, hi) = match hz.side {
        Side::Left => (b, o),
        Side::Right => (-o, -b),
        Side::Centre if matches!(hz.kind, HazardKind::Unknown | HazardKind::Tilt) => (-o, o),
        Side::Centre => (-b, b),
    };
    let y = to_pixel(scene.spec, hz.distance_m, 0.0).1;
    c.line((px(hi), y), (px(lo), y), rgb(230, 30, 30), 4);
    let cx = px(scene.side_centre(hz.side));
    c.fill(cx - 6, y - 6, 13, 13, rgb(230, 30, 30));
    c.outline(cx - 6, y - 6, 13, 13, rgb(255, 255, 255), 1);
    let name = hazard_name(hz.kind);
    let label_w = name.len() as u32 * 7 + 4;
    c.fill(cx + 9, y - 8, label_w, 15, rgb(255, 255, 255));
    c.text(name, cx + 11, y - 7, BODY, rgb(200, 0, 0));
}

/// The rover's place below the map and a 1 m scale bar.
fn scale(c: &mut Canvas, s: &GridSpec, cp: u32) {
    let base = TOP + (s.nx as u32 * cp) as i32;
    let mid = to_pixel(s, 0.0, 0.0).0;
    c.text("^ rover (x = 0)", mid - 45, base + 6, BODY, rgb(0, 0, 0));
    let bar = (1.0 / s.voxel_m * cp as f32).round() as i32;
    let sy = base + 40;
    c.line((LEFT, sy), (LEFT + bar, sy), rgb(0, 0, 0), 3);
    c.line((LEFT, sy - 6), (LEFT, sy + 6), rgb(0, 0, 0), 2);
    c.line((LEFT + bar, sy - 6), (LEFT + bar, sy + 6), rgb(0, 0, 0), 2);
    c.text("1 m", LEFT + bar + 8, sy - 6, BODY, rgb(0, 0, 0));
}

fn hazard_name(k: HazardKind) -> &'static str {
    match k {
        HazardKind::Slope => "SLOPE",
        HazardKind::Step => "STEP",
        HazardKind::Belly => "UNDER BELLY",
        HazardKind::DropOff => "DROP-OFF",
        HazardKind::Unknown => "UNKNOWN",
        HazardKind::Tilt => "TILT",
    }
}

/// What each workcase means, in words.
pub fn workcase_name(w: u8) -> &'static str {
    match w {
        1 => "flat",
        2 => "uphill, straight",
        3 => "uphill, left side only",
        4 => "uphill, diagonal, left",
        5 => "uphill, right side only",
        6 => "uphill, diagonal, right",
        7 => "uphill, diagonal, full width",
        8 => "downhill, straight",
        9 => "downhill, left side",
        10 => "downhill, right side",
        _ => "?",
    }
}

/// The verdict and the legend, to the right of the map.
fn panel(c: &mut Canvas, scene: &Scene<'_>, x: i32) {
    let mut at = Lines { x, y: TOP };
    decision_badge(c, scene.verdict, &mut at);
    verdict_lines(c, scene, &mut at);
    let remembered = (0..scene.spec.nx)
        .any(|ix| (0..scene.spec.ny).any(|iy| scene.remembered_confidence(ix, iy).is_some()));
    legend(c, x, at.y + 16, remembered);
}

/// Where the next line of the panel goes.
struct Lines {
    x: i32,
    y: i32,
}

impl Lines {
    /// One line of body text, then move down.
    fn line(&mut self, c: &mut Canvas, s: &str) {
        c.text(s, self.x, self.y, BODY, rgb(0, 0, 0));
        self.y += 17;
    }
}

/// The frame number and the decision as a coloured badge.
fn decision_badge(c: &mut Canvas, v: &crate::Verdict, at: &mut Lines) {
    let (word, colour) = match v.decision {
        Decision::Go => ("GO", rgb(0, 150, 0)),
        Decision::Stop => ("STOP", rgb(210, 0, 0)),
        Decision::Unknown => ("UNKNOWN (stop)", rgb(220, 120, 0)),
    };
    let x = at.x;
    c.text(
        &format!("frame {}", v.frame),
        x,
        at.y,
        BODY,
        rgb(60, 60, 60),
    );
    at.y += 20;
    c.fill(x - 4, at.y - 4, word.len() as u32 * 10 + 8, 28, colour);
    c.text(word, x, at.y, LARGE, rgb(255, 255, 255));
    at.y += 36;
}

/// The verdict in words: feature, seen fraction, hazards, the highest point of each
/// band, the camera attitude used and the rover's limits.
fn verdict_lines(c: &mut Canvas, scene: &Scene<'_>, at: &mut Lines) {
    let v = scene.verdict;
    match v.feature {
        Some(f) if v.decision == Decision::Go => {
            at.line(
                c,
                &format!("workcase {}: {}", f.workcase, workcase_name(f.workcase)),
            );
            if let Some(d) = f.distance_m {
                at.line(c, &format!("toe distance  {d:.2} m"));
            }
            if let Some(g) = f.gradient_deg {
                at.line(c, &format!("gradient      {g:.1}°"));
            }
            if let Some(a) = f.alpha_deg {
                at.line(c, &format!("alpha         {a:.1}°"));
            }
        }
        _ => {}
    }
    at.line(
        c,
        &format!("seen          {:.0} %", v.seen_fraction * 100.0),
    );
    if v.hazards.is_empty() {
        at.line(c, "hazards: none");
    } else {
        at.line(c, "hazards (the deciding one first):");
        for h in &v.hazards {
            at.line(
                c,
                &format!(
                    "  {} {} at {:.2} m",
                    hazard_name(h.kind).to_lowercase(),
                    format!("{:?}", h.side).to_lowercase(),
                    h.distance_m
                ),
            );
        }
    }
    // What the wheels and the belly meet: the highest seen point of each band.
    let highest = |side: Side| {
        (0..scene.spec.nx)
            .filter_map(|ix| super::side::band_height(scene, side, ix))
            .reduce(f32::max)
            .map_or("-".to_string(), |z| format!("{z:.2}"))
    };
    at.line(
        c,
        &format!(
            "highest m: left {} belly {} right {}",
            highest(Side::Left),
            highest(Side::Centre),
            highest(Side::Right)
        ),
    );
    let m = v.mount;
    at.line(
        c,
        &format!(
            "camera pitch {:.1}° roll {:.1}° ({})",
            m.pitch_deg,
            m.roll_deg,
            if m.from_accelerometer {
                "accel."
            } else {
                "config"
            }
        ),
    );
    let r = &scene.config.rover;
    at.line(
        c,
        &format!(
            "limits: step {:.2} m, belly {:.2} m, slope {:.0}°",
            r.wheel_radius_m, r.belly_clearance_m, r.max_slope_deg
        ),
    );
}

/// The colour bar of ground heights and the swatches of what the picture marks,
/// from `y` down.
fn legend(c: &mut Canvas, x: i32, mut y: i32, remembered: bool) {
    c.text("ground height", x, y, BODY, rgb(0, 0, 0));
    y += 18;
    let bar_w = 200;
    for k in 0..bar_w {
        let t = f64::from(k) / f64::from(bar_w - 1);
        c.fill(x + k, y, 1, 14, turbo(t));
    }
    y += 16;
    c.text(&format!("{:.1} m", Z_RANGE_M.0), x, y, SMALL, rgb(0, 0, 0));
    c.text(
        "0",
        x + (bar_w as f64 * 0.4) as i32 - 2,
        y,
        SMALL,
        rgb(0, 0, 0),
    );
    c.text(
        &format!("+{:.1} m", Z_RANGE_M.1),
        x + bar_w - 30,
        y,
        SMALL,
        rgb(0, 0, 0),
    );
    y += 20;
    let swatch = |c: &mut Canvas, y: i32, fill: [u8; 3], hatch: bool, label: &str| {
        c.fill(x, y, 14, 14, rgb(fill[0], fill[1], fill[2]));
        if hatch {
            for k in 0..14 {
                for j in 0..14 {
                    if (k + j) % 5 == 0 {
                        c.set(x + k, y + j, rgb(110, 110, 110));
                    }
                }
            }
        }
        c.text(label, x + 20, y + 1, BODY, rgb(0, 0, 0));
    };
    swatch(c, y, [215, 215, 215], true, "should be seen, not seen");
    y += 20;
    swatch(c, y, [70, 70, 70], false, "out of the camera's view");
    y += 20;
    swatch(c, y, [230, 30, 30], false, "hazard (near edge)");
    y += 20;
    swatch(c, y, [200, 0, 200], false, "toe line of the slope");
    y += 20;
    c.outline(x, y, 14, 14, rgb(0, 0, 0), 2);
    c.text("wheel tracks", x + 20, y + 1, BODY, rgb(0, 0, 0));
    if remembered {
        y += 20;
        let f = fade(rgb(255, 128, 0), 0.6);
        swatch(
            c,
            y,
            [f.r(), f.g(), f.b()],
            false,
            "remembered, out of view: greyer",
        );
        c.text(
            "the longer ago or farther seen",
            x + 20,
            y + 14,
            SMALL,
            rgb(40, 40, 40),
        );
    }
}

/// `colour` faded toward grey by `k` (0: unchanged, 1: grey).
fn fade(colour: Rgb888, k: f32) -> Rgb888 {
    let f = |v: u8| (f32::from(v) + k * (150.0 - f32::from(v))).round() as u8;
    rgb(f(colour.r()), f(colour.g()), f(colour.b()))
}
