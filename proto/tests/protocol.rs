//! Round trips, arbitrary input, corruption and resynchronisation, the freshness
//! guard, and the test vectors published in PROTOCOL.md.

use proptest::prelude::*;
use rover_terrain_proto::can::{self, Assembler, Received};
use rover_terrain_proto::serial::{self, Decoder, Message, CRC};
use rover_terrain_proto::vectors::{self, sample_go, sample_stop};
use rover_terrain_proto::{
    Command, Decision, DecodeError, Freshness, HazardKind, Heartbeat, Odometry, ServiceState, Side,
    Verdict,
};

fn verdict_strategy() -> impl Strategy<Value = Verdict> {
    (
        0u8..3,
        proptest::option::of((1u8..6, 0u8..3)),
        1u8..=10,
        any::<u32>(),
        any::<u8>(),
        proptest::option::of(0u16..0xFFFF),
        proptest::option::of(-32767i16..=32767),
        proptest::option::of(-32767i16..=32767),
        0u16..=1000,
    )
        .prop_map(|(d, hz, wc, seq, age, dist, grad, alpha, seen)| {
            let decision = [Decision::Go, Decision::Stop, Decision::Unknown][d as usize];
            let kinds = [
                HazardKind::Slope,
                HazardKind::Step,
                HazardKind::Belly,
                HazardKind::DropOff,
                HazardKind::Unknown,
                HazardKind::Tilt,
            ];
            let sides = [Side::Left, Side::Centre, Side::Right];
            Verdict {
                decision,
                hazard: hz.map(|(k, s)| (kinds[k as usize - 1], sides[s as usize])),
                workcase: if decision == Decision::Go { wc } else { 0 },
                seq,
                age_10ms: age,
                distance_cm: dist,
                gradient_ddeg: grad,
                alpha_ddeg: alpha,
                seen_permille: seen,
            }
        })
}

fn heartbeat_strategy() -> impl Strategy<Value = Heartbeat> {
    (
        0u8..4,
        any::<bool>(),
        any::<bool>(),
        any::<u16>(),
        any::<u16>(),
        any::<u8>(),
    )
        .prop_map(|(s, cam, mem, rate, dropped, seq)| Heartbeat {
            state: [
                ServiceState::Starting,
                ServiceState::Running,
                ServiceState::Degraded,
                ServiceState::Stopping,
            ][s as usize],
            camera_ok: cam,
            memory_fused: mem,
            frame_rate_chz: rate,
            dropped,
            seq,
        })
}

