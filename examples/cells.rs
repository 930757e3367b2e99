//! Debug aid: print the ground-cell grid of one rendered scene (a JSON terrain element,
//! or an array of them, on the command line), seen cells as heights in cm (`^` where the image's top edge
//! cuts the cell), unseen expected cells as `?`. With `STRIP=IY` in the environment,
//! also every cell of strip IY: mean, top, peak, low, crest and foot heights, cut or not.
//! With `CONFIG=FILE` (a TOML configuration, as `sweep`'s `DUMP` writes one for a
//! random rig), that mount and camera instead of the default. A second argument, a
//! seed, adds Kinect noise; `FLYING=FRACTION` then mixes edge pixels too (as `sweep`).
use rover_terrain::sim::{self, Element, Terrain};
use rover_terrain::{Config, Pipeline};

fn main() {
    let arg = std::env::args()
        .nth(1)
        .expect("a terrain element (or an array of them) as JSON");
    let elements: Vec<Element> = if arg.trim_start().starts_with('[') {
        serde_json::from_str(&arg).unwrap()
    } else {
        vec![serde_json::from_str(&arg).unwrap()]
    };
    let config = match std::env::var("CONFIG") {
        Ok(path) => Config::load(std::path::Path::new(&path)).unwrap(),
        Err(_) => Config::default(),
    };
    let mut frame = sim::render(&Terrain::new(elements), &config);
    if let Some(seed) = std::env::args().nth(2).and_then(|s| s.parse().ok()) {
        sim::KinectNoise {
            seed,
            ..Default::default()
        }
        .apply(&mut frame, config.camera.hfov_deg);
        // FLYING=FRACTION: mix edge pixels too, with the same seed (as `sweep` does).
        if let Some(fraction) = std::env::var("FLYING").ok().and_then(|v| v.parse().ok()) {
            sim::FlyingPixels {
                seed,
                fraction,
                ..Default::default()
            }
            .apply(&mut frame);
        }
    }
    let mut p = Pipeline::new(config).unwrap();
    let v = p.process(&frame).unwrap().clone();
    println!("{}", v.to_json());
    let spec = *p.grid().spec();
    let exp = p.analyzer().expected();
    for ix in (0..spec.nx).rev() {
        let mut line = format!("{:5.2} ", spec.x_centre(ix));
        for iy in (0..spec.ny).rev() {
            let c = spec.cell(ix, iy);
            let cell = p.grid().cells()[c];
            let cut = p.grid().cut()[c];
            line += &if cell.n >= 3 {
                format!(
                    "{:3.0}{}",
                    cell.z * 100.0,
                    if cut {
                        "^"
                    } else if cell.n < 10 {
                        "'"
                    } else {
                        " "
                    }
                )
            } else if exp[c] {
                "   ?".into()
            } else {
                "    ".into()
            };
        }
        println!("{line}");
    }
    if let Some(iy) = std::env::var("STRIP")
        .ok()
        .and_then(|s| s.parse::<usize>().ok())
    {
        for ix in 0..spec.nx {
            let c = spec.cell(ix, iy);
            let cell = p.grid().cells()[c];
            println!(
                "ix {ix} x {:.3} y {:.3} n {} z {:.3} top {:.3} peak {:.3} low {:.3} crest {:.3} foot {:.3} \
                 crest at ({:.3}, {:.3}) foot at ({:.3}, {:.3}) top at ({:.3}, {:.3}) cut {}",
                cell.x,
                cell.y,
                cell.n,
                cell.z,
                cell.top,
                cell.peak,
                cell.low,
                cell.crest,
                cell.foot,
                cell.crest_xy[0],
                cell.crest_xy[1],
                cell.foot_xy[0],
                cell.foot_xy[1],
                cell.top_xy[0],
                cell.top_xy[1],
                p.grid().cut()[c]
            );
        }
    }
}
