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

#[cfg(test)]
mod tests {
    use super::*;

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