fn decode_all(bytes: &[u8]) -> Vec<Result<Message, DecodeError>> {
    let mut d = Decoder::new();
    bytes.iter().filter_map(|&b| d.push(b)).collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn verdicts_round_trip_over_serial_and_can(v in verdict_strategy()) {
        let frame = serial::encode(&Message::Verdict(v));
        prop_assert_eq!(frame.iter().filter(|&&b| b == 0).count(), 1, "one delimiter, at the end");
        prop_assert_eq!(*frame.last().unwrap(), 0);
        prop_assert_eq!(decode_all(&frame), vec![Ok(Message::Verdict(v))]);
        let [core, ext] = can::verdict_frames(&v);
        let mut a = Assembler::default();
        prop_assert_eq!(a.push(&core), (Ok(Received::Other), None));
        prop_assert_eq!(a.push(&ext), (Ok(Received::Verdict(v)), None));
    }

    #[test]
    fn heartbeats_round_trip(h in heartbeat_strategy()) {
        let frame = serial::encode(&Message::Heartbeat(h));
        prop_assert_eq!(decode_all(&frame), vec![Ok(Message::Heartbeat(h))]);
        let f = can::heartbeat_frame(&h);
        prop_assert_eq!(Assembler::default().push(&f).0, Ok(Received::Heartbeat(h)));
    }

    #[test]
    fn odometry_round_trips(b in any::<[u8; 8]>()) {
        let o = Odometry::decode(&b).unwrap();
        prop_assert_eq!(o.encode(), b);
        let frame = serial::encode(&Message::Odometry(o));
        prop_assert_eq!(decode_all(&frame), vec![Ok(Message::Odometry(o))]);
        let f = can::odometry_frame(&o);
        prop_assert_eq!(f.id, can::ODOMETRY_ID);
        prop_assert_eq!(Assembler::default().push(&f).0, Ok(Received::Odometry(o)));
    }

    /// Any pose and any motion within half of each counter's range: the difference
    /// of the two messages is the motion, to the wire's resolution, across wraps.
    #[test]
    fn odometry_differences_are_the_motion(
        seq in any::<u8>(), lost in 0u8..100,
        t in 40_000u64..10_000_000, dt in -32_000i64..32_000,
        fwd in -1.0e5f64..1.0e5, dfwd in -30.0f64..30.0,
        lat in -100.0f64..100.0, dlat in -0.25f64..0.25,
        hd in -100.0f64..100.0, dhd in -3.1f64..3.1,
    ) {
        let a = Odometry::from_pose(seq, t, fwd, lat, hd);
        let b = Odometry::from_pose(seq.wrapping_add(lost + 1), (t as i64 + dt) as u64, fwd + dfwd, lat + dlat, hd + dhd);
        let m = b.since(&a);
        prop_assert_eq!(m.messages, lost + 1);
        prop_assert_eq!(i64::from(m.dt_ms), dt);
        prop_assert!((f64::from(m.forward_mm) / 1000.0 - dfwd).abs() <= 0.0011, "{:?}", m);
        prop_assert!((f64::from(m.lateral_mm) / 1000.0 - dlat).abs() <= 0.0021, "{:?}", m);
        prop_assert!((f64::from(m.dheading_rad) - dhd).abs() <= 2e-4, "{:?}", m);
    }

    #[test]
    fn arbitrary_bytes_never_panic_and_never_fake_a_frame_count(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        let results = decode_all(&bytes);
        // At most one result per delimiter.
        prop_assert!(results.len() <= bytes.iter().filter(|&&b| b == 0).count());
    }

    #[test]
    fn any_single_bit_flip_is_rejected(v in verdict_strategy(), bit in 0usize..(21 * 8)) {
        let mut frame = serial::encode(&Message::Verdict(v)).to_vec();
        let body = frame.len() - 1; // not the delimiter
        let bit = bit % (body * 8);
        frame[bit / 8] ^= 1 << (bit % 8);
        let results = decode_all(&frame);
        // A flip may create a delimiter (splitting the frame) or remove none; no
        // piece may decode as a valid message.
        prop_assert!(results.iter().all(|r| r.is_err()), "{:?}", results);
    }

    #[test]
    fn garbage_between_frames_costs_at_most_the_garbage(
        vs in proptest::collection::vec(verdict_strategy(), 1..20),
        garbage in proptest::collection::vec(proptest::collection::vec(any::<u8>(), 0..30), 20),
    ) {
        let mut stream = Vec::new();
        for (v, g) in vs.iter().zip(&garbage) {
            stream.extend_from_slice(g);
            stream.push(0); // garbage ends at a delimiter at worst
            stream.extend_from_slice(&serial::encode(&Message::Verdict(*v)));
        }
        let good: Vec<Verdict> = decode_all(&stream)
            .into_iter()
            .filter_map(|r| match r { Ok(Message::Verdict(v)) => Some(v), _ => None })
            .collect();
        // Every intact frame is delivered, once, in order (garbage could by chance
        // hold a valid frame of its own: only with a matching CRC, which random bytes
        // in these lengths do not reach).
        prop_assert_eq!(good, vs);
    }
}

#[test]
fn crc_is_the_catalogued_ccitt_false() {
    assert_eq!(CRC.checksum(b"123456789"), 0x29B1);
}

