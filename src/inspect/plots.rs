//! The validation plots `rover-terrain validate` writes beside its report: error
//! against distance, and the confusion matrix of workcases.

use super::canvas::{rgb, Canvas, BODY, SMALL};
use crate::verdict::Decision;

/// Size of the error plot, pixels.
pub const ERROR_SIZE: (u32, u32) = (900, 640);
/// Size of the confusion matrix, pixels.
pub const CONFUSION_SIZE: (u32, u32) = (640, 620);

/// One panel of an x–y scatter with a logarithmic y axis (errors span decades).
struct Panel {
    x0: i32,
    y0: i32,
    w: i32,
    h: i32,
    x_max: f64,
    /// log10 of the lowest and highest y shown.
    decades: (i32, i32),
}

impl Panel {
    fn px(&self, x: f64) -> i32 {
        self.x0 + (x / self.x_max * f64::from(self.w)).round() as i32
    }

    /// Pixel row of `y`; values below the axis sit on it.
    fn py(&self, y: f64) -> i32 {
        let (lo, hi) = (f64::from(self.decades.0), f64::from(self.decades.1));
        let l = if y > 0.0 { y.log10().clamp(lo, hi) } else { lo };
        self.y0 + self.h - ((l - lo) / (hi - lo) * f64::from(self.h)).round() as i32
    }

    fn axes(&self, c: &mut Canvas, title: &str, y_label: &str) {
        c.outline(
            self.x0,
            self.y0,
            self.w as u32 + 1,
            self.h as u32 + 1,
            rgb(0, 0, 0),
            1,
        );
        let mut x = 0.0;
        while x <= self.x_max + 1e-9 {
            c.line(
                (self.px(x), self.y0),
                (self.px(x), self.y0 + self.h),
                rgb(230, 230, 230),
                1,
            );
            c.text(
                &format!("{x:.1}"),
                self.px(x) - 9,
                self.y0 + self.h + 5,
                SMALL,
                rgb(0, 0, 0),
            );
            x += 0.5;
        }
        for d in self.decades.0..=self.decades.1 {
            let y = 10f64.powi(d);
            c.line(
                (self.x0, self.py(y)),
                (self.x0 + self.w, self.py(y)),
                rgb(225, 225, 225),
                1,
            );
            let label = if d < 0 {
                format!("{:.*}", (-d) as usize, y)
            } else {
                format!("{y:.0}")
            };
            c.text(
                &label,
                self.x0 - 6 - label.len() as i32 * 6,
                self.py(y) - 5,
                SMALL,
                rgb(0, 0, 0),
            );
        }
        c.text(title, self.x0, self.y0 - 18, BODY, rgb(0, 0, 0));
        c.text(
            y_label,
            self.x0 + self.w - y_label.len() as i32 * 6,
            self.y0 - 14,
            SMALL,
            rgb(60, 60, 60),
        );
    }

    fn limit(
        &self,
        c: &mut Canvas,
        y: f64,
        label: &str,
        colour: embedded_graphics::pixelcolor::Rgb888,
    ) {
        let yy = self.py(y);
        let mut x = self.x0;
        while x < self.x0 + self.w {
            c.line((x, yy), ((x + 8).min(self.x0 + self.w), yy), colour, 1);
            x += 14;
        }
        c.text(
            label,
            self.x0 + self.w - label.len() as i32 * 6 - 4,
            yy - 12,
            SMALL,
            colour,
        );
    }
}

fn marker(c: &mut Canvas, x: i32, y: i32, noisy: bool) {
    if noisy {
        for k in 0..7 {
            c.line(
                (x - k / 2, y + 3 - k),
                (x + k / 2, y + 3 - k),
                rgb(230, 120, 0),
                1,
            );
        }
    } else {
        c.fill(x - 3, y - 3, 7, 7, rgb(30, 90, 220));
    }
}

/// One measured feature for [`error_plot`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorPoint {
    /// The expected toe distance, metres (the x axis).
    pub expected_distance_m: f64,
    /// Absolute toe distance error, millimetres; `None` when not measured.
    pub distance_error_mm: Option<f64>,
    /// Absolute gradient error, degrees; `None` when not measured.
    pub gradient_error_deg: Option<f64>,
    /// Whether the frame had sensor noise (drawn as a triangle, else a square).
    pub noisy: bool,
}

/// The bars [`error_plot`] draws dashed: (distance in millimetres, gradient in
/// degrees) for clean and for noisy frames.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorBars {
    /// Clean frames' bar.
    pub clean: (f64, f64),
    /// Noisy frames' bar.
    pub noisy: (f64, f64),
}

