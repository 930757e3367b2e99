//! The link end to end over real pseudo-terminals: the protocol through garbage and
//! bit flips, `send` → `monitor` byte-exact with `analyze`, SLCAN, and a link that
//! fails and is reopened with backoff.

use std::io::{Read, Write};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use rand::{Rng, SeedableRng};
use rover_terrain::link::proto::can::{Assembler, Received};
use rover_terrain::link::proto::serial::{encode, Decoder, Message};
use rover_terrain::link::proto::{Decision, HazardKind, Side, Verdict};
use rover_terrain::link::{slcan, LinkTarget, Resilient, BACKOFF_MIN};
use serialport::{SerialPort, TTYPort};

fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_rover-terrain"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

fn pair() -> (TTYPort, TTYPort) {
    let (mut master, mut slave) = TTYPort::pair().expect("pseudo-terminal pair");
    master.set_timeout(Duration::from_secs(5)).unwrap();
    slave.set_timeout(Duration::from_secs(5)).unwrap();
    (master, slave)
}

fn verdict(seq: u32, rng: &mut impl Rng) -> Verdict {
    let go = rng.gen_bool(0.6);
    Verdict {
        decision: if go { Decision::Go } else { Decision::Stop },
        hazard: (!go).then_some((HazardKind::Step, Side::Left)),
        workcase: if go { rng.gen_range(1..=10) } else { 0 },
        seq,
        age_10ms: rng.gen(),
        distance_cm: Some(rng.gen_range(0..400)),
        gradient_ddeg: go.then(|| rng.gen_range(-300..300)),
        alpha_ddeg: None,
        seen_permille: rng.gen_range(0..=1000),
    }
}

#[test]
fn ten_thousand_verdicts_through_garbage_and_bit_flips_over_a_pty() {
    let (mut master, mut slave) = pair();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(42);
    let mut stream = Vec::new();
    let (mut intact, mut corrupted) = (Vec::new(), 0usize);
    // The bytes since the last delimiter: garbage there merges into the next frame.
    let mut dirty = false;
    for seq in 0..10_000u32 {
        if rng.gen_bool(0.1) {
            let n = rng.gen_range(1..40);
            let garbage: Vec<u8> = (0..n).map(|_| rng.gen()).collect();
            dirty = garbage.last() != Some(&0);
            stream.extend_from_slice(&garbage);
        }
        let v = verdict(seq, &mut rng);
        let mut frame = encode(&Message::Verdict(v)).to_vec();
        let flip = rng.gen_bool(0.1);
        if flip {
            let body = frame.len() - 1;
            let bit = rng.gen_range(0..body * 8);
            frame[bit / 8] ^= 1 << (bit % 8);
        }
        if flip || dirty {
            corrupted += 1;
        } else {
            intact.push(v);
        }
        dirty = false;
        stream.extend_from_slice(&frame);
    }
    let total = stream.len();
    let writer = std::thread::spawn(move || {
        for chunk in stream.chunks(997) {
            master.write_all(chunk).unwrap();
        }
        master.flush().unwrap();
        master // keep the master open until the reader is done
    });
    let (mut decoder, mut got, mut rejected) = (Decoder::new(), Vec::new(), 0usize);
    let mut read = 0;
    let mut buf = [0u8; 4096];
    while read < total {
        let n = slave.read(&mut buf).expect("bytes keep coming");
        read += n;
        for &b in &buf[..n] {
            match decoder.push(b) {
                Some(Ok(Message::Verdict(v))) => got.push(v),
                Some(Ok(m @ (Message::Heartbeat(_) | Message::Odometry(_)))) => {
                    panic!("only verdicts were sent: {m:?}")
                }
                Some(Err(_)) => rejected += 1,
                None => {}
            }
        }
    }
    drop(writer.join().unwrap());
    assert!(
        corrupted > 1500,
        "the test corrupts a good share: {corrupted}"
    );
    assert_eq!(
        got.len(),
        intact.len(),
        "every intact frame delivered, none of the corrupted ones"
    );
    assert_eq!(got, intact, "in order, once each");
    assert!(
        rejected >= corrupted,
        "every corrupted frame was rejected ({rejected} < {corrupted})"
    );
}

