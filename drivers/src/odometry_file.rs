//! `odometry.txt`: the motor controller's odometry recorded beside a recording's
//! frames, so that a replayed drive carries its motion.
//!
//! One line per frame that had odometry, in any order; `#` starts a comment:
//!
//! ```text
//! # frame file            odometry (PROTOCOL.md's 8 bytes, hex)
//! d-12.345678-17.pgm      2a3930dc050a0040
//! ```
//!
//! The bytes are the last odometry message received before the frame was captured,
//! as it came over the link (its counters wrap; the reader takes differences).

use std::collections::HashMap;
use std::path::Path;

use crate::DriverError;

/// The file's name in a recording directory.
pub const FILE_NAME: &str = "odometry.txt";

/// The odometry of each frame file named in `dir`'s `odometry.txt`; empty when the
/// directory has none. A malformed line is an error naming the line.
pub fn read(dir: &Path) -> Result<HashMap<String, [u8; 8]>, DriverError> {
    let path = dir.join(FILE_NAME);
    if !path.is_file() {
        return Ok(HashMap::new());
    }
    let text = std::fs::read_to_string(&path).map_err(|e| DriverError::io(&path, e))?;
    let mut out = HashMap::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let bad = |what: &str| DriverError::malformed(&path, format!("line {}: {what}", i + 1));
        let mut parts = line.split_whitespace();
        let (Some(name), Some(hex), None) = (parts.next(), parts.next(), parts.next()) else {
            return Err(bad("expected a frame file name and 16 hex digits"));
        };
        let bytes = parse_hex(hex).ok_or_else(|| bad("the odometry is not 16 hex digits"))?;
        if out.insert(name.to_string(), bytes).is_some() {
            return Err(bad(&format!("{name} has odometry twice")));
        }
    }
    Ok(out)
}

/// One line of the file: the frame file's name and the message's bytes.
pub fn line(frame_file: &str, bytes: &[u8; 8]) -> String {
    let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
    format!("{frame_file} {hex}\n")
}

fn parse_hex(s: &str) -> Option<[u8; 8]> {
    if s.len() != 16 || !s.is_ascii() {
        return None;
    }
    let mut out = [0u8; 8];
    for (i, b) in out.iter_mut().enumerate() {
        *b = u8::from_str_radix(&s[2 * i..2 * i + 2], 16).ok()?;
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_round_trip_and_bad_lines_are_named() {
        let dir = tempfile::tempdir().unwrap();
        assert!(read(dir.path()).unwrap().is_empty(), "no file: no odometry");
        let b = [0x2a, 0x39, 0x30, 0xdc, 0x05, 0x0a, 0x00, 0x40];
        let text = format!(
            "# frames\n{}\n{}",
            line("a.png", &b),
            line("b.png", &[0; 8])
        );
        std::fs::write(dir.path().join(FILE_NAME), text).unwrap();
        let m = read(dir.path()).unwrap();
        assert_eq!((m["a.png"], m["b.png"], m.len()), (b, [0; 8], 2));
        for (bad, what) in [
            ("a.png 2a3930dc050a00", "line 1"),
            ("a.png zz3930dc050a0040", "line 1"),
            ("a.png\n", "line 1"),
            ("a.png 0000000000000000\na.png 0000000000000000", "line 2"),
        ] {
            std::fs::write(dir.path().join(FILE_NAME), bad).unwrap();
            let e = read(dir.path()).unwrap_err().to_string();
            assert!(e.contains(what) && e.contains(FILE_NAME), "{bad}: {e}");
        }
    }
}
