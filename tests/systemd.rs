//! The systemd unit: `systemd-analyze verify` accepts it (with ExecStart pointing at
//! the binary just built), and `systemd-analyze security --offline=true` rates its
//! exposure at most 3.0. Needs `systemd-analyze` (Debian: `apt-get install systemd`).

use std::process::Command;

/// The unit with the install path replaced by the binary under test.
fn unit_for_test(dir: &std::path::Path) -> std::path::PathBuf {
    let text = include_str!("../systemd/rover-terrain.service");
    assert!(text.contains("ExecStart=/usr/local/bin/rover-terrain run"));
    let p = dir.join("rover-terrain.service");
    std::fs::write(
        &p,
        text.replace(
            "/usr/local/bin/rover-terrain",
            env!("CARGO_BIN_EXE_rover-terrain"),
        ),
    )
    .unwrap();
    p
}

fn analyze(args: &[&str]) -> std::process::Output {
    Command::new("systemd-analyze")
        .args(args)
        .output()
        .expect("systemd-analyze (apt-get install systemd)")
}

#[test]
fn the_unit_verifies() {
    let dir = tempfile::tempdir().unwrap();
    let unit = unit_for_test(dir.path());
    let out = analyze(&["verify", "--recursive-errors=no", unit.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        !stderr.contains("rover-terrain.service:"),
        "no complaint about the unit: {stderr}"
    );
    // The same check refuses a unit with a misspelt key.
    let text = std::fs::read_to_string(&unit).unwrap();
    std::fs::write(&unit, text.replace("WatchdogSec=", "WatchDogSec=")).unwrap();
    let out = analyze(&["verify", "--recursive-errors=no", unit.to_str().unwrap()]);
    assert!(!out.status.success(), "a misspelt key is an error");
}

#[test]
fn the_unit_exposure_is_at_most_3() {
    let dir = tempfile::tempdir().unwrap();
    let unit = unit_for_test(dir.path());
    let out = analyze(&["security", "--offline=true", unit.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let level: f64 = stdout
        .lines()
        .find_map(|l| {
            l.split("Overall exposure level for rover-terrain.service: ")
                .nth(1)
        })
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no exposure level in {stdout}"));
    assert!(level <= 3.0, "exposure {level}: {stdout}");
}

#[test]
fn the_unit_keeps_the_watchdog_and_notify_contract() {
    let text = include_str!("../systemd/rover-terrain.service");
    for line in [
        "Type=notify",
        "NotifyAccess=main",
        "User=rover-terrain",
        "ProtectSystem=strict",
        "NoNewPrivileges=yes",
        "DevicePolicy=closed",
        "SupplementaryGroups=video dialout plugdev",
    ] {
        assert!(text.lines().any(|l| l == line), "missing {line}");
    }
    let watchdog = text
        .lines()
        .find_map(|l| l.strip_prefix("WatchdogSec="))
        .expect("WatchdogSec");
    let secs: f64 = watchdog.trim_end_matches('s').parse().unwrap();
    let config = rover_terrain::Config::default();
    // The pings follow the frames: the watchdog must outlast a frame timeout and a
    // camera reopen's first backoff, or a brief hiccup restarts the service.
    assert!(
        secs * 1e3 > (config.service.frame_timeout_ms as f64) * 4.0,
        "{secs}"
    );
}
