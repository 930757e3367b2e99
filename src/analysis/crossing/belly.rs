//! The belly band: anything taller than the belly clearance over the tracks beside it,
//! and the tracks' height per row it is measured against.

use super::{line_fit, Frame, Region, FRONT_RISING_M, ROUGH_LINE_RMS_M, ROUGH_SPREAD_M};
use crate::verdict::{Hazard, HazardKind, Verdict};

/// Anything under the belly taller than the belly clearance above the line between
/// the two wheel tracks at the same distance ([`belly_underside`]; each track's height the
/// median height of its cells seen whole in that row; a row with none borrows the
/// nearest row within 3 cells, else the other track's or the ground plane z = 0,
/// unless the track there is past the sensor's horizon: then the row is beyond view
/// and not judged). A cell the image's top edge cuts
/// holds only what lies below the edge: a ramp rising out of view left in one such
/// track cell a few centimetres of its side face, and that "track height" put the
/// ramp's side in the belly band 40 cm above it (`sweep -- families 100 5501 random`
/// #55 noisy). A belly cell beside a track is also measured against that track cell's
/// upper surface: a face along the band edge is the side of what stands in the track.
/// A belly cell off the band's edges that the image's top edge cuts, already more
/// than a wheel radius above the tracks beside it (which are seen), is an obstacle
/// whose top is not seen: unknown ground there, whatever its bound, unless the cell
/// shows that top levelling off ([`belly_top_seen`]).
pub fn belly(f: &Frame, values: &mut Vec<f32>, track_ref: &mut [[f32; 2]], verdict: &mut Verdict) {
    let clearance = f.cfg.rover.belly_clearance_m as f32;
    let r = f.cfg.rover.wheel_radius_m as f32;
    let s = f.spec;
    track_medians(f, values, track_ref, |c| {
        f.seen_whole(c).then(|| f.cells[c].z)
    });
    let tc = f.cfg.rover.track_centre_m() as f32;
    for ix in 0..s.nx {
        let mut wheels = [None; 2];
        let mut beyond_view = false;
        for (k, region) in [Region::Left, Region::Right].into_iter().enumerate() {
            wheels[k] = (0..=3usize)
                .flat_map(|d| [ix.checked_sub(d), Some(ix + d)])
                .flatten()
                .filter_map(|j| track_ref.get(j).map(|r| r[k]))
                .find(|v| !v.is_nan());
            // No track data near this row because the track is past the horizon:
            // how high the wheels stand here is not known.
            beyond_view |= wheels[k].is_none() && f.strips(region).any(|iy| f.past[s.cell(ix, iy)]);
        }
        if beyond_view {
            continue;
        }
        let higher = higher_track(wheels);
        // The belly band's own lowest ground in the row, seen whole (see
        // `belly_underside`).
        let floor = f
            .strips(Region::Belly)
            .map(|iy| s.cell(ix, iy))
            .filter(|&c| f.seen_whole(c))
            .map(|c| f.cells[c].z)
            .reduce(f32::min)
            .unwrap_or(f32::NEG_INFINITY);
        for iy in f.strips(Region::Belly) {
            let c = s.cell(ix, iy);
            if !f.seen[c] {
                continue;
            }
            // Beside a track, the band's edge cells hold the side face of whatever
            // stands in the track: it is as high as the track there, not under the belly.
            // A track cell the image's top edge cuts (or past the horizon) is at least
            // as high as its top (a ramp rising out of view: its upper surface there is
            // only partly seen). A face on the band's edge line splits its points
            // between the two strips as they fall, so that one row's track cell may
            // hold only its foot: the track cells of the rows before and after count
            // too (a coarse camera's rows meet the face every other cell).
            let beside = [iy.checked_sub(1), Some(iy + 1)]
                .into_iter()
                .flatten()
                .filter(|&j| j < s.ny && f.region[j] != Region::Belly)
                .flat_map(|j| (ix.saturating_sub(1)..(ix + 2).min(s.nx)).map(move |i| s.cell(i, j)))
                .filter(|&j| f.seen[j])
                .map(|j| {
                    let cell = &f.cells[j];
                    if f.past[j] {
                        cell.top.max(cell.crest)
                    } else {
                        cell.crest
                    }
                })
                .fold(f32::NEG_INFINITY, f32::max);
            let top = f.cells[c].top;
            let (rigid, underside) = belly_underside(wheels, tc, s.y_centre(iy), floor, clearance);
            let edge = || {
                [iy.checked_sub(1), Some(iy + 1)]
                    .into_iter()
                    .any(|j| j.is_none_or(|j| j >= s.ny || f.region[j] != Region::Belly))
            };
            // The band's own ground (its upper surface) meets the rolled body itself:
            // one track far down beside it (see `belly_underside`).
            let kind = if top > underside.max(beside + clearance) || f.cells[c].crest > rigid {
                Some(HazardKind::Belly)
            } else if f.past[c]
                && top - beside.max(higher) > r
                && !edge()
                && !on_track_surface(f, ix, iy, r)
                && !belly_top_seen(f, ix, iy, beside.max(higher) + r)
            {
                // Rising out of the image more than a wheel radius above the higher
                // of the tracks beside it, which are seen: an obstacle whose top is
                // not seen. How tall it is, is not known. (An edge cell may hold the
                // side of a ramp under the track beside it, rising out of view with
                // it; a ramp drawn wider than the track reaches into the band, its
                // part there under the line between the tracks by a third of its
                // height, and rises out of view with the track.)
                Some(HazardKind::Unknown)
            } else {
                None
            };
            if let Some(kind) = kind {
                verdict.add_hazard(Hazard {
                    kind,
                    side: Region::Belly.side(),
                    distance_m: s.origin[0] + ix as f32 * s.voxel_m,
                });
            }
        }
    }
}

