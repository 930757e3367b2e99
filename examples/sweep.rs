//! A randomised sweep of scenes the fixtures do not contain: every workcase family
//! with random distances, gradients and angles, clean and with Kinect noise, checked
//! against the bars. `cargo run --release --example sweep -- [N] [SEED]`.

use rand::{Rng, SeedableRng};
use rover_terrain::sim::{self, Element, Expectation, Extent, KinectNoise, Terrain};
use rover_terrain::validate::{compare, CLEAN, NOISY};
use rover_terrain::{Config, Decision, Pipeline};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(60);
    let seed: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let config = Config::default();
    let mut pipeline = Pipeline::new(config.clone()).unwrap();
    let (mut failures, mut total) = (0, 0);
    for i in 0..n {
        let family = i % 8;
        let d: f64 = rng.gen_range(0.75..2.0);
        let g: f64 = rng.gen_range(8.0..26.0);
        let a: f64 = rng.gen_range(12.0..35.0) * if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        let cap = if rng.gen_bool(0.3) {
            Some(rng.gen_range(0.15..0.4))
        } else {
            None
        };
        let ramp = |toe, y, g, a, e| Element::Ramp {
            toe_x_m: toe,
            ref_y_m: y,
            gradient_deg: g,
            alpha_deg: a,
            extent: e,
            cap_m: cap,
        };
        let (el, wc, alpha) = match family {
            0 => (ramp(d, 0.0, g, 0.0, Extent::Full), 2, None),
            1 => (ramp(d, 0.45, g, 0.0, Extent::Left), 3, None),
            2 => (ramp(d, 0.45, g, a, Extent::Left), 4, Some(a)),
            3 => (ramp(d, -0.45, g, 0.0, Extent::Right), 5, None),
            4 => (ramp(d, -0.45, g, a, Extent::Right), 6, Some(a)),
            5 => (ramp(d, 0.0, g, a, Extent::Full), 7, Some(a)),
            6 => (ramp(d, 0.0, -g.min(20.0), 0.0, Extent::Full), 8, None),
            _ => {
                let left = rng.gen_bool(0.5);
                let y = if left { 0.45 } else { -0.45 };
                (
                    ramp(
                        d,
                        y,
                        -g.min(20.0),
                        0.0,
                        if left { Extent::Left } else { Extent::Right },
                    ),
                    if left { 9 } else { 10 },
                    None,
                )
            }
        };
        let gradient = match &el {
            Element::Ramp { gradient_deg, .. } => *gradient_deg,
            _ => unreachable!(),
        };
        let want = Expectation {
            verdict: Decision::Go,
            workcase: Some(wc),
            distance_m: Some(d),
            gradient_deg: Some(gradient),
            alpha_deg: alpha,
            hazard: None,
        };
        let frame = sim::render(&Terrain::new(vec![el.clone()]), &config);
        for noisy in [false, true] {
            let mut f = frame.clone();
            if noisy {
                KinectNoise {
                    seed: seed * 1000 + i as u64,
                    ..Default::default()
                }
                .apply(&mut f, config.camera.hfov_deg);
            }
            let v = pipeline.process(&f).unwrap().clone();
            let fails = compare(&want, if noisy { &NOISY } else { &CLEAN }, &v);
            total += 1;
            if !fails.is_empty() {
                failures += 1;
                println!(
                    "FAIL #{i} noisy={noisy} {el:?}: {fails:?} hazards={:?}",
                    v.hazards
                );
            }
        }
    }
    println!("{} of {total} passed", total - failures);
}
