//! Criterion benchmarks of the whole pipeline on a 640×480 frame (the bar's camera),
//! and of the terrain memory's per-frame work (moving the map by the odometry and
//! fusing a frame in) on its own. Run: `cargo bench --bench pipeline`.

use criterion::{criterion_group, criterion_main, Criterion};
use rover_terrain::memory::{Motion, TerrainMemory};
use rover_terrain::sim::{self, Element, Extent, KinectNoise, Terrain};
use rover_terrain::{Config, Pipeline};

fn frames() -> Vec<(&'static str, rover_terrain_drivers::DepthFrame)> {
    let config = Config::default();
    let ramp = Terrain::new(vec![Element::Ramp {
        toe_x_m: 1.0,
        ref_y_m: 0.45,
        gradient_deg: 20.0,
        alpha_deg: -26.0,
        extent: Extent::Left,
        cap_m: None,
        round_m: None,
    }]);
    let mut noisy = sim::render(&ramp, &config);
    KinectNoise::default().apply(&mut noisy, config.camera.hfov_deg);
    vec![
        ("flat", sim::render(&Terrain::flat(), &config)),
        ("diagonal_ramp", sim::render(&ramp, &config)),
        ("diagonal_ramp_noisy", noisy),
        (
            "drop_off",
            sim::render(
                &Terrain::new(vec![Element::DropOff {
                    x_m: 1.5,
                    depth_m: 1.0,
                }]),
                &config,
            ),
        ),
    ]
}

fn pipeline(c: &mut Criterion) {
    let mut group = c.benchmark_group("pipeline_640x480");
    let mut p = Pipeline::new(Config::default()).expect("default config works");
    for (name, frame) in frames() {
        group.bench_function(name, |b| {
            b.iter(|| p.process(&frame).expect("frame fits").decision)
        });
    }
    group.finish();
}

/// The memory stage on each frame's cells: the map moved by 3 cm and 0.5° (as `bench`
/// drives it), then the frame fused in, after the map has filled.
fn memory(c: &mut Criterion) {
    let mut group = c.benchmark_group("memory_640x480");
    let config = Config::default();
    let mut p = Pipeline::new(config.clone()).expect("default config works");
    let motion = Motion {
        forward_m: 0.03,
        lateral_m: 0.0,
        dheading_rad: 0.5f32.to_radians(),
        dt_s: 1.0 / 30.0,
    };
    for (name, frame) in frames() {
        p.process(&frame).expect("frame fits");
        let (cells, cut) = (p.grid().cells(), p.grid().cut());
        let expected = p.analyzer().expected();
        let mut m = TerrainMemory::new(&config, *p.grid().spec());
        for _ in 0..20 {
            m.advance(&motion);
            m.fuse(cells, expected, cut);
        }
        group.bench_function(name, |b| {
            b.iter(|| {
                m.advance(&motion);
                m.fuse(cells, expected, cut)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, pipeline, memory);
criterion_main!(benches);
