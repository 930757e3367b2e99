//! libfreenect `fakenect` sessions, as libfreenect's `record` tool writes them.
//!
//! A session is a directory with `INDEX.txt`, one file name a line, in arrival order:
//! - `d-<seconds>-<timestamp>.pgm`: a depth frame, header `P5 640 480 65535` followed by
//!   raw 11-bit disparity as `u16` in **little-endian** order (2047 = no data);
//! - `r-<seconds>-<timestamp>.ppm`: a colour frame (`P6`);
//! - `a-<seconds>-<timestamp>.dump`: the raw tilt state (accelerometer).
//!
//! Raw disparity is converted to millimetres with libfreenect's own registration
//! formula (`freenect_raw_to_mm` in `registration.c`) when the session has a
//! `device.json` (newer `record` versions write the device's zero-plane parameters
//! there), so our millimetres are those libfreenect's `FREENECT_DEPTH_MM` mode gives.
//! Without `device.json` we use the standard Kinect v1 fit
//! `mm = 1000 / (3.3309495161 − 0.0030711016 · raw)` (the one ROS's openni/freenect
//! stacks use), valid for raw < 1084; other values are "no data".

use std::path::{Path, PathBuf};

use crate::image::{decode_pgm_depth, read_file_into, ByteOrder};
use crate::{DepthFrame, DriverError};

/// Raw disparity value meaning "no data".
pub const RAW_NO_DATA: u16 = 2047;
/// Number of raw disparity codes (11 bits).
pub const RAW_CODES: usize = 2048;
/// libfreenect's largest metric depth in its tables, millimetres.
pub const MAX_MM: u16 = 10_000;

/// The zero-plane registration parameters of one Kinect (from `device.json`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Registration {
    /// Distance between the depth CMOS and the IR emitter, cm.
    pub dcmos_emitter_distance: f64,
    /// Reference plane distance, mm.
    pub reference_distance: f64,
    /// Reference pixel size, mm.
    pub reference_pixel_size: f64,
    /// The device's constant disparity shift.
    pub const_shift: i32,
}

impl Registration {
    /// libfreenect's built-in defaults ("ripped from my Kinect" in registration.c).
    pub const LIBFREENECT_DEFAULT: Registration = Registration {
        dcmos_emitter_distance: 7.5,
        reference_distance: 120.0,
        reference_pixel_size: 0.1042,
        const_shift: 200,
    };

    /// Parse `device.json` as libfreenect's recorder writes it.
    pub fn from_device_json(text: &str, path: &Path) -> Result<Self, DriverError> {
        let value: serde_json::Value = serde_json::from_str(text)
            .map_err(|e| DriverError::malformed(path, format!("invalid JSON: {e}")))?;
        let num = |v: &serde_json::Value, key: &str| -> Result<f64, DriverError> {
            v.get(key).and_then(|x| x.as_f64()).ok_or_else(|| {
                DriverError::malformed(path, format!("missing or non-numeric \"{key}\""))
            })
        };
        let zp = value
            .get("reg_info")
            .and_then(|r| r.get("zero_plane_info"))
            .ok_or_else(|| DriverError::malformed(path, "missing reg_info.zero_plane_info"))?;
        let reg = Registration {
            dcmos_emitter_distance: num(zp, "dcmos_emitter_distance")?,
            reference_distance: num(zp, "reference_distance")?,
            reference_pixel_size: num(zp, "reference_pixel_size")?,
            const_shift: num(&value, "const_shift")? as i32,
        };
        if !(reg.reference_distance > 0.0 && reg.reference_pixel_size > 0.0) {
            return Err(DriverError::malformed(
                path,
                "zero_plane_info has a non-positive reference distance or pixel size",
            ));
        }
        Ok(reg)
    }

    /// Write this registration as a minimal `device.json` that libfreenect reads.
    pub fn to_device_json(&self) -> String {
        serde_json::json!({
            "reg_info": {
                "zero_plane_info": {
                    "dcmos_emitter_distance": self.dcmos_emitter_distance,
                    "dcmos_rcmos_distance": 2.3,
                    "reference_distance": self.reference_distance,
                    "reference_pixel_size": self.reference_pixel_size,
                },
                "pad_info": {"start_lines": 0, "end_lines": 0, "cropping_lines": 0},
            },
            "const_shift": self.const_shift,
        })
        .to_string()
    }
}

