//! Where the rover's belly would strike a drawn scene, by hand: from the terrain's
//! height field and the rover's size alone, never from a rendered frame or the
//! analysis. The sweeps use it where a scene drawn as climbable is not: a ramp under
//! one half of the corridor rises under the belly band too, and once its edge on the
//! centre line stands high enough over the other track's ground, the belly meets it.

use super::sight::TOP_REACH_M;
use super::terrain::Terrain;
use crate::config::Config;
use crate::verdict::{Decision, Side, Verdict};

/// How far over the underside the ground must stand (metres) for a go whose view
/// reaches it to be wrong ([`go_over_a_strike`]): the analysis reads the band in 5 cm
/// cells, and a face on the centre line lies at a cell's edge.
pub const STRIKE_MARGIN_M: f64 = 0.05;

/// Spacing of the rows and of the points across the belly band [`belly_strike`]
/// samples, metres: finer than the grid's 5 cm cells.
const SAMPLE_M: f64 = 0.01;

/// The nearest distance along x (metres, from the rover's origin up to the corridor's
/// end, rows `SAMPLE_M` (1 cm) apart) where the ground under the belly band stands more
/// than `margin_m` (metres) over the rover's underside, or `None` where it strikes
/// nowhere. The underside at a row is the analysis' rigid body: the line between the
/// two wheel tracks' centre lines at their ground's height there, raised by the belly
/// clearance upright to it (the clearance times the secant of the roll): with one
/// track on a ramp `h` high and one on level ground, `2·tc` apart, it stands over the
/// centre line at `h/2 + clearance · sqrt(1 + (h / 2tc)²)`.
///
/// Heights are the terrain's at the sampled points ([`Terrain::field`]'s): a 25 cm
/// rock under the belly on level ground never strikes a 32 cm clearance; a ramp on one
/// half of the corridor (its edge on the centre line) strikes once `h` passes 0.91 m
/// on the default rover.
pub fn belly_strike(terrain: &Terrain, config: &Config, margin_m: f64) -> Option<f64> {
    let rover = &config.rover;
    let (tc, bhw) = (rover.track_centre_m(), rover.belly_half_width_m);
    let clearance = rover.belly_clearance_m;
    let length = config.analysis.corridor_length_m;
    let rows = (length / SAMPLE_M).floor() as usize;
    let across = (2.0 * bhw / SAMPLE_M).round() as usize;
    // Prepared once: a rough field's waves, drawn again per query by
    // `Terrain::height`, are tabulated.
    let field = terrain.field();
    (0..=rows).map(|i| i as f64 * SAMPLE_M).find(|&x| {
        let (left, right) = (field.height(x, tc), field.height(x, -tc));
        let slope = (left - right) / (2.0 * tc);
        (0..=across).any(|j| {
            let y = -bhw + j as f64 * SAMPLE_M;
            let underside = right + slope * (y + tc) + clearance * slope.hypot(1.0);
            field.height(x, y) > underside + margin_m
        })
    })
}

/// Whether `v` is not go for the belly striking the ground `strike_m` (metres,
/// [`belly_strike`]) out: it is not go, has a hazard, and every hazard lies in the
/// belly band no nearer than [`TOP_REACH_M`] before the strike. Such a stop is right
/// for a scene drawn as climbable.
pub fn not_go_for_belly_strike(v: &Verdict, strike_m: f64) -> bool {
    v.decision != Decision::Go
        && !v.hazards.is_empty()
        && v.hazards
            .iter()
            .all(|h| h.side == Side::Centre && f64::from(h.distance_m) >= strike_m - TOP_REACH_M)
}

