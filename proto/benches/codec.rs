//! Encode and decode times: `cargo bench -p rover-terrain-proto`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use rover_terrain_proto::serial::{decode_frame, encode, Message};
use rover_terrain_proto::{Decision, HazardKind, Side, Verdict};

fn codec(c: &mut Criterion) {
    let v = Verdict {
        decision: Decision::Stop,
        hazard: Some((HazardKind::Step, Side::Left)),
        workcase: 0,
        seq: 123_456,
        age_10ms: 2,
        distance_cm: Some(130),
        gradient_ddeg: None,
        alpha_ddeg: None,
        seen_permille: 1000,
    };
    let msg = Message::Verdict(v);
    c.bench_function("encode_verdict", |b| b.iter(|| encode(black_box(&msg))));
    let wire = encode(&msg);
    c.bench_function("decode_verdict", |b| {
        b.iter(|| {
            let mut frame = [0u8; 22];
            let n = wire.len() - 1;
            frame[..n].copy_from_slice(&wire[..n]);
            decode_frame(black_box(&mut frame[..n]))
        })
    });
}

criterion_group!(benches, codec);
criterion_main!(benches);
