//! Rendered scenes for the analysis tests: a frame of the terrain through the
//! pipeline, and the default rover's wheel-track bands.

use rover_terrain::sim::{self, Element, Extent, Terrain};
use rover_terrain::{Config, Pipeline, Verdict};

/// The verdict on a clean frame of `elements`, rendered and analysed with `config`.
pub fn analyse(elements: Vec<Element>, config: &Config) -> Verdict {
    let [v] = analyse_views(elements, config, [None]);
    v
}

/// The verdict on a frame of `elements` with Kinect v1 noise drawn from `seed`.
#[allow(dead_code)] // not every test binary uses it
pub fn analyse_noisy(elements: Vec<Element>, config: &Config, seed: u64) -> Verdict {
    let [v] = analyse_views(elements, config, [Some(seed)]);
    v
}

/// The verdicts on one rendering of `elements`, once per view: clean (`None`) or
/// with Kinect v1 noise drawn from the seed. The frame is rendered once, which is
/// what a test of several views of a scene spends its time on.
pub fn analyse_views<const N: usize>(
    elements: Vec<Element>,
    config: &Config,
    views: [Option<u64>; N],
) -> [Verdict; N] {
    let clean = sim::render(&Terrain::new(elements), config);
    views.map(|view| {
        let mut frame = clean.clone();
        if let Some(seed) = view {
            sim::KinectNoise {
                seed,
                ..Default::default()
            }
            .apply(&mut frame, config.camera.hfov_deg);
        }
        Pipeline::new(config.clone())
            .unwrap()
            .process(&frame)
            .unwrap()
            .clone()
    })
}

/// The default rover's left wheel track, side faces along both its edges.
pub const LEFT_TRACK: Extent = Extent::Band {
    from_m: 0.2,
    to_m: 0.7,
};

/// The default rover's right wheel track.
#[allow(dead_code)] // not every test binary uses both
pub const RIGHT_TRACK: Extent = Extent::Band {
    from_m: -0.7,
    to_m: -0.2,
};