/// A lookup table from raw 11-bit disparity to millimetres (0 = no data).
#[derive(Debug, Clone)]
pub struct RawToMm {
    table: Box<[u16; RAW_CODES]>,
}

impl RawToMm {
    /// The table libfreenect builds from a device's registration
    /// (`freenect_raw_to_mm`, integer division and truncation as in the C code).
    pub fn from_registration(reg: &Registration) -> Self {
        let mut table = Box::new([0u16; RAW_CODES]);
        for (raw, slot) in table.iter_mut().enumerate() {
            let param_coeff = 4i64;
            // C: ((raw - paramCoeff*const_shift) / paramCoeff) is integer division.
            let shifted = (raw as i64 - param_coeff * i64::from(reg.const_shift)) / param_coeff;
            let fixed_ref_x = shifted as f64 - 0.375;
            let metric = fixed_ref_x * reg.reference_pixel_size;
            let mm = 10.0
                * (metric * reg.reference_distance / (reg.dcmos_emitter_distance - metric)
                    + reg.reference_distance);
            *slot = clamp_mm(mm);
        }
        table[RAW_NO_DATA as usize] = 0;
        RawToMm { table }
    }

    /// The standard Kinect v1 fit, for sessions without `device.json`.
    pub fn standard() -> Self {
        let mut table = Box::new([0u16; RAW_CODES]);
        for (raw, slot) in table.iter_mut().enumerate() {
            let denom = 3.330_949_516_1 - 0.003_071_101_6 * raw as f64;
            *slot = if denom > 0.0 {
                clamp_mm((1000.0 / denom).round())
            } else {
                0
            };
        }
        table[RAW_NO_DATA as usize] = 0;
        RawToMm { table }
    }

    /// Millimetres for one raw value; anything outside the 11-bit range is no data.
    #[inline]
    pub fn convert(&self, raw: u16) -> u16 {
        self.table.get(raw as usize).copied().unwrap_or(0)
    }

    /// The raw value whose millimetres are nearest to `mm` (for writing sessions);
    /// `RAW_NO_DATA` for 0 or a depth the table cannot express.
    pub fn raw_for_mm(&self, mm: u16) -> u16 {
        if mm == 0 {
            return RAW_NO_DATA;
        }
        let mut best = (u32::MAX, RAW_NO_DATA);
        for (raw, &v) in self.table.iter().enumerate() {
            if v == 0 {
                continue;
            }
            let d = (i32::from(v) - i32::from(mm)).unsigned_abs();
            if d < best.0 {
                best = (d, raw as u16);
            }
        }
        best.1
    }
}

fn clamp_mm(mm: f64) -> u16 {
    if mm.is_finite() && mm > 0.0 && mm <= f64::from(MAX_MM) {
        mm as u16 // truncation, as C's conversion to uint16_t
    } else {
        0
    }
}

/// Accelerometer counts per g (the Kionix KXSD9 in the Kinect, as libfreenect's
/// `FREENECT_COUNTS_PER_G`).
pub const COUNTS_PER_G: f64 = 819.0;
/// Standard gravity, m/s² (libfreenect's `GRAVITY`).
pub const GRAVITY: f64 = 9.80665;
/// Size of libfreenect's `freenect_raw_tilt_state` as `record` dumps it: three
/// `int16_t`, an `int8_t`, one byte of padding, an `int` status.
pub const TILT_DUMP_BYTES: usize = 12;

/// The Kinect's tilt state: raw accelerometer counts and the motor's state, as in an
/// `a-*.dump` file (libfreenect's `freenect_raw_tilt_state`).
///
/// Axes (the Kinect's, as the Kinect for Windows SDK documents them): right-handed, y
/// up, z along the optical axis, x to the camera's left. A level, still Kinect reads
/// about 819 counts (1 g) on y.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TiltState {
    /// Raw accelerometer x, y, z, counts ([`COUNTS_PER_G`] per g).
    pub accel: [i16; 3],
    /// The tilt motor's raw angle.
    pub tilt_angle: i8,
    /// `freenect_tilt_status_code`: 0 stopped, 1 at limit, 4 moving.
    pub tilt_status: i32,
}

