//! `bench --soak SECONDS`: the whole service for as long as asked, at the recording's
//! pace (30 Hz for image fixtures), its verdicts over a real pseudo-terminal that a
//! reader thread decodes; reports frame arrival → bytes on the link (median, p99,
//! max), drops, and resident memory at the start (1 s in, after warm-up) and end.

use std::io::Read;
use std::time::{Duration, Instant};

use anyhow::Context;
use rover_terrain::link::proto::serial::{Decoder, Message};
use rover_terrain::link::LinkTarget;
use rover_terrain::service::{self, Notifier};
use rover_terrain::Config;
use rover_terrain_drivers::CameraSpec;
use serialport::SerialPort;

/// Resident set size of this process, kB (`VmRSS` in /proc/self/status).
pub fn rss_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmRSS:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
}

/// What the pty reader decoded.
#[derive(Debug, Default, serde::Serialize)]
struct Decoded {
    verdicts: u64,
    heartbeats: u64,
    errors: u64,
}

/// Run the soak and return its JSON report.
pub fn run(config: Config, camera: CameraSpec, seconds: f64) -> anyhow::Result<serde_json::Value> {
    anyhow::ensure!(
        seconds.is_finite() && seconds >= 2.0,
        "--soak needs at least 2 seconds"
    );
    let (mut master, slave) =
        serialport::TTYPort::pair().context("opening a pseudo-terminal pair")?;
    let slave_path = slave.name().context("the pseudo-terminal has no name")?;
    master
        .set_timeout(Duration::from_millis(200))
        .context("pty timeout")?;
    let (done_tx, done_rx) = crossbeam_channel::bounded::<()>(0);
    let reader_done = done_rx.clone();
    let reader = std::thread::spawn(move || {
        let mut decoded = Decoded::default();
        let mut decoder = Decoder::new();
        let mut buf = [0u8; 4096];
        loop {
            match master.read(&mut buf) {
                Ok(n) => {
                    for &b in &buf[..n] {
                        match decoder.push(b) {
                            Some(Ok(Message::Verdict(_))) => decoded.verdicts += 1,
                            Some(Ok(Message::Heartbeat(_))) => decoded.heartbeats += 1,
                            Some(Ok(Message::Odometry(_))) => decoded.errors += 1, // not ours to send
                            Some(Err(_)) => decoded.errors += 1,
                            None => {}
                        }
                    }
                }
                Err(e) if e.kind() == std::io::ErrorKind::TimedOut => {
                    if reader_done.try_recv().is_err_and(|e| e.is_disconnected()) {
                        break;
                    }
                }
                Err(_) => break,
            }
        }
        decoded
    });
    // Resident memory once a second.
    let sampler_done = done_rx;
    let sampler = std::thread::spawn(move || {
        let mut samples = Vec::new();
        while sampler_done
            .recv_timeout(Duration::from_secs(1))
            .is_err_and(|e| e.is_timeout())
        {
            samples.extend(rss_kb());
        }
        samples
    });

    let mut options = service::Options::from_config(config, camera)?;
    options.config.service.loop_replay = true;
    options.link = LinkTarget::Serial(slave_path);
    let (stop_tx, stop_rx) = crossbeam_channel::bounded(1);
    let timer = std::thread::spawn(move || {
        std::thread::sleep(Duration::from_secs_f64(seconds));
        let _ = stop_tx.send(());
    });
    let start = Instant::now();
    let summary = service::run(options, Notifier::disabled(), stop_rx)?;
    let elapsed = start.elapsed().as_secs_f64();
    let _ = timer.join();
    drop(done_tx);
    let samples = sampler.join().unwrap_or_default();
    let decoded = reader.join().unwrap_or_default();
    drop(slave);
    Ok(serde_json::json!({
        "seconds": elapsed,
        "fps": summary.analysed as f64 / elapsed,
        "frames_in": summary.frames_in,
        "analysed": summary.analysed,
        "dropped": summary.dropped,
        "rejected": summary.rejected,
        "link_failures": summary.link_failures,
        "link_unsent": summary.link_dropped,
        "arrival_to_link_us": {
            "p50": summary.latency.p50_us,
            "p99": summary.latency.p99_us,
            "max": summary.latency.max_us,
            "count": summary.latency.count,
        },
        "rss_kb": {
            "start": samples.first(),
            "end": samples.last(),
            "max": samples.iter().max(),
        },
        "decoded_on_pty": decoded,
    }))
}
