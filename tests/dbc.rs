//! config/rover-terrain.dbc, parsed by a DBC parser, describes exactly what the
//! encoder puts in each CAN frame.

use can_dbc::{ByteOrder, MessageId, ValueType, DBC};
use rover_terrain::link::proto::{
    can, Decision, HazardKind, Heartbeat, Odometry, ServiceState, Side, Verdict,
};

fn raw(data: &[u8; 8], start: u64, size: u64, signed: bool) -> i64 {
    let word = u64::from_le_bytes(*data);
    let v = (word >> start)
        & if size == 64 {
            u64::MAX
        } else {
            (1u64 << size) - 1
        };
    if signed && size < 64 && v >> (size - 1) == 1 {
        (v | !((1u64 << size) - 1)) as i64
    } else {
        v as i64
    }
}

#[test]
fn the_dbc_matches_the_encoder() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/config/rover-terrain.dbc"
    ))
    .unwrap();
    let dbc = DBC::try_from(text.as_str()).unwrap_or_else(|e| panic!("DBC does not parse: {e:?}"));
    let v = Verdict {
        decision: Decision::Stop,
        hazard: Some((HazardKind::Belly, Side::Right)),
        workcase: 0,
        seq: 0xA1B2_C3D4,
        age_10ms: 7,
        distance_cm: Some(1234),
        gradient_ddeg: Some(-115),
        alpha_ddeg: Some(-260),
        seen_permille: 861,
    };
    let h = Heartbeat {
        state: ServiceState::Degraded,
        camera_ok: true,
        memory_fused: true,
        frame_rate_chz: 2997,
        dropped: 12,
        seq: 200,
    };
    let o = Odometry {
        seq: 77,
        time_ms: 54_321,
        forward_mm: 40_000,
        lateral_2mm: 200,
        heading: 0x8000,
    };
    let frames = [
        can::verdict_frames(&v)[0],
        can::verdict_frames(&v)[1],
        can::heartbeat_frame(&h),
        can::odometry_frame(&o),
    ];
    let expected: &[(u16, &str, f64)] = &[
        (can::VERDICT_ID, "Decision", 1.0),
        (can::VERDICT_ID, "HazardKind", 3.0),
        (can::VERDICT_ID, "HazardSide", 2.0),
        (can::VERDICT_ID, "Workcase", 0.0),
        (can::VERDICT_ID, "SeqLow", f64::from(0xD4u8)),
        (can::VERDICT_ID, "Age", 70.0),
        (can::VERDICT_ID, "Distance", 12.34),
        (can::VERDICT_ID, "Gradient", -11.5),
        (can::VERDICT_EXT_ID, "Alpha", -26.0),
        (can::VERDICT_EXT_ID, "SeenFraction", 86.1),
        (can::VERDICT_EXT_ID, "Seq", f64::from(0xA1B2_C3D4u32)),
        (can::HEARTBEAT_ID, "State", 2.0),
        (can::HEARTBEAT_ID, "CameraOk", 1.0),
        (can::HEARTBEAT_ID, "MemoryFused", 1.0),
        (can::HEARTBEAT_ID, "FrameRate", 29.97),
        (can::HEARTBEAT_ID, "Dropped", 12.0),
        (can::HEARTBEAT_ID, "Counter", 200.0),
        (can::ODOMETRY_ID, "OdoCounter", 77.0),
        (can::ODOMETRY_ID, "OdoTime", 54.321),
        (can::ODOMETRY_ID, "OdoForward", 40.0),
        (can::ODOMETRY_ID, "OdoLateral", 0.4),
        (can::ODOMETRY_ID, "OdoHeading", 180.0),
    ];
    let mut checked = 0;
    for msg in dbc.messages() {
        let id = match msg.message_id() {
            MessageId::Standard(id) => *id,
            other => panic!("{other:?}: the protocol uses 11-bit IDs"),
        };
        let frame = frames
            .iter()
            .find(|f| f.id == id)
            .unwrap_or_else(|| panic!("DBC message {id:#x} is not sent"));
        assert_eq!(*msg.message_size(), 8);
        for sig in msg.signals() {
            assert_eq!(*sig.byte_order(), ByteOrder::LittleEndian, "{}", sig.name());
            let signed = *sig.value_type() == ValueType::Signed;
            let value = raw(&frame.data, *sig.start_bit(), *sig.signal_size(), signed) as f64
                * sig.factor()
                + sig.offset();
            let want = expected
                .iter()
                .find(|(i, n, _)| *i == id && *n == sig.name())
                .unwrap_or_else(|| panic!("signal {} of {id:#x} has no expectation", sig.name()));
            assert!(
                (value - want.2).abs() < 1e-6,
                "{}: DBC decodes {value}, encoder meant {}",
                sig.name(),
                want.2
            );
            checked += 1;
        }
    }
    assert_eq!(
        checked,
        expected.len(),
        "every expected signal is in the DBC"
    );
}
