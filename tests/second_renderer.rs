//! A second renderer, written from the documented conventions alone, checks the first.
//!
//! `sim::render` marches each pixel's ray through a height field, and takes the ray
//! from the library's own `Projector`: a convention error there (a sign of roll or yaw,
//! the principal point, optical depth against range) would be drawn and analysed alike,
//! and every sweep would pass. This file shares neither: it builds each pixel's ray from
//! the README's formulas (FOV model, pinhole, URDF rpy, depth along the optical axis)
//! with its own rotations, and meets piecewise-planar terrain with vertical faces and
//! half-ellipsoid rocks exactly, by intersecting every plane, face and rock. Then:
//! - on random mounts and cameras over the issue's ranges, the two renderers agree pixel
//!   for pixel on one-track ramps, ground falling away beside a track, steps under a
//!   track and rocks;
//! - as a user would, its frames of the issue's scenes go to the real binary as 16-bit
//!   PNGs with a hand-written config, and come back go (or stop) as they should;
//! - random draws of the scene families made of planes and rocks (one-track ramps and
//!   descents, ramps out of view, ground falling away beside a track, two ramps, rocks
//!   under the belly), of pebble fields on flat ground and of impassable edges, on
//!   random rigs, drawn by it, pass their bars; so do two pebbles one behind the other
//!   in a track (go), and two rocks so (stop).
//!
//! The renderer is in `common/second_renderer.rs`.

use std::path::Path;
use std::process::Command;

use rand::{Rng, SeedableRng};
use rover_terrain::sim::{self, Element, Extent, Terrain};
use rover_terrain::{Config, Pipeline, Verdict};
use serde_json::Value;

#[path = "common/second_renderer.rs"]
mod second;
use second::{planar, rig_of, Lens, Rig};

/// The wheel track on one side: from the belly band's edge (0.2 m) to the outer
/// edge (0.7 m), mirrored on the right.
fn track(left: bool) -> Extent {
    let (from_m, to_m) = if left { (0.2, 0.7) } else { (-0.7, -0.2) };
    Extent::Band { from_m, to_m }
}

/// Everything beyond one track's inner edge.
fn beside(left: bool) -> Extent {
    let (from_m, to_m) = if left { (0.2, 100.0) } else { (-100.0, -0.2) };
    Extent::Band { from_m, to_m }
}

/// A planar face from a toe line `toe` metres ahead where y = `y0`, `gradient`
/// degrees across it (negative downhill), its left end nearer by `alpha` degrees.
fn ramp(toe: f64, y0: f64, gradient: f64, alpha: f64, extent: Extent) -> Terrain {
    Terrain::new(vec![Element::ramp(toe, y0, gradient, alpha, extent)])
}

/// A vertical step of `height` metres at `x` metres.
fn step(x_m: f64, height_m: f64, extent: Extent) -> Terrain {
    Terrain::new(vec![Element::Step {
        x_m,
        height_m,
        extent,
    }])
}

/// Flat ground with a rock under the belly, `belly` metres high, and a pebble of
/// 4-9 cm in each track, all within `at` metres ahead.
fn rocks(rng: &mut impl Rng, belly: f64, at: (f64, f64)) -> Terrain {
    let mut e = vec![Element::Rock {
        x_m: rng.gen_range(at.0..at.1),
        y_m: rng.gen_range(-0.04..0.04),
        radius_m: rng.gen_range(0.12..0.17),
        height_m: belly,
    }];
    for y in [0.45, -0.45] {
        e.push(Element::Rock {
            x_m: rng.gen_range(at.0..at.1),
            y_m: y + rng.gen_range(-0.1..0.1),
            radius_m: rng.gen_range(0.05..0.1),
            height_m: rng.gen_range(0.04..0.09),
        });
    }
    Terrain::new(e)
}

/// Flat ground with 3-6 pebbles of 4-9 cm in the tracks, `at` metres ahead.
fn pebbles(rng: &mut impl Rng, at: (f64, f64)) -> Terrain {
    let mut t = Terrain::new(Vec::new());
    for _ in 0..rng.gen_range(3..7) {
        let side = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        let y = side * rng.gen_range(0.3..0.6);
        t = with_rock(t, rng, at, y, (0.05, 0.1), (0.04, 0.09));
    }
    t
}

