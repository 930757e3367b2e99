//! `monitor`: the motor controller's view on the bench. Decodes what arrives on a
//! link and prints one JSON line per message (verdict lines exactly as
//! `analyze --format wire` prints them), plus lines for rejected frames, sequence gaps
//! and staleness as the controller's freshness guard sees them.

use std::io::{Read, Write};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::Context;
use rover_terrain::link::proto::can::{Assembler, Received};
use rover_terrain::link::proto::serial::{Decoder, Message};
use rover_terrain::link::proto::{self, DecodeError, Freshness};
use rover_terrain::link::{slcan, wire, LinkTarget};
use serde_json::json;

/// How long one read waits before the staleness check runs.
const POLL: Duration = Duration::from_millis(50);

struct Monitor {
    out: std::io::StdoutLock<'static>,
    guard: Freshness,
    start: Instant,
    valid: u64,
    errors: u64,
    stale_reported: bool,
}

impl Monitor {
    fn now_ms(&self) -> u64 {
        self.start.elapsed().as_millis() as u64
    }

    fn line(&mut self, v: serde_json::Value) -> anyhow::Result<()> {
        writeln!(self.out, "{v}").context("writing to stdout")?;
        self.out.flush().context("writing to stdout")
    }

    fn verdict(&mut self, v: proto::Verdict) -> anyhow::Result<()> {
        let (lost_before, now) = (self.guard.lost(), self.now_ms());
        self.guard.on_verdict(now, v);
        self.valid += 1;
        self.stale_reported = false;
        if self.guard.lost() > lost_before {
            let missing = self.guard.lost() - lost_before;
            self.line(json!({"type": "gap", "before_seq": v.seq, "missing": missing}))?;
        }
        self.line(wire::verdict_json(&v))
    }

    fn message(&mut self, r: Result<Message, DecodeError>) -> anyhow::Result<()> {
        match r {
            Ok(Message::Verdict(v)) => self.verdict(v),
            Ok(Message::Heartbeat(h)) => {
                self.valid += 1;
                self.line(wire::heartbeat_json(&h))
            }
            Ok(Message::Odometry(o)) => {
                self.valid += 1;
                self.line(wire::odometry_json(&o))
            }
            Err(e) => self.error(e),
        }
    }

    fn error(&mut self, e: DecodeError) -> anyhow::Result<()> {
        self.errors += 1;
        self.line(json!({"type": "error", "error": format!("{e:?}")}))
    }

    fn tick(&mut self) -> anyhow::Result<()> {
        let now = self.now_ms();
        if self.guard.last().is_some() && self.guard.stale(now) && !self.stale_reported {
            self.stale_reported = true;
            let seq = self.guard.last().map(|v| v.seq);
            self.line(json!({"type": "stale", "last_seq": seq, "command": "stop"}))?;
        }
        Ok(())
    }
}

/// `monitor`'s arguments.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// serial:PATH, slcan:PATH or can:IFACE (feature socketcan).
    #[arg(long)]
    link: LinkTarget,
    /// Serial speed.
    #[arg(long, default_value_t = rover_terrain::link::DEFAULT_BAUD)]
    baud: u32,
    /// Exit after this many valid messages (verdicts, heartbeats and odometry).
    #[arg(long)]
    count: Option<u64>,
    /// No valid verdict for this long and the controller would stop, ms.
    #[arg(long, default_value_t = 200)]
    deadline_ms: u64,
}

/// Run the monitor until `count` valid messages (or forever), or the link closes.
pub fn run(args: Args) -> anyhow::Result<ExitCode> {
    let Args {
        link: target,
        baud,
        count,
        deadline_ms,
    } = args;
    let target = &target;
    let mut m = Monitor {
        out: std::io::stdout().lock(),
        guard: Freshness::new(deadline_ms),
        start: Instant::now(),
        valid: 0,
        errors: 0,
        stale_reported: false,
    };
    let done = |m: &Monitor| count.is_some_and(|c| m.valid >= c);
    match target {
        LinkTarget::Serial(path) | LinkTarget::Slcan(path) => {
            let mut port = serialport::new(path, baud)
                .timeout(POLL)
                .open()
                .with_context(|| format!("link {target}: opening"))?;
            let is_slcan = matches!(target, LinkTarget::Slcan(_));
            if is_slcan {
                port.write_all(slcan::OPEN_COMMANDS)
                    .with_context(|| format!("link {target}: opening the CAN channel"))?;
            }
            let (mut decoder, mut assembler, mut line) =
                (Decoder::new(), Assembler::default(), Vec::<u8>::new());
            let mut buf = [0u8; 512];
            while !done(&m) {
                let n = match port.read(&mut buf) {
                    Ok(0) => break,
                    Ok(n) => n,
                    Err(e) if e.kind() == std::io::ErrorKind::TimedOut => {
                        m.tick()?;
                        continue;
                    }
                    Err(e) => {
                        // A pseudo-terminal whose other side closed reports EIO.
                        log::info!("link {target}: {e}");
                        break;
                    }
                };
                for &b in &buf[..n] {
                    if done(&m) {
                        break;
                    }
                    if !is_slcan {
                        if let Some(r) = decoder.push(b) {
                            m.message(r)?;
                        }
                        continue;
                    }
                    if b != b'\r' {
                        if line.len() < 64 {
                            line.push(b);
                        }
                        continue;
                    }
                    if let Some(frame) = slcan::parse(&line) {
                        let (r, orphan) = assembler.push(&frame);
                        for got in orphan.into_iter().map(Ok).chain([r]) {
                            match got {
                                Ok(Received::Verdict(v)) | Ok(Received::CoreOnly(v)) => {
                                    m.verdict(v)?
                                }
                                Ok(Received::Heartbeat(h)) => {
                                    m.valid += 1;
                                    m.line(wire::heartbeat_json(&h))?;
                                }
                                Ok(Received::Odometry(o)) => {
                                    m.valid += 1;
                                    m.line(wire::odometry_json(&o))?;
                                }
                                Ok(Received::Other) => {}
                                Err(e) => m.error(e)?,
                            }
                        }
                    }
                    line.clear();
                }
                m.tick()?;
            }
        }
        LinkTarget::Can(_) => anyhow::bail!(
            "link {target}: monitor reads serial: and slcan: links; use candump for SocketCAN"
        ),
        LinkTarget::Stdout => anyhow::bail!(
            "link stdout: nothing to monitor; send --link stdout prints the wire form itself"
        ),
    }
    eprintln!(
        "monitor: {} valid messages, {} rejected frames, {} sequence gaps ({} verdicts lost)",
        m.valid,
        m.errors,
        m.guard.gaps(),
        m.guard.lost()
    );
    if let Some(c) = count.filter(|&c| m.valid < c) {
        anyhow::bail!("link {target}: closed after {} of {c} messages", m.valid);
    }
    Ok(ExitCode::SUCCESS)
}
