//! Synthetic depth frames: a height-field terrain ray-cast as the configured camera
//! sees it, with an optional Kinect v1 noise model. Used to make `fixtures/`, by the
//! tests, and by the bench.

mod catalogue;
pub mod clearance;
pub mod drive;
pub mod families;
mod noise;
pub mod random;
pub mod sight;
mod terrain;

pub use catalogue::{catalogue, Expectation, Scene, SceneConfig, Tolerance, CLEAN, NOISY};
pub use noise::{FlyingPixels, KinectNoise};
pub use terrain::{toe_rounding, Element, Extent, HeightField, StoneShape, Terrain, ROUGH_WAVES};

use nalgebra::Vector3;
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
    render_from(terrain, config, Pose::default())
}

/// Where the rover stands on a terrain for [`render_from`]: its origin at (x, y) of
/// the terrain's coordinates, metres, heading counter-clockwise from the terrain's
/// x axis, radians. The default is the terrain's origin, facing +x.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pose {
    /// Terrain x of the rover origin, metres.
    pub x: f64,
    /// Terrain y of the rover origin, metres.
    pub y: f64,
    /// Heading, radians, counter-clockwise.
    pub heading: f64,
}

impl Pose {
    /// The terrain coordinates of the rover-frame point (x, y).
    pub fn to_terrain(&self, x: f64, y: f64) -> (f64, f64) {
        self.to_terrain_by(self.heading.sin_cos(), x, y)
    }

    /// [`Pose::to_terrain`] with the heading's (sin, cos) given, for many points.
    fn to_terrain_by(self, (s, c): (f64, f64), x: f64, y: f64) -> (f64, f64) {
        (self.x + c * x - s * y, self.y + s * x + c * y)
    }
}

/// Render `terrain` as the camera in `config` sees it with the rover at `pose`: a
/// frame of a drive.
pub fn render_from(terrain: &Terrain, config: &Config, pose: Pose) -> DepthFrame {
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
                    *px = cast(terrain, pose, projector, u, v);
                }
            });
        }
    });
    DepthFrame::from_pixels(w, h, pixels)
}

/// The span of a ray's parameter `t` (metres along `d` per unit) that the march
/// walks: from where the ray (origin height `oz`, rise `dz` per unit of `t`) comes down
/// to the terrain's highest point to where it passes its lowest (`bounds`, widened by a
/// margin so that a surface lying exactly at a bound is inside), within [`FAR_M`];
/// `None` when the ray never is between them.
fn march_span((lo, hi): (f64, f64), oz: f64, dz: f64) -> Option<(f64, f64)> {
    let (lo, hi) = (lo - 0.01, hi + 0.01);
    let (t0, t1) = if dz < 0.0 {
        (((oz - hi) / -dz).max(0.0), ((oz - lo) / -dz).min(FAR_M))
    } else if oz <= hi {
        (0.0, FAR_M)
    } else {
        return None;
    };
    (t0 <= t1).then_some((t0, t1))
}

/// The ray from rover-frame `o` along `d` in the terrain's frame, the rover at `pose`
/// (`heading`: its (sin, cos)): origin and direction.
fn ray_in_terrain(
    pose: Pose,
    heading: (f64, f64),
    o: &Vector3<f64>,
    d: &Vector3<f64>,
) -> ([f64; 3], [f64; 3]) {
    let (s, c) = heading;
    let (ox, oy) = pose.to_terrain_by(heading, o.x, o.y);
    ([ox, oy, o.z], [c * d.x - s * d.y, s * d.x + c * d.y, d.z])
}

