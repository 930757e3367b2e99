//! The whole service, once warm, allocates nothing per frame: camera thread (replaying
//! from memory), analysis, link thread writing COBS frames to a real pseudo-terminal,
//! heartbeats, watchdog pings to a real notify socket, and the controller's odometry
//! coming back on the pty into the terrain memory, and a viewer writing every frame
//! into an MCAP file (`run --mcap`) beside it. A counting global allocator
//! watches 45 frames (1.5 s) after a warm-up of 15.

use std::io::Read;
use std::io::Write;
use std::os::unix::net::UnixDatagram;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use rover_terrain::link::proto::serial::{self, Decoder, Message};
use rover_terrain::link::proto::Odometry;
use rover_terrain::link::LinkTarget;
use rover_terrain::service::{self, Notifier, Options, StopReason};
use rover_terrain::Config;
use rover_terrain_drivers::{CameraSpec, Faults};
use serialport::{SerialPort, TTYPort};

#[path = "common/counting.rs"]
mod counting;
use counting::{Counting, ALLOCATIONS, COUNTING};

#[global_allocator]
static GLOBAL: Counting = Counting;

const WARM_UP: usize = 15;
const WATCHED: usize = 45;

#[test]
fn the_running_service_allocates_nothing_per_frame() {
    let dir = tempfile::tempdir().unwrap();
    let socket_path = dir.path().join("notify.sock");
    let socket = UnixDatagram::bind(&socket_path).unwrap();
    socket
        .set_read_timeout(Some(Duration::from_millis(100)))
        .unwrap();
    // This test binary holds only this test: setting the environment is safe here.
    std::env::set_var("NOTIFY_SOCKET", &socket_path);
    std::env::set_var("WATCHDOG_USEC", "200000");
    let notifier = Notifier::from_env().unwrap();

    let (mut master, slave) = TTYPort::pair().unwrap();
    master.set_timeout(Duration::from_millis(100)).unwrap();
    let mut config = Config::default();
    config.service.stats_interval_s = 3600;
    config.service.loop_replay = true;
    let options = Options {
        config,
        camera: CameraSpec::Fake(concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/scenes").into()),
        link: LinkTarget::Serial(slave.name().unwrap()),
        baud: 115_200,
        faults: Faults::default(),
        frames: None,
        // A viewer writing an MCAP file of every frame: its thread builds pictures
        // (allocating, not counted); what the analysis hands it must not allocate.
        mcap: Some(dir.path().join("run.mcap")),
        foxglove: None,
    };
    let (stop_tx, stop_rx) = crossbeam_channel::bounded::<()>(1);

    // The notify socket reader: counts pings into a stack buffer.
    let pings = std::sync::Arc::new(AtomicUsize::new(0));
    let pings_seen = std::sync::Arc::clone(&pings);
    let notify_reader = std::thread::spawn(move || {
        let mut buf = [0u8; 512];
        let mut quiet = 0;
        while quiet < 20 {
            match socket.recv(&mut buf) {
                Ok(n) if &buf[..n] == b"WATCHDOG=1" => {
                    pings_seen.fetch_add(1, Ordering::Relaxed);
                    quiet = 0;
                }
                Ok(_) => quiet = 0,
                Err(_) => quiet += 1,
            }
        }
    });

    // The motor controller: odometry at 50 Hz on the same pty, a slow drive, until the
    // reader is done (stack only: it runs while allocations are counted).
    let mut controller = master.try_clone_native().unwrap();
    let driving = std::sync::Arc::new(AtomicBool::new(true));
    let still_driving = std::sync::Arc::clone(&driving);
    let controller = std::thread::spawn(move || {
        let mut k = 0u64;
        while still_driving.load(Ordering::Relaxed) {
            let t = k as f64 * 0.02;
            let o = Odometry::from_pose(k as u8, k * 20, 0.1 * t, 0.0, 0.05 * t);
            let _ = controller.write_all(&serial::encode(&Message::Odometry(o)));
            k += 1;
            std::thread::sleep(Duration::from_millis(20)); // the controller's pace
        }
    });

    // The pty reader: turns counting on after the warm-up, off after the watched frames,
    // then stops the service.
    let reader = std::thread::spawn(move || {
        let mut decoder = Decoder::new();
        let mut buf = [0u8; 1024];
        let (mut verdicts, mut heartbeats, mut fused) = (0usize, 0usize, 0usize);
        while verdicts < WARM_UP + WATCHED {
            let Ok(n) = master.read(&mut buf) else {
                continue;
            };
            for &b in &buf[..n] {
                match decoder.push(b) {
                    Some(Ok(Message::Verdict(_))) => {
                        verdicts += 1;
                        if verdicts == WARM_UP {
                            COUNTING.store(true, Ordering::SeqCst);
                        }
                        if verdicts == WARM_UP + WATCHED {
                            COUNTING.store(false, Ordering::SeqCst);
                        }
                    }
                    Some(Ok(Message::Heartbeat(h))) if COUNTING.load(Ordering::Relaxed) => {
                        heartbeats += 1;
                        fused += usize::from(h.memory_fused);
                    }
                    _ => {}
                }
            }
        }
        drop(stop_tx);
        (heartbeats, fused, master)
    });

    let summary = service::run(options, notifier, stop_rx).unwrap();
    let (heartbeats, fused, _master) = reader.join().unwrap();
    driving.store(false, Ordering::Relaxed);
    controller.join().unwrap();
    notify_reader.join().unwrap();
    drop(slave);

    assert_eq!(summary.reason, StopReason::Signal);
    let written = summary.viewer_written.expect("the viewer ran");
    assert!(
        written + summary.viewer_dropped >= summary.analysed && written >= 10,
        "every analysed frame written or counted dropped: {written} + {} of {}",
        summary.viewer_dropped,
        summary.analysed
    );
    assert!(summary.analysed >= (WARM_UP + WATCHED) as u64);
    assert!(
        heartbeats >= 5,
        "heartbeats went out while watched: {heartbeats}"
    );
    assert!(
        fused >= 3,
        "the terrain memory fused frames over the odometry while watched: {fused} of {heartbeats}"
    );
    assert!(
        pings.load(Ordering::Relaxed) >= 5,
        "watchdog pings went out: {}",
        pings.load(Ordering::Relaxed)
    );
    assert_eq!(
        ALLOCATIONS.load(Ordering::SeqCst),
        0,
        "allocations while {WATCHED} frames went camera → analysis → pty"
    );
}