/// The higher of the two wheel tracks' heights `[left, right]` (metres), the one
/// known, or the ground plane (z = 0) where neither is.
fn higher_track(wheels: [Option<f32>; 2]) -> f32 {
    wheels.into_iter().flatten().reduce(f32::max).unwrap_or(0.0)
}

/// Where the belly's underside rests, less its clearance, over strip centre `y`
/// (metres left), and by how much its clearance grows measured upright (the secant
/// of the body's roll): on the line between the two wheel tracks' heights `[left,
/// right]` at their centre lines (±`tc`), as the rigid body rolls when one track
/// stands higher than the other; one track's height where the other's is not known,
/// and the ground plane (z = 0) where neither is, level.
fn belly_line(wheels: [Option<f32>; 2], tc: f32, y: f32) -> (f32, f32) {
    match wheels {
        [Some(left), Some(right)] => {
            let slope = (left - right) / (2.0 * tc);
            (right + slope * (y + tc), slope.hypot(1.0))
        }
        [Some(v), None] | [None, Some(v)] => (v, 1.0),
        [None, None] => (0.0, 1.0),
    }
}

/// Where the belly's underside passes over strip centre `y` (metres left), metres,
/// as `(rigid, obstacles)`. `rigid` is the rigid body's:
/// [`belly_line`] plus the clearance upright to it (the secant of the roll), never
/// higher than the higher track plus the clearance (the rule before the line: this
/// one only ever stops more). `obstacles`, what an obstacle standing on the belly
/// band's ground is measured against, is `rigid` raised to the lower of the band's own
/// lowest ground in the row (`floor`, seen whole) and the higher track, plus the
/// clearance, where that lies higher.
///
/// Measured from the higher track alone, a 0.5 m block from 15 cm right of the centre
/// line to 5 cm left of it passed under a body whose left track climbed a ramp 0.27 m
/// high beside it: the belly passes 0.42 m up over the block's right edge, not 0.59 m.
/// The floor: ground falling away beyond one track's inner edge rolls the body, and
/// the line between the tracks passes under the flat ground the band lies on, which
/// is no obstacle standing under the belly (unless it stands above both tracks, as a
/// ridge between two trenches: then the tracks' height holds). That ground itself
/// meets the rolled body once its surface stands over `rigid`: on the default rover
/// when the lower track is some 0.5 m down, a 30-35° roll (`sweep -- oblique 100 4603
/// random` #13, an 18.9° descent under the right track, 0.64 m down 2.98 m out, was a
/// go). The paper's workcases 9 and 10, ground falling away at 10-15° from 1 m or
/// farther, stay within it over the 3 m corridor.
fn belly_underside(
    wheels: [Option<f32>; 2],
    tc: f32,
    y: f32,
    floor: f32,
    clearance: f32,
) -> (f32, f32) {
    let higher = higher_track(wheels);
    let (line, secant) = belly_line(wheels, tc, y);
    let rigid = (line + clearance * secant).min(higher + clearance);
    (rigid, rigid.max(floor.min(higher) + clearance))
}

