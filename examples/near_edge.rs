//! Impassable hazards where a random rig's view starts: a hunt for false gos.
//!
//! `cargo run --release --example near_edge -- N SEED [far]` draws N random rigs
//! (`sim::families::Rig::random`) and on each one hazard a rover must not be sent
//! onto: a step up or down over the wheel radius (under one track or across the
//! corridor), a ramp steeper than the slope limit, or a block under the belly over
//! its clearance, placed from 0.35 m before the near edge of what the rig sees
//! (`sim::families::footprint`) to 0.12 m past it (with `far`: from that edge to
//! 1.2 m past it). Each scene is analysed clean and with Kinect v1 noise; every go is
//! printed, and the last line counts them. With `far`, a hazard that starts past the
//! far end of what the rig sees is not in the frame at all: any verdict passes there,
//! and a last line counts those frames. `DUMP=DIR` writes each such scene's
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
//!
//! `-- N SEED rough` puts, on the same rigs, a ramp on rough ground (±2.5 cm, drawn
//! as plane waves or as value noise, correlation 10-20 cm) whose toe lies 0.3-0.7 m
//! before the end of the view: half climbable (12-25°, should be go), half over the
//! slope limit (31.5-40°, must not be go). The last line counts the gos on steep
//! ramps and the other verdicts on climbable ones; `ALL=1` prints every frame's drawn
//! and measured gradient.
//!
//! `-- N SEED short` puts, on the same rigs, a ramp over the slope limit (30.5-40°,
//! under one track or across the corridor, straight or diagonal, on smooth or rough
//! ground) whose toe lies 0.05-0.45 m before the end of the view. A go is wrong only
//! where the ramp rises at least 5 cm in a track before where the verdict says that
//! track's view ends (`seen_to_m`: a go vouches for the ground up to there, no
//! farther); the last line counts those gos and the gos on ramps that rise only past
//! the view.

