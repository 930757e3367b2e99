//! A randomised sweep of scenes the fixtures do not contain, checked against the
//! issue's bars, clean and with Kinect v1 noise:
//! `cargo run --release --example sweep -- [workcases|hazards] [N] [SEED]`, or
//! `-- families [N] [SEED] [default|random] [FAMILY-INDEX]` for the scene families of
//! `sim::families` on the default rig or on random mounts and cameras (without an
//! index, `Family::ALL`'s in turn; index 11 is `Family::LATER`'s rock under the belly
//! beside a one-track ramp), or
//! `-- natural [N] [SEED] [default|random] [FAMILY-INDEX]` for the same scenes drawn
//! another way (`families::restyled`: value-noise rough ground, stones of four other
//! shapes), or `-- bevelled [N] [SEED] [default|random] [FAMILY-INDEX]` for them
//! with every band's vertical sides sloping (`families::bevelled`: a one-track
//! ramp's side face fading over 2-15 cm), or `-- widened [N] [SEED]
//! [default|random] [FAMILY-INDEX]` for them with each band under one side wider
//! than the track (`families::widened`: its inner edge 0-15 cm into the belly band),
//! or
//! `-- hazards N SEED random` for the go/stop edges on random rigs, each edge where
//! the rig sees the tracks, or `-- edges N SEED` for impassable edges that sweep
//! does not draw (a step down under one side, a descent steeper than the limit, a
//! block in a track, ditches, a too-steep ramp met obliquely), also on random rigs,
//! where any verdict but go passes (a ditch whose floor the camera cannot see is
//! unknown ground); `-- oblique N SEED`, climbable ramps up and down whose toe line
//! runs at 20-60° to the axle, on random rigs, judged go or not, except where the
//! camera meets the surface in the tracks at under `GRAZING_DEG` (a descent as steep
//! as the line of sight to it is not seen there): any verdict passes, and the last
//! lines count those frames; `families`, `natural`, `bevelled` and `widened` excuse a scene due
//! go in the same way, its incidence taken on its planes alone (no rough ground, no
//! stones, each band's sides drawn vertical).
//! `ONLY=3,7` checks
//! just those scenes of the sweep. The last line counts the failures and, of them,
//! the gos where a stop was due. `DUMP=DIR` writes each failing scene's terrain
//! (`N.json`, for `cells`) and configuration (`N.toml`, for `cells`' `CONFIG` and
//! `rover-terrain inspect --config`) there; with `ALL=1`, every scene's. `FLYING=FRACTION` also mixes that fraction
//! of the noisy frames' depth-edge pixels (`sim::FlyingPixels`, as time-of-flight
//! cameras give). `EXACT=1` draws each frame with the second renderer of
//! `tests/common/second_renderer.rs` (its own rays, exact planes and faces) instead of
//! `sim::render`; scenes it cannot draw (rough ground, stones, rocks on anything but
//! flat ground) are skipped, and the last line counts them. `ALL=1` also prints every
//! frame's verdict (decision, hazards, feature, tilt, how far each band is seen):
//! two builds' outputs, sorted, diff to exactly the frames whose verdict changed.
//! `WANT=1` also prints each frame's expectation on a line of its own (`want #N
//! noisy=...`), so that errors in distance and gradient can be tallied over frames
//! that pass as well as those that fail. A go where a stop was due also prints, for
//! each stone or rock drawn 12 cm or higher, how high its apex stands over the ground
//! before it (`RELIEF #N ...`, sampled from the height field); a stop where a go was
//! due prints it for every stone and rock.

