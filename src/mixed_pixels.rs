//! Mixed ("flying") pixels at depth edges, found in the depth image before binning.
//!
//! Where a near surface ends in front of a far one, a time-of-flight camera (Kinect
//! v2), a stereo matcher or a renderer that averages over a pixel's footprint returns,
//! for the pixels on the edge, depths between the two surfaces: points hanging in the
//! air along the line of sight behind the edge. Along a track's edge with ground
//! falling away beside it they stand between the two levels and read as a step.
//!
//! The jump that counts is the step a surface seen at `analysis.mixed_pixel_angle_deg`
//! (2.5°) to the line of sight makes from one pixel to the next: `depth · pixel angle
//! / tan(angle)`, 78 mm at 2 m for a Kinect v1. A pixel is mixed when, along its image
//! row or its column, it lies inside such a jump, alone or with one neighbour:
//! - its depth lies between the surfaces either side, more than the jump from each:
//!   both lie almost along its line of sight, one in front, one behind;
//! - and on at least one side the next pixel out continues that side's surface
//!   (their depths differ by less than the jump).
//!
//! It is also mixed when it floats: none of its four neighbours (two at least
//! returned) lies within the jump of it. Mixed pixels need not keep the edge's order,
//! and a pixel mixed one way beside one mixed the other way stands alone so.
//!
//! The continuation condition keeps a surface seen at a grazing angle (far ground from
//! a low camera, a descent nearly as steep as the line of sight to it): there every
//! step along the grazing direction is long, so no pixel has a short step beyond its
//! neighbour, only the pixel where such a surface meets a jump goes, and across that
//! direction each pixel has neighbours on its surface, so none floats. What the filter
//! cannot tell from a mixed pixel is a real surface seen one or two pixels wide between
//! two jumps (a far stair tread): that goes too, and its cells are judged as if unseen,
//! never as ground. Outside the image counts as no return.
//!
//! This is PCL's "shadow points" / ROS's "veil points" filter written for a depth
//! image: no normals are needed, the image's neighbours give the geometry. By hand
//! because it runs inside the binning pass (a cheap vectorised test marks the few
//! candidate pixels of a row, this exact test runs on those alone) and no crate works
//! on a bare depth row without copying it into a cloud first.

use crate::projection::Projector;

/// The per-axis jump thresholds for one camera, per millimetre of depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MixedPixels {
    /// Least jump to a neighbour along a row, as a fraction of the pixel's depth.
    per_mm_u: f32,
    /// Least jump to a neighbour along a column, as a fraction of the pixel's depth.
    per_mm_v: f32,
}

impl MixedPixels {
    /// No pixel is mixed: every depth is binned as it is.
    pub const OFF: MixedPixels = MixedPixels {
        per_mm_u: f32::INFINITY,
        per_mm_v: f32::INFINITY,
    };

    /// The filter for `projector`'s camera with neighbours within `angle_deg` of the
    /// line of sight; [`MixedPixels::OFF`] for 0.
    pub fn new(projector: &Projector, angle_deg: f64) -> Self {
        if angle_deg <= 0.0 {
            return MixedPixels::OFF;
        }
        let per_tan = 1.0 / angle_deg.to_radians().tan();
        let [au, av] = projector.pixel_angle();
        MixedPixels {
            per_mm_u: (au * per_tan) as f32,
            per_mm_v: (av * per_tan) as f32,
        }
    }

    /// Whether the filter drops anything.
    pub fn is_on(&self) -> bool {
        self.per_mm_u.is_finite() || self.per_mm_v.is_finite()
    }

    /// The least jump between neighbours along a row and along a column at a pixel
    /// of depth 1 mm: `[u, v]`, millimetres per millimetre.
    pub fn per_mm(&self) -> [f32; 2] {
        [self.per_mm_u, self.per_mm_v]
    }

