//! Logging for the binary: env_logger on stderr. Under systemd (stderr is the journal
//! stream named by `JOURNAL_STREAM`) lines carry no timestamp (journald adds its own)
//! and start with the syslog priority (`<3>` error ... `<7>` debug), so journald keeps
//! the levels (`journalctl -p warning` works).

use std::io::Write;

/// Whether stderr is the journal stream systemd connected (`JOURNAL_STREAM` holds
/// its `device:inode`).
pub fn stderr_is_journal() -> bool {
    use std::os::unix::fs::MetadataExt;
    let Ok(want) = std::env::var("JOURNAL_STREAM") else {
        return false;
    };
    let Ok(meta) = std::fs::metadata("/proc/self/fd/2") else {
        return false;
    };
    want == format!("{}:{}", meta.dev(), meta.ino())
}

/// The syslog priority of a log level.
fn priority(level: log::Level) -> u8 {
    match level {
        log::Level::Error => 3,
        log::Level::Warn => 4,
        log::Level::Info => 6,
        log::Level::Debug | log::Level::Trace => 7,
    }
}

/// Start logging at `default_level` (a filter such as `warn`), unless `RUST_LOG` is
/// set, which wins.
pub fn init(default_level: &str) {
    let mut builder = env_logger::Builder::new();
    builder.parse_filters(default_level);
    if let Ok(filters) = std::env::var("RUST_LOG") {
        builder.parse_filters(&filters);
    }
    if stderr_is_journal() {
        builder.format(|buf, record| {
            writeln!(
                buf,
                "<{}>{}: {}",
                priority(record.level()),
                record.target(),
                record.args()
            )
        });
    }
    builder.init();
}
