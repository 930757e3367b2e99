//! A verdict in wire units, and the JSON both `analyze --format wire` and `monitor`
//! print, so that what the controller receives can be compared byte for byte with
//! what the analysis said.

use rover_terrain_proto as proto;
use serde::Serialize;

use crate::verdict::{Decision, HazardKind, Side, Verdict};

fn clamp_round<T: TryFrom<i64>>(v: f64, lo: i64, hi: i64) -> Option<T> {
    v.is_finite()
        .then(|| (v.round() as i64).clamp(lo, hi))
        .and_then(|x| T::try_from(x).ok())
}

/// The wire form of a verdict; `age_ms` is the time from frame capture to sending.
pub fn to_wire(v: &Verdict, age_ms: f64) -> proto::Verdict {
    let decision = match v.decision {
        Decision::Go => proto::Decision::Go,
        Decision::Stop => proto::Decision::Stop,
        Decision::Unknown => proto::Decision::Unknown,
    };
    let hazard = v.hazards.first().map(|h| {
        let kind = match h.kind {
            HazardKind::Slope => proto::HazardKind::Slope,
            HazardKind::Step => proto::HazardKind::Step,
            HazardKind::Belly => proto::HazardKind::Belly,
            HazardKind::DropOff => proto::HazardKind::DropOff,
            HazardKind::Unknown => proto::HazardKind::Unknown,
            HazardKind::Tilt => proto::HazardKind::Tilt,
        };
        let side = match h.side {
            Side::Left => proto::Side::Left,
            Side::Centre => proto::Side::Centre,
            Side::Right => proto::Side::Right,
        };
        (kind, side)
    });
    let f = v.feature.filter(|_| v.decision == Decision::Go);
    let distance_m = match f {
        Some(f) => f.distance_m,
        None => v.hazards.first().map(|h| h.distance_m),
    };
    proto::Verdict {
        decision,
        hazard,
        workcase: f.map_or(0, |f| f.workcase),
        seq: v.frame as u32,
        age_10ms: clamp_round(age_ms / 10.0, 0, 255).unwrap_or(255),
        distance_cm: distance_m.and_then(|d| clamp_round(f64::from(d) * 100.0, 0, 0xFFFE)),
        gradient_ddeg: f
            .and_then(|f| f.gradient_deg)
            .and_then(|g| clamp_round(f64::from(g) * 10.0, -32767, 32767)),
        alpha_ddeg: f
            .and_then(|f| f.alpha_deg)
            .and_then(|a| clamp_round(f64::from(a) * 10.0, -32767, 32767)),
        seen_permille: clamp_round(f64::from(v.seen_fraction) * 1000.0, 0, 1000).unwrap_or(0),
    }
}

fn name_kind(k: proto::HazardKind) -> &'static str {
    match k {
        proto::HazardKind::Slope => "slope",
        proto::HazardKind::Step => "step",
        proto::HazardKind::Belly => "belly",
        proto::HazardKind::DropOff => "drop_off",
        proto::HazardKind::Unknown => "unknown",
        proto::HazardKind::Tilt => "tilt",
    }
}

fn name_side(s: proto::Side) -> &'static str {
    match s {
        proto::Side::Left => "left",
        proto::Side::Centre => "centre",
        proto::Side::Right => "right",
    }
}

/// The wire verdict as JSON: keys in sorted order, no timing and no age, so that the
/// same frame gives the same bytes whoever prints it. Only numbers and `'static`
/// names, so writing it with [`serde_json::to_writer`] allocates nothing.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct VerdictJson {
    alpha_deg: Option<f64>,
    distance_m: Option<f64>,
    gradient_deg: Option<f64>,
    hazard: Option<HazardJson>,
    seen_fraction: f64,
    seq: u32,
    #[serde(rename = "type")]
    kind: &'static str,
    verdict: &'static str,
    workcase: Option<u8>,
}

#[derive(Debug, Clone, Copy, Serialize)]
struct HazardJson {
    kind: &'static str,
    side: &'static str,
}

impl From<&proto::Verdict> for VerdictJson {
    fn from(v: &proto::Verdict) -> Self {
        VerdictJson {
            alpha_deg: v.alpha_ddeg.map(|a| f64::from(a) / 10.0),
            distance_m: v.distance_cm.map(|d| f64::from(d) / 100.0),
            gradient_deg: v.gradient_ddeg.map(|g| f64::from(g) / 10.0),
            hazard: v.hazard.map(|(k, s)| HazardJson {
                kind: name_kind(k),
                side: name_side(s),
            }),
            seen_fraction: f64::from(v.seen_permille) / 1000.0,
            seq: v.seq,
            kind: "verdict",
            verdict: match v.decision {
                proto::Decision::Go => "go",
                proto::Decision::Stop => "stop",
                proto::Decision::Unknown => "unknown",
            },
            workcase: (v.workcase != 0).then_some(v.workcase),
        }
    }
}

/// A heartbeat as JSON (keys sorted), written without allocating like [`VerdictJson`].
#[derive(Debug, Clone, Copy, Serialize)]
pub struct HeartbeatJson {
    camera_ok: bool,
    dropped: u16,
    memory_fused: bool,
    frame_rate_hz: f64,
    seq: u8,
    state: &'static str,
    #[serde(rename = "type")]
    kind: &'static str,
}

impl From<&proto::Heartbeat> for HeartbeatJson {
    fn from(h: &proto::Heartbeat) -> Self {
        HeartbeatJson {
            camera_ok: h.camera_ok,
            dropped: h.dropped,
            memory_fused: h.memory_fused,
            frame_rate_hz: f64::from(h.frame_rate_chz) / 100.0,
            seq: h.seq,
            state: match h.state {
                proto::ServiceState::Starting => "starting",
                proto::ServiceState::Running => "running",
                proto::ServiceState::Degraded => "degraded",
                proto::ServiceState::Stopping => "stopping",
            },
            kind: "heartbeat",
        }
    }
}

/// An odometry message as one JSON value: its raw counters in SI units (they wrap:
/// see `PROTOCOL.md`).
pub fn odometry_json(o: &proto::Odometry) -> serde_json::Value {
    serde_json::json!({
        "forward_m": f64::from(o.forward_mm) / 1000.0,
        "heading_deg": f64::from(o.heading) * 360.0 / f64::from(proto::HEADING_UNITS_PER_TURN),
        "lateral_m": f64::from(o.lateral_2mm) * 0.002,
        "seq": o.seq,
        "time_s": f64::from(o.time_ms) / 1000.0,
        "type": "odometry",
    })
}

/// The wire verdict as one JSON value (see [`VerdictJson`]).
pub fn verdict_json(v: &proto::Verdict) -> serde_json::Value {
    to_value(VerdictJson::from(v))
}

/// A heartbeat as one JSON value (see [`HeartbeatJson`]).
pub fn heartbeat_json(h: &proto::Heartbeat) -> serde_json::Value {
    to_value(HeartbeatJson::from(h))
}

fn to_value(v: impl Serialize) -> serde_json::Value {
    // Plain structs of numbers, strings and options always serialise.
    serde_json::to_value(v).unwrap_or(serde_json::Value::Null)
}
