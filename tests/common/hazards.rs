//! Questions the analysis tests ask of a verdict's hazards.

use rover_terrain::{HazardKind, Side, Verdict};

/// The distance ahead (m) of `v`'s first hazard of `kind` on `side`, if it has one.
pub fn hazard(v: &Verdict, kind: HazardKind, side: Side) -> Option<f32> {
    v.hazards
        .iter()
        .find(|h| h.kind == kind && h.side == side)
        .map(|h| h.distance_m)
}
