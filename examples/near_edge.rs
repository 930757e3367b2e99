//! Impassable hazards where a random rig's view starts: a hunt for false gos.
//!
//! `cargo run --release --example near_edge -- N SEED [far]` draws N random rigs
//! (`sim::families::Rig::random`) and on each one hazard a rover must not be sent
//! onto: a step up or down over the wheel radius (under one track or across the
//! corridor), a ramp steeper than the slope limit, or a block under the belly over
//! its clearance, placed from 0.35 m before the near edge of what the rig sees
//! (`sim::families::footprint`) to 0.12 m past it (with `far`: from that edge to
//! 1.2 m past it). Each scene is analysed clean and with Kinect v1 noise; every go is
//! printed, and the last line counts them. `DUMP=DIR` writes each such scene's
//! terrain (`N.json`) and configuration (`N.toml`) for the `cells` example.
//!
//! There is no other bar: unknown and stop are both right here (a hazard below the
//! image is not seen, only its effect on the ground beyond it).
//!
//! `-- N SEED passable` is the control: on the rigs (of N) whose view ends inside the
//! corridor, a climbable ramp (10-27°, under one track or across the corridor) whose
//! toe lies in the last 0.35 m of what the rig sees, where
//! it rises out of the image within a few cells. It should be go; every other verdict
//! is printed with its hazards, and the last line counts them.

use rand::{Rng, SeedableRng};
use rover_terrain::sim::{self, families, Element, Extent, KinectNoise, Terrain};
use rover_terrain::{Config, Decision, Pipeline};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(200);
    let seed: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let far = args.get(3).map(String::as_str) == Some("far");
    let passable = args.get(3).map(String::as_str) == Some("passable");
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let (mut total, mut flagged) = (0, 0);
    for i in 0..n {
        let config = families::Rig::random(&mut rng).config;
        let (near, end) = families::footprint(&config);
        let element = if passable {
            // Only rigs whose view ends inside the corridor: else the ramp would rise
            // out of the corridor, not out of the image.
            if end > config.analysis.corridor_length_m - 0.1 {
                continue;
            }
            let toe = rng.gen_range(end - 0.35..end - 0.02);
            let gradient = rng.gen_range(10.0..27.0);
            let extent = [Extent::Left, Extent::Right, Extent::Full][rng.gen_range(0..3)];
            Element::ramp(toe, 0.0, gradient, 0.0, extent)
        } else {
            let x = if far {
                rng.gen_range(near..near + 1.2)
            } else {
                rng.gen_range((near - 0.35).max(0.3)..near + 0.12)
            };
            impassable(&mut rng, i, x, &config)
        };
        let terrain = Terrain::new(vec![element]);
        let frame = sim::render(&terrain, &config);
        let mut pipeline = Pipeline::new(config.clone()).expect("a random rig is a valid rig");
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
            total += 1;
            // A go is wrong here, anything else on the passable control.
            if (v.decision == Decision::Go) == passable {
                continue;
            }
            flagged += 1;
            println!(
                "{} #{i} noisy={noisy} near={near:.3} end={end:.3} {:?} mount={:?} cam={}x{} feature={:?} hazards={:?}",
                if passable { "NOT GO" } else { "GO" },
                terrain.elements,
                config.mount,
                config.camera.width,
                config.camera.height,
                v.feature,
                v.hazards
            );
            if let Ok(dir) = std::env::var("DUMP") {
                let dir = std::path::Path::new(&dir);
                std::fs::create_dir_all(dir).expect("DUMP is a writable directory");
                let json = serde_json::to_string(&terrain.elements).expect("terrain serialises");
                std::fs::write(dir.join(format!("{i}.json")), json).expect("DUMP writable");
                let toml = toml::to_string(&config).expect("configuration serialises");
                std::fs::write(dir.join(format!("{i}.toml")), toml).expect("DUMP writable");
            }
        }
    }
    let counted = if passable { "not go" } else { "go" };
    println!("{total} frames, {flagged} {counted}");
}

/// The `i`-th impassable hazard at `x` metres on the rig `config`: a step up or down
/// over the wheel radius, a ramp over the slope limit, a block over the belly
/// clearance, in turn.
fn impassable(rng: &mut impl Rng, i: usize, x: f64, config: &Config) -> Element {
    let r = config.rover.wheel_radius_m;
    let extent = [Extent::Left, Extent::Right, Extent::Full][rng.gen_range(0..3)];
    match i % 4 {
        0 => Element::Step {
            x_m: x,
            height_m: rng.gen_range(r + 0.003..0.3),
            extent,
        },
        1 => Element::Step {
            x_m: x,
            height_m: -rng.gen_range(r + 0.003..0.3),
            extent,
        },
        2 => Element::ramp(x, 0.0, rng.gen_range(31.0..50.0), 0.0, extent),
        _ => Element::Block {
            x_m: x + 0.125,
            y_m: rng.gen_range(-0.08..0.08),
            length_m: 0.25,
            width_m: 0.25,
            height_m: rng.gen_range(config.rover.belly_clearance_m + 0.01..0.6),
        },
    }
}
