//! What one analysed frame concludes: go / stop / unknown, the hazards that decided
//! it, the obstacle feature (workcase and its measures), how much was seen.

use serde::Serialize;

/// The decision for the motor controller.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Decision {
    /// The corridor ahead can be crossed.
    Go,
    /// A hazard makes the corridor impassable.
    Stop,
    /// Too little is known to say; the controller treats it as stop.
    Unknown,
}

/// What kind of hazard was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HazardKind {
    /// A slope at or above the maximum in a wheel track.
    Slope,
    /// A step higher than the wheel radius in a wheel track.
    Step,
    /// Something taller than the belly clearance under the belly.
    Belly,
    /// The ground ends: unseen ground beyond an edge, or a fall deeper than a wheel
    /// radius.
    DropOff,
    /// Ground the camera should see but does not.
    Unknown,
    /// The rover's predicted roll or pitch passes the operator's limit
    /// (`rover.max_roll_deg`, `rover.max_pitch_deg`; off by default).
    Tilt,
}

/// Which part of the corridor a hazard is in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// The left wheel track (y > 0).
    Left,
    /// The band under the belly, or the corridor as a whole.
    Centre,
    /// The right wheel track (y < 0).
    Right,
}

/// One hazard: kind, side and forward distance from the rover origin.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Hazard {
    /// What it is.
    pub kind: HazardKind,
    /// Where it is across the corridor.
    pub side: Side,
    /// Forward distance from the rover origin to its near edge, metres. For a step
    /// or slope in a track, where the wheel meets it: up to a wheel radius before
    /// the ground's own edge.
    pub distance_m: f32,
}

/// The obstacle feature of a passable corridor (paper §3.2; definitions in docs/design.md).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Feature {
    /// 1 flat; 2 uphill; 3/5 uphill left/right only; 4/6 diagonal uphill left/right;
    /// 7 diagonal uphill full width; 8 downhill; 9/10 downhill left/right.
    pub workcase: u8,
    /// Forward distance to the toe line, metres (at the centre line, or at the centre
    /// of the affected track for one-sided cases). A face met almost side-on (a side
    /// slope), whose toe line meets that line behind the rover or past the corridor,
    /// takes the toe line's nearest point within the affected tracks instead, never
    /// under 0 (0: a track is on the face already).
    pub distance_m: Option<f32>,
    /// Steepest slope of the face across the toe line, degrees, negative downhill.
    pub gradient_deg: Option<f32>,
    /// Angle of the toe line to the lateral axis, degrees, positive when its left end
    /// is nearer.
    pub alpha_deg: Option<f32>,
    /// Whether the toe line lies where the camera sees the ground. `false` when it
    /// lies in the blind zone before the nearest seen ground: the face was seen
    /// already rising and `distance_m` is where the fitted face meets the ground, an
    /// extrapolation.
    pub toe_seen: bool,
}

impl Feature {
    /// Flat ground.
    pub const FLAT: Feature = Feature {
        workcase: 1,
        distance_m: None,
        gradient_deg: None,
        alpha_deg: None,
        toe_seen: true,
    };
}

/// How far each band of the corridor is seen (to the far edge of its last seen cell,
/// the nearest over its strips) before the sensor's horizon (where the
/// surface leaves the image, or the flat-ground view ends), metres forward.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct SeenTo {
    /// The left wheel track.
    pub left: f32,
    /// The band under the belly.
    pub centre: f32,
    /// The right wheel track.
    pub right: f32,
}

/// The rover body's predicted attitude along the corridor: the largest roll and
/// pitch it meets with its front axle anywhere on the seen ground (see
/// [`crate::analysis`]'s tilt prediction for how, and its limits).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Tilt {
    /// Largest predicted roll, degrees, positive left side up.
    pub roll_deg: f32,
    /// Front-axle distance where it is met, metres forward of the rover origin.
    pub roll_at_m: f32,
    /// Largest predicted pitch, degrees, positive nose up (climbing).
    pub pitch_deg: f32,
    /// Front-axle distance where it is met, metres forward of the rover origin.
    pub pitch_at_m: f32,
}

