//! The messages of `PROTOCOL.md`'s test vectors and their bytes, for implementers
//! in other languages to check themselves against (`cargo run -p rover-terrain-proto
//! --example vectors` prints the table; a test checks the document against it).

use crate::serial::{encode, Message};
use crate::{Decision, HazardKind, Heartbeat, Odometry, ServiceState, Side, Verdict};

/// The "go" vector.
pub fn sample_go() -> Verdict {
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

/// The "stop" vector.
pub fn sample_stop() -> Verdict {
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

/// The "heartbeat" vector.
pub fn sample_heartbeat() -> Heartbeat {
    Heartbeat {
        state: ServiceState::Running,
        camera_ok: true,
        memory_fused: false,
        frame_rate_chz: 3000,
        dropped: 2,
        seq: 9,
    }
}

/// The "odometry" vector: 1.5 m forward, 2 cm to the left, heading 90°, at 12.345 s.
pub fn sample_odometry() -> Odometry {
    Odometry {
        seq: 42,
        time_ms: 12_345,
        forward_mm: 1500,
        lateral_2mm: 10,
        heading: 0x4000,
    }
}

/// Lower-case hex, bytes separated by spaces.
pub fn hex(bytes: &[u8]) -> heapless::String<96> {
    const HEX: &[u8; 16] = b"0123456789abcdef";
    let mut s = heapless::String::new();
    for (i, b) in bytes.iter().enumerate() {
        if i > 0 {
            let _ = s.push(' ');
        }
        let _ = s.push(HEX[usize::from(b >> 4)] as char);
        let _ = s.push(HEX[usize::from(b & 0xF)] as char);
    }
    s
}

/// Every vector: its name in `PROTOCOL.md` and its bytes in hex.
pub fn table() -> [(&'static str, heapless::String<96>); 9] {
    [
        ("go-serial", hex(&encode(&Message::Verdict(sample_go())))),
        ("go-can-310", hex(&sample_go().core())),
        ("go-can-311", hex(&sample_go().ext())),
        (
            "stop-serial",
            hex(&encode(&Message::Verdict(sample_stop()))),
        ),
        ("stop-can-310", hex(&sample_stop().core())),
        (
            "heartbeat-serial",
            hex(&encode(&Message::Heartbeat(sample_heartbeat()))),
        ),
        ("heartbeat-can-312", hex(&sample_heartbeat().encode())),
        (
            "odometry-serial",
            hex(&encode(&Message::Odometry(sample_odometry()))),
        ),
        ("odometry-can-320", hex(&sample_odometry().encode())),
    ]
}