/// Copy bytes from one pty master to another (the wire between two devices).
fn relay(
    mut from: TTYPort,
    mut to: TTYPort,
    stop: std::sync::Arc<std::sync::atomic::AtomicBool>,
) -> std::thread::JoinHandle<()> {
    from.set_timeout(Duration::from_millis(50)).unwrap();
    std::thread::spawn(move || {
        let mut buf = [0u8; 1024];
        while !stop.load(std::sync::atomic::Ordering::Relaxed) {
            match from.read(&mut buf) {
                Ok(n) if n > 0 => to.write_all(&buf[..n]).unwrap(),
                _ => {}
            }
        }
    })
}

fn fixture(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/scenes")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn send_and_monitor_over_ptys_deliver_exactly_what_analyze_says() {
    let inputs = [
        "diagonal_left.png",
        "step_15cm.png",
        "flat.png",
        "drop_off.png",
        "downhill_straight.png",
    ]
    .map(fixture);
    let analyze = bin()
        .args(["analyze", "--format", "wire"])
        .args(&inputs)
        .output()
        .unwrap();
    assert!(analyze.status.success());
    let want = String::from_utf8(analyze.stdout).unwrap();

    let (m1, s1) = pair();
    let (m2, s2) = pair();
    let (p1, p2) = (s1.name().unwrap(), s2.name().unwrap());
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let r = relay(m1, m2, stop.clone());
    let monitor = bin()
        .args(["monitor", "--link", &format!("serial:{p2}"), "--count", "5"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let send = bin()
        .args(["send", "--link", &format!("serial:{p1}")])
        .args(&inputs)
        .output()
        .unwrap();
    assert!(
        send.status.success(),
        "{}",
        String::from_utf8_lossy(&send.stderr)
    );
    let out = monitor.wait_with_output().unwrap();
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    r.join().unwrap();
    drop((s1, s2));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        want,
        "byte-exact with analyze --format wire"
    );
    assert_eq!(want.lines().count(), 5);
}

#[test]
fn slcan_carries_the_verdicts_as_can_frames_over_a_pty() {
    let inputs = ["uphill_right.png", "belly_block_40cm.png"].map(fixture);
    let (mut master, slave) = pair();
    let path = slave.name().unwrap();
    let send = bin()
        .args(["send", "--link", &format!("slcan:{path}")])
        .args(&inputs)
        .output()
        .unwrap();
    assert!(
        send.status.success(),
        "{}",
        String::from_utf8_lossy(&send.stderr)
    );
    let mut bytes = Vec::new();
    let mut buf = [0u8; 1024];
    master.set_timeout(Duration::from_millis(200)).unwrap();
    while let Ok(n) = master.read(&mut buf) {
        if n == 0 {
            break;
        }
        bytes.extend_from_slice(&buf[..n]);
    }
    let text = String::from_utf8(bytes).unwrap();
    assert!(
        text.starts_with("C\rS6\rO\r"),
        "adapter opened at 500 kbit/s: {text:?}"
    );
    let mut a = Assembler::default();
    let mut verdicts = Vec::new();
    for line in text.split('\r').filter(|l| l.starts_with('t')) {
        let f = slcan::parse(line.as_bytes()).unwrap_or_else(|| panic!("bad SLCAN line {line:?}"));
        if let (Ok(Received::Verdict(v)), None) = a.push(&f) {
            verdicts.push(rover_terrain::link::wire::verdict_json(&v).to_string());
        }
    }
    let want = bin()
        .args(["analyze", "--format", "wire"])
        .args(&inputs)
        .output()
        .unwrap();
    assert_eq!(
        verdicts.join("\n") + "\n",
        String::from_utf8(want.stdout).unwrap()
    );
}

#[test]
fn a_failing_link_is_reopened_with_backoff_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let link = dir.path().join("ttyROVER");
    let target = LinkTarget::Serial(link.display().to_string());
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let t0 = Instant::now();
    // Not there yet: the first attempt fails, later sends inside the backoff do not
    // even try (and so cannot block).
    let mut r = Resilient::new(target, 115_200);
    assert!(!r.is_open());
    assert_eq!(r.failures(), 1);
    for k in 0..5 {
        assert!(!r.send_verdict_at(t0, &verdict(k, &mut rng)));
    }
    assert_eq!(
        (r.failures(), r.dropped()),
        (1, 5),
        "no attempt inside the backoff"
    );
    // Plug it in: the next send after the backoff reopens and delivers.
    let (mut master, slave) = pair();
    std::os::unix::fs::symlink(slave.name().unwrap(), &link).unwrap();
    let later = t0 + BACKOFF_MIN * 4;
    let v = verdict(99, &mut rng);
    assert!(r.send_verdict_at(later, &v));
    assert_eq!(r.reopened(), 1);
    let mut d = Decoder::new();
    let mut buf = [0u8; 64];
    let got = loop {
        let n = master.read(&mut buf).unwrap();
        if let Some(m) = buf[..n].iter().find_map(|&b| d.push(b)) {
            break m;
        }
    };
    assert_eq!(got, Ok(Message::Verdict(v)));
    // Unplug it: writes fail, the failure is counted, the backoff grows.
    drop(master);
    drop(slave);
    // The kernel hangs the terminal up asynchronously: keep sending (bounded by a
    // deadline, yielding, no sleeping) until a write reports it.
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut failed = false;
    let mut k = 0;
    while !failed && Instant::now() < deadline {
        failed = !r.send_verdict_at(later, &verdict(100 + k, &mut rng));
        k += 1;
        std::thread::yield_now();
    }
    assert!(failed, "a write to an unplugged pty fails");
    assert_eq!(r.failures(), 2);
    assert!(!r.is_open());
    assert!(r.backoff() > BACKOFF_MIN);
}

