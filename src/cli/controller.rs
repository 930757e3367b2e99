//! `controller`: a motor controller on the bench. Sends the wheel odometry of a steady
//! drive (a speed, a turn rate, optionally wheel slip) over a link at a fixed rate, as
//! the real controller would, so the service's terrain memory can be tried without a
//! rover.

use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::Context;
use rover_terrain::link::{self, proto, LinkTarget};

/// `controller`'s arguments.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// serial:PATH, slcan:PATH, can:IFACE (feature socketcan) or stdout (JSON lines).
    #[arg(long, default_value = "stdout")]
    link: LinkTarget,
    /// Serial speed.
    #[arg(long, default_value_t = link::DEFAULT_BAUD)]
    baud: u32,
    /// Forward speed, m/s (negative: backwards).
    #[arg(long, default_value_t = 0.2, allow_negative_numbers = true)]
    speed_mps: f64,
    /// Turn rate, degrees per second, counter-clockwise positive.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    turn_dps: f64,
    /// Messages per second.
    #[arg(long, default_value_t = 50.0)]
    rate_hz: f64,
    /// Stop after this many messages (default: until interrupted).
    #[arg(long)]
    count: Option<u64>,
}

/// The counters of a steady drive `t` seconds after the start: forward travel, m, and
/// heading, radians. Forward travel is along the rover's own x axis, so a turn does not
/// change it.
fn pose_at(t: f64, speed_mps: f64, turn_dps: f64) -> (f64, f64) {
    (speed_mps * t, turn_dps.to_radians() * t)
}

/// Send odometry until `count` messages or the link fails.
pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    anyhow::ensure!(
        args.rate_hz.is_finite() && args.rate_hz > 0.0 && args.rate_hz <= 1000.0,
        "--rate-hz must be in (0, 1000], got {}",
        args.rate_hz
    );
    anyhow::ensure!(
        args.speed_mps.is_finite() && args.speed_mps.abs() <= 10.0,
        "--speed-mps must be within ±10 m/s, got {}",
        args.speed_mps
    );
    anyhow::ensure!(
        args.turn_dps.is_finite() && args.turn_dps.abs() <= 360.0,
        "--turn-dps must be within ±360 °/s, got {}",
        args.turn_dps
    );
    let mut transport = link::open(&args.link, args.baud)
        .with_context(|| format!("link {}: opening", args.link))?;
    let period = Duration::from_secs_f64(1.0 / args.rate_hz);
    let start = Instant::now();
    let mut next = start;
    let mut sent = 0u64;
    while args.count.is_none_or(|c| sent < c) {
        let now = Instant::now();
        if next > now {
            std::thread::sleep(next - now);
        }
        let t = sent as f64 / args.rate_hz;
        let (forward, heading) = pose_at(t, args.speed_mps, args.turn_dps);
        let o = proto::Odometry::from_pose(sent as u8, (t * 1000.0) as u64, forward, 0.0, heading);
        transport
            .send_odometry(&o)
            .and_then(|()| transport.flush())
            .with_context(|| format!("link {}: sending odometry", args.link))?;
        sent += 1;
        next += period;
    }
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_steady_drive_sends_the_travel_since_the_last_message() {
        let (f0, h0) = pose_at(1.0, 0.3, 10.0);
        let (f1, h1) = pose_at(1.02, 0.3, 10.0);
        let a = proto::Odometry::from_pose(50, 1000, f0, 0.0, h0);
        let b = proto::Odometry::from_pose(51, 1020, f1, 0.0, h1);
        let m = b.since(&a);
        assert_eq!((m.messages, m.dt_ms, m.forward_mm), (1, 20, 6));
        assert!((f64::from(m.dheading_rad) - 0.2f64.to_radians()).abs() < 2e-4);
    }
}
