//! Criterion benchmarks of the whole pipeline and its binning pass on a 640×480
//! frame (the bar's camera). Run: `cargo bench --bench pipeline`.

use criterion::{criterion_group, criterion_main, Criterion};
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

criterion_group!(benches, pipeline);
criterion_main!(benches);