#[path = "../tests/common/second_renderer.rs"]
mod second;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rover_terrain::analysis::GRAZING_DEG;
use rover_terrain::sim::{
    self, families, random, Element, Expectation, KinectNoise, Terrain, Tolerance,
};
use rover_terrain::validate::{compare, CLEAN, NOISY};
use rover_terrain::{Config, Decision, Pipeline};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mode = args.get(1).map_or("workcases", String::as_str);
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(80);
    let seed: u64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // ONLY=i,j,... renders just those scenes (the draws before them still happen).
    let only: Option<Vec<usize>> = std::env::var("ONLY")
        .ok()
        .map(|v| v.split(',').filter_map(|s| s.parse().ok()).collect());
    let random_rig = args.get(4).map(String::as_str) == Some("random");
    // FLYING=FRACTION: mix that fraction of the noisy frames' edge pixels too.
    let flying: Option<f64> = std::env::var("FLYING").ok().and_then(|v| v.parse().ok());
    // `families` mode: just this family (its index in `families::Family::ALL`, then
    // `LATER`: `families::Family::by_index`).
    let family = args.get(5).and_then(|s| s.parse::<usize>().ok());
    let (mut failures, mut total, mut false_go, mut excused) = (0, 0, 0, (0, 0));
    let exact = std::env::var("EXACT").is_ok_and(|v| v == "1");
    // ALL=1: every frame's verdict, passed or not (see the module doc).
    let all = std::env::var("ALL").is_ok_and(|v| v == "1");
    // WANT=1: also each frame's expectation, on a line of its own.
    let want_too = std::env::var("WANT").is_ok_and(|v| v == "1");
    let mut not_drawn = 0;
    for i in 0..n {
        let (terrain, want, config, tol) = draw(&mut rng, mode, i, random_rig, family);
        if only.as_ref().is_some_and(|o| !o.contains(&i)) {
            continue;
        }
        let mut pipeline = Pipeline::new(config.clone()).expect("config works");
        let frame = if exact {
            let Some(frame) = second::frame(&terrain, &config) else {
                not_drawn += 1;
                continue;
            };
            frame
        } else {
            sim::render(&terrain, &config)
        };
        let unseen = unseen_at_grazing(mode, &want, &terrain, &config);
        for noisy in [false, true] {
            let mut f = frame.clone();
            if noisy {
                KinectNoise {
                    seed: seed * 1000 + i as u64,
                    ..Default::default()
                }
                .apply(&mut f, config.camera.hfov_deg);
                if let Some(fraction) = flying {
                    sim::FlyingPixels {
                        seed: seed * 1000 + i as u64,
                        fraction,
                        ..Default::default()
                    }
                    .apply(&mut f);
                }
            }
            let v = pipeline.process(&f).expect("frame fits");
            if unseen {
                excused.0 += 1;
                excused.1 += usize::from(v.decision != Decision::Go);
            }
            let fails = if unseen {
                Vec::new()
            } else if mode == "edges" {
                // Stop or unknown: a ditch whose floor lies in its own shadow is unknown
                // ground (how deep it is, is not seen); only a go fails.
                if v.decision == Decision::Go {
                    vec![format!("go where {:?} was due", want.verdict)]
                } else {
                    Vec::new()
                }
            } else {
                compare(&want, if noisy { &tol.1 } else { &tol.0 }, v)
            };
            if all {
                println!(
                    "#{i} noisy={noisy} {:?} hazards={:?} feature={:?} tilt={:?} seen_to={:?}",
                    v.decision, v.hazards, v.feature, v.tilt, v.seen_to_m
                );
            }
            if want_too {
                println!("want #{i} noisy={noisy} {want:?}");
            }
            total += 1;
            if v.decision == Decision::Go && want.verdict != Decision::Go {
                false_go += 1;
            }
            if let (Ok(dir), true) = (std::env::var("DUMP"), all || !fails.is_empty()) {
                dump(std::path::Path::new(&dir), i, &terrain, &config);
            }
            if !fails.is_empty() {
                failures += 1;
                println!(
                    "FAIL #{i} noisy={noisy} {:?} mount={:?} cam={}x{}: {fails:?} hazards={:?} feature={:?}",
                    terrain.elements, config.mount, config.camera.width, config.camera.height, v.hazards, v.feature
                );
                for r in triage_reliefs(&terrain, v.decision, want.verdict) {
                    println!("RELIEF #{i} noisy={noisy} {r}");
                }
            }
        }
    }
    println!(
        "{} passed, {failures} failed, {false_go} false go",
        total - failures
    );
    if exact {
        println!("{not_drawn} scenes not drawn (not made of planes and rocks)");
    }
    if mode == "oblique" || FAMILY_MODES.contains(&mode) {
        println!(
            "{} frames met a surface under {GRAZING_DEG}° (any verdict passes), {} of them not go",
            excused.0, excused.1
        );
    }
}