/// Whether belly cell (`ix`, `iy`), past the horizon, lies on the surface of the wheel
/// track on its side carried across: that track's cells seen in row `ix` (below the
/// horizon, at least [`CROSS_MIN_CELLS`]) lie on one line across the strips (within
/// rough ground's spread, [`ROUGH_LINE_RMS_M`]), and the cell's top stands no more
/// than a wheel radius `r` above that line carried to its centre. A ramp under one
/// side met diagonally rises across the corridor as well as along it: where it
/// covers the belly band's half too, the band's cells stand above the track's middle
/// by its cross slope (a 24° ramp over y ≥ 0 whose toe line runs at −35° to the axle
/// rose 11 cm from the track's middle to the corridor's centre line, and was an
/// obstacle whose top is not seen: `sweep -- workcases 60 6609` #18, #26). The
/// surface the rover climbs rising out of view is not one.
fn on_track_surface(f: &Frame, ix: usize, iy: usize, r: f32) -> bool {
    let s = f.spec;
    let y = s.y_centre(iy);
    let side = if y >= 0.0 {
        Region::Left
    } else {
        Region::Right
    };
    let across = || {
        (0..s.ny)
            .filter(move |&j| f.region[j] == side)
            .map(move |j| (j, s.cell(ix, j)))
            .filter(|&(_, c)| f.seen_whole(c))
            .map(|(j, c)| (s.y_centre(j), f.cells[c].z))
    };
    if across().count() < CROSS_MIN_CELLS {
        return false;
    }
    line_fit(across()).is_some_and(|(p, rms)| {
        rms <= f64::from(ROUGH_LINE_RMS_M)
            && f64::from(f.cells[s.cell(ix, iy)].top) <= p.z(f64::from(y), 0.0) + f64::from(r)
    })
}