impl TiltState {
    /// The accelerometer in m/s² (libfreenect's `freenect_get_mks_accel`).
    pub fn accel_mps2(&self) -> [f64; 3] {
        self.accel.map(|c| f64::from(c) / COUNTS_PER_G * GRAVITY)
    }

    /// Decode an `a-*.dump` file's bytes (little-endian, as recorded on x86 and ARM).
    pub fn from_dump(bytes: &[u8], path: &Path) -> Result<Self, DriverError> {
        if bytes.len() != TILT_DUMP_BYTES {
            return Err(DriverError::malformed(
                path,
                format!(
                    "a tilt-state dump is {TILT_DUMP_BYTES} bytes, this one {}",
                    bytes.len()
                ),
            ));
        }
        let i16_at = |i: usize| i16::from_le_bytes([bytes[i], bytes[i + 1]]);
        Ok(TiltState {
            accel: [i16_at(0), i16_at(2), i16_at(4)],
            tilt_angle: bytes[6] as i8,
            tilt_status: i32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]),
        })
    }

    /// The bytes `record` writes for this state.
    pub fn to_dump(&self) -> [u8; TILT_DUMP_BYTES] {
        let mut b = [0u8; TILT_DUMP_BYTES];
        for (i, c) in self.accel.iter().enumerate() {
            b[2 * i..2 * i + 2].copy_from_slice(&c.to_le_bytes());
        }
        b[6] = self.tilt_angle as u8;
        b[8..12].copy_from_slice(&self.tilt_status.to_le_bytes());
        b
    }
}

/// One tilt-state entry of a session's index.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TiltEntry {
    /// Wall-clock time of the reading at recording, seconds.
    pub time_s: f64,
    /// The state read.
    pub state: TiltState,
}

/// One colour entry of a session's index.
#[derive(Debug, Clone, PartialEq)]
pub struct ColourEntry {
    /// The frame file (`r-*.ppm`).
    pub path: PathBuf,
    /// Wall-clock time of arrival at recording, seconds.
    pub time_s: f64,
    /// The Kinect's own frame timestamp.
    pub timestamp: u32,
}

/// Decode a binary PPM (`P6 W H 255`, as libfreenect's `record` writes colour) into
/// `frame`.
pub fn decode_ppm(
    bytes: &[u8],
    path: &Path,
    frame: &mut crate::ColourFrame,
) -> Result<(), DriverError> {
    let bad = |what: &str| DriverError::malformed(path, what.to_string());
    // Header: four whitespace-separated tokens, then one whitespace byte.
    let mut tokens = Vec::with_capacity(4);
    let mut i = 0;
    while tokens.len() < 4 {
        while i < bytes.len() && bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        let start = i;
        while i < bytes.len() && !bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        if start == i {
            return Err(bad("truncated PPM header"));
        }
        tokens.push(&bytes[start..i]);
    }
    if tokens[0] != b"P6" {
        return Err(bad("not a binary PPM (P6)"));
    }
    let num = |t: &[u8]| {
        std::str::from_utf8(t)
            .ok()
            .and_then(|s| s.parse::<usize>().ok())
    };
    let (w, h, max) = match (num(tokens[1]), num(tokens[2]), num(tokens[3])) {
        (Some(w), Some(h), Some(m)) => (w, h, m),
        _ => return Err(bad("PPM header has a non-numeric size")),
    };
    if max != 255 {
        return Err(bad("only 8-bit PPM (maxval 255) is supported"));
    }
    if w == 0 || h == 0 || w > crate::MAX_WIDTH || h > crate::MAX_HEIGHT {
        return Err(DriverError::malformed(
            path,
            format!("PPM size {w}x{h} is out of range"),
        ));
    }
    let data = &bytes[(i + 1).min(bytes.len())..];
    if data.len() < w * h * 3 {
        return Err(DriverError::malformed(
            path,
            format!("truncated: {} of {} pixel bytes", data.len(), w * h * 3),
        ));
    }
    frame.reshape(w, h).copy_from_slice(&data[..w * h * 3]);
    Ok(())
}

