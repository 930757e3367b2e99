//! Debug aid for rough ramps: scene I of `sweep -- families N SEED [default|random]
//! [FAMILY-INDEX]`, its measured toe distance and gradient against the drawn ramp's
//! and against the least-squares plane of the rendered surface itself (no sensor)
//! over the part of the face the verdict says is seen, in both wheel tracks. On rough
//! ground the drawn ramp is not what the ground is: bumps 15-20 cm long move the
//! surface's own plane by centimetres, which no plane fit can recover.
//! `cargo run --release --example surface_fit -- 30 21 default 5 5`.

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
        if i != want {
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
            return;
        };
        println!("measured: {:?}", v.feature);
        println!("drawn:    toe {toe_x_m:.4} m, gradient {gradient_deg:.2}°");
        let far = f64::from(v.seen_to_m.left.min(v.seen_to_m.right));
        let (inner, outer) = (config.rover.belly_half_width_m, config.rover.track_outer_m);
        // Least squares z = a·x + c over a 1 cm lattice of the tracks, toe to far.
        let field = d.terrain.field();
        let (mut sx, mut sz, mut sxx, mut sxz, mut m) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let (down, near) = (gradient_deg < 0.0, toe_x_m.max(0.0));
        let mut x = near;
        while x < far {
            let mut y = inner;
            while y < outer {
                for y in [y, -y] {
                    let z = field.height(x, y);
                    (sx, sz, sxx, sxz, m) = (sx + x, sz + z, sxx + x * x, sxz + x * z, m + 1.0);
                }
                y += 0.01;
            }
            x += 0.01;
        }
        if m < 3.0 {
            println!("no face seen past the toe (seen to {far:.2} m)");
            return;
        }
        let a = (m * sxz - sx * sz) / (m * sxx - sx * sx);
        let c = (sz - a * sx) / m;
        println!(
            "surface:  toe {:.4} m, gradient {:.2}° (plane of the rendered {} from {near:.2} to {far:.2} m)",
            -c / a,
            a.atan().to_degrees(),
            if down { "descent" } else { "ramp" },
        );
    }
}
