//! Synthetic depth frames: a height-field terrain ray-cast as the configured camera
//! sees it, with an optional Kinect v1 noise model. Used to make `fixtures/`, by the
//! tests, and by the bench.

mod catalogue;
pub mod families;
mod noise;
pub mod random;
mod terrain;

pub use catalogue::{catalogue, Expectation, Scene, SceneConfig};
pub use noise::KinectNoise;
pub use terrain::{Element, Extent, HeightField, Terrain, ROUGH_WAVES};

use rover_terrain_drivers::DepthFrame;

use crate::config::Config;
use crate::projection::Projector;

/// Farthest optical depth the renderer looks, metres (no hit within it = no return).
pub const FAR_M: f64 = 10.0;
/// March step along the ray, metres (smaller than any scene feature).
const STEP_M: f64 = 0.01;

/// Render `terrain` as the camera in `config` sees it: optical depth in millimetres,
/// 0 where the ray hits nothing within [`FAR_M`].
pub fn render(terrain: &Terrain, config: &Config) -> DepthFrame {
    let (w, h) = (config.camera.width as usize, config.camera.height as usize);
    let projector = Projector::new(config, w, h);
    let mut pixels = vec![0u16; w * h];
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(8);
    let rows_per = h.div_ceil(threads);
    let field = terrain.field();
    let terrain = &field;
    std::thread::scope(|scope| {
        for (chunk_i, chunk) in pixels.chunks_mut(rows_per * w).enumerate() {
            let projector = &projector;
            scope.spawn(move || {
                for (k, px) in chunk.iter_mut().enumerate() {
                    let (u, v) = (k % w, chunk_i * rows_per + k / w);
                    *px = cast(terrain, projector, u, v);
                }
            });
        }
    });
    DepthFrame::from_pixels(w, h, pixels)
}

/// The optical depth (mm) at which pixel (u, v)'s ray meets the terrain.
fn cast(terrain: &HeightField, projector: &Projector, u: usize, v: usize) -> u16 {
    let d = projector.ray(u, v);
    let o = projector.point(u, v, 0.0);
    // A margin, so that a surface lying exactly at a bound is inside the interval.
    let (lo, hi) = terrain.bounds();
    let (lo, hi) = (lo - 0.01, hi + 0.01);
    let above = |t: f64| o.z + t * d.z - terrain.height(o.x + t * d.x, o.y + t * d.y);
    let (mut t0, t1) = if d.z < 0.0 {
        (((o.z - hi) / -d.z).max(0.0), ((o.z - lo) / -d.z).min(FAR_M))
    } else if o.z <= hi {
        (0.0, FAR_M)
    } else {
        return 0;
    };
    if t0 > t1 {
        return 0;
    }
    let dt = STEP_M / d.norm();
    if above(t0) <= 0.0 {
        return to_mm(t0);
    }
    let mut t = t0;
    loop {
        let next = (t + dt).min(t1);
        if above(next) <= 0.0 {
            t0 = t;
            let mut t_hit = next;
            for _ in 0..40 {
                let mid = 0.5 * (t0 + t_hit);
                if above(mid) <= 0.0 {
                    t_hit = mid;
                } else {
                    t0 = mid;
                }
            }
            return to_mm(t_hit);
        }
        if next >= t1 {
            return 0;
        }
        t = next;
    }
}

fn to_mm(t: f64) -> u16 {
    let mm = (t * 1000.0).round();
    if (1.0..=f64::from(u16::MAX)).contains(&mm) {
        mm as u16
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_ground_renders_the_exact_depth() {
        let mut c = Config::default();
        c.camera.width = 64;
        c.camera.height = 48;
        let f = render(&Terrain::flat(), &c);
        let p = Projector::new(&c, 64, 48);
        for (u, v) in [(0, 47), (32, 24), (63, 30)] {
            let r = p.ray(u, v);
            let want = (0.8 / -r.z * 1000.0).round() as u16;
            assert_eq!(f.pixels()[v * 64 + u], want);
        }
        // The top rows look above the horizon's near part but still hit ground
        // within FAR_M or nothing; never a bogus value.
        assert!(f.pixels().iter().all(|&d| d == 0 || d >= 800));
    }

    #[test]
    fn a_wall_is_hit_at_its_face() {
        let mut c = Config::default();
        c.camera.width = 64;
        c.camera.height = 48;
        c.mount.pitch_deg = 0.0;
        let t = Terrain::new(vec![Element::Step {
            x_m: 2.0,
            height_m: 3.0,
            extent: Extent::Full,
        }]);
        let f = render(&t, &c);
        // The centre ray (level) hits the wall at x = 2.0 exactly.
        assert_eq!(f.pixels()[24 * 64 + 32], 2000);
    }
}