/// Most hazards a verdict carries: one per kind and side.
pub const MAX_HAZARDS: usize = 18;

/// Per-stage processing time of one frame, microseconds.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct StageTimes {
    /// Projection, transform and voxel binning (one fused pass over the image).
    pub bin: f32,
    /// Voxel centroids and ground cells.
    pub voxels: f32,
    /// Crossing analysis: steps, slopes, belly, gaps and drop-offs.
    pub crossing: f32,
    /// Feature analysis: workcase and measures.
    pub feature: f32,
    /// Terrain memory: moving the map by the odometry and fusing the frame in (0
    /// when the memory is off).
    pub memory: f32,
    /// The whole frame.
    pub total: f32,
}

/// Everything one frame concludes.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// The frame's sequence number.
    pub frame: u64,
    /// Go, stop or unknown.
    pub decision: Decision,
    /// The obstacle feature; `None` unless the decision is go.
    pub feature: Option<Feature>,
    /// The hazards found, nearest first; in a stop, the hazards that stop the rover
    /// come first and unknown ground after them (see [`Verdict::order_hazards`]).
    /// The first decided the verdict.
    pub hazards: heapless::Vec<Hazard, MAX_HAZARDS>,
    /// Fraction of the corridor cells the camera should see that it did see, 0..=1.
    pub seen_fraction: f32,
    /// How far each band is seen before the sensor's horizon, metres.
    pub seen_to_m: SeenTo,
    /// The rover's predicted roll and pitch along the seen corridor; `None` when no
    /// wheel-track ground is seen.
    pub tilt: Option<Tilt>,
    /// Depth pixels inside the range limits.
    pub points_in: u32,
    /// Points that fell inside the voxel grid.
    pub points_binned: u32,
    /// Occupied voxels.
    pub voxels: u32,
    /// Processing time per stage.
    pub timing_us: StageTimes,
    /// The camera pitch and roll the frame was analysed with.
    pub mount: MountUsed,
    /// Whether the frame was fused with the terrain memory.
    pub memory: MemoryUse,
}

/// How the verdict used the terrain memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MemoryState {
    /// `[memory] enabled = false`: single frames.
    #[default]
    Off,
    /// Enabled, but no trusted odometry: single frames (the map starts again).
    SingleFrame,
    /// The frame fused with the remembered map.
    Fused,
}

/// How a verdict used the terrain memory.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MemoryUse {
    /// Off, single frame (no trusted odometry) or fused.
    pub state: MemoryState,
    /// Why the frame stood alone while the memory is enabled: `no_odometry`,
    /// `odometry_timeout` or `odometry_jump`; `None` otherwise.
    pub reason: Option<&'static str>,
    /// Ground cells out of the camera's view that came from memory.
    pub remembered_cells: u32,
    /// Their mean confidence, 0..=1: 1 for ground just seen from near, falling with
    /// the travel and time since it was seen and with the range it was seen from (0
    /// when none).
    pub remembered_confidence: f32,
    /// Hazards out of the camera's view that came from memory.
    pub remembered_hazards: u32,
}

/// The camera attitude a verdict was computed with (diagnostics).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MountUsed {
    /// Pitch, degrees, positive looking down.
    pub pitch_deg: f32,
    /// Roll, degrees, positive left side up.
    pub roll_deg: f32,
    /// Whether they came from the accelerometer (auto-level) rather than the config.
    pub from_accelerometer: bool,
}

impl Default for Verdict {
    fn default() -> Self {
        Verdict {
            frame: 0,
            decision: Decision::Unknown,
            feature: None,
            hazards: heapless::Vec::new(),
            seen_fraction: 0.0,
            seen_to_m: SeenTo::default(),
            tilt: None,
            points_in: 0,
            points_binned: 0,
            voxels: 0,
            timing_us: StageTimes::default(),
            mount: MountUsed::default(),
            memory: MemoryUse::default(),
        }
    }
}

impl Verdict {
    /// Whether the rover may cross (the decision is go).
    pub fn traversable(&self) -> bool {
        self.decision == Decision::Go
    }