    /// Whether pixel (u, v) of `depth` (row-major, `width` wide, millimetres, 0 = no
    /// return) is a mixed pixel. Pixels with no return are not.
    pub fn is_mixed(&self, depth: &[u16], width: usize, u: usize, v: usize) -> bool {
        let height = depth.len() / width.max(1);
        let b = match depth.get(v * width + u) {
            Some(&d) if d != 0 && u < width => f32::from(d),
            _ => return false,
        };
        // The depths two pixels either side along each axis; 0 outside the image.
        let at = |du: isize, dv: isize| {
            let (x, y) = (u as isize + du, v as isize + dv);
            if x < 0 || y < 0 || x >= width as isize || y >= height as isize {
                0.0
            } else {
                f32::from(depth[y as usize * width + x as usize])
            }
        };
        let row = [at(-2, 0), at(-1, 0), at(1, 0), at(2, 0)];
        let col = [at(0, -2), at(0, -1), at(0, 1), at(0, 2)];
        let (ju, jv) = (b * self.per_mm_u, b * self.per_mm_v);
        let inside = |[p2, p1, n1, n2]: [f32; 4], jump| between_jumps(p2, p1, b, n1, n2, jump);
        inside(row, ju)
            || inside(col, jv)
            || isolated(b, [row[1], row[2]], ju, [col[1], col[2]], jv)
    }
}

/// Whether `b` floats: at least two of its four neighbours (`row` pair within
/// `ju`, `col` pair within `jv`) returned, and none continues its surface. A pixel
/// mixed towards the far side while its own neighbours were mixed the other way
/// stands alone so.
fn isolated(b: f32, row: [f32; 2], ju: f32, col: [f32; 2], jv: f32) -> bool {
    let returned = row.iter().chain(&col).filter(|&&d| d != 0.0).count();
    let near = |d: f32, jump: f32| d != 0.0 && (d - b).abs() <= jump;
    returned >= 2 && !row.iter().any(|&d| near(d, ju)) && !col.iter().any(|&d| near(d, jv))
}

