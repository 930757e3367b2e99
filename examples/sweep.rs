//! A randomised sweep of scenes the fixtures do not contain, checked against the
//! issue's bars, clean and with Kinect v1 noise:
//! `cargo run --release --example sweep -- [workcases|hazards] [N] [SEED]`.

use rand::SeedableRng;
use rover_terrain::sim::{self, random, KinectNoise};
use rover_terrain::validate::{compare, CLEAN, NOISY};
use rover_terrain::{Config, Pipeline};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mode = args.get(1).map_or("workcases", String::as_str);
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(80);
    let seed: u64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let config = Config::default();
    let mut pipeline = Pipeline::new(config.clone()).expect("default config works");
    let (mut failures, mut total) = (0, 0);
    for i in 0..n {
        let (terrain, want) = match mode {
            "hazards" => random::hazard_scene(&mut rng, i),
            _ => random::workcase_scene(&mut rng, i),
        };
        let frame = sim::render(&terrain, &config);
        for noisy in [false, true] {
            let mut f = frame.clone();
            if noisy {
                KinectNoise {
                    seed: seed * 1000 + i as u64,
                    ..Default::default()
                }
                .apply(&mut f, config.camera.hfov_deg);
            }
            let v = pipeline.process(&f).expect("frame fits");
            let fails = compare(&want, if noisy { &NOISY } else { &CLEAN }, v);
            total += 1;
            if !fails.is_empty() {
                failures += 1;
                println!(
                    "FAIL #{i} noisy={noisy} {:?}: {fails:?} hazards={:?}",
                    terrain.elements, v.hazards
                );
            }
        }
    }
    println!("{} passed, {failures} failed", total - failures);
}
