//! Write rendered scenes as a libfreenect fakenect session (INDEX.txt, d-*.pgm raw
//! 11-bit little-endian, r-*.ppm colour, a-*.dump tilt states at the configured mount,
//! device.json), e.g. to replay through libfreenect's fakenect:
//! `cargo run --example record_scene -- OUT_DIR`.
use rover_terrain::sim::{self, Element, Extent, Terrain};
use rover_terrain::Config;
use rover_terrain_drivers::fakenect::{Registration, SessionWriter};

fn main() {
    let out = std::env::args().nth(1).expect("an output directory");
    let config = Config::default();
    let ramp = |g, a, e| Element::Ramp {
        toe_x_m: 1.0,
        ref_y_m: 0.0,
        gradient_deg: g,
        alpha_deg: a,
        extent: e,
        cap_m: None,
        round_m: None,
    };
    let scenes = [
        Terrain::flat(),
        Terrain::new(vec![ramp(15.0, 0.0, Extent::Full)]),
        Terrain::new(vec![Element::Step {
            x_m: 1.4,
            height_m: 0.2,
            extent: Extent::Full,
        }]),
    ];
    let mut w = SessionWriter::create(
        std::path::Path::new(&out),
        Some(Registration::LIBFREENECT_DEFAULT),
    )
    .expect("new session");
    for (i, t) in scenes.iter().enumerate() {
        let f = sim::render(t, &config);
        let (t, stamp) = (1_700_000_000.0 + i as f64 / 30.0, 1000 + 33 * i as u32);
        w.write_depth(&f, t, stamp).expect("frame written");
        // A colour frame to go with it (the depth, false-coloured: the scene renderer
        // has no colour), as `record` writes the RGB stream.
        let mut colour = rover_terrain_drivers::ColourFrame::default();
        let px = colour.reshape(f.width(), f.height());
        for (rgb, &mm) in px.chunks_exact_mut(3).zip(f.pixels()) {
            let v = (mm / 20).min(255) as u8;
            rgb.copy_from_slice(&[v, 255 - v, 128]);
        }
        w.write_colour(&colour, t + 0.0005, stamp)
            .expect("colour written");
        // The still Kinect's accelerometer at the configured mount, as `record`
        // snapshots it after each frame.
        let tilt = rover_terrain::level::tilt_for(config.mount.pitch_deg, config.mount.roll_deg);
        w.write_tilt(&tilt, t + 0.001, stamp).expect("tilt written");
    }
}
