//! Prints PROTOCOL.md's test-vector table: `cargo run -p rover-terrain-proto --example vectors`.

use rover_terrain_proto::serial::{self, Message};
use rover_terrain_proto::{Decision, HazardKind, Heartbeat, ServiceState, Side, Verdict};

fn sample_go() -> Verdict {
    Verdict {
        decision: Decision::Go,
        hazard: None,
        workcase: 4,
        seq: 0x0102_0304,
        age_10ms: 3,
        distance_cm: Some(100),
        gradient_ddeg: Some(200),
        alpha_ddeg: Some(-260),
        seen_permille: 861,
    }
}

fn sample_stop() -> Verdict {
    Verdict {
        decision: Decision::Stop,
        hazard: Some((HazardKind::Step, Side::Left)),
        workcase: 0,
        seq: 7,
        age_10ms: 1,
        distance_cm: Some(130),
        gradient_ddeg: None,
        alpha_ddeg: None,
        seen_permille: 1000,
    }
}

fn sample_heartbeat() -> Heartbeat {
    Heartbeat {
        state: ServiceState::Running,
        camera_ok: true,
        frame_rate_chz: 3000,
        dropped: 2,
        seq: 9,
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect::<Vec<_>>()
        .join(" ")
}

fn main() {
    let rows = [
        (
            "go-serial",
            hex(&serial::encode(&Message::Verdict(sample_go()))),
        ),
        ("go-can-310", hex(&sample_go().core())),
        ("go-can-311", hex(&sample_go().ext())),
        (
            "stop-serial",
            hex(&serial::encode(&Message::Verdict(sample_stop()))),
        ),
        ("stop-can-310", hex(&sample_stop().core())),
        (
            "heartbeat-serial",
            hex(&serial::encode(&Message::Heartbeat(sample_heartbeat()))),
        ),
        ("heartbeat-can-312", hex(&sample_heartbeat().encode())),
    ];
    for (name, bytes) in rows {
        println!("| `{name}` | `{bytes}` |");
    }
}
