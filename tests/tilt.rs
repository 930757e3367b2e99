//! The rover's predicted roll and pitch (issue 12), against hand calculations on
//! rendered ramps: reported in every verdict, a `tilt` stop only where the operator
//! set a limit.

use rover_terrain::sim::{Element, Extent};
use rover_terrain::{Config, Decision, HazardKind};

#[path = "common/scenes.rs"]
mod scenes;

use scenes::{analyse, LEFT_TRACK};

/// Centre line to centre line of the default tracks, metres.
const SPACING: f64 = 0.9;

#[test]
fn flat_ground_predicts_a_level_body() {
    let v = analyse(vec![], &Config::default());
    let t = v.tilt.expect("tracks seen");
    assert!(t.roll_deg.abs() < 0.3 && t.pitch_deg.abs() < 0.3, "{t:?}");
}

#[test]
fn a_full_width_ramp_pitches_the_body_by_its_gradient() {
    let (toe, g) = (1.0, 12.0);
    let v = analyse(
        vec![Element::ramp(toe, 0.0, g, 0.0, Extent::Full)],
        &Config::default(),
    );
    assert_eq!(v.decision, Decision::Go);
    let t = v.tilt.unwrap();
    // With both axles on the ramp the body lies along it.
    assert!((f64::from(t.pitch_deg) - g).abs() < 0.7, "{t:?}");
    assert!(f64::from(t.pitch_at_m) >= toe + 0.6 - 0.05, "{t:?}");
    assert!(t.roll_deg.abs() < 0.5, "{t:?}");
}

#[test]
fn a_ramp_under_one_track_rolls_the_body_toward_the_other_side() {
    let (toe, g) = (0.9_f64, 15.0_f64);
    let v = analyse(
        vec![Element::ramp(toe, 0.45, g, 0.0, LEFT_TRACK)],
        &Config::default(),
    );
    assert_eq!(v.decision, Decision::Go);
    let t = v.tilt.unwrap();
    // Left side up: the left track stands (x − toe)·tan g above the right one.
    let x = f64::from(t.roll_at_m);
    let hand = ((x - toe) * g.to_radians().tan())
        .atan2(SPACING)
        .to_degrees();
    assert!(t.roll_deg > 0.0, "{t:?}");
    assert!(
        (f64::from(t.roll_deg) - hand).abs() < 1.0,
        "{t:?}, hand {hand}"
    );
    assert!(
        hand > 15.0,
        "the ramp is seen far enough to roll the body: {t:?}"
    );
}

#[test]
fn limits_stop_where_the_prediction_first_passes_them() {
    let (toe, g) = (0.9_f64, 15.0_f64);
    let one_track = vec![Element::ramp(toe, 0.45, g, 0.0, LEFT_TRACK)];
    let mut c = Config::default();
    c.rover.max_roll_deg = Some(10.0);
    // Roll passes 10° where the left track is 0.9·tan 10° up.
    let at = toe + SPACING * 10f64.to_radians().tan() / g.to_radians().tan();
    assert_tilt_stop_at(one_track.clone(), &c, at);
    // A limit the terrain stays under changes nothing.
    c.rover.max_roll_deg = Some(45.0);
    assert_eq!(analyse(one_track, &c).decision, Decision::Go);

    // Pitch: the front axle on a 12° ramp, the rear still on the flat, passes 10°
    // where the front has risen wheelbase·tan 10°.
    let (toe, g) = (1.0_f64, 12.0_f64);
    let full = vec![Element::ramp(toe, 0.0, g, 0.0, Extent::Full)];
    let mut c = Config::default();
    c.rover.max_pitch_deg = Some(10.0);
    let wb = c.rover.wheelbase_m;
    let at = toe + wb * 10f64.to_radians().tan() / g.to_radians().tan();
    assert_tilt_stop_at(full.clone(), &c, at);
    c.rover.max_pitch_deg = Some(15.0);
    assert_eq!(analyse(full, &c).decision, Decision::Go);
}

/// `elements` under `config` stop for tilt first, within 0.1 m of `at` (metres).
fn assert_tilt_stop_at(elements: Vec<Element>, config: &Config, at: f64) {
    let v = analyse(elements, config);
    assert_eq!(v.decision, Decision::Stop);
    let h = v.hazards.first().unwrap();
    assert_eq!(h.kind, HazardKind::Tilt);
    assert!(
        (f64::from(h.distance_m) - at).abs() < 0.1,
        "{h:?}, hand {at}"
    );
}