/// The modes that draw `sim::families`' scenes: as drawn, restyled, with sloping
/// band sides, with bands wider than the track.
const FAMILY_MODES: [&str; 4] = ["families", "natural", "bevelled", "widened"];

/// Whether scene `terrain` of `mode`, expected `want` on `config`'s rig, is excused: a
/// climbable surface the camera meets at grazing incidence somewhere in the tracks (a
/// descent as steep as the line of sight to it) is not seen there, so any verdict
/// passes, and go is the analysis' inference. In `families`, `natural` and
/// `bevelled` (and `widened`), for a scene due go, judged on its planes alone (the far flanks of rough
/// ground's bumps and of stones face away from the camera too, and excuse nothing).
fn unseen_at_grazing(mode: &str, want: &Expectation, terrain: &Terrain, config: &Config) -> bool {
    match mode {
        "oblique" => grazing(terrain, config),
        m if FAMILY_MODES.contains(&m) && want.verdict == Decision::Go => {
            grazing(&planes_of(terrain), config)
        }
        _ => false,
    }
}

/// [`reliefs`] for a failed frame that decided `got` where `want` was due: for a false
/// go the stones that should have stopped it (12 cm or higher); for a false stop
/// every stone, any of which may stand over a wheel radius above the dip before it;
/// otherwise none.
fn triage_reliefs(terrain: &Terrain, got: Decision, want: Decision) -> Vec<String> {
    match (got, want) {
        (Decision::Go, w) if w != Decision::Go => reliefs(terrain, 0.12),
        (Decision::Stop, Decision::Go) => reliefs(terrain, 0.0),
        _ => Vec::new(),
    }
}

/// For a false go's or a false stop's triage: each stone and rock of `terrain` drawn
/// `least_m` high or higher (metres), with how high its apex stands over the ground
/// the wheel comes from, sampled from the height field (a hand calculation, not the
/// analysis): its apex, and the mean over the 0.3 m before its foot along x. Rough
/// ground dips under some stones, and a stone drawn 15 cm high then stands a wheel
/// radius or little more over that ground; one drawn 9 cm high on a bump past a dip
/// may stand more.
fn reliefs(terrain: &Terrain, least_m: f64) -> Vec<String> {
    terrain
        .elements
        .iter()
        .filter_map(|e| match *e {
            Element::Stone {
                x_m,
                y_m,
                radius_m,
                height_m,
                ..
            }
            | Element::Rock {
                x_m,
                y_m,
                radius_m,
                height_m,
            } if height_m >= least_m => {
                let apex = terrain.height(x_m, y_m);
                let before = (0..7)
                    .map(|k| terrain.height(x_m - radius_m - 0.05 * f64::from(k), y_m))
                    .sum::<f64>()
                    / 7.0;
                Some(format!(
                    "drawn {height_m:.3} m at ({x_m:.2}, {y_m:.2}): apex {apex:.3} m, {:.3} m over the ground before it",
                    apex - before
                ))
            }
            _ => None,
        })
        .collect()
}

/// Write scene `i`'s terrain (`i.json`, for `cells`) and configuration (`i.toml`)
/// into `dir`.
fn dump(dir: &std::path::Path, i: usize, terrain: &Terrain, config: &Config) {
    std::fs::create_dir_all(dir).expect("DUMP is a writable directory");
    let json = serde_json::to_string(&terrain.elements).expect("terrain serialises");
    std::fs::write(dir.join(format!("{i}.json")), json).expect("DUMP writable");
    let toml = toml::to_string(&config).expect("configuration serialises");
    std::fs::write(dir.join(format!("{i}.toml")), toml).expect("DUMP writable");
}