/// One depth entry of a session's index.
#[derive(Debug, Clone, PartialEq)]
pub struct DepthEntry {
    /// The frame file.
    pub path: PathBuf,
    /// Wall-clock time of arrival at recording, seconds.
    pub time_s: f64,
    /// The Kinect's own frame timestamp.
    pub timestamp: u32,
}

/// An opened fakenect session: its depth frames and how to convert them.
#[derive(Debug, Clone)]
pub struct Session {
    dir: PathBuf,
    depth: Vec<DepthEntry>,
    tilt: Vec<TiltEntry>,
    colour: Vec<ColourEntry>,
    registration: Option<Registration>,
    to_mm: RawToMm,
}

impl Session {
    /// Whether `dir` looks like a session (has an `INDEX.txt`).
    pub fn is_session(dir: &Path) -> bool {
        dir.join("INDEX.txt").is_file()
    }

    /// Open a session: parse `INDEX.txt`, check every listed file exists, read
    /// `device.json` if present.
    pub fn open(dir: &Path) -> Result<Self, DriverError> {
        let index = dir.join("INDEX.txt");
        let text = std::fs::read_to_string(&index).map_err(|e| DriverError::io(&index, e))?;
        let mut depth = Vec::new();
        let mut tilt = Vec::new();
        let mut colour = Vec::new();
        for (n, line) in text.lines().enumerate() {
            let name = line.trim();
            if name.is_empty() {
                continue;
            }
            let (kind, time_s, timestamp) = parse_entry_name(name).ok_or_else(|| {
                DriverError::malformed(
                    &index,
                    format!(
                        "line {}: {name:?} is not <d|r|a>-<seconds>-<timestamp>.<ext>",
                        n + 1
                    ),
                )
            })?;
            let path = dir.join(name);
            if !path.is_file() {
                return Err(DriverError::MissingFile {
                    path,
                    index: index.clone(),
                });
            }
            match kind {
                'd' => depth.push(DepthEntry {
                    path,
                    time_s,
                    timestamp,
                }),
                'r' => colour.push(ColourEntry {
                    path,
                    time_s,
                    timestamp,
                }),
                'a' => {
                    let bytes = std::fs::read(&path).map_err(|e| DriverError::io(&path, e))?;
                    tilt.push(TiltEntry {
                        time_s,
                        state: TiltState::from_dump(&bytes, &path)?,
                    });
                }
                _ => {}
            }
        }
        if depth.is_empty() {
            return Err(DriverError::Empty {
                path: dir.to_path_buf(),
            });
        }
        let device = dir.join("device.json");
        let registration = if device.is_file() {
            let text = std::fs::read_to_string(&device).map_err(|e| DriverError::io(&device, e))?;
            Some(Registration::from_device_json(&text, &device)?)
        } else {
            None
        };
        let to_mm = registration
            .as_ref()
            .map_or_else(RawToMm::standard, RawToMm::from_registration);
        Ok(Session {
            dir: dir.to_path_buf(),
            depth,
            tilt,
            colour,
            registration,
            to_mm,
        })
    }

    /// The session directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The depth frames, in arrival order.
    pub fn depth_entries(&self) -> &[DepthEntry] {
        &self.depth
    }

    /// The tilt-state readings, in arrival order.
    pub fn tilt_entries(&self) -> &[TiltEntry] {
        &self.tilt
    }

    /// The last tilt state read at or before `time_s` (the first one if all are
    /// later), as fakenect replays them; `None` if the session has none.
    pub fn tilt_at(&self, time_s: f64) -> Option<&TiltState> {
        let after = self.tilt.partition_point(|e| e.time_s <= time_s);
        self.tilt.get(after.saturating_sub(1)).map(|e| &e.state)
    }

    /// The colour frames, in arrival order.
    pub fn colour_entries(&self) -> &[ColourEntry] {
        &self.colour
    }

    /// The last colour frame recorded at or before `time_s` (the first if all are
    /// later); `None` if the session has no colour.
    pub fn colour_at(&self, time_s: f64) -> Option<&ColourEntry> {
        let after = self.colour.partition_point(|e| e.time_s <= time_s);
        self.colour.get(after.saturating_sub(1))
    }