/// Whether `v` is a go whose belly band is reported seen to or past `struck_m`
/// (metres, [`belly_strike`] with [`STRIKE_MARGIN_M`]): a go over ground the belly
/// strikes within what it claims seen.
pub fn go_over_a_strike(v: &Verdict, struck_m: f64) -> bool {
    v.decision == Decision::Go && f64::from(v.seen_to_m.centre) >= struck_m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::{Element, Extent};
    use crate::verdict::{Hazard, HazardKind};

    #[test]
    fn a_strike_excuses_a_belly_stop_near_it_and_fails_a_go_that_saw_it() {
        let belly = |distance_m: f32, side: Side| Hazard {
            kind: HazardKind::Belly,
            side,
            distance_m,
        };
        let with = |hazards: &[Hazard]| {
            let mut v = Verdict {
                decision: Decision::Stop,
                ..Verdict::default()
            };
            hazards.iter().for_each(|&h| v.add_hazard(h));
            v
        };
        assert!(not_go_for_belly_strike(
            &with(&[belly(2.95, Side::Centre)]),
            2.81
        ));
        // Too near before the strike, or in a track: another obstacle's.
        assert!(!not_go_for_belly_strike(
            &with(&[belly(2.45, Side::Centre)]),
            2.81
        ));
        assert!(!not_go_for_belly_strike(
            &with(&[belly(2.95, Side::Right)]),
            2.81
        ));
        assert!(!not_go_for_belly_strike(&with(&[]), 2.81));
        let mut v = with(&[]);
        v.decision = Decision::Go;
        v.seen_to_m.centre = 3.0;
        assert!(go_over_a_strike(&v, 2.9) && !not_go_for_belly_strike(&v, 2.81));
        v.seen_to_m.centre = 2.85;
        assert!(!go_over_a_strike(&v, 2.9));
    }

    #[test]
    fn a_half_plane_ramp_strikes_where_its_edge_passes_the_rolled_underside() {
        // A 25° ramp under the right half from 0.8 m stands h = (x − 0.8) · tan 25° on
        // y ≤ 0. Over y = 0 the underside stands at h/2 + 0.32 · sqrt(1 + (h/0.9)²);
        // they meet where h²(1/4 − 0.32²/0.81) = 0.32²: h = 0.91028 m, x = 0.8 +
        // 0.91028 / 0.46631 = 2.7521 m, the first 1 cm row past it 2.76 m.
        let c = Config::default();
        let ramp = |toe: f64, g: f64, extent: Extent| {
            Terrain::new(vec![Element::ramp(toe, 0.0, g, 0.0, extent)])
        };
        let x = belly_strike(&ramp(0.8, 25.0, Extent::Right), &c, 0.0).expect("strikes");
        assert!((x - 2.76).abs() < 1e-9, "{x}");
        // Mirrored, under the left half: the same row.
        let x = belly_strike(&ramp(0.8, 25.0, Extent::Left), &c, 0.0).expect("strikes");
        assert!((x - 2.76).abs() < 1e-9, "{x}");
        // 5 cm over it: (h/2 − 0.05)² = 0.32² (1 + h²/0.81), h = 1.12388 m; at 28°
        // x = 0.8 + 1.12388 / 0.53171 = 2.9137 m, the row 2.92 m.
        let x = belly_strike(&ramp(0.8, 28.0, Extent::Right), &c, 0.05).expect("strikes");
        assert!((x - 2.92).abs() < 1e-9, "{x}");
        // From 1.0 m at 25° it stands 0.93 m at the corridor's end, struck at 2.96 m;
        // at 15° it reaches 2.0 · tan 15° = 0.536 m: no strike.
        let x = belly_strike(&ramp(1.0, 25.0, Extent::Right), &c, 0.0).expect("strikes");
        assert!((x - 2.96).abs() < 1e-9, "{x}");
        assert_eq!(belly_strike(&ramp(1.0, 15.0, Extent::Right), &c, 0.0), None);
        // Across the whole corridor it lifts both tracks alike: no strike.
        assert_eq!(belly_strike(&ramp(0.8, 25.0, Extent::Full), &c, 0.0), None);
    }

    #[test]
    fn a_rock_under_the_belly_strikes_only_over_the_clearance() {
        let c = Config::default();
        let rock = |height_m: f64| {
            Terrain::new(vec![Element::Rock {
                x_m: 1.5,
                y_m: 0.0,
                radius_m: 0.15,
                height_m,
            }])
        };
        assert_eq!(belly_strike(&rock(0.25), &c, 0.0), None);
        // A 0.38 m rock (a half-ellipsoid, radius 0.15 m) stands over 0.32 m where
        // 0.38 · sqrt(1 − (d / 0.15)²) > 0.32: d < 0.15 · sqrt(1 − (0.32/0.38)²) =
        // 0.0809 m, so from x = 1.5 − 0.0809 = 1.4191 m: the row 1.42 m.
        let x = belly_strike(&rock(0.38), &c, 0.0).expect("strikes");
        assert!((x - 1.42).abs() < 1e-9, "{x}");
    }
}