/// `t` with a rock of 15-20 cm in a track, `at` metres ahead.
fn boulder_among(rng: &mut impl Rng, t: Terrain, at: (f64, f64)) -> Terrain {
    let side = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
    let with = with_rock(t.clone(), rng, at, side * 0.45, (0.15, 0.2), (0.15, 0.2));
    if with.elements.len() > t.elements.len() {
        with
    } else {
        // No room among the pebbles: the rock alone.
        with_rock(
            Terrain::new(Vec::new()),
            rng,
            at,
            side * 0.45,
            (0.15, 0.2),
            (0.15, 0.2),
        )
    }
}

/// `t` with a rock of a radius and height (metres) in the ranges given, centred `y`
/// metres left and `at` metres ahead, where it touches no other rock (else `t`).
fn with_rock(
    t: Terrain,
    rng: &mut impl Rng,
    at: (f64, f64),
    y: f64,
    radius: (f64, f64),
    height: (f64, f64),
) -> Terrain {
    let (x, r, h) = (
        rng.gen_range(at.0..at.1),
        rng.gen_range(radius.0..radius.1),
        rng.gen_range(height.0..height.1),
    );
    let apart = t.elements.iter().all(|e| match *e {
        Element::Rock {
            x_m, y_m, radius_m, ..
        } => (x - x_m).hypot(y - y_m) >= r + radius_m,
        _ => true,
    });
    let mut e = t.elements;
    if apart {
        e.push(Element::Rock {
            x_m: x,
            y_m: y,
            radius_m: r,
            height_m: h,
        });
    }
    Terrain::new(e)
}

/// The second renderer's frame of a terrain it can draw.
fn exact(terrain: &Terrain, rig: &Rig) -> Vec<u16> {
    planar(terrain)
        .unwrap_or_else(|| panic!("planar terrain: {:?}", terrain.elements))
        .render(rig)
}

/// The verdict on the second renderer's frame of `terrain` as `config`'s camera sees it.
fn verdict_of(terrain: &Terrain, config: &Config) -> Verdict {
    let frame = second::frame(terrain, config)
        .unwrap_or_else(|| panic!("planar terrain: {:?}", terrain.elements));
    Pipeline::new(config.clone())
        .unwrap()
        .process(&frame)
        .unwrap()
        .clone()
}

#[test]
fn hand_cases_of_the_second_renderer() {
    // Flat ground, a camera pitched 30° at 0.8 m: the centre ray meets it 0.8/sin 30°
    // along the axis, optical depth 1.6 m.
    let rig = rig_of(&Config::default());
    let at = |t: &Terrain, rig: &Rig, u, v| planar(t).unwrap().depth_mm(rig.at, rig.ray(u, v));
    assert_eq!(at(&Terrain::flat(), &rig, 320, 240), 1600);
    // A wall 1 m ahead of a level camera: optical depth 1 m anywhere on it.
    let level = Rig {
        rpy: [0.0, 0.0, 0.0],
        ..rig
    };
    for (u, v) in [(320, 240), (0, 100), (639, 0)] {
        assert_eq!(at(&step(1.0, 2.0, Extent::Full), &level, u, v), 1000);
    }
    // A 20° ramp from 1 m: the centre ray, down 30° from 0.8 m, meets
    // z = tan 20°·(x − 1) where 0.8 − x·tan 30° = tan 20°·(x − 1).
    let (t30, t20) = (30f64.to_radians().tan(), 20f64.to_radians().tan());
    let x = (0.8 + t20) / (t30 + t20);
    let want = (x / 30f64.to_radians().cos() * 1000.0).round() as u16;
    assert_eq!(
        at(&ramp(1.0, 0.0, 20.0, 0.0, Extent::Full), &rig, 320, 240),
        want
    );
    // Yawed 10° left and looking level at a wall along y = 0.5 over x ≥ 0: the centre
    // ray meets it at x = 0.5/tan 10°, optical depth 0.5/sin 10°.
    let yawed = Rig {
        rpy: [0.0, 0.0, 10.0],
        ..rig
    };
    let wall = step(
        0.0,
        2.0,
        Extent::Band {
            from_m: 0.5,
            to_m: 9.0,
        },
    );
    let want = (0.5 / 10f64.to_radians().sin() * 1000.0).round() as u16;
    assert_eq!(at(&wall, &yawed, 320, 240), want);
    // Looking straight down from 0.8 m onto a rock 0.2 m high: its top at 0.6 m; and
    // 5 cm off its centre (radius 0.1 m) at 0.2·√(1 − 0.25) below the top's height.
    let down = Rig {
        at: [1.0, 0.0, 0.8],
        rpy: [0.0, 90.0, 0.0],
        ..rig
    };
    let rock = |x_m| {
        Terrain::new(vec![Element::Rock {
            x_m,
            y_m: 0.0,
            radius_m: 0.1,
            height_m: 0.2,
        }])
    };
    assert_eq!(at(&rock(1.0), &down, 320, 240), 600);
    let want = ((0.8 - 0.2 * 0.75f64.sqrt()) * 1000.0).round() as u16;
    assert_eq!(at(&rock(1.05), &down, 320, 240), want);
    // A 10 cm step under the left track, 1.5 m ahead: a ray that meets its top does
    // so at z = 0.1, one that meets the ground beside it at z = 0.
    let s = step(1.5, 0.1, track(true));
    let (mut top, mut beside) = (0, 0);
    for v in (0..480).step_by(20) {
        for u in (0..640).step_by(20) {
            let (d, t) = (rig.ray(u, v), f64::from(at(&s, &rig, u, v)) / 1000.0);
            let (x, y, z) = (t * d[0], t * d[1], 0.8 + t * d[2]);
            if t > 0.0 && x > 1.52 && (0.22..0.68).contains(&y) {
                assert!((z - 0.1).abs() < 0.002, "({u},{v}): {x} {y} {z}");
                top += 1;
            } else if t > 0.0 && x > 1.52 && y < 0.18 {
                assert!(z.abs() < 0.002, "({u},{v}): {x} {y} {z}");
                beside += 1;
            }
        }
    }
    assert!(top > 20 && beside > 20, "{top} {beside}");
}

