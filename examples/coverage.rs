//! What a mount sees of the corridor (`rover_terrain::coverage`).
//!
//! `cargo run --release --example coverage -- CONFIG.toml` prints a config's coverage,
//! as `check-config` does; `-- random N SEED` draws N random rigs from the issue's
//! ranges (`sim::families::Rig::random`, seeded) and counts those that leave a wheel
//! track's strip never seen whole, with each one's mount.

use rand::SeedableRng;
use rover_terrain::coverage::Coverage;
use rover_terrain::sim::families::Rig;
use rover_terrain::{Config, Side};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.as_slice() {
        [random, n, seed] if random == "random" => {
            let (n, seed): (usize, u64) = (n.parse()?, seed.parse()?);
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            let mut uncovered = 0;
            for i in 0..n {
                let config = Rig::random(&mut rng).config;
                let coverage = Coverage::for_rover(&config);
                let never: Vec<String> = coverage
                    .never_whole()
                    .filter(|s| s.band != Side::Centre)
                    .map(|s| format!("{:+.3}", s.y_m))
                    .collect();
                if !never.is_empty() {
                    uncovered += 1;
                    let (m, c) = (&config.mount, &config.camera);
                    println!(
                        "#{i}: y = {} m never whole; {}x{} {:.1}°, mount {:.2} m high, roll {:.1}°, pitch {:.1}°, yaw {:.1}°",
                        never.join(", "),
                        c.width,
                        c.height,
                        c.hfov_deg,
                        m.z_m,
                        m.roll_deg,
                        m.pitch_deg,
                        m.yaw_deg
                    );
                }
            }
            println!("{uncovered} of {n} rigs leave a track strip never seen whole");
        }
        [path] => {
            let config = Config::load(std::path::Path::new(path))?;
            print!("{}", Coverage::for_rover(&config).report());
        }
        _ => anyhow::bail!("usage: coverage CONFIG.toml | coverage random N SEED"),
    }
    Ok(())
}