    /// Read colour frame `entry` into `frame`.
    pub fn read_colour(
        &self,
        entry: &ColourEntry,
        scratch: &mut Vec<u8>,
        frame: &mut crate::ColourFrame,
    ) -> Result<(), DriverError> {
        read_file_into(&entry.path, scratch)?;
        decode_ppm(scratch, &entry.path, frame)?;
        frame.timestamp_s = entry.time_s;
        Ok(())
    }

    /// The registration from `device.json`, if the session has one.
    pub fn registration(&self) -> Option<&Registration> {
        self.registration.as_ref()
    }

    /// Read depth frame `i` into `frame`, converted to millimetres.
    pub fn read_depth(
        &self,
        i: usize,
        scratch: &mut Vec<u8>,
        frame: &mut DepthFrame,
    ) -> Result<(), DriverError> {
        let entry = &self.depth[i];
        read_file_into(&entry.path, scratch)?;
        decode_pgm_depth(scratch, ByteOrder::LittleEndian, &entry.path, frame)?;
        for p in frame.pixels_mut() {
            *p = self.to_mm.convert(*p);
        }
        frame.timestamp_s = entry.time_s;
        Ok(())
    }
}

/// Parse `d-1290000000.123456-123456.pgm` into ('d', seconds, timestamp).
fn parse_entry_name(name: &str) -> Option<(char, f64, u32)> {
    let mut chars = name.chars();
    let kind = chars.next()?;
    if !matches!(kind, 'd' | 'r' | 'a') || chars.next()? != '-' {
        return None;
    }
    let rest = &name[2..];
    let (stem, _ext) = rest.rsplit_once('.')?;
    let (time, stamp) = stem.rsplit_once('-')?;
    let time_s: f64 = time.parse().ok()?;
    let timestamp: u32 = stamp.parse().ok()?;
    time_s.is_finite().then_some((kind, time_s, timestamp))
}

/// Writes a session exactly as libfreenect's `record` does (depth frames and tilt
/// states, plus `device.json` when a registration is given).
#[derive(Debug)]
pub struct SessionWriter {
    dir: PathBuf,
    index: String,
    to_raw: Vec<u16>,
}

impl SessionWriter {
    /// Start a session in `dir` (created if needed; an existing `INDEX.txt` is an
    /// error, as in libfreenect's recorder).
    pub fn create(dir: &Path, registration: Option<Registration>) -> Result<Self, DriverError> {
        std::fs::create_dir_all(dir).map_err(|e| DriverError::io(dir, e))?;
        let index = dir.join("INDEX.txt");
        if index.exists() {
            return Err(DriverError::malformed(
                &index,
                "index already exists; use a different directory",
            ));
        }
        let to_mm = match &registration {
            Some(reg) => {
                let path = dir.join("device.json");
                std::fs::write(&path, reg.to_device_json())
                    .map_err(|e| DriverError::io(&path, e))?;
                RawToMm::from_registration(reg)
            }
            None => RawToMm::standard(),
        };
        let to_raw = (0..=MAX_MM).map(|mm| to_mm.raw_for_mm(mm)).collect();
        Ok(SessionWriter {
            dir: dir.to_path_buf(),
            index: String::new(),
            to_raw,
        })
    }

    /// Append one colour frame (an `r-*.ppm`, `P6 W H 255` and RGB bytes).
    pub fn write_colour(
        &mut self,
        frame: &crate::ColourFrame,
        time_s: f64,
        timestamp: u32,
    ) -> Result<(), DriverError> {
        let name = format!("r-{time_s:.6}-{timestamp}.ppm");
        let mut bytes = format!("P6 {} {} 255\n", frame.width(), frame.height()).into_bytes();
        bytes.extend_from_slice(frame.rgb());
        let path = self.dir.join(&name);
        std::fs::write(&path, bytes).map_err(|e| DriverError::io(&path, e))?;
        self.append(&name)
    }

    /// Append one tilt state (an `a-*.dump`) with its time and the timestamp of the
    /// last depth frame, as `record` does.
    pub fn write_tilt(
        &mut self,
        state: &TiltState,
        time_s: f64,
        timestamp: u32,
    ) -> Result<(), DriverError> {
        let name = format!("a-{time_s:.6}-{timestamp}.dump");
        let path = self.dir.join(&name);
        std::fs::write(&path, state.to_dump()).map_err(|e| DriverError::io(&path, e))?;
        self.append(&name)
    }