#[test]
fn both_renderers_draw_the_same_frames_on_random_mounts_and_cameras() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(20_261_126);
    for i in 0..24 {
        let rig = Rig::random(&mut rng, 0.25);
        let left = rng.gen_bool(0.5);
        let s = if left { 1.0 } else { -1.0 };
        let terrain = match i % 4 {
            0 => ramp(
                rng.gen_range(0.8..1.8),
                0.45 * s,
                rng.gen_range(15.0..25.0),
                rng.gen_range(-10.0..26.0) * s,
                track(left),
            ),
            1 => ramp(
                rng.gen_range(1.0..1.6),
                0.45 * s,
                -rng.gen_range(10.0..15.0),
                0.0,
                beside(left),
            ),
            2 => step(rng.gen_range(0.8..1.8), 0.15, track(left)),
            _ => rocks(&mut rng, 0.3, (1.0, 2.0)),
        };
        let ours = sim::render(&terrain, &rig.config());
        let second = exact(&terrain, &rig);
        let off: Vec<(usize, u16, u16)> = (0..second.len())
            .filter(|&k| ours.pixels()[k].abs_diff(second[k]) > 1)
            .map(|k| (k, ours.pixels()[k], second[k]))
            .collect();
        let why = format!("{:?} on {rig:?}", terrain.elements);
        // A ray that cuts a face's corner for less than the march's 1 cm step is not
        // seen to meet it by the sim: it goes on to ground farther off, or to none.
        // That is a pixel or two a row along a face's top edge, always farther.
        assert!(
            off.iter()
                .all(|&(_, ours, exact)| ours == 0 || ours > exact),
            "{why}: the sim drew a nearer surface than there is: {off:?}"
        );
        assert!(
            off.len() * 200 <= second.len(),
            "{why}: {} of {} pixels differ, e.g. {:?}",
            off.len(),
            second.len(),
            &off[..off.len().min(5)]
        );
        let hits = second.iter().filter(|&&d| d > 0).count();
        assert!(hits * 2 > second.len(), "{why}: the ground is in view");
        // And so is what stands off it (z more than 1 cm from 0).
        let relief = (0..second.len())
            .filter(|&k| {
                let (u, v) = (k % rig.width, k / rig.width);
                let t = f64::from(second[k]) / 1000.0;
                t > 0.0 && (rig.at[2] + t * rig.ray(u, v)[2]).abs() > 0.01
            })
            .count();
        assert!(relief >= 20, "{why}: {relief} pixels off the flat");
    }
}