/// The test along one axis, on the depths `p2 p1 b n1 n2` around `b` (0 = no
/// return, which continues nothing and is between nothing). `b` is mixed when it
/// lies inside the jump between two surfaces, more than `jump` from each, with at
/// most one other pixel inside it:
/// - alone: between `p1` and `n1`, with `p2` continuing `p1` or `n2` continuing `n1`
///   (within `jump`);
/// - with `n1`: both between `p1` and `n2`, `p2` continuing `p1`;
/// - with `p1`: both between `p2` and `n1`, `n2` continuing `n1`.
///
/// A pair of mixed pixels need not keep the edge's order (the near one's depth may
/// lie beyond the far one's), so a pair is judged against the surfaces either side
/// of it, not against each other.
fn between_jumps(p2: f32, p1: f32, b: f32, n1: f32, n2: f32, jump: f32) -> bool {
    let continues = |outer: f32, inner: f32| outer != 0.0 && (outer - inner).abs() <= jump;
    // Whether `x` lies between surfaces `lo` and `hi` (either order), clear of both.
    let inside = |x: f32, lo: f32, hi: f32| {
        let (near, far) = (lo.min(hi), lo.max(hi));
        near != 0.0 && x - near > jump && far - x > jump
    };
    let alone = inside(b, p1, n1) && (continues(p2, p1) || continues(n2, n1));
    let first = inside(b, p1, n2) && inside(n1, p1, n2) && continues(p2, p1);
    let second = inside(b, p2, n1) && inside(p1, p2, n1) && continues(n2, n1);
    alone || first || second
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Config;

    fn filter() -> MixedPixels {
        let c = Config::default();
        MixedPixels::new(
            &Projector::new(&c, 640, 480),
            c.analysis.mixed_pixel_angle_deg,
        )
    }

    #[test]
    fn the_jump_threshold_is_the_pixel_angle_over_the_tangent() {
        // Kinect v1: 57° over 640 pixels, 2·tan(28.5°)/640 rad per pixel at the
        // centre; at 2 m and 2.5° the least jump is 2000 · that / tan(2.5°).
        let [u, v] = filter().per_mm();
        let au = 2.0 * 28.5f64.to_radians().tan() / 640.0;
        let av = 2.0 * 21.5f64.to_radians().tan() / 480.0;
        let want = |a: f64| 2000.0 * a / 2.5f64.to_radians().tan();
        assert!((f64::from(u) * 2000.0 - want(au)).abs() < 0.01, "{u}");
        assert!((f64::from(v) * 2000.0 - want(av)).abs() < 0.01, "{v}");
        // About 78 mm at 2 m: a few depth quantisation steps (11 mm each) are far below it.
        assert!((74.0..82.0).contains(&(u * 2000.0)), "{}", u * 2000.0);
        assert!(!MixedPixels::OFF.is_on() && filter().is_on());
    }

    /// A 9×5 image, every row `row`.
    fn rows(row: [u16; 9]) -> Vec<u16> {
        row.repeat(5)
    }

    #[test]
    fn a_pixel_between_two_surfaces_is_mixed_and_the_surfaces_are_not() {
        let f = filter();
        // Near ground at 1.5 m, far at 2.2 m, one pixel at 1.8 m between.
        let d = rows([1500, 1500, 1500, 1500, 1800, 2200, 2200, 2200, 2200]);
        let mixed: Vec<usize> = (0..9).filter(|&u| f.is_mixed(&d, 9, u, 2)).collect();
        assert_eq!(mixed, vec![4]);
        // Two mixed pixels side by side: both go, in the edge's order or not.
        for pair in [[1700, 2000], [2000, 1700]] {
            let d = rows([1500, 1500, 1500, 1500, pair[0], pair[1], 2200, 2200, 2200]);
            let mixed: Vec<usize> = (0..9).filter(|&u| f.is_mixed(&d, 9, u, 2)).collect();
            assert_eq!(mixed, vec![4, 5], "{pair:?}");
        }
        // Three in a row are a surface seen at a grazing angle: its ends go, as they
        // would were they mixed, its middle stays.
        let d = rows([1500, 1500, 1500, 1700, 1850, 2000, 2200, 2200, 2200]);
        let mixed: Vec<usize> = (0..9).filter(|&u| f.is_mixed(&d, 9, u, 2)).collect();
        assert_eq!(mixed, vec![3, 5]);
        // The same along a column.
        let col: Vec<u16> = [1500u16, 1500, 1500, 1800, 2200, 2200, 2200]
            .iter()
            .flat_map(|&z| [z; 5])
            .collect();
        assert!(f.is_mixed(&col, 5, 2, 3));
        assert!(!(0..7).any(|v| v != 3 && f.is_mixed(&col, 5, 2, v)));
        // Switched off, nothing is mixed.
        assert!(!MixedPixels::OFF.is_mixed(&col, 5, 2, 3));
    }

    #[test]
    fn a_surface_seen_at_a_grazing_angle_and_a_thin_object_are_kept() {
        let f = filter();
        // Steps of 120 mm at ~2 m: a surface within 2° of the line of sight, seen
        // pixel after pixel. No pixel has a short step beyond its neighbour.
        let d = rows([1500, 1620, 1740, 1860, 1980, 2100, 2220, 2340, 2460]);
        assert!(!(0..9).any(|u| f.is_mixed(&d, 9, u, 2)));
        // A pixel nearer than both neighbours (a thin post, a noise spike) is not
        // between them.
        let d = rows([2000, 2000, 2000, 2000, 1500, 2000, 2000, 2000, 2000]);
        assert!(!(0..9).any(|u| f.is_mixed(&d, 9, u, 2)));
        // Depth noise of a few quantisation steps is not a jump.
        let d = rows([2000, 2000, 2026, 2000, 2026, 2052, 2026, 2052, 2052]);
        assert!(!(0..9).any(|u| f.is_mixed(&d, 9, u, 2)));
        // A neighbour with no return, or a pixel with none, decides nothing.
        let d = rows([1500, 1500, 1500, 0, 1800, 2200, 2200, 2200, 2200]);
        assert!(!f.is_mixed(&d, 9, 4, 2));
        let d = rows([1500, 1500, 1500, 1500, 0, 2200, 2200, 2200, 2200]);
        assert!(!(0..9).any(|u| f.is_mixed(&d, 9, u, 2)));
    }

    #[test]
    fn the_jump_scales_with_depth() {
        let f = filter();
        // 30 mm either side is a jump at 0.6 m (threshold ~23 mm) and not at 2 m
        // (~78 mm).
        let near = rows([570, 570, 570, 570, 600, 630, 630, 630, 630]);
        assert!(f.is_mixed(&near, 9, 4, 2));
        let far = rows([1970, 1970, 1970, 1970, 2000, 2030, 2030, 2030, 2030]);
        assert!(!f.is_mixed(&far, 9, 4, 2));
    }
}
