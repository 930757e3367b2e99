//! Write the depth frame the PCL comparison uses (`benches/peers/compare.sh`): flat
//! ground as the default rig sees it (Kinect v1 FOV model, 640×480, camera 0.8 m up,
//! pitched 30°), rendered by `sim`, as a 16-bit PGM both programs read.
//!
//! `cargo run --release --example peer_frame -- OUT.pgm`

use rover_terrain::sim::{self, Terrain};
use rover_terrain::Config;
use rover_terrain_drivers::image::encode_pgm_depth;

fn main() -> std::process::ExitCode {
    let Some(out) = std::env::args().nth(1) else {
        eprintln!("usage: peer_frame OUT.pgm");
        return std::process::ExitCode::from(2);
    };
    let frame = sim::render(&Terrain::new(vec![]), &Config::default());
    if let Err(e) = std::fs::write(&out, encode_pgm_depth(&frame)) {
        eprintln!("peer_frame: {out}: {e}");
        return std::process::ExitCode::FAILURE;
    }
    std::process::ExitCode::SUCCESS
}