/// Writes `depth` as a 16-bit greyscale PNG and `rig` as a config, runs
/// `rover-terrain analyze` on them, and returns the verdict.
fn analyze(dir: &Path, name: &str, rig: &Rig, depth: &[u16]) -> Value {
    let png = dir.join(format!("{name}.png"));
    let file = std::fs::File::create(&png).unwrap();
    let mut encoder = png::Encoder::new(file, rig.width as u32, rig.height as u32);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.set_depth(png::BitDepth::Sixteen);
    let bytes: Vec<u8> = depth.iter().flat_map(|d| d.to_be_bytes()).collect();
    encoder
        .write_header()
        .unwrap()
        .write_image_data(&bytes)
        .unwrap();
    let config = dir.join(format!("{name}.toml"));
    std::fs::write(&config, rig.toml()).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rover-terrain"))
        .arg("analyze")
        .arg("--config")
        .arg(&config)
        .arg(&png)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn the_issues_scenes_drawn_by_the_second_renderer_are_go_through_the_binary() {
    let dir = tempfile::tempdir().unwrap();
    let kinect = rig_of(&Config::default());
    let low_wide = Rig {
        at: [0.1, -0.05, 0.55],
        rpy: [-6.0, 20.0, 5.0],
        ..kinect
    };
    let d435 = Rig {
        width: 848,
        height: 480,
        lens: Lens::Pinhole {
            fx: 425.0,
            fy: 427.0,
            cx: 431.0,
            cy: 236.0,
        },
        at: [0.0, 0.05, 1.0],
        rpy: [8.0, 38.0, -7.0],
        min_range: 0.3,
    };
    let kinect2 = Rig {
        width: 512,
        height: 424,
        lens: Lens::Fov {
            hfov: 70.6,
            vfov: 60.0,
        },
        at: [-0.1, 0.0, 0.9],
        rpy: [3.0, 30.0, 0.0],
        min_range: 0.5,
    };
    // (rig, terrain, workcase, toe distance (m), gradient (°))
    let cases = [
        // A 20° ramp under the left track only, rising out of the image.
        (
            kinect,
            ramp(1.2, 0.45, 20.0, 0.0, track(true)),
            3,
            1.2,
            20.0,
        ),
        (d435, ramp(1.3, 0.45, 18.0, 0.0, track(true)), 3, 1.3, 18.0),
        // Diagonal under the right track.
        (
            kinect2,
            ramp(1.1, -0.45, 22.0, 15.0, track(false)),
            6,
            1.1,
            22.0,
        ),
        // The ground beyond one track's inner edge falls away.
        (
            kinect,
            ramp(1.3, 0.45, -12.0, 0.0, beside(true)),
            9,
            1.3,
            -12.0,
        ),
        (
            low_wide,
            ramp(1.2, -0.45, -14.0, 0.0, beside(false)),
            10,
            1.2,
            -14.0,
        ),
        // Table 2 case 3 with the default mount: the toe (0.474 m) below the image.
        (
            kinect,
            ramp(0.474, 0.45, 20.0, 0.0, track(true)),
            3,
            0.474,
            20.0,
        ),
    ];
    for (i, (rig, terrain, workcase, toe, gradient)) in cases.into_iter().enumerate() {
        let v = analyze(dir.path(), &format!("go{i}"), &rig, &exact(&terrain, &rig));
        let why = format!("{:?} on {rig:?}: {v}", terrain.elements);
        assert_eq!(v["verdict"], "go", "{why}");
        assert_eq!(v["workcase"], workcase, "{why}");
        let g = v["gradient_deg"].as_f64().unwrap();
        assert!((g - gradient).abs() <= 1.5, "{why}");
        if v["toe_seen"] != false {
            let d = v["distance_m"].as_f64().unwrap();
            assert!((d - toe).abs() <= 0.04, "{why}");
        }
    }
    // And what must stop: a 35° ramp and a 15 cm step under one track, a 0.3 m drop
    // beside it.
    let stops = [
        (kinect, ramp(1.2, 0.45, 35.0, 0.0, track(true))),
        (d435, step(1.4, 0.15, track(false))),
        (kinect2, step(1.3, -0.3, beside(true))),
    ];
    for (i, (rig, terrain)) in stops.into_iter().enumerate() {
        let v = analyze(
            dir.path(),
            &format!("stop{i}"),
            &rig,
            &exact(&terrain, &rig),
        );
        assert_eq!(
            v["verdict"], "stop",
            "{:?} on {rig:?}: {v}",
            terrain.elements
        );
    }
}

#[test]
fn random_draws_of_the_issues_families_drawn_by_the_second_renderer_pass() {
    use rover_terrain::analysis::GRAZING_DEG;
    use rover_terrain::sim::families::{self, Family};
    use rover_terrain::sim::random::edge_scene_within;
    use rover_terrain::sim::Expectation;
    use rover_terrain::validate::{compare, CLEAN};
    use rover_terrain::Decision;
    // The families made of planes, vertical faces and rocks on flat ground.
    let drawn = [
        Family::OneTrackRamp,
        Family::RampOutOfView,
        Family::HalfPlaneDescent,
        Family::OneTrackDescent,
        Family::TwoRamps,
        Family::BellyRock,
    ];
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(31);
    let (mut judged, mut failed, mut grazing) = (0, Vec::new(), 0);
    for i in 0..48 {
        let rig = families::Rig::random(&mut rng);
        let span = families::judged_span(&rig.config);
        let (terrain, expect) = match i % 4 {
            // Impassable edges.
            0 => edge_scene_within(&mut rng, i, span),
            // Pebbles of 4-9 cm in the tracks on flat ground (the families draw them
            // on rough ground): go; with a rock of 15-20 cm in a track: stop.
            1 => {
                let boulder = rng.gen_bool(0.5);
                let mut t = pebbles(&mut rng, (span.start, span.end));
                if boulder {
                    t = boulder_among(&mut rng, t, (span.start, span.end));
                }
                let want = if boulder {
                    Decision::Stop
                } else {
                    Decision::Go
                };
                (t, Expectation::decision(want))
            }
            _ => {
                let d = families::draw(&mut rng, drawn[i % drawn.len()], rig.clone());
                (d.terrain, d.expect)
            }
        };
        let c = &rig.config;
        // A descent as steep as the line of sight to it gives no points: any verdict.
        let descent = terrain
            .elements
            .iter()
            .any(|e| matches!(e, Element::Ramp { gradient_deg, .. } if *gradient_deg < 0.0));
        if descent && families::least_incidence_deg(&terrain, c) < f64::from(GRAZING_DEG) {
            grazing += 1;
            continue;
        }
        let v = verdict_of(&terrain, c);
        let why = format!("#{i} {:?} on {:?}: {v:?}", terrain.elements, c.mount);
        if expect.verdict == Decision::Go {
            let fails = compare(&expect, &CLEAN, &v);
            if !fails.is_empty() {
                failed.push(format!("{why}: {fails:?}"));
            }
        } else {
            assert_ne!(v.decision, Decision::Go, "{why}");
        }
        judged += 1;
    }
    assert!(
        judged >= 40,
        "{judged} judged, {grazing} at grazing incidence"
    );
    assert!(failed.is_empty(), "{failed:#?}");
}

#[test]
fn pebbles_one_behind_another_in_a_track_are_go_and_rocks_so_are_stop() {
    use rover_terrain::sim::families;
    use rover_terrain::Decision;
    // Two stones in one track, the second 5-15 cm behind the first and beside it: the
    // track's cells rise 7-9 cm and stay up for a stone and a half, which a plane fit
    // reads as a face steeper than the rover climbs. A wheel climbs them as steps.
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(205);
    let mut not_go = Vec::new();
    for i in 0..32 {
        let rig = families::Rig::random(&mut rng);
        let c = &rig.config;
        let span = families::judged_span(c);
        let tall = i % 2 == 1;
        let (h, side) = (
            if tall { (0.15, 0.2) } else { (0.07, 0.09) },
            if rng.gen_bool(0.5) { 1.0 } else { -1.0 },
        );
        let x = rng.gen_range(span.start..(span.end - 0.3).max(span.start + 0.01));
        let (r1, r2) = (rng.gen_range(0.06..0.1), rng.gen_range(0.06..0.1));
        let y1 = side * rng.gen_range(0.35..0.55);
        let y2 = y1 - side * (r1 + r2 + 0.01);
        let dx = rng.gen_range(0.05..0.15);
        let rock =
            |x_m: f64, y_m: f64, radius_m: f64, rng: &mut rand_chacha::ChaCha8Rng| Element::Rock {
                x_m,
                y_m,
                radius_m,
                height_m: rng.gen_range(h.0..h.1),
            };
        let terrain = Terrain::new(vec![
            rock(x, y1, r1, &mut rng),
            rock(x + dx, y2, r2, &mut rng),
        ]);
        let v = verdict_of(&terrain, c);
        let why = format!("#{i} {:?} on {:?}: {v:?}", terrain.elements, c.mount);
        if tall {
            assert_ne!(v.decision, Decision::Go, "{why}");
        } else if v.decision != Decision::Go {
            not_go.push(why);
        }
    }
    assert!(not_go.is_empty(), "{not_go:#?}");
}