    /// Add a hazard, keeping only the nearest one per kind and side.
    pub fn add_hazard(&mut self, h: Hazard) {
        if let Some(old) = self
            .hazards
            .iter_mut()
            .find(|o| o.kind == h.kind && o.side == h.side)
        {
            if h.distance_m < old.distance_m {
                old.distance_m = h.distance_m;
            }
            return;
        }
        // One per kind and side: 6 × 3 ≤ MAX_HAZARDS, so this cannot overflow.
        let _ = self.hazards.push(h);
    }

    /// What the hazards alone decide: stop for any but unknown ground, unknown for
    /// unknown ground alone, `None` with no hazard (the analysis then decides).
    pub fn hazards_decision(&self) -> Option<Decision> {
        if self.hazards.iter().any(|h| h.kind != HazardKind::Unknown) {
            Some(Decision::Stop)
        } else if !self.hazards.is_empty() {
            Some(Decision::Unknown)
        } else {
            None
        }
    }

    /// Order the hazards nearest first, except that in a stop (`decision` set) the
    /// hazards that stop the rover come before unknown ground: the first hazard is
    /// the one that decided the verdict, as the wire form and `analyze` name it. A
    /// belly rock whose top leaves the image is `unknown` where its top is cut and a
    /// `belly` hazard where its seen part already passes the clearance, often in the
    /// same cell; the order of the two was left to the sort.
    pub fn order_hazards(&mut self) {
        let stop = self.decision == Decision::Stop;
        let after = |h: &Hazard| stop && h.kind == HazardKind::Unknown;
        self.hazards.sort_unstable_by(|a, b| {
            after(a)
                .cmp(&after(b))
                .then(a.distance_m.total_cmp(&b.distance_m))
        });
    }

    /// The verdict as one JSON object (the `analyze` output line).
    pub fn to_json(&self) -> serde_json::Value {
        let r4 = |v: f32| (f64::from(v) * 1e4).round() / 1e4;
        let r3 = |v: f32| (f64::from(v) * 1e3).round() / 1e3;
        let f = self.feature;
        let hazards: Vec<_> = self
            .hazards
            .iter()
            .map(|h| serde_json::json!({"kind": h.kind, "side": h.side, "distance_m": r4(h.distance_m)}))
            .collect();
        let t = self.timing_us;
        let r1 = |v: f32| (f64::from(v) * 10.0).round() / 10.0;
        serde_json::json!({
            "frame": self.frame,
            "verdict": self.decision,
            "traversable": self.traversable(),
            "workcase": f.map(|f| f.workcase),
            "distance_m": f.and_then(|f| f.distance_m).map(r4),
            "gradient_deg": f.and_then(|f| f.gradient_deg).map(r3),
            "alpha_deg": f.and_then(|f| f.alpha_deg).map(r3),
            "toe_seen": f.map(|f| f.toe_seen),
            "hazards": hazards,
            "seen_fraction": r3(self.seen_fraction),
            "seen_to_m": {
                "left": r3(self.seen_to_m.left),
                "centre": r3(self.seen_to_m.centre),
                "right": r3(self.seen_to_m.right),
            },
            "tilt": self.tilt.map(|t| serde_json::json!({
                "roll_deg": r3(t.roll_deg), "roll_at_m": r3(t.roll_at_m),
                "pitch_deg": r3(t.pitch_deg), "pitch_at_m": r3(t.pitch_at_m),
            })),
            "points_in": self.points_in,
            "points_binned": self.points_binned,
            "voxels": self.voxels,
            "timing_us": {
                "bin": r1(t.bin), "voxels": r1(t.voxels), "crossing": r1(t.crossing),
                "feature": r1(t.feature), "memory": r1(t.memory), "total": r1(t.total),
            },
            "memory": {
                "state": self.memory.state,
                "reason": self.memory.reason,
                "remembered_cells": self.memory.remembered_cells,
                "remembered_confidence": r3(self.memory.remembered_confidence),
                "remembered_hazards": self.memory.remembered_hazards,
            },
            "mount": {
                "pitch_deg": r3(self.mount.pitch_deg),
                "roll_deg": r3(self.mount.roll_deg),
                "source": if self.mount.from_accelerometer { "accelerometer" } else { "config" },
            },
        })
    }
}
