//! An RGB image to draw on with `embedded-graphics` (lines, rectangles, circles, and
//! its built-in bitmap fonts, so text needs no font installed), written as PNG.

use std::convert::Infallible;

use embedded_graphics::mono_font::{MonoFont, MonoTextStyle};
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Line, PrimitiveStyle, Rectangle};
use embedded_graphics::text::{Baseline, Text};

/// Small text (6×10 pixels a character, with °).
pub const SMALL: &MonoFont<'static> = &embedded_graphics::mono_font::iso_8859_1::FONT_6X10;
/// Body text (7×13).
pub const BODY: &MonoFont<'static> = &embedded_graphics::mono_font::iso_8859_1::FONT_7X13;
/// Headings (10×20).
pub const LARGE: &MonoFont<'static> = &embedded_graphics::mono_font::iso_8859_1::FONT_10X20;

/// Shorthand for a colour.
pub const fn rgb(r: u8, g: u8, b: u8) -> Rgb888 {
    Rgb888::new(r, g, b)
}

/// An RGB image, row-major, 3 bytes a pixel.
#[derive(Debug, Clone)]
pub struct Canvas {
    width: u32,
    height: u32,
    px: Vec<u8>,
}

impl Canvas {
    /// A `width × height` image filled with `background`.
    pub fn new(width: u32, height: u32, background: Rgb888) -> Self {
        let mut px = Vec::with_capacity(width as usize * height as usize * 3);
        for _ in 0..width as usize * height as usize {
            px.extend_from_slice(&[background.r(), background.g(), background.b()]);
        }
        Canvas { width, height, px }
    }

    /// Width, pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height, pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Set one pixel; outside the image, nothing.
    pub fn set(&mut self, x: i32, y: i32, c: Rgb888) {
        if x >= 0 && y >= 0 && (x as u32) < self.width && (y as u32) < self.height {
            let i = (y as usize * self.width as usize + x as usize) * 3;
            self.px[i..i + 3].copy_from_slice(&[c.r(), c.g(), c.b()]);
        }
    }

    /// The colour of one pixel (tests).
    pub fn get(&self, x: u32, y: u32) -> Rgb888 {
        let i = (y as usize * self.width as usize + x as usize) * 3;
        Rgb888::new(self.px[i], self.px[i + 1], self.px[i + 2])
    }

    /// Fill a rectangle (top-left corner, size in pixels).
    pub fn fill(&mut self, x: i32, y: i32, w: u32, h: u32, c: Rgb888) {
        let _ = Rectangle::new(Point::new(x, y), Size::new(w, h))
            .into_styled(PrimitiveStyle::with_fill(c))
            .draw(self);
    }

    /// Outline a rectangle.
    pub fn outline(&mut self, x: i32, y: i32, w: u32, h: u32, c: Rgb888, width: u32) {
        let _ = Rectangle::new(Point::new(x, y), Size::new(w, h))
            .into_styled(PrimitiveStyle::with_stroke(c, width))
            .draw(self);
    }

    /// A straight line.
    pub fn line(&mut self, from: (i32, i32), to: (i32, i32), c: Rgb888, width: u32) {
        let _ = Line::new(Point::new(from.0, from.1), Point::new(to.0, to.1))
            .into_styled(PrimitiveStyle::with_stroke(c, width))
            .draw(self);
    }

    /// Text with its top-left corner at (x, y).
    pub fn text(&mut self, s: &str, x: i32, y: i32, font: &MonoFont<'_>, c: Rgb888) {
        let style = MonoTextStyle::new(font, c);
        let _ = Text::with_baseline(s, Point::new(x, y), style, Baseline::Top).draw(self);
    }

    /// The image as PNG bytes (8-bit RGB).
    pub fn png(&self) -> Vec<u8> {
        let mut out = Vec::new();
        {
            let mut enc = png::Encoder::new(&mut out, self.width, self.height);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            // Writing into a Vec cannot fail; the header and data sizes are ours.
            if let Ok(mut w) = enc.write_header() {
                let _ = w.write_image_data(&self.px);
            }
        }
        out
    }
}

impl OriginDimensions for Canvas {
    fn size(&self) -> Size {
        Size::new(self.width, self.height)
    }
}

impl DrawTarget for Canvas {
    type Color = Rgb888;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<Rgb888>>,
    {
        for Pixel(p, c) in pixels {
            self.set(p.x, p.y, c);
        }
        Ok(())
    }
}

/// The "turbo" colour map (Mikhail, Google 2019, polynomial fit) at `t` in 0..=1:
/// dark blue → cyan → green → yellow → red.
pub fn turbo(t: f64) -> Rgb888 {
    let x = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let poly = |c: [f64; 6]| {
        let v = c[0] + x * (c[1] + x * (c[2] + x * (c[3] + x * (c[4] + x * c[5]))));
        (v.clamp(0.0, 1.0) * 255.0).round() as u8
    };
    rgb(
        poly([
            0.13572138,
            4.61539260,
            -42.66032258,
            132.13108234,
            -152.94239396,
            59.28637943,
        ]),
        poly([
            0.09140261,
            2.19418839,
            4.84296658,
            -14.18503333,
            4.27729857,
            2.82956604,
        ]),
        poly([
            0.10667330,
            12.64194608,
            -60.58204836,
            110.36276771,
            -89.90310912,
            27.34824973,
        ]),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drawing_lands_where_asked_and_the_png_decodes() {
        let mut c = Canvas::new(40, 20, rgb(0, 0, 0));
        c.fill(2, 3, 4, 5, rgb(255, 0, 0));
        assert_eq!(c.get(2, 3), rgb(255, 0, 0));
        assert_eq!(c.get(5, 7), rgb(255, 0, 0));
        assert_eq!(c.get(6, 7), rgb(0, 0, 0));
        c.text("A°", 10, 2, SMALL, rgb(255, 255, 255));
        let lit = (10..22)
            .flat_map(|x| (2..12).map(move |y| (x, y)))
            .filter(|&(x, y)| c.get(x, y) == rgb(255, 255, 255))
            .count();
        assert!(lit > 10, "the text drew pixels: {lit}");
        let png = c.png();
        let dec = png::Decoder::new(std::io::Cursor::new(png));
        let reader = dec.read_info().unwrap();
        assert_eq!((reader.info().width, reader.info().height), (40, 20));
    }

    #[test]
    fn turbo_runs_blue_to_red() {
        let (lo, hi) = (turbo(0.1), turbo(1.0));
        assert!(lo.b() > lo.r() && hi.r() > hi.b(), "{lo:?} {hi:?}");
        assert_eq!(turbo(f64::NAN), turbo(0.0));
    }
}