/// Absolute errors against the expected distance, on log scales: toe distance in
/// millimetres (top) and gradient in degrees (bottom), clean fixtures as blue squares,
/// Kinect-noise ones as orange triangles, each bar dashed. An exact result sits on the
/// bottom axis.
pub fn error_plot(rows: &[ErrorPoint], bars: ErrorBars) -> Canvas {
    let (w, h) = ERROR_SIZE;
    let mut c = Canvas::new(w, h, rgb(255, 255, 255));
    let x_max = rows
        .iter()
        .map(|r| r.expected_distance_m)
        .fold(2.0f64, f64::max)
        .ceil();
    let top = Panel {
        x0: 80,
        y0: 60,
        w: 780,
        h: 220,
        x_max,
        decades: (-3, 2),
    };
    let bottom = Panel {
        x0: 80,
        y0: 360,
        w: 780,
        h: 220,
        x_max,
        decades: (-4, 1),
    };
    c.text(
        "Validation: error against the distance of the feature (fixtures/)",
        80,
        10,
        BODY,
        rgb(0, 0, 0),
    );
    top.axes(&mut c, "toe distance error (log scale)", "millimetres");
    bottom.axes(&mut c, "gradient error (log scale)", "degrees");
    let [clean, noisy] = [bars.clean, bars.noisy];
    top.limit(&mut c, clean.0, "clean bar", rgb(30, 90, 220));
    top.limit(&mut c, noisy.0, "noisy bar", rgb(230, 120, 0));
    bottom.limit(&mut c, clean.1, "clean bar", rgb(30, 90, 220));
    bottom.limit(&mut c, noisy.1, "noisy bar", rgb(230, 120, 0));
    for r in rows {
        let d = r.expected_distance_m;
        if let Some(e) = r.distance_error_mm {
            marker(&mut c, top.px(d), top.py(e), r.noisy);
        }
        if let Some(e) = r.gradient_error_deg {
            marker(&mut c, bottom.px(d), bottom.py(e), r.noisy);
        }
    }
    c.text("expected toe distance, m", 380, 610, BODY, rgb(0, 0, 0));
    marker(&mut c, 600, 17, false);
    c.text("clean", 610, 11, SMALL, rgb(0, 0, 0));
    marker(&mut c, 670, 17, true);
    c.text("Kinect v1 noise", 680, 11, SMALL, rgb(0, 0, 0));
    c
}

/// The class labels of the confusion matrix: workcases 1-10, then stop and unknown.
pub const CLASSES: [&str; 12] = [
    "wc1", "wc2", "wc3", "wc4", "wc5", "wc6", "wc7", "wc8", "wc9", "wc10", "stop", "unknown",
];

/// The confusion-matrix class of a verdict: its workcase (0-9), stop (10) or
/// unknown (11, also a go without a workcase).
pub fn class(decision: Decision, workcase: Option<u8>) -> usize {
    match (decision, workcase) {
        (Decision::Go, Some(w)) if (1..=10).contains(&w) => usize::from(w - 1),
        (Decision::Stop, _) => 10,
        _ => 11,
    }
}

/// The confusion matrix of the fixture suite from its counts (expected [`class`]
/// down, analysed class across): counts in the cells, the diagonal green, anything
/// off it red.
pub fn confusion(m: &[[u32; 12]; 12]) -> Canvas {
    let (w, h) = CONFUSION_SIZE;
    let mut c = Canvas::new(w, h, rgb(255, 255, 255));
    let (x0, y0, cell) = (110, 90, 40);
    c.text(
        "Validation: workcases, expected (rows) vs analysed (columns)",
        10,
        10,
        BODY,
        rgb(0, 0, 0),
    );
    c.text("analysed ->", x0, y0 - 46, BODY, rgb(60, 60, 60));
    c.text("expected", 10, y0 - 20, BODY, rgb(60, 60, 60));
    for (k, name) in CLASSES.iter().enumerate() {
        let p = k as i32 * cell;
        c.text(name, x0 + p + 3, y0 - 18, SMALL, rgb(0, 0, 0));
        c.text(name, x0 - 60, y0 + p + 14, SMALL, rgb(0, 0, 0));
    }
    let max = m.iter().flatten().copied().max().unwrap_or(1).max(1);
    for (i, row) in m.iter().enumerate() {
        for (j, &n) in row.iter().enumerate() {
            let (x, y) = (x0 + j as i32 * cell, y0 + i as i32 * cell);
            let shade = 255 - (f64::from(n) / f64::from(max) * 150.0) as u8;
            let fill = match (n, i == j) {
                (0, _) => rgb(250, 250, 250),
                (_, true) => rgb(shade - 60, 255, shade - 60),
                (_, false) => rgb(255, shade - 80, shade - 80),
            };
            c.fill(x, y, cell as u32, cell as u32, fill);
            c.outline(
                x,
                y,
                cell as u32 + 1,
                cell as u32 + 1,
                rgb(200, 200, 200),
                1,
            );
            if n > 0 {
                let s = n.to_string();
                c.text(
                    &s,
                    x + cell / 2 - s.len() as i32 * 3 - 1,
                    y + 14,
                    BODY,
                    rgb(0, 0, 0),
                );
            }
        }
    }
    let total: u32 = m.iter().flatten().sum();
    let right: u32 = (0..12).map(|k| m[k][k]).sum();
    c.text(
        &format!("{right} of {total} fixtures in the expected class"),
        x0,
        y0 + 12 * cell + 16,
        BODY,
        rgb(0, 0, 0),
    );
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_put_go_workcases_stop_and_unknown_apart() {
        assert_eq!(class(Decision::Go, Some(1)), 0);
        assert_eq!(class(Decision::Go, Some(10)), 9);
        assert_eq!(class(Decision::Stop, None), 10);
        assert_eq!(class(Decision::Unknown, None), 11);
        assert_eq!(
            class(Decision::Go, None),
            11,
            "a go without a workcase is not a class"
        );
    }
}