/// Whether what stands in belly cell (`ix`, `iy`), past the horizon, shows its top
/// levelling off before the view ends: nothing in the cell rises (its points span
/// rough ground's spread at most, [`ROUGH_SPREAD_M`], or none stands
/// [`FRONT_RISING_M`] over the highest point of the strip's last cell seen whole
/// before it, one or two cells back, as on a rounded top's shoulder, which falls away
/// across the cell), its top stands less than [`FRONT_RISING_M`] over that cell's top
/// or the strip's next cell, seen, stands no higher (the top no longer rises where the
/// view ends), and one of the
/// two cells seen whole before that one holds ground no higher than `ground` (metres:
/// a wheel radius over the tracks beside it), so that the front from the ground to
/// the top is seen. The top is then seen: the belly test measures it against the
/// clearance, and what lies past the view's end is beyond view, as anywhere else.
///
/// A 25 cm boulder under the belly 1.6 m out, whose level top the image's top edge
/// cut 4-8 cm past where it was first seen whole, was `unknown` (`sweep -- natural
/// 100 12213 random 8` #12, a 320×240 camera 0.73 m high pitched 39°); so was a
/// 26.4 cm one whose shoulder's cut cell spans 1.8 cm (`natural 100 12313 random 8`
/// #38); so was a 17.2 cm rock whose first cut cell's top stood 1.04 cm over the cell
/// before it and the next cut cell's lower (`families 100 12909 random 11` #68,
/// clean). A wall or a block whose face the view ends on holds the face in the cut
/// cell (its points span more than the spread and rise over the cell before), or
/// ground in the cell before it (the cut cell's top stands far over it). A gentle
/// ramp under the belly rising out of view a little over a wheel radius high may
/// pass: what it does past the cut is beyond view, as under the tracks.
pub(super) fn belly_top_seen(f: &Frame, ix: usize, iy: usize, ground: f32) -> bool {
    let s = f.spec;
    let whole = |i: usize| {
        let c = s.cell(i, iy);
        f.seen_whole(c).then_some(&f.cells[c])
    };
    let before = |i: usize| (1..=2).filter_map(move |d| i.checked_sub(d));
    let cut = &f.cells[s.cell(ix, iy)];
    let Some((i, last)) = before(ix).find_map(|i| whole(i).map(|c| (i, c))) else {
        return false;
    };
    // The strip's next cell, seen, no higher: the top levelled off there.
    let next_lower = ix + 1 < s.nx && {
        let c = s.cell(ix + 1, iy);
        f.seen[c] && f.cells[c].top <= cut.top
    };
    (cut.peak - cut.low <= ROUGH_SPREAD_M || cut.peak < last.peak + FRONT_RISING_M)
        && (cut.top < last.top + FRONT_RISING_M || next_lower)
        && before(i).filter_map(whole).any(|c| c.low <= ground)
}

/// Fewest seen cells of a track's row for [`on_track_surface`] to carry its line.
const CROSS_MIN_CELLS: usize = 4;

/// Per cell row, each track's median height, `[left, right]`: the median over the
/// track's strips of `height(cell)` where it is `Some` (NaN where none is).
pub(crate) fn track_medians(
    f: &Frame,
    values: &mut Vec<f32>,
    out: &mut [[f32; 2]],
    height: impl Fn(usize) -> Option<f32>,
) {
    for (ix, row) in out.iter_mut().enumerate() {
        for (k, region) in [Region::Left, Region::Right].into_iter().enumerate() {
            values.clear();
            values.extend(
                f.strips(region)
                    .filter_map(|iy| height(f.spec.cell(ix, iy))),
            );
            row[k] = median(values);
        }
    }
}