#[test]
fn the_controller_simulator_sends_odometry_the_protocol_decodes_over_a_pty() {
    let (mut master, slave) = pair();
    let path = slave.name().unwrap();
    let out = bin()
        .args(["controller", "--link", &format!("serial:{path}")])
        .args(["--count", "40", "--rate-hz", "200", "--speed-mps", "0.4"])
        .args(["--turn-dps", "-20"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut decoder = Decoder::new();
    let mut got = Vec::new();
    let mut buf = [0u8; 512];
    while got.len() < 40 {
        let n = master.read(&mut buf).expect("40 messages arrive");
        for &b in &buf[..n] {
            match decoder.push(b) {
                Some(Ok(Message::Odometry(o))) => got.push(o),
                Some(other) => panic!("only odometry is sent: {other:?}"),
                None => {}
            }
        }
    }
    drop(slave);
    // 200 Hz at 0.4 m/s turning clockwise at 20°/s: 2 mm and -0.1° per message,
    // as wrapped differences of cumulative counters; 39 messages cover 78 mm.
    for w in got.windows(2) {
        let m = w[1].since(&w[0]);
        assert_eq!((m.messages, m.dt_ms), (1, 5), "{m:?}");
        assert_eq!(m.forward_mm, 2, "{m:?}");
        assert!(
            (f64::from(m.dheading_rad) + 0.1f64.to_radians()).abs() < 2e-4,
            "{m:?}"
        );
    }
    let total = got[39].since(&got[0]);
    assert_eq!(total.forward_mm, 78);
    assert!((f64::from(total.dheading_rad) + 3.9f64.to_radians()).abs() < 2e-4);
}

#[test]
fn odometry_comes_back_on_serial_and_slcan_links_through_garbage() {
    use rover_terrain::link::proto::{can, Odometry};
    let sent = [
        Odometry::from_pose(1, 20, 0.5, 0.01, 0.2),
        Odometry::from_pose(2, 40, 0.51, 0.01, 0.21),
    ];
    for kind in ["serial", "slcan"] {
        let (mut master, slave) = pair();
        let target: LinkTarget = format!("{kind}:{}", slave.name().unwrap()).parse().unwrap();
        let mut link = rover_terrain::link::open(&target, 115_200).unwrap();
        // A verdict-sized garbage frame and a stray line first: skipped, not fatal.
        for o in &sent {
            let bytes: Vec<u8> = if kind == "serial" {
                let mut b = vec![7, 7, 7, 0];
                b.extend_from_slice(&encode(&Message::Odometry(*o)));
                b
            } else {
                let mut b = b"t31080000000000000000\rnonsense\r".to_vec();
                b.extend_from_slice(slcan::encode(&can::odometry_frame(o)).as_bytes());
                b
            };
            master.write_all(&bytes).unwrap();
        }
        master.flush().unwrap();
        let mut got = Vec::new();
        let deadline = Instant::now() + Duration::from_secs(5);
        while got.len() < sent.len() && Instant::now() < deadline {
            link.receive_odometry(&mut |o| got.push(o)).unwrap();
        }
        assert_eq!(got, sent, "{kind}");
    }
}
