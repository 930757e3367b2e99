//! A deterministic slice of the randomised sweep (`examples/sweep.rs` runs more):
//! scenes the fixtures do not contain, every workcase family and every go/stop edge,
//! clean and with Kinect v1 noise, against the bars.

use rand::SeedableRng;
use rover_terrain::sim::{self, random, KinectNoise};
use rover_terrain::validate::{compare, CLEAN, NOISY};
use rover_terrain::{Config, Pipeline};

fn sweep(hazards: bool, n: usize, seed: u64) {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let config = Config::default();
    let mut pipeline = Pipeline::new(config.clone()).unwrap();
    let mut failures = Vec::new();
    for i in 0..n {
        let (terrain, want) = if hazards {
            random::hazard_scene(&mut rng, i)
        } else {
            random::workcase_scene(&mut rng, i)
        };
        let mut frame = sim::render(&terrain, &config);
        for noisy in [false, true] {
            if noisy {
                KinectNoise {
                    seed: seed + i as u64,
                    ..Default::default()
                }
                .apply(&mut frame, config.camera.hfov_deg);
            }
            let v = pipeline.process(&frame).unwrap();
            let fails = compare(&want, if noisy { &NOISY } else { &CLEAN }, v);
            if !fails.is_empty() {
                failures.push(format!(
                    "#{i} noisy={noisy} {:?}: {fails:?}",
                    terrain.elements
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn random_workcase_scenes_meet_the_bars() {
    sweep(false, 16, 77);
}

#[test]
fn random_go_stop_edges_get_the_right_verdict_and_hazard() {
    sweep(true, 18, 78);
}