/// The median of `values` (reordered in place: a selection, not a sort; it runs
/// for every row of both tracks); NaN when empty.
pub(crate) fn median(values: &mut [f32]) -> f32 {
    let n = values.len();
    if n == 0 {
        return f32::NAN;
    }
    let (below, &mut mid, _) = values.select_nth_unstable_by(n / 2, f32::total_cmp);
    if n % 2 == 1 {
        mid
    } else {
        // The other middle value is the largest below it.
        let lower = below.iter().copied().max_by(f32::total_cmp).unwrap_or(mid);
        0.5 * (lower + mid)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_belly_passes_over_the_line_or_the_belly_band_s_floor_never_above_the_higher_track() {
        let c = 0.32;
        // By hand, the ramp of the test below: the line over y = 0.05 m is 0.15 m up,
        // the clearance upright 0.32 · √1.09; the belly band's floor at 0.
        let (rigid, u) = belly_underside([Some(0.27), Some(0.0)], 0.45, 0.05, 0.0, c);
        assert!((u - (0.15 + c * 1.09f32.sqrt())).abs() < 1e-6, "{u}");
        assert_eq!(rigid, u);
        // Ground falling away beyond the left track's inner edge, 0.5 m down: the line
        // passes under the belly band's flat ground, which holds the belly at its
        // clearance over it for what stands on that ground. Over y = 0.15 m the line
        // stands 0.5 · 0.6 / 0.9 = 0.333 m down, the clearance upright 0.32 · √(1 +
        // (0.5 / 0.9)²) = 0.366 m: the rigid body passes 3.3 cm over the ground there.
        let (rigid, u) = belly_underside([Some(-0.5), Some(0.0)], 0.45, 0.15, 0.0, c);
        assert!((u - c).abs() < 1e-6, "{u}");
        let by_hand = -0.5 * 0.6 / 0.9 + c * (1.0f32 + (0.5f32 / 0.9).powi(2)).sqrt();
        assert!(
            (rigid - by_hand).abs() < 1e-6 && rigid > 0.0,
            "{rigid} {by_hand}"
        );
        // 0.7 m down, a 38° roll: 0.467 m down, 0.32 · 1.27 up, under the ground.
        let (rigid, _) = belly_underside([Some(-0.7), Some(0.0)], 0.45, 0.15, 0.0, c);
        assert!(rigid < -0.05, "{rigid}");
        // A ridge between two trenches 0.2 m deep: the tracks' height holds.
        let (rigid, u) = belly_underside([Some(-0.2), Some(-0.2)], 0.45, 0.0, 0.0, c);
        assert!((u - (c - 0.2)).abs() < 1e-6 && rigid == u, "{u}");
        // Never above the higher track plus the clearance (however steep the roll).
        for dy in [0.1f32, 0.5, 1.0, 2.0] {
            for y in [-0.2f32, 0.0, 0.2] {
                let (rigid, u) = belly_underside([Some(dy), Some(0.0)], 0.45, y, 0.0, c);
                assert!(u <= dy + c + 1e-6 && rigid <= u, "{dy} {y}: {u}");
            }
        }
    }

    #[test]
    fn the_belly_rests_on_the_line_between_the_tracks_its_clearance_upright_under_roll() {
        // By hand: tracks 0.9 m apart, the left one 0.27 m up. Over y = 0.05 m the
        // line stands 0.27 · 0.5 / 0.9 = 0.15 m up; the roll's secant is √(1 + 0.3²).
        let (line, secant) = belly_line([Some(0.27), Some(0.0)], 0.45, 0.05);
        assert!((line - 0.15).abs() < 1e-6, "{line}");
        assert!((secant - 1.09f32.sqrt()).abs() < 1e-6, "{secant}");
        // Mirrored: the right track up, over y = −0.05 m.
        let (line, _) = belly_line([Some(0.0), Some(0.27)], 0.45, -0.05);
        assert!((line - 0.15).abs() < 1e-6, "{line}");
        // Level tracks: their height, no roll.
        assert_eq!(belly_line([Some(0.04), Some(0.04)], 0.45, 0.1), (0.04, 1.0));
        // One track not known: the other's height, level; neither: the ground plane.
        assert_eq!(belly_line([None, Some(0.2)], 0.45, 0.1), (0.2, 1.0));
        assert_eq!(belly_line([None, None], 0.45, 0.1), (0.0, 1.0));
    }

    #[test]
    fn the_median_by_selection_is_the_sorted_middle() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        assert!(median(&mut []).is_nan());
        for len in 1..=14 {
            for _ in 0..50 {
                // Few distinct values, so that ties are common.
                let mut v: Vec<f32> = (0..len)
                    .map(|_| f32::from(rng.gen_range(-4i8..4)) * 0.01)
                    .collect();
                let mut sorted = v.clone();
                sorted.sort_unstable_by(f32::total_cmp);
                let n = sorted.len();
                let want = if n % 2 == 1 {
                    sorted[n / 2]
                } else {
                    0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
                };
                assert_eq!(median(&mut v), want, "{sorted:?}");
            }
        }
    }
}
