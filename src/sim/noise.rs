use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use rover_terrain_drivers::DepthFrame;
use serde::{Deserialize, Serialize};

/// A Kinect v1 noise model, deterministic for a seed:
/// - depth-dependent Gaussian noise along the ray, `σ = sigma_per_m2 · Z²`
///   (Khoshelham & Elberink 2012 give 1.425e-3 m⁻¹);
/// - disparity quantisation to 1/8 pixel for a 7.5 cm baseline and the focal length
///   implied by the horizontal FOV;
/// - random dropout of a fraction of the pixels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct KinectNoise {
    /// Random seed.
    pub seed: u64,
    /// σ of the depth noise per squared metre of depth, 1/m.
    pub sigma_per_m2: f64,
    /// Fraction of pixels lost, 0..1.
    pub dropout: f64,
    /// Projector-camera baseline, metres.
    pub baseline_m: f64,
    /// Disparity subpixel steps per pixel.
    pub subpixel: f64,
}

impl Default for KinectNoise {
    fn default() -> Self {
        KinectNoise {
            seed: 1,
            sigma_per_m2: 1.425e-3,
            dropout: 0.01,
            baseline_m: 0.075,
            subpixel: 8.0,
        }
    }
}

impl KinectNoise {
    /// Apply the noise to a clean frame from a camera with horizontal FOV `hfov_deg`.
    pub fn apply(&self, frame: &mut DepthFrame, hfov_deg: f64) {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        let focal_px = frame.width() as f64 / 2.0 / (hfov_deg.to_radians() / 2.0).tan();
        let fb = focal_px * self.baseline_m;
        let unit = Normal::new(0.0, 1.0).expect("unit normal is valid");
        for p in frame.pixels_mut() {
            // Draw for every pixel so the pattern does not depend on the scene.
            let drop = rng.gen::<f64>() < self.dropout;
            let n: f64 = unit.sample(&mut rng);
            if *p == 0 {
                continue;
            }
            if drop {
                *p = 0;
                continue;
            }
            let z = f64::from(*p) * 1e-3;
            let noisy = z + n * self.sigma_per_m2 * z * z;
            if noisy <= 0.0 {
                *p = 0;
                continue;
            }
            let disparity = (fb / noisy * self.subpixel).round() / self.subpixel;
            let q = if disparity > 0.0 { fb / disparity } else { 0.0 };
            let mm = (q * 1000.0).round();
            *p = if (1.0..=65535.0).contains(&mm) {
                mm as u16
            } else {
                0
            };
        }
    }
}

/// Mixed ("flying") pixels at depth edges, as time-of-flight cameras and renderers
/// that average over a pixel's footprint give: a pixel whose depth differs from one
/// of its four neighbours' by more than `min_jump_m` takes, with probability
/// `fraction`, a depth drawn uniformly between its own and that neighbour's (the
/// farthest such neighbour). Pixels with no return stay so and mix with none.
/// Deterministic for `seed`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FlyingPixels {
    /// Random seed.
    pub seed: u64,
    /// Fraction of the edge pixels mixed, 0..1.
    pub fraction: f64,
    /// Least depth jump to a neighbour that makes an edge, metres.
    pub min_jump_m: f64,
}

impl Default for FlyingPixels {
    fn default() -> Self {
        FlyingPixels {
            seed: 1,
            fraction: 0.5,
            min_jump_m: 0.05,
        }
    }
}

impl FlyingPixels {
    /// Mix the edge pixels of `frame`.
    pub fn apply(&self, frame: &mut DepthFrame) {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        let (w, h) = (frame.width(), frame.height());
        let before = frame.pixels().to_vec();
        let jump = self.min_jump_m * 1000.0;
        for (k, p) in frame.pixels_mut().iter_mut().enumerate() {
            let (u, v) = (k % w, k / w);
            let own = f64::from(before[k]);
            let (mix, t): (bool, f64) = (rng.gen_bool(self.fraction), rng.gen());
            if own == 0.0 || !mix {
                continue;
            }
            let neighbours = [
                (u > 0).then(|| k - 1),
                (u + 1 < w).then(|| k + 1),
                (v > 0).then(|| k - w),
                (v + 1 < h).then(|| k + w),
            ];
            let far = neighbours
                .into_iter()
                .flatten()
                .map(|j| f64::from(before[j]))
                .filter(|&d| d > 0.0 && (d - own).abs() > jump)
                .reduce(|m, d| {
                    if (d - own).abs() > (m - own).abs() {
                        d
                    } else {
                        m
                    }
                });
            if let Some(other) = far {
                *p = (own + t * (other - own)).round() as u16;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flying_pixels_mix_only_across_depth_edges() {
        // Columns 0-7 at 1 m, 8-15 at 2 m, and one pixel with no return.
        let mut px: Vec<u16> = (0..16 * 4)
            .map(|k| if k % 16 < 8 { 1000 } else { 2000 })
            .collect();
        px[16 * 2 + 3] = 0;
        let clean = DepthFrame::from_pixels(16, 4, px);
        let flying = FlyingPixels {
            seed: 9,
            fraction: 1.0,
            min_jump_m: 0.05,
        };
        let (mut a, mut b) = (clean.clone(), clean.clone());
        flying.apply(&mut a);
        flying.apply(&mut b);
        assert_eq!(a.pixels(), b.pixels());
        let mut moved = 0;
        for (k, (&got, &was)) in a.pixels().iter().zip(clean.pixels()).enumerate() {
            let u = k % 16;
            if u == 7 || u == 8 {
                // An edge pixel lands between its depth and its neighbour's.
                assert!((1000..=2000).contains(&got), "{k}: {got}");
                moved += usize::from(got != was);
            } else {
                assert_eq!(got, was, "{k}: not at an edge");
            }
        }
        assert!(moved >= 6, "{moved}");
        // No mixing at all with fraction 0.
        let mut c = clean.clone();
        FlyingPixels {
            fraction: 0.0,
            ..flying
        }
        .apply(&mut c);
        assert_eq!(c.pixels(), clean.pixels());
    }

    #[test]
    fn deterministic_and_about_the_right_size() {
        // Camera width matters: it sets the focal length and so the disparity step.
        let clean = DepthFrame::from_pixels(640, 16, vec![2000; 10_240]);
        let noise = KinectNoise {
            seed: 3,
            ..Default::default()
        };
        let (mut a, mut b) = (clean.clone(), clean.clone());
        noise.apply(&mut a, 57.0);
        noise.apply(&mut b, 57.0);
        assert_eq!(a.pixels(), b.pixels());
        let valid: Vec<f64> = a
            .pixels()
            .iter()
            .filter(|&&p| p != 0)
            .map(|&p| f64::from(p))
            .collect();
        let dropped = 10_240 - valid.len();
        assert!((50..200).contains(&dropped), "{dropped}");
        let mean = valid.iter().sum::<f64>() / valid.len() as f64;
        let sd =
            (valid.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / valid.len() as f64).sqrt();
        // σ = 1.425e-3 · 4 m² = 5.7 mm, plus quantisation (step ≈ 11 mm at 2 m with
        // a 589 px focal length): about 6.6 mm in all, no bias.
        assert!((mean - 2000.0).abs() < 2.0, "{mean}");
        assert!(sd > 5.0 && sd < 9.0, "{sd}");
    }
}