    fn append(&mut self, name: &str) -> Result<(), DriverError> {
        self.index.push_str(name);
        self.index.push('\n');
        let index = self.dir.join("INDEX.txt");
        std::fs::write(&index, &self.index).map_err(|e| DriverError::io(&index, e))
    }

    /// Append one depth frame (millimetres) with its arrival time and timestamp;
    /// returns the frame file's name.
    pub fn write_depth(
        &mut self,
        frame: &DepthFrame,
        time_s: f64,
        timestamp: u32,
    ) -> Result<String, DriverError> {
        let name = format!("d-{time_s:.6}-{timestamp}.pgm");
        let mut bytes = format!("P5 {} {} 65535\n", frame.width(), frame.height()).into_bytes();
        for &mm in frame.pixels() {
            let raw = self.to_raw.get(mm as usize).copied().unwrap_or(RAW_NO_DATA);
            bytes.extend_from_slice(&raw.to_le_bytes());
        }
        let path = self.dir.join(&name);
        std::fs::write(&path, bytes).map_err(|e| DriverError::io(&path, e))?;
        self.append(&name)?;
        Ok(name)
    }

    /// Record the controller's odometry (PROTOCOL.md's 8 bytes) with the depth frame
    /// file `frame_file`, in the session's `odometry.txt`.
    pub fn write_odometry(&mut self, frame_file: &str, bytes: &[u8; 8]) -> Result<(), DriverError> {
        use std::io::Write;
        let path = self.dir.join(crate::odometry_file::FILE_NAME);
        let mut f = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .map_err(|e| DriverError::io(&path, e))?;
        f.write_all(crate::odometry_file::line(frame_file, bytes).as_bytes())
            .map_err(|e| DriverError::io(&path, e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn libfreenect_table_is_monotonic_and_plausible() {
        let t = RawToMm::from_registration(&Registration::LIBFREENECT_DEFAULT);
        assert_eq!(t.convert(RAW_NO_DATA), 0);
        assert_eq!(t.convert(4000), 0);
        // Known points of the Kinect curve: raw ~ 600 is about 0.6-0.7 m, ~ 900 about 1.6 m.
        let (a, b) = (t.convert(600), t.convert(900));
        assert!((550..750).contains(&a), "{a}");
        assert!((1300..2000).contains(&b), "{b}");
        let mut last = 0;
        for raw in 500..1000 {
            let v = t.convert(raw);
            assert!(v >= last, "not monotonic at {raw}");
            last = v;
        }
    }

    #[test]
    fn standard_fit_matches_published_points() {
        let t = RawToMm::standard();
        // 1000/(3.3309495161-0.0030711016*800) = 1144.07 mm
        assert_eq!(t.convert(800), 1144);
        assert_eq!(t.convert(1100), 0);
    }

    #[test]
    fn raw_for_mm_inverts_within_a_code_step() {
        let t = RawToMm::from_registration(&Registration::LIBFREENECT_DEFAULT);
        for mm in [700u16, 1000, 1500, 2500, 3500] {
            let back = t.convert(t.raw_for_mm(mm));
            let step = 1.0e-5 * f64::from(mm) * f64::from(mm) + 3.0; // ~quantisation step
            assert!(
                (f64::from(back) - f64::from(mm)).abs() <= step,
                "{mm} -> {back}"
            );
        }
        assert_eq!(t.raw_for_mm(0), RAW_NO_DATA);
    }

    #[test]
    fn tilt_dumps_round_trip_and_replay_by_time() {
        let dir = tempfile::tempdir().unwrap();
        let mut w = SessionWriter::create(dir.path(), None).unwrap();
        let frame = DepthFrame::from_pixels(2, 1, vec![1000, 1000]);
        let level = TiltState {
            accel: [0, 819, 0],
            tilt_angle: 0,
            tilt_status: 0,
        };
        let tilted = TiltState {
            accel: [-12, 627, -526],
            tilt_angle: -60,
            tilt_status: 4,
        };
        w.write_depth(&frame, 10.0, 1).unwrap();
        w.write_tilt(&level, 10.01, 1).unwrap();
        w.write_depth(&frame, 10.1, 2).unwrap();
        w.write_tilt(&tilted, 10.11, 2).unwrap();
        let s = Session::open(dir.path()).unwrap();
        assert_eq!(s.tilt_entries().len(), 2);
        assert_eq!(s.tilt_at(9.0), Some(&level), "before any: the first");
        assert_eq!(s.tilt_at(10.05), Some(&level));
        assert_eq!(s.tilt_at(10.2), Some(&tilted));
        let g = level.accel_mps2();
        assert!((g[1] - GRAVITY).abs() < 1e-12 && g[0] == 0.0);
        let name = std::fs::read_to_string(dir.path().join("INDEX.txt")).unwrap();
        assert!(name.contains("a-10.110000-2.dump"), "{name}");
        let bytes = std::fs::read(dir.path().join("a-10.110000-2.dump")).unwrap();
        assert_eq!(bytes.len(), TILT_DUMP_BYTES);
        assert_eq!(
            TiltState::from_dump(&bytes, Path::new("x")).unwrap(),
            tilted
        );
        // A dump of the wrong size names the file.
        std::fs::write(dir.path().join("a-10.110000-2.dump"), [0u8; 5]).unwrap();
        let e = Session::open(dir.path()).unwrap_err().to_string();
        assert!(
            e.contains("a-10.110000-2.dump") && e.contains("12 bytes"),
            "{e}"
        );
    }

    #[test]
    fn colour_frames_round_trip_and_bad_ones_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let mut w = SessionWriter::create(dir.path(), None).unwrap();
        let depth = DepthFrame::from_pixels(2, 1, vec![1000, 1000]);
        let mut colour = crate::ColourFrame::default();
        colour.reshape(2, 1).copy_from_slice(&[1, 2, 3, 4, 5, 6]);
        w.write_depth(&depth, 5.0, 1).unwrap();
        w.write_colour(&colour, 5.01, 1).unwrap();
        let s = Session::open(dir.path()).unwrap();
        assert_eq!(s.colour_entries().len(), 1);
        let e = s.colour_at(6.0).unwrap().clone();
        let mut back = crate::ColourFrame::default();
        s.read_colour(&e, &mut Vec::new(), &mut back).unwrap();
        assert_eq!(
            (back.width(), back.height(), back.rgb()),
            (2, 1, &[1u8, 2, 3, 4, 5, 6][..])
        );
        let p = Path::new("r.ppm");
        for (bytes, why) in [
            (&b"P6 2 1 255\n\x01\x02"[..], "truncated"),
            (&b"P5 2 1 255\n\x01\x02\x03\x04\x05\x06"[..], "P6"),
            (&b"P6 2 1 65535\n"[..], "maxval"),
            (&b"P6 2"[..], "header"),
            (&b"P6 0 1 255\n"[..], "out of range"),
        ] {
            let e = decode_ppm(bytes, p, &mut back).unwrap_err().to_string();
            assert!(e.contains("r.ppm") && e.contains(why), "{e}");
        }
    }

    #[test]
    fn entry_names() {
        assert_eq!(
            parse_entry_name("d-1294706818.473542-12345.pgm"),
            Some(('d', 1294706818.473542, 12345))
        );
        assert_eq!(parse_entry_name("x-1-2.pgm"), None);
        assert_eq!(parse_entry_name("d-abc-2.pgm"), None);
        assert_eq!(parse_entry_name("d-1.0-2"), None);
    }

    #[test]
    fn device_json_round_trip_and_errors() {
        let reg = Registration::LIBFREENECT_DEFAULT;
        let p = Path::new("device.json");
        assert_eq!(
            Registration::from_device_json(&reg.to_device_json(), p).unwrap(),
            reg
        );
        let e = Registration::from_device_json("{", p)
            .unwrap_err()
            .to_string();
        assert!(e.contains("invalid JSON"), "{e}");
        let e = Registration::from_device_json("{}", p)
            .unwrap_err()
            .to_string();
        assert!(e.contains("zero_plane_info"), "{e}");
    }
}
