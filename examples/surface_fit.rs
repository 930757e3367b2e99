//! Debug aid for rough ramps: scene I of `sweep -- families N SEED [default|random]
//! [FAMILY-INDEX]`, its measured toe distance and gradient against the drawn ramp's
//! and against the least-squares plane of the rendered surface itself (no sensor)
//! over the part of the face the verdict says is seen, in both wheel tracks. On rough
//! ground the drawn ramp is not what the ground is: bumps 15-20 cm long move the
//! surface's own plane by centimetres, which no plane fit can recover.
//! `cargo run --release --example surface_fit -- 30 21 default 5 5`. With `all` for
//! the scene (`-- 200 4001 random 5 all`), every scene with a ramp, one line each:
//! scene, measured toe (m) and gradient (°) or `-`, the surface's, the drawn ramp's.

use rand::SeedableRng;
use rover_terrain::sim::{self, families, Element};
use rover_terrain::Pipeline;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |k: usize| args.get(k).map(String::as_str);
    let n: usize = arg(1).and_then(|s| s.parse().ok()).unwrap_or(30);
    let seed: u64 = arg(2).and_then(|s| s.parse().ok()).unwrap_or(21);
    let random = arg(3) == Some("random");
    let family: Option<usize> = arg(4).and_then(|s| s.parse().ok());
    // One scene, or every scene (`all`), one line each.
    let all = arg(5) == Some("all");
    let want: usize = arg(5).and_then(|s| s.parse().ok()).unwrap_or(0);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    for i in 0..n {
        let rig = if random {
            families::Rig::random(&mut rng)
        } else {
            families::Rig::default_rig()
        };
        let fam = match family {
            Some(k) => families::Family::ALL[k],
            None => families::Family::ALL[i % families::Family::ALL.len()],
        };
        let d = families::draw(&mut rng, fam, rig);
        if i != want && !all {
            continue;
        }
        let config = d.rig.config.clone();
        let frame = sim::render(&d.terrain, &config);
        let v = Pipeline::new(config.clone())
            .expect("the rig's config is valid")
            .process(&frame)
            .expect("a rendered frame fits")
            .clone();
        let Some(Element::Ramp {
            toe_x_m,
            gradient_deg,
            ..
        }) = d
            .terrain
            .elements
            .iter()
            .find(|e| matches!(e, Element::Ramp { .. }))
            .cloned()
        else {
            println!("scene {i} has no ramp: {:?}", d.terrain.elements);
            continue;
        };
        if !all {
            println!("measured: {:?}", v.feature);
            println!("drawn:    toe {toe_x_m:.4} m, gradient {gradient_deg:.2}°");
        }
        let far = f64::from(v.seen_to_m.left.min(v.seen_to_m.right));
        let (down, near) = (gradient_deg < 0.0, toe_x_m.max(0.0));
        let Some((surface_toe, surface_deg)) =
            families::surface_toe(&d.terrain, &config, near, far)
        else {
            println!("scene {i}: no face seen past the toe (seen to {far:.2} m)");
            continue;
        };
        if all {
            // scene, measured toe and gradient (or -), surface's, drawn.
            let measured = v.feature.and_then(|f| f.distance_m.zip(f.gradient_deg));
            let (mt, mg) = match measured {
                Some((t, g)) => (format!("{t:.4}"), format!("{g:.2}")),
                None => ("-".into(), "-".into()),
            };
            println!(
                "{i} {mt} {mg} {surface_toe:.4} {surface_deg:.2} {toe_x_m:.4} {gradient_deg:.2}"
            );
            continue;
        }
        println!(
            "surface:  toe {surface_toe:.4} m, gradient {surface_deg:.2}° (plane of the rendered {} from {near:.2} to {far:.2} m)",
            if down { "descent" } else { "ramp" },
        );
    }
}