use rand::{Rng, SeedableRng};
use rover_terrain::sim::{self, families, Element, Extent, KinectNoise, Terrain};
use rover_terrain::verdict::SeenTo;
use rover_terrain::{Config, Decision, Pipeline};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(200);
    let seed: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let mode = match args.get(3).map(String::as_str) {
        Some("far") => Mode::Far,
        Some("passable") => Mode::Passable,
        Some("rough") => Mode::Rough,
        Some("short") => Mode::Short,
        _ => Mode::Near,
    };
    let (far, passable, rough) = (
        mode == Mode::Far,
        mode == Mode::Passable,
        mode == Mode::Rough,
    );
    let (mut steep_go, mut climbable_not_go, mut past_view) = (0, 0, 0);
    let mut short_go_at_view_end = 0;
    let mut steep_frames = 0;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let (mut total, mut flagged) = (0, 0);
    for i in 0..n {
        let config = families::Rig::random(&mut rng).config;
        let (near, end) = families::footprint(&config);
        let Some(Scene {
            terrain,
            steep,
            unseen,
        }) = scene(&mut rng, mode, i, &config, (near, end))
        else {
            continue;
        };
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
            // A go is wrong here, anything else on the passable control; on rough
            // ramps, a go on a steep one or anything else on a climbable one.
            let go = v.decision == Decision::Go;
            // A go on a short steep ramp is wrong only where the verdict vouches for
            // some of its rise: it rises in a track before where that track's view
            // ends (`seen_to_m`), the contract of a go.
            let rise = (mode == Mode::Short).then(|| rise_seen(&terrain, &config, &v.seen_to_m));
            let wrong = if rough {
                go == steep
            } else if let Some(rise) = rise {
                let vouched = rise >= SHORT_RISE_M;
                short_go_at_view_end += usize::from(go && !vouched);
                go && vouched
            } else {
                go != passable && !unseen
            };
            past_view += usize::from(unseen);
            steep_frames += usize::from(steep);
            if rough && std::env::var("ALL").is_ok() {
                print_measure(i, noisy, end, &terrain, &config, v);
            }
            if !wrong {
                continue;
            }
            flagged += 1;
            if rough && steep {
                steep_go += 1;
            } else if rough {
                climbable_not_go += 1;
            }
            if let Some(rise) = rise {
                print!("risen {rise:.3} m where the view ends: ");
            }
            println!(
                "{} #{i} noisy={noisy} near={near:.3} end={end:.3} {:?} mount={:?} cam={}x{} feature={:?} hazards={:?}",
                if go { "GO" } else { "NOT GO" },
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
    if rough {
        println!(
            "{total} frames ({steep_frames} steep), {steep_go} go on a steep rough ramp, {climbable_not_go} not go on a climbable one"
        );
    } else if mode == Mode::Short {
        println!(
            "{total} frames, {flagged} go on a steep ramp risen {SHORT_RISE_M} m or more where the view ends, {short_go_at_view_end} go on one that rises only past it"
        );
    } else {
        let counted = if passable { "not go" } else { "go" };
        println!("{total} frames, {flagged} {counted}");
        if far {
            println!(
                "{past_view} frames with the hazard wholly past the view (any verdict passes)"
            );
        }
    }
}

/// Which scenes `near_edge` draws (its third argument).
#[derive(Clone, Copy, PartialEq)]
enum Mode {
    /// An impassable hazard where the view starts.
    Near,
    /// An impassable hazard up to 1.2 m past where the view starts.
    Far,
    /// A climbable ramp whose toe lies in the last 0.35 m of the view.
    Passable,
    /// A climbable or steep ramp on rough ground, toe 0.3-0.7 m before the view ends.
    Rough,
    /// A ramp over the slope limit, smooth or rough, straight or diagonal, toe
    /// 0.05-0.45 m before the view ends.
    Short,
}

/// How high a `Short` ramp must rise in a track before where that track's view ends
/// for a go to be wrong, metres: a rise of this much is seen (a face of at least a
/// cell and a half at 31°).
const SHORT_RISE_M: f64 = 0.05;

/// How high the ramp of a `Short` scene (its last element, without the rough ground
/// under it) stands, metres, at the farthest point of either wheel track the verdict
/// says is seen (`seen_to`, per track; at eleven points across the track).
fn rise_seen(terrain: &Terrain, config: &Config, seen_to: &SeenTo) -> f64 {
    let (inner, outer) = (config.rover.belly_half_width_m, config.rover.track_outer_m);
    let ramp = Terrain::new(terrain.elements.last().into_iter().cloned().collect());
    let field = ramp.field();
    let track = |to: f32, side: f64| {
        (0..=10)
            .map(|k| f64::from(k) / 10.0)
            .map(|t| field.height(f64::from(to), side * (inner + t * (outer - inner))))
            .fold(f64::MIN, f64::max)
    };
    track(seen_to.left, 1.0).max(track(seen_to.right, -1.0))
}

/// One drawn scene: its terrain, whether its ramp is over the slope limit (`Rough`),
/// and whether its hazard starts past the far end of the view (`Far`).
struct Scene {
    terrain: Terrain,
    steep: bool,
    unseen: bool,
}

/// Scene `i` of `mode` on the rig `config`, which sees flat ground from `near` to
/// `end` metres, or `None` for a rig the mode skips (its view does not end inside the
/// corridor).
fn scene(
    rng: &mut impl Rng,
    mode: Mode,
    i: usize,
    config: &Config,
    (near, end): (f64, f64),
) -> Option<Scene> {
    if mode == Mode::Rough {
        let (terrain, steep) = families::rough_ramp_at_view_end(rng, config)?;
        return Some(Scene {
            terrain,
            steep,
            unseen: false,
        });
    }
    if mode == Mode::Short {
        if !families::view_ends_in_corridor(end, config) {
            return None;
        }
        let toe = rng.gen_range(end - 0.45..end - 0.05);
        let gradient = rng.gen_range(30.5..40.0);
        let alpha = if rng.gen_bool(0.5) {
            0.0
        } else {
            rng.gen_range(-30.0..30.0)
        };
        let extent = [Extent::Left, Extent::Right, Extent::Full][rng.gen_range(0..3)];
        let mut elements = Vec::new();
        if rng.gen_bool(0.5) {
            elements.push(Element::Rough {
                amplitude_m: 0.025,
                correlation_m: rng.gen_range(0.1..0.2),
                seed: rng.gen(),
            });
        }
        elements.push(Element::ramp(toe, 0.0, gradient, alpha, extent));
        return Some(Scene {
            terrain: Terrain::new(elements),
            steep: false,
            unseen: false,
        });
    }
    let (element, unseen) = if mode == Mode::Passable {
        if !families::view_ends_in_corridor(end, config) {
            return None;
        }
        let toe = rng.gen_range(end - 0.35..end - 0.02);
        let gradient = rng.gen_range(10.0..27.0);
        let extent = [Extent::Left, Extent::Right, Extent::Full][rng.gen_range(0..3)];
        (Element::ramp(toe, 0.0, gradient, 0.0, extent), false)
    } else {
        let x = if mode == Mode::Far {
            rng.gen_range(near..near + 1.2)
        } else {
            rng.gen_range((near - 0.35).max(0.3)..near + 0.12)
        };
        let element = impassable(rng, i, x, config);
        // With `far`, the hazard may start past what the rig sees of flat ground
        // at all: nothing of it is in the frame, and any verdict passes.
        let near_edge = match element {
            Element::Block { x_m, .. } => x_m,
            _ => x,
        };
        (element, near_edge >= end)
    };
    Some(Scene {
        terrain: Terrain::new(vec![element]),
        steep: false,
        unseen,
    })
}

/// Prints a rough-ramp frame's drawn and measured gradient (`ALL=1`).
fn print_measure(
    i: usize,
    noisy: bool,
    end: f64,
    terrain: &Terrain,
    config: &Config,
    v: &rover_terrain::Verdict,
) {
    if let Some(Element::Ramp {
        toe_x_m,
        gradient_deg,
        extent,
        ..
    }) = terrain.elements.last()
    {
        println!(
            "ALL #{i} noisy={noisy} drawn {gradient_deg:.1} toe {toe_x_m:.2} end {end:.2} {extent:?} cam={} -> {:?} measured {:?} seen {:?}",
            config.camera.width, v.decision, v.feature.map(|f| f.gradient_deg), v.seen_to_m
        );
    }
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