/// Whether the camera meets `terrain`'s surface under the tracks somewhere at under
/// [`GRAZING_DEG`] ([`families::least_incidence_deg`], a hand calculation).
fn grazing(terrain: &Terrain, config: &Config) -> bool {
    families::least_incidence_deg(terrain, config) < f64::from(GRAZING_DEG)
}

/// `terrain`'s planar elements alone (ramps, steps, blocks, drop-offs): without its
/// rough ground and its stones, and with each band's sloping sides drawn vertical
/// again (`Extent::Bevelled` as the `Extent::Band` it was drawn from). A bevel's
/// outer side falls away from the camera as steeply as a wall and lies 1-7 cm inside
/// the track: judged on it, every bevelled one-track ramp and every pair of ramps
/// was excused (`bevelled 100 901 default 9`: 200 of 200 frames), and their false
/// stops went uncounted. The ground the tracks drive on is the band's own.
fn planes_of(terrain: &Terrain) -> Terrain {
    Terrain::new(
        terrain
            .elements
            .iter()
            .filter(|e| {
                !matches!(
                    e,
                    Element::Rough { .. }
                        | Element::Lumpy { .. }
                        | Element::Rock { .. }
                        | Element::Stone { .. }
                )
            })
            .cloned()
            .map(|mut e| {
                if let Element::Ramp { extent, .. } | Element::Step { extent, .. } = &mut e {
                    *extent = extent.sharp();
                }
                e
            })
            .collect(),
    )
}

/// Scene `i` of `mode`: its terrain, expectation, configuration and tolerances
/// (clean, noisy).
fn draw(
    rng: &mut ChaCha8Rng,
    mode: &str,
    i: usize,
    random_rig: bool,
    family: Option<usize>,
) -> (Terrain, Expectation, Config, (Tolerance, Tolerance)) {
    let tol = (CLEAN, NOISY);
    match mode {
        // On random rigs (`edges` and `oblique` always, `hazards` when asked), each
        // scene where its rig sees both tracks.
        "edges" | "oblique" | "hazards" if random_rig || mode != "hazards" => {
            let rig = families::Rig::random(rng);
            let at = families::judged_span(&rig.config);
            let (t, w) = match mode {
                "hazards" => random::hazard_scene_within(rng, i, at),
                // Impassable edges the hazard sweep does not draw.
                "edges" => random::edge_scene_within(rng, i, at),
                // Climbable ramps up and down met obliquely.
                _ => random::oblique_scene_within(rng, at),
            };
            (t, w, rig.config, tol)
        }
        "hazards" => {
            let (t, w) = random::hazard_scene(rng, i);
            (t, w, Config::default(), tol)
        }
        m if FAMILY_MODES.contains(&m) => {
            let rig = if random_rig {
                families::Rig::random(rng)
            } else {
                families::Rig::default_rig()
            };
            let fam = match family {
                Some(k) => families::Family::by_index(k).expect("a family index"),
                None => families::Family::ALL[i % families::Family::ALL.len()],
            };
            let mut d = families::draw(rng, fam, rig);
            type Restyle = fn(&mut ChaCha8Rng, families::Draw) -> families::Draw;
            let restyle: Option<(u64, Restyle)> = match mode {
                "natural" => Some((1, families::restyled)),
                "bevelled" => Some((2, families::bevelled)),
                "widened" => Some((3, families::widened)),
                _ => None,
            };
            if let Some((stream, restyle)) = restyle {
                // Its own stream, so the scenes are `families`' scenes, drawn anew.
                let mut style = rng.clone();
                style.set_stream(stream);
                d = restyle(&mut style, d);
            }
            (d.terrain, d.expect, d.rig.config, d.tolerance)
        }
        _ => {
            let (t, w) = random::workcase_scene(rng, i);
            (t, w, Config::default(), tol)
        }
    }
}
