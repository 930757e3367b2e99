//! After warm-up, processing a frame allocates nothing on the heap: a counting global
//! allocator watches 100 frames of varied terrain (mixed pixels at a rock's edges
//! among them), each analysed and written out as a JSON line (the README's stdout
//! link).

use std::sync::atomic::Ordering;

use rover_terrain::link::{wire, JsonLines, Transport};
use rover_terrain::sim::{self, Element, Extent, KinectNoise, Terrain};
use rover_terrain::{Config, Pipeline};

#[path = "common/counting.rs"]
mod counting;
use counting::{Counting, ALLOCATIONS, COUNTING};

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn processing_allocates_nothing_after_warm_up() {
    let mut config = Config::default();
    // The camera's range ends 2.77 m out on flat ground, inside the corridor: the
    // cells where the ground leaves it are marked as the view's end in every frame.
    config.camera.max_range_m = 2.8;
    let ramp = |toe_x_m, gradient_deg, alpha_deg, extent| Element::Ramp {
        toe_x_m,
        ref_y_m: 0.0,
        gradient_deg,
        alpha_deg,
        extent,
        cap_m: None,
        round_m: None,
    };
    let scenes = [
        Terrain::flat(),
        Terrain::new(vec![ramp(0.9, 20.0, 0.0, Extent::Full)]),
        Terrain::new(vec![ramp(1.0, 18.0, -20.0, Extent::Left)]),
        Terrain::new(vec![ramp(1.2, -12.0, 0.0, Extent::Right)]),
        Terrain::new(vec![ramp(1.1, 36.0, 0.0, Extent::Full)]),
        Terrain::new(vec![Element::Step {
            x_m: 1.4,
            height_m: 0.15,
            extent: Extent::Full,
        }]),
        Terrain::new(vec![Element::Rock {
            x_m: 1.3,
            y_m: 0.0,
            radius_m: 0.2,
            height_m: 0.4,
        }]),
        Terrain::new(vec![Element::DropOff {
            x_m: 1.5,
            depth_m: 1.0,
        }]),
        // A diagonal ramp under the left track whose sides slope over 13 cm: the face
        // fit leaves out the two edge strips that stand a share of its height low.
        Terrain::new(vec![ramp(
            1.0,
            18.0,
            20.0,
            Extent::Bevelled {
                from_m: 0.2,
                to_m: 0.7,
                side_m: 0.13,
            },
        )]),
    ];
    let mut frames: Vec<_> = scenes.iter().map(|t| sim::render(t, &config)).collect();
    let mut noisy = frames[1].clone();
    KinectNoise::default().apply(&mut noisy, config.camera.hfov_deg);
    frames.push(noisy);
    // A rock's edges with mixed pixels: the filter's exact test runs on them.
    let mut flying = frames[6].clone();
    sim::FlyingPixels::default().apply(&mut flying);
    frames.push(flying);
    let (w, h) = (frames[0].width(), frames[0].height());
    frames.push(rover_terrain_drivers::DepthFrame::from_pixels(
        w,
        h,
        vec![0; w * h],
    ));

    let mut pipeline = Pipeline::new(config).unwrap();
    // The JSON-lines link writes into memory reserved up front, as stdout's buffer is.
    let mut link = JsonLines::to_writer(Vec::with_capacity(256 * 1024), "memory");
    // Warm-up: one pass over every kind of frame.
    let mut decisions = Vec::new();
    let mut expected = Vec::new();
    for f in &frames {
        let v = pipeline.process(f).unwrap();
        decisions.push(v.decision);
        expected.push(wire::verdict_json(&wire::to_wire(v, 0.0)));
    }
    // The frames really differ: not every verdict is the same.
    decisions.dedup();
    assert!(decisions.len() >= 3, "{decisions:?}");

    ALLOCATIONS.store(0, Ordering::SeqCst);
    COUNTING.store(true, Ordering::SeqCst);
    let mut go = 0;
    for i in 0..100 {
        let v = pipeline.process(&frames[i % frames.len()]).unwrap();
        go += usize::from(v.traversable());
        link.send_verdict(&wire::to_wire(v, 0.0)).unwrap();
    }
    COUNTING.store(false, Ordering::SeqCst);
    assert_eq!(
        ALLOCATIONS.load(Ordering::SeqCst),
        0,
        "heap allocations while processing"
    );
    assert!(go > 0 && go < 100);

    // With the terrain memory fusing every frame over odometry, and falling back now
    // and then, nothing allocates either.
    let motion = rover_terrain::memory::Motion {
        forward_m: 0.03,
        dheading_rad: 0.01,
        dt_s: 0.033,
        ..Default::default()
    };
    let _ = pipeline.process_moved(&frames[0], Ok(motion)).unwrap();
    ALLOCATIONS.store(0, Ordering::SeqCst);
    COUNTING.store(true, Ordering::SeqCst);
    let mut fused = 0;
    for i in 0..100 {
        let m = if i % 17 == 16 {
            Err(rover_terrain::memory::odometry::Untrusted::Jump)
        } else {
            Ok(motion)
        };
        let v = pipeline
            .process_moved(&frames[i % frames.len()], m)
            .unwrap();
        fused += usize::from(v.memory.remembered_cells > 0);
    }
    COUNTING.store(false, Ordering::SeqCst);
    assert_eq!(
        ALLOCATIONS.load(Ordering::SeqCst),
        0,
        "heap allocations with the memory"
    );
    assert!(fused > 50, "the memory was used: {fused}");

    // The lines written are the verdicts, in order (sequence numbers aside: the
    // pipeline counts frames on).
    let text = String::from_utf8(link.into_inner()).unwrap();
    let lines: Vec<_> = text.lines().collect();
    assert_eq!(lines.len(), 100);
    for (i, line) in lines.iter().enumerate() {
        let mut got: serde_json::Value = serde_json::from_str(line).unwrap();
        let mut want = expected[i % frames.len()].clone();
        got["seq"] = 0.into();
        want["seq"] = 0.into();
        assert_eq!(got, want, "line {i}");
    }
}
