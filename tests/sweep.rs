//! A deterministic slice of the randomised sweep (`examples/sweep.rs` runs more):
//! scenes the fixtures do not contain, every workcase family and every go/stop edge,
//! clean and with Kinect v1 noise (or a noisier camera's), against the bars.

use rand::SeedableRng;
use rover_terrain::sim::{self, random, KinectNoise};
use rover_terrain::validate::{compare, CLEAN, NOISY};
use rover_terrain::{Config, Pipeline};

/// Draw `n` random scenes from `seed` (the go/stop edges with `hazards`, else the
/// workcases) and check each clean and noisy frame against the bars. The noisy
/// frames' depth σ is `sigma_scale` times a Kinect v1's, and `dropout` of their
/// pixels are lost.
fn sweep(hazards: bool, n: usize, seed: u64, (sigma_scale, dropout): (f64, f64)) {
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
                    sigma_per_m2: sigma_scale * KinectNoise::default().sigma_per_m2,
                    dropout,
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
    sweep(false, 16, 77, (1.0, KinectNoise::default().dropout));
}

#[test]
fn random_go_stop_edges_get_the_right_verdict_and_hazard() {
    sweep(true, 18, 78, (1.0, KinectNoise::default().dropout));
}

/// A RealSense D435-like camera (848×480, fx ≈ 425 px, 50 mm baseline, 0.08 px
/// subpixel error) has a depth σ of z² · 0.08 / (425 · 0.05) = 3.8 mm per squared
/// metre, 2.6 times a Kinect v1's: the go/stop edges keep their verdicts and hazards
/// with depth noise that high and 3 % of the pixels lost.
#[test]
fn a_camera_noisier_than_a_kinect_keeps_the_go_stop_edges() {
    sweep(true, 18, 79, (2.6, 0.03));
}

#[test]
fn random_posts_in_a_track_are_never_go() {
    // Posts 3-8 cm square and 16-50 cm high in a track, on flat or rough ground or up a
    // one-track ramp, on random rigs that see them whole (`sweep -- posts`): before
    // posts were read at their top, a third of such frames went.
    use rover_terrain::sim::families::{judged_span, Rig};
    use rover_terrain::Decision;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(10_417);
    let mut failures = Vec::new();
    for i in 0..12 {
        let (rig, terrain) = (0..100)
            .find_map(|_| {
                let rig = Rig::random(&mut rng);
                let at = judged_span(&rig.config);
                random::post_scene_within(&mut rng, &rig.config, at).map(|(t, _)| (rig, t))
            })
            .expect("one of 100 random rigs sees a post whole");
        let mut pipeline = Pipeline::new(rig.config.clone()).unwrap();
        let mut frame = sim::render(&terrain, &rig.config);
        for noisy in [false, true] {
            if noisy {
                KinectNoise {
                    seed: 10_417_000 + i,
                    ..Default::default()
                }
                .apply(&mut frame, rig.config.camera.hfov_deg);
            }
            let v = pipeline.process(&frame).unwrap();
            if v.decision == Decision::Go {
                failures.push(format!("#{i} noisy={noisy} {:?}", terrain.elements));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