#[test]
fn typed_errors_for_each_malformation() {
    let v = sample_go();
    let raw_with = |f: &dyn Fn(&mut Vec<u8>)| {
        // Build a raw frame, mutate, recompute the CRC unless told otherwise, COBS it.
        let mut raw = vec![1u8, serial::TYPE_VERDICT];
        raw.extend_from_slice(&v.core());
        raw.extend_from_slice(&v.ext());
        f(&mut raw);
        let crc = CRC.checksum(&raw).to_le_bytes();
        raw.extend_from_slice(&crc);
        let mut out = vec![0u8; raw.len() + 4];
        let n = cobs::encode(&raw, &mut out);
        out.truncate(n);
        out.push(0);
        decode_all(&out)
    };
    assert_eq!(raw_with(&|r| r[0] = 2), vec![Err(DecodeError::Version(2))]);
    assert_eq!(raw_with(&|r| r[1] = 9), vec![Err(DecodeError::Type(9))]);
    assert_eq!(
        raw_with(&|r| r.truncate(10)),
        vec![Err(DecodeError::Length { kind: 1, got: 8 })]
    );
    assert_eq!(raw_with(&|r| r[2] = 3), vec![Err(DecodeError::Field(0))]);
    assert_eq!(raw_with(&|r| r[3] = 11), vec![Err(DecodeError::Field(1))]);
    assert_eq!(
        raw_with(&|r| r[4] ^= 1),
        vec![Err(DecodeError::Inconsistent)]
    );
    let mut frame = serial::encode(&Message::Verdict(v)).to_vec();
    let n = frame.len();
    frame[n - 2] ^= 0x40;
    assert!(matches!(
        decode_all(&frame)[..],
        [Err(DecodeError::Crc { .. })] | [Err(DecodeError::Cobs)]
    ));
    assert_eq!(decode_all(&[7, 7, 0]), vec![Err(DecodeError::Cobs)]);
    assert_eq!(decode_all(&[2, 5, 0]), vec![Err(DecodeError::TooShort)]);
    assert_eq!(
        decode_all(&[1u8; 100].iter().copied().chain([0]).collect::<Vec<_>>()),
        vec![Err(DecodeError::TooLong)]
    );
    assert_eq!(decode_all(&[0, 0, 0]), vec![]);
}

#[test]
fn protocol_md_vectors_are_what_the_code_produces() {
    let doc = include_str!("../../PROTOCOL.md");
    let vectors = vectors::table();
    for (name, want) in vectors {
        let line = doc
            .lines()
            .find(|l| l.starts_with(&format!("| `{name}` |")))
            .unwrap_or_else(|| panic!("PROTOCOL.md has no vector {name}; the code gives: {want}"));
        let got = line.split('|').nth(2).unwrap().trim().trim_matches('`');
        assert_eq!(got, want.as_str(), "vector {name}");
    }
}

#[test]
fn freshness_stops_without_fresh_go_and_counts_gaps() {
    let mut f = Freshness::new(200);
    assert_eq!(f.command(0), Command::Stop, "nothing received yet");
    let mut v = sample_go();
    v.seq = 10;
    f.on_verdict(1000, v);
    assert_eq!(f.command(1000), Command::Go);
    assert_eq!(f.command(1200), Command::Go);
    assert_eq!(f.command(1201), Command::Stop, "stale");
    assert!(f.stale(1201));
    v.seq = 13;
    f.on_verdict(1300, v);
    assert_eq!((f.gaps(), f.lost()), (1, 2));
    v.seq = 12; // older: ignored
    f.on_verdict(1310, v);
    assert_eq!(f.stale_rejected(), 1);
    assert_eq!(f.last().unwrap().seq, 13);
    let mut s = sample_stop();
    s.seq = 14;
    f.on_verdict(1320, s);
    assert_eq!(f.command(1320), Command::Stop, "a stop verdict stops");
    let mut w = sample_go();
    w.seq = u32::MAX;
    let mut g = Freshness::new(100);
    g.on_verdict(0, w);
    w.seq = 0; // wraps
    g.on_verdict(10, w);
    assert_eq!((g.gaps(), g.stale_rejected()), (0, 0));
}

#[test]
fn a_core_without_its_extension_is_still_delivered() {
    let v = sample_go();
    let [core, _ext] = can::verdict_frames(&v);
    let mut a = Assembler::default();
    assert_eq!(a.push(&core), (Ok(Received::Other), None));
    let (_, orphan) = a.push(&core);
    match orphan {
        Some(Received::CoreOnly(c)) => {
            assert_eq!(
                (c.decision, c.workcase, c.seq),
                (v.decision, v.workcase, v.seq & 0xff)
            );
        }
        other => panic!("{other:?}"),
    }
}