/// The optical depth (mm) at which pixel (u, v)'s ray meets the terrain.
fn cast(terrain: &HeightField, pose: Pose, projector: &Projector, u: usize, v: usize) -> u16 {
    let d = projector.ray(u, v);
    let o = projector.point(u, v, 0.0);
    let heading = pose.heading.sin_cos();
    let height = |x: f64, y: f64| {
        let (tx, ty) = pose.to_terrain_by(heading, x, y);
        terrain.height(tx, ty)
    };
    let above = |t: f64| o.z + t * d.z - height(o.x + t * d.x, o.y + t * d.y);
    let Some((mut t0, t1)) = march_span(terrain.bounds(), o.z, d.z) else {
        return 0;
    };
    let dt = STEP_M / d.norm();
    if above(t0) <= 0.0 {
        return to_mm(t0);
    }
    // Before `reach` the ray is above a bound on the ground: the march steps on
    // without asking the height there (two steps' margin for rounding), so that its
    // steps, and the bracket it finds, are the ones it took asking at every step.
    let (origin, dir) = ray_in_terrain(pose, heading, &o, &d);
    let reach = terrain.reach(origin, dir, t0, t1) - 2.0 * dt;
    let mut t = t0;
    loop {
        let next = (t + dt).min(t1);
        if next >= reach && above(next) <= 0.0 {
            t0 = t;
            let mut t_hit = next;
            for _ in 0..40 {
                // The hit lies in (t0, t_hit] and rounding is monotonic: once both ends
                // round to the same millimetre, so does every later bisection.
                if to_mm(t0) == to_mm(t_hit) {
                    break;
                }
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

    /// Depth (mm) at which pixel (u, v)'s ray meets the plane `n·p = k`, by hand.
    fn hand_depth(p: &Projector, u: usize, v: usize, n: [f64; 3], k: f64) -> f64 {
        let (o, d) = (p.point(u, v, 0.0), p.ray(u, v));
        let t =
            (k - (n[0] * o.x + n[1] * o.y + n[2] * o.z)) / (n[0] * d.x + n[1] * d.y + n[2] * d.z);
        t * 1000.0
    }

    fn small(mut c: Config) -> Config {
        c.camera.width = 96;
        c.camera.height = 72;
        c
    }

    #[test]
    fn flat_ground_on_any_mount_and_camera_matches_the_hand_calculation() {
        let mut c = small(Config::default());
        c.mount.z_m = 1.1;
        c.mount.pitch_deg = 38.0;
        c.mount.roll_deg = -8.0;
        c.mount.yaw_deg = 9.0;
        c.mount.x_m = 0.2;
        c.mount.y_m = -0.07;
        for pinhole in [false, true] {
            if pinhole {
                // D435-like: off-centre principal point, unequal focal lengths.
                c.camera.fx = Some(48.0);
                c.camera.fy = Some(47.0);
                c.camera.cx = Some(52.0);
                c.camera.cy = Some(31.0);
            }
            let f = render(&Terrain::flat(), &c);
            let p = Projector::new(&c, 96, 72);
            let mut checked = 0;
            for (u, v) in [(0, 71), (48, 40), (95, 60), (10, 30), (80, 71)] {
                let want = hand_depth(&p, u, v, [0.0, 0.0, 1.0], 0.0);
                let got = f64::from(f.pixels()[v * 96 + u]);
                if want > 0.0 && want < FAR_M * 1000.0 {
                    assert!((got - want).abs() <= 1.0, "({u},{v}) {got} vs {want}");
                    checked += 1;
                }
            }
            assert!(checked >= 4);
        }
    }

    #[test]
    fn a_ramp_and_a_side_face_are_hit_where_the_hand_calculation_says() {
        let c = small(Config::default());
        let p = Projector::new(&c, 96, 72);
        // A diagonal ramp: z = tan g·((x − toe)cos a + (y − y0)sin a) past the toe.
        let (toe, y0, g, a) = (1.1_f64, 0.45_f64, 20.0_f64, 15.0_f64);
        let t = Terrain::new(vec![Element::Ramp {
            toe_x_m: toe,
            ref_y_m: y0,
            gradient_deg: g,
            alpha_deg: a,
            extent: Extent::Full,
            cap_m: None,
            round_m: None,
        }]);
        let f = render(&t, &c);
        let (tg, (sa, ca)) = (g.to_radians().tan(), a.to_radians().sin_cos());
        let n = [-tg * ca, -tg * sa, 1.0];
        let k = -tg * (toe * ca + y0 * sa);
        let mut on_face = 0;
        for v in (0..72).step_by(7) {
            for u in (0..96).step_by(9) {
                let got = f64::from(f.pixels()[v * 96 + u]);
                let hit = p.point(u, v, got / 1000.0);
                let across = (hit.x - toe) * ca + (hit.y - y0) * sa;
                if got > 0.0 && across > 0.02 {
                    let want = hand_depth(&p, u, v, n, k);
                    assert!((got - want).abs() <= 1.0, "({u},{v}) {got} vs {want}");
                    on_face += 1;
                }
            }
        }
        assert!(on_face > 10);
        // A 1 m wall along y = 0.2 (a band's side face): rays to its left hit the
        // plane y = 0.2 where the hit lies on the face.
        let t = Terrain::new(vec![Element::Step {
            x_m: 0.0,
            height_m: 1.0,
            extent: Extent::Band {
                from_m: 0.2,
                to_m: 5.0,
            },
        }]);
        let f = render(&t, &c);
        let mut on_wall = 0;
        for v in 0..72 {
            for u in 0..96 {
                let want = hand_depth(&p, u, v, [0.0, 1.0, 0.0], 0.2);
                if want <= 0.0 {
                    continue;
                }
                let hit = p.point(u, v, want / 1000.0);
                if hit.z > 0.01 && hit.z < 0.99 && hit.x > 0.0 && p.ray(u, v).y > 0.0 {
                    let got = f64::from(f.pixels()[v * 96 + u]);
                    assert!((got - want).abs() <= 1.0, "({u},{v}) {got} vs {want}");
                    on_wall += 1;
                }
            }
        }
        assert!(on_wall > 50, "{on_wall}");
    }

    #[test]
    fn a_rounded_toe_is_hit_where_the_hand_calculation_says() {
        // A 22° ramp whose toe line at x = 1.3 m is rounded over 0.36 m: every pixel
        // that sees the rounding (1.12 m < x < 1.48 m) sees the parabola
        // tan 22° · (x − 1.12)² / 0.72, within the depth's millimetre.
        let c = Config::default();
        let (w, h) = (c.camera.width as usize, c.camera.height as usize);
        let p = Projector::new(&c, w, h);
        let t = Terrain::new(vec![
            Element::ramp(1.3, 0.0, 22.0, 0.0, Extent::Full).toe_rounded(Some(0.36))
        ]);
        let f = render(&t, &c);
        let tan = 22f64.to_radians().tan();
        let mut on_rounding = 0;
        for v in (0..h).step_by(4) {
            for u in (0..w).step_by(8) {
                let got = f64::from(f.pixels()[v * w + u]);
                if got <= 0.0 {
                    continue;
                }
                let hit = p.point(u, v, got / 1000.0);
                if (1.12..1.48).contains(&hit.x) {
                    let want = tan * (hit.x - 1.12).powi(2) / 0.72;
                    assert!(
                        (hit.z - want).abs() < 0.002,
                        "({u},{v}) {} vs {want}",
                        hit.z
                    );
                    on_rounding += 1;
                }
            }
        }
        assert!(on_rounding > 100, "{on_rounding}");
    }

    #[test]
    fn rough_ground_has_the_stated_amplitude_and_correlation() {
        let (amp, ell) = (0.025, 0.15);
        let t = Terrain::new(vec![Element::Rough {
            amplitude_m: amp,
            correlation_m: ell,
            seed: 7,
        }]);
        let field = t.field();
        let pts: Vec<(f64, f64)> = (0..120)
            .flat_map(|i| (0..60).map(move |j| (i as f64 * 0.025, j as f64 * 0.025 - 0.75)))
            .collect();
        let h: Vec<f64> = pts.iter().map(|&(x, y)| field.height(x, y)).collect();
        let n = h.len() as f64;
        let mean = h.iter().sum::<f64>() / n;
        let sd = (h.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
        assert!(h.iter().all(|v| v.abs() <= amp + 1e-12));
        assert!(mean.abs() < 0.3 * amp, "mean {mean}");
        assert!((0.3 * amp..0.6 * amp).contains(&sd), "sd {sd}");
        // Correlation at a lag of one correlation length: exp(−1/2) ≈ 0.61 for a
        // Gaussian covariance; at four lengths, about nothing.
        let corr = |lag: f64| {
            let pairs: Vec<(f64, f64)> = pts
                .iter()
                .filter(|&&(x, _)| x + lag < 3.0)
                .map(|&(x, y)| (field.height(x, y) - mean, field.height(x + lag, y) - mean))
                .collect();
            pairs.iter().map(|(a, b)| a * b).sum::<f64>() / pairs.len() as f64 / (sd * sd)
        };
        assert!((0.4..0.8).contains(&corr(ell)), "corr(ℓ) {}", corr(ell));
        assert!(corr(4.0 * ell).abs() < 0.25, "corr(4ℓ) {}", corr(4.0 * ell));
        // The same seed draws the same ground.
        assert_eq!(t.height(1.234, 0.321), t.clone().height(1.234, 0.321));
    }

    #[test]
    fn value_noise_ground_takes_its_lattice_values_and_blends_smoothly() {
        let (amp, spacing) = (0.025, 0.12);
        let lumpy = |seed| {
            Terrain::new(vec![Element::Lumpy {
                amplitude_m: amp,
                spacing_m: spacing,
                seed,
            }])
        };
        let t = lumpy(11);
        // At lattice points the height is a lattice value; halfway between two, the
        // smoothstep weighs both by one half.
        let at = |i: f64, j: f64| t.height(i * spacing, j * spacing);
        for (i, j) in [(3.0, -2.0), (10.0, 4.0), (-1.0, 0.0)] {
            let mid = t.height((i + 0.5) * spacing, j * spacing);
            assert!((mid - 0.5 * (at(i, j) + at(i + 1.0, j))).abs() < 1e-12);
        }
        // Within ±amplitude, spread over it (uniform lattice values: σ = a/√3 at
        // lattice points), mean about 0, and continuous with its slope bounded by
        // the smoothstep's (1.5 × the largest step between lattice values, 2a, over
        // the spacing): 1 mm apart, heights differ by at most that much.
        let h: Vec<f64> = (0..400)
            .flat_map(|i| (0..40).map(move |j| (i as f64, j as f64 - 20.0)))
            .map(|(i, j)| at(i, j))
            .collect();
        let n = h.len() as f64;
        let mean = h.iter().sum::<f64>() / n;
        let sd = (h.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
        assert!(h.iter().all(|v| v.abs() <= amp));
        assert!(mean.abs() < 0.05 * amp, "mean {mean}");
        assert!((sd / amp - 3f64.sqrt().recip()).abs() < 0.03, "sd {sd}");
        for k in 0..200 {
            let (x, y) = (k as f64 * 0.0137, 0.3 - k as f64 * 0.0041);
            let bound = 1.5 * 2.0 * amp / spacing * 0.001 + 1e-12;
            assert!((t.height(x + 0.001, y) - t.height(x, y)).abs() <= bound);
        }
        // The same seed draws the same ground, another seed other ground.
        assert_eq!(at(2.0, 3.0), lumpy(11).height(2.0 * spacing, 3.0 * spacing));
        assert_ne!(at(2.0, 3.0), lumpy(12).height(2.0 * spacing, 3.0 * spacing));
    }

    #[test]
    fn stones_have_their_profiles_by_hand() {
        let (h, r) = (0.09, 0.15);
        let height = |shape, d: f64| {
            Terrain::new(vec![Element::Stone {
                x_m: 1.0,
                y_m: 0.4,
                radius_m: r,
                height_m: h,
                shape,
            }])
            .height(1.0 + d * 0.6, 0.4 + d * 0.8)
        };
        for shape in StoneShape::ALL {
            assert!((height(shape, 0.0) - h).abs() < 1e-12, "{shape:?} top");
            assert_eq!(height(shape, r), 0.0, "{shape:?} rim");
            assert_eq!(height(shape, 0.2), 0.0, "{shape:?} outside");
        }
        assert!((height(StoneShape::Cone, 0.5 * r) - 0.5 * h).abs() < 1e-12);
        // A sphere through the rim and the top: radius (R² + h²)/2h = 0.17 m, its
        // centre 0.08 m below the ground; at 0.1 m out, √(0.17² − 0.1²) − 0.08.
        let cap = (0.17f64.powi(2) - 0.1f64.powi(2)).sqrt() - 0.08;
        assert!((height(StoneShape::Cap, 0.1) - cap).abs() < 1e-12);
        // σ = R/3: a third of the way out, e^(−1/2) of the top.
        let mound = h * (-0.5f64).exp();
        assert!((height(StoneShape::Mound, r / 3.0) - mound).abs() < 1e-12);
        let boulder = h * (1.0 - 0.5f64.powi(4)).powf(0.25);
        assert!((height(StoneShape::Boulder, 0.5 * r) - boulder).abs() < 1e-12);
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

    #[test]
    fn the_march_skips_no_ground_before_its_bound() {
        // Every family's scenes (ramps, some with rounded toes, steps, blocks, stones,
        // rough ground) on random rigs, from a pose off the origin: along each
        // pixel's ray, the ground lies below the ray everywhere before `reach`, so
        // skipping the height queries there cannot change a depth.
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(77);
        let (mut skipped, mut marched) = (0.0, 0.0);
        for (i, family) in families::Family::ALL.iter().cycle().take(40).enumerate() {
            let rig = families::Rig::random(&mut rng);
            let mut d = families::draw(&mut rng, *family, rig);
            if i % 2 == 1 {
                d = families::restyled(&mut rng, d);
            }
            if i % 3 == 2 {
                d = families::rounded(&mut rng, d);
            }
            let c = d.rig.config;
            let (w, h) = (c.camera.width as usize, c.camera.height as usize);
            let p = Projector::new(&c, w, h);
            let field = d.terrain.field();
            let pose = Pose {
                x: 0.1 * i as f64 - 2.0,
                y: 0.05 * i as f64 - 1.0,
                heading: 0.03 * i as f64 - 0.6,
            };
            let heading = pose.heading.sin_cos();
            // A 32 × 24 sample of the image's pixels.
            let pixels = (0..32).flat_map(|a| (0..24).map(move |b| (a * w / 32, b * h / 24)));
            for (u, v) in pixels {
                let (r, o) = (p.ray(u, v), p.point(u, v, 0.0));
                let Some((t0, t1)) = march_span(field.bounds(), o.z, r.z) else {
                    continue;
                };
                let (origin, dir) = ray_in_terrain(pose, heading, &o, &r);
                let reach = field.reach(origin, dir, t0, t1);
                assert!((t0..=t1).contains(&reach), "scene {i} ({u}, {v})");
                let mut t = t0;
                while t < reach {
                    let (x, y) = (origin[0] + t * dir[0], origin[1] + t * dir[1]);
                    let above = origin[2] + t * dir[2] - field.height(x, y);
                    assert!(above > 0.0, "scene {i} ({u}, {v}): {above} m at t = {t}");
                    t += 0.002;
                }
                skipped += reach - t0;
                marched += t1 - t0;
            }
        }
        // And the bound does skip: here 45 % of the rays' spans between the terrain's
        // height bounds (which run on below the ground, to its lowest point).
        assert!(skipped > 0.3 * marched, "{skipped} of {marched} m skipped");
    }
}
