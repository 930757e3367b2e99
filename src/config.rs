//! The service configuration: a TOML file where every key has a default (the paper's
//! rover and a Kinect v1), so a file may set any subset. `config/rover-terrain.toml`
//! documents every key. Angles are degrees, lengths metres.

use std::path::Path;

use serde::Deserialize;

use crate::Error;

/// The whole configuration.
#[derive(Debug, Clone, PartialEq, Default, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Config {
    /// The depth camera's image and optics.
    pub camera: CameraConfig,
    /// Where the camera sits on the rover.
    pub mount: MountConfig,
    /// The rover's geometry and climbing limits.
    pub rover: RoverConfig,
    /// Voxel grid and analysis parameters.
    pub analysis: AnalysisConfig,
    /// Where verdicts go (`run`).
    pub link: LinkConfig,
    /// The service loop: timeouts, heartbeat, metrics, logging (`run`).
    pub service: ServiceConfig,
    /// Terrain memory: frames fused over the controller's odometry.
    pub memory: MemoryConfig,
    /// ROS 2 / Foxglove output: the TF frame names.
    pub ros: RosConfig,
}

/// `[ros]`: how the analysis is named for ROS 2 tooling and Foxglove (`--mcap`).
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct RosConfig {
    /// The rover body frame of the TF tree (REP 103: x forward, y left, z up).
    pub base_frame: String,
    /// The depth camera's optical frame (REP 103 optical: z forward, x right, y down).
    pub camera_frame: String,
}

impl Default for RosConfig {
    fn default() -> Self {
        RosConfig {
            base_frame: "base_link".into(),
            camera_frame: "camera_depth_optical_frame".into(),
        }
    }
}

impl RosConfig {
    /// `[ros]`: frame names non-empty, without spaces, and not the same.
    fn check(&self) -> Result<(), Invalid> {
        for (key, v) in [
            ("ros.base_frame", &self.base_frame),
            ("ros.camera_frame", &self.camera_frame),
        ] {
            if v.is_empty() || v.chars().any(char::is_whitespace) {
                return Err((
                    key,
                    format!("{v:?}: a TF frame name, non-empty, without spaces"),
                ));
            }
        }
        if self.base_frame == self.camera_frame {
            return Err(("ros.camera_frame", "must differ from ros.base_frame".into()));
        }
        Ok(())
    }
}

/// `[memory]`: the rover-centred height map that keeps what the camera saw as it
/// passes out of view, moved with the controller's odometry.
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct MemoryConfig {
    /// Fuse frames over odometry. Off: every verdict from its own frame alone.
    pub enabled: bool,
    /// A remembered cell not seen again within this much travel is forgotten, metres.
    pub max_travel_m: f64,
    /// A remembered cell not seen again within this time is forgotten, seconds.
    pub max_age_s: f64,
    /// Frames that must have seen a cell (at a consistent height) before it is
    /// remembered once out of view: one noisy frame is never remembered.
    pub min_frames: u32,
    /// The map reaches this far behind the rover origin, metres (at least to the
    /// rear axle, for reversing).
    pub behind_m: f64,
    /// No odometry for this long and the verdicts fall back to single frames, seconds.
    pub odometry_timeout_s: f64,
    /// Odometry that implies more than this speed is a jump, not motion: fall back,
    /// m/s.
    pub max_speed_mps: f64,
    /// Odometry that implies more than this turn rate is a jump: fall back, °/s.
    pub max_turn_dps: f64,
    /// A rover that has not moved (under 1 cm) since a verdict last reported a hazard
    /// holds that hazard for this long after it, seconds, however few verdicts
    /// reported it: another frame from the same place only rolls the sensor's noise
    /// again, and cannot clear what it found. 0: off (a hazard one verdict reported
    /// is gone at the next that misses it, standing or not).
    pub standing_hold_s: f64,
}

impl Default for MemoryConfig {
    fn default() -> Self {
        MemoryConfig {
            enabled: true,
            max_travel_m: 1.5,
            max_age_s: 30.0,
            min_frames: 2,
            behind_m: 0.8,
            odometry_timeout_s: 0.5,
            max_speed_mps: 2.0,
            max_turn_dps: 90.0,
            standing_hold_s: 1.0,
        }
    }
}

impl MemoryConfig {
    /// `[memory]`: lengths, times and limits positive and finite.
    fn check(&self) -> Result<(), Invalid> {
        positive("memory.max_travel_m", self.max_travel_m)?;
        positive("memory.max_age_s", self.max_age_s)?;
        within("memory.min_frames", self.min_frames, 1, 1000)?;
        positive_below("memory.behind_m", self.behind_m, 10.0)?;
        positive_below("memory.odometry_timeout_s", self.odometry_timeout_s, 30.0)?;
        positive_below("memory.max_speed_mps", self.max_speed_mps, 50.0)?;
        positive_below("memory.max_turn_dps", self.max_turn_dps, 3600.0)?;
        finite("memory.standing_hold_s", self.standing_hold_s)?;
        within("memory.standing_hold_s", self.standing_hold_s, 0.0, 30.0)?;
        Ok(())
    }
}

/// `[link]`: where `run` sends verdicts.
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct LinkConfig {
    /// `serial:PATH`, `slcan:PATH`, `can:IFACE` or `stdout` (JSON lines).
    pub target: String,
    /// Serial speed for `serial:` and `slcan:` links, baud.
    pub baud: u32,
}

impl Default for LinkConfig {
    fn default() -> Self {
        LinkConfig {
            target: "stdout".into(),
            baud: crate::link::DEFAULT_BAUD,
        }
    }
}

/// `[service]`: the `run` loop.
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct ServiceConfig {
    /// No frame for this long and the verdict is "unknown" (the controller stops), ms.
    pub frame_timeout_ms: u64,
    /// Heartbeat period, ms; while no frames arrive, an "unknown" verdict is sent
    /// every period too.
    pub heartbeat_ms: u64,
    /// Period of the metrics log line and the systemd STATUS, seconds.
    pub stats_interval_s: u64,
    /// Frame buffers allocated at start and reused (camera, queue, analysis), 3..=16.
    pub pool_frames: u32,
    /// Log level when RUST_LOG is not set: off, error, warn, info, debug or trace.
    pub log_level: String,
    /// A recorded source (`fake:`) starts again at its end instead of ending the run.
    pub loop_replay: bool,
}

impl Default for ServiceConfig {
    fn default() -> Self {
        ServiceConfig {
            frame_timeout_ms: 250,
            heartbeat_ms: 100,
            stats_interval_s: 5,
            pool_frames: 3,
            log_level: "info".into(),
            loop_replay: false,
        }
    }
}

/// `[camera]`: the image the camera is expected to deliver and how pixels map to rays.
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct CameraConfig {
    /// Expected image width, pixels.
    pub width: u32,
    /// Expected image height, pixels.
    pub height: u32,
    /// Horizontal field of view, degrees (the paper's model, eq. 1-4).
    pub hfov_deg: f64,
    /// Vertical field of view, degrees.
    pub vfov_deg: f64,
    /// Depths nearer than this are discarded, metres.
    pub min_range_m: f64,
    /// Depths farther than this are discarded, metres.
    pub max_range_m: f64,
    /// Pinhole focal length along u, pixels; with fy, cx, cy replaces the FOV model.
    pub fx: Option<f64>,
    /// Pinhole focal length along v, pixels.
    pub fy: Option<f64>,
    /// Pinhole principal point u, pixels.
    pub cx: Option<f64>,
    /// Pinhole principal point v, pixels.
    pub cy: Option<f64>,
    /// The camera `run` reads: `freenect[:INDEX]`, `v4l:PATH` (or `v4l:NAME`),
    /// `fake:PATH` or `mcap:PATH[#TOPIC]` (a ROS 2 bag); unset = the bundled fixtures through the fake camera.
    pub source: Option<String>,
    /// Frame rate asked of a V4L2 camera, frames per second.
    pub fps: u32,
    /// Millimetres per unit of a V4L2 camera's Z16/Y16 pixels (RealSense D4xx: 1.0).
    pub depth_scale_mm: f64,
}

/// `[mount]`: the camera's pose in the rover body frame (REP 103: x forward, y left,
/// z up, origin on the ground).
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct MountConfig {
    /// Forward offset of the camera, metres.
    pub x_m: f64,
    /// Left offset of the camera, metres.
    pub y_m: f64,
    /// Height of the camera above the ground, metres.
    pub z_m: f64,
    /// Roll about the forward axis, degrees (positive = left side up).
    pub roll_deg: f64,
    /// Pitch, degrees (positive = looking down).
    pub pitch_deg: f64,
    /// Yaw, degrees (positive = looking left).
    pub yaw_deg: f64,
    /// Use the camera's accelerometer (Kinect) for pitch and roll instead of
    /// `pitch_deg` and `roll_deg`, which stay the values until a reading arrives.
    pub auto_level: bool,
}

/// `[rover]`: the rover's geometry and what it can climb.
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct RoverConfig {
    /// Wheel radius, metres: a step higher than this is impassable.
    pub wheel_radius_m: f64,
    /// Belly clearance, metres: anything taller under the belly is impassable.
    pub belly_clearance_m: f64,
    /// Steepest slope the wheels can climb, degrees.
    pub max_slope_deg: f64,
    /// Half-width of the band under the belly, metres (|y| below it).
    pub belly_half_width_m: f64,
    /// Outer edge of the wheel tracks, metres (tracks span belly_half_width..this).
    pub track_outer_m: f64,
    /// Front axle to rear axle, metres: the span the predicted pitch is taken over.
    pub wheelbase_m: f64,
    /// Largest predicted body roll the rover may meet, degrees; beyond it a `tilt`
    /// hazard stops it. `None` (the default): roll is predicted and reported only.
    pub max_roll_deg: Option<f64>,
    /// Largest predicted body pitch the rover may meet, degrees; beyond it a `tilt`
    /// hazard stops it. `None` (the default): pitch is predicted and reported only.
    pub max_pitch_deg: Option<f64>,
}

/// `[analysis]`: voxel grid and analysis parameters.
#[derive(Debug, Clone, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct AnalysisConfig {
    /// Voxel edge, metres.
    pub voxel_m: f64,
    /// Length of the analysed corridor ahead of the rover origin, metres.
    pub corridor_length_m: f64,
    /// Lowest height kept in the voxel grid, metres.
    pub z_min_m: f64,
    /// Highest height kept in the voxel grid, metres.
    pub z_max_m: f64,
    /// Height above or below the ground that counts as a rise or fall, metres.
    pub rise_threshold_m: f64,
    /// A toe line more than this off the lateral axis is "diagonal", degrees.
    pub diagonal_min_deg: f64,
    /// Fewer points than this in a ground cell and the cell counts as unseen.
    pub min_points_per_cell: u32,
    /// Below this fraction of the visible corridor seen, the verdict is unknown.
    pub min_seen_fraction: f64,
    /// Unseen cells in a row along a strip that make a gap (drop-off or unknown).
    pub gap_min_cells: u32,
    /// A depth pixel whose two neighbours along a row or column lie within this angle
    /// of its line of sight, one in front and one behind, is a mixed ("flying")
    /// pixel at a depth edge and is not binned ([`crate::mixed_pixels`]), degrees in
    /// [0, 45); 0 bins every pixel.
    pub mixed_pixel_angle_deg: f64,
}

impl Default for CameraConfig {
    fn default() -> Self {
        CameraConfig {
            width: 640,
            height: 480,
            hfov_deg: 57.0,
            vfov_deg: 43.0,
            min_range_m: 0.4,
            max_range_m: 4.5,
            fx: None,
            fy: None,
            cx: None,
            cy: None,
            source: None,
            fps: 30,
            depth_scale_mm: 1.0,
        }
    }
}

impl Default for MountConfig {
    fn default() -> Self {
        MountConfig {
            x_m: 0.0,
            y_m: 0.0,
            z_m: 0.8,
            roll_deg: 0.0,
            pitch_deg: 30.0,
            yaw_deg: 0.0,
            auto_level: false,
        }
    }
}

impl Default for RoverConfig {
    fn default() -> Self {
        RoverConfig {
            wheel_radius_m: 0.11,
            belly_clearance_m: 0.32,
            max_slope_deg: 30.0,
            belly_half_width_m: 0.2,
            track_outer_m: 0.7,
            wheelbase_m: 0.6,
            max_roll_deg: None,
            max_pitch_deg: None,
        }
    }
}

impl Default for AnalysisConfig {
    fn default() -> Self {
        AnalysisConfig {
            voxel_m: 0.05,
            corridor_length_m: 3.0,
            z_min_m: -1.5,
            z_max_m: 2.0,
            rise_threshold_m: 0.03,
            diagonal_min_deg: 8.0,
            min_points_per_cell: 3,
            min_seen_fraction: 0.5,
            gap_min_cells: 2,
            // Mixed pixels at an edge lie within about 1° of the line of sight; ground
            // seen from 0.5 m at 3.5 m meets it at 8°, depth noise of a few
            // quantisation steps is a surface at 15° or more. At 3° and more, rough
            // descents seen at grazing incidence lost enough points to show gaps.
            mixed_pixel_angle_deg: 2.5,
        }
    }
}

/// Largest voxel grid accepted, in voxels (keeps a bad config from eating memory).
pub const MAX_VOXELS: usize = 16 * 1024 * 1024;

impl Config {
    /// Parse and validate TOML text; `origin` names the file in errors.
    pub fn from_toml(text: &str, origin: &str) -> Result<Self, Error> {
        let config: Config = toml::from_str(text).map_err(|e| Error::Config {
            message: format!("{origin}: {}", e.to_string().trim_end()),
        })?;
        config.validate().map_err(|(key, why)| {
            let line = find_key_line(text, key)
                .map(|l| format!(", line {l}"))
                .unwrap_or_default();
            Error::Config {
                message: format!("{origin}{line}: {key}: {why}"),
            }
        })?;
        Ok(config)
    }

    /// Read, parse and validate a config file.
    pub fn load(path: &Path) -> Result<Self, Error> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::Config {
            message: format!("{}: {e}", path.display()),
        })?;
        Self::from_toml(&text, &path.display().to_string())
    }

    /// What a live camera is asked for: `[camera]` width, height, fps, depth scale.
    pub fn camera_options(&self) -> rover_terrain_drivers::CameraOptions {
        rover_terrain_drivers::CameraOptions {
            width: self.camera.width,
            height: self.camera.height,
            fps: self.camera.fps,
            depth_scale_mm: self.camera.depth_scale_mm as f32,
        }
    }

    /// Size the camera to what the source says of its own optics (a ROS 2 bag's image
    /// size and `CameraInfo`): width and height, and the pinhole intrinsics when it has
    /// them (replacing `fx`, `fy`, `cx`, `cy`). Returns what changed, for the log;
    /// `None` when nothing did.
    pub fn apply_intrinsics(&mut self, k: &rover_terrain_drivers::Intrinsics) -> Option<String> {
        let c = &mut self.camera;
        let before = (c.width, c.height, c.fx, c.fy, c.cx, c.cy);
        c.width = u32::try_from(k.width).unwrap_or(u32::MAX);
        c.height = u32::try_from(k.height).unwrap_or(u32::MAX);
        if let Some((fx, fy, cx, cy)) = k.pinhole {
            (c.fx, c.fy, c.cx, c.cy) = (Some(fx), Some(fy), Some(cx), Some(cy));
        }
        let after = (c.width, c.height, c.fx, c.fy, c.cx, c.cy);
        (after != before).then(|| match k.pinhole {
            Some((fx, fy, cx, cy)) => format!(
                "camera from the source: {}x{}, pinhole fx {fx:.2} fy {fy:.2} cx {cx:.2} cy {cy:.2} px (replacing [camera])",
                k.width, k.height
            ),
            None => format!(
                "camera from the source: {}x{} (no calibration: [camera] field of view kept)",
                k.width, k.height
            ),
        })
    }

    /// The camera's intrinsics for `width × height` images, as a pinhole: the
    /// configured fx/fy/cx/cy scaled to that size, or the FOV model's equivalent
    /// (fx = w / 2 / tan(hfov / 2), principal point at the image centre).
    pub fn intrinsics_for(&self, width: usize, height: usize) -> rover_terrain_drivers::Intrinsics {
        let c = &self.camera;
        let (w, h) = (f64::from(c.width), f64::from(c.height));
        let pinhole = self.pinhole().unwrap_or_else(|| {
            (
                w / 2.0 / (c.hfov_deg.to_radians() / 2.0).tan(),
                h / 2.0 / (c.vfov_deg.to_radians() / 2.0).tan(),
                w / 2.0,
                h / 2.0,
            )
        });
        rover_terrain_drivers::Intrinsics {
            width: c.width as usize,
            height: c.height as usize,
            pinhole: Some(pinhole),
        }
        .scaled_to(width, height)
    }

    /// Whether the camera uses pinhole intrinsics rather than the FOV model.
    pub fn pinhole(&self) -> Option<(f64, f64, f64, f64)> {
        let c = &self.camera;
        match (c.fx, c.fy, c.cx, c.cy) {
            (Some(fx), Some(fy), Some(cx), Some(cy)) => Some((fx, fy, cx, cy)),
            _ => None,
        }
    }

    /// Check every value; on failure, the dotted key and what is wrong. Section by
    /// section, in file order, then what spans sections (the grid's size).
    pub fn validate(&self) -> Result<(), Invalid> {
        self.camera.check()?;
        self.mount.check()?;
        self.rover.check()?;
        self.analysis.check()?;
        self.link.check()?;
        self.service.check()?;
        self.memory.check()?;
        self.ros.check()?;
        self.check_grid()
    }

    /// The voxel grid the corridor needs fits, and a voxel is narrower than the belly band.
    fn check_grid(&self) -> Result<(), Invalid> {
        let (a, r) = (&self.analysis, &self.rover);
        let cells = |len: f64| (len / a.voxel_m).ceil();
        let voxels = cells(a.corridor_length_m)
            * cells(2.0 * r.track_outer_m)
            * cells(a.z_max_m - a.z_min_m);
        if voxels > MAX_VOXELS as f64 {
            return Err((
            "analysis.voxel_m",
            format!("the voxel grid would hold {voxels:.0} voxels (at most {MAX_VOXELS}); use larger voxels or a shorter corridor"),
        ));
        }
        if a.voxel_m > r.belly_half_width_m {
            return Err((
                "analysis.voxel_m",
                format!(
                    "must not exceed rover.belly_half_width_m ({})",
                    r.belly_half_width_m
                ),
            ));
        }
        Ok(())
    }
}

/// A failed check: the dotted key and what is wrong with its value.
pub type Invalid = (&'static str, String);

fn finite(key: &'static str, v: f64) -> Result<(), Invalid> {
    if v.is_finite() {
        Ok(())
    } else {
        Err((key, format!("must be a finite number, got {v}")))
    }
}

fn positive(key: &'static str, v: f64) -> Result<(), Invalid> {
    finite(key, v)?;
    if v > 0.0 {
        Ok(())
    } else {
        Err((key, format!("must be positive, got {v}")))
    }
}

/// Positive and below `limit` (an angle short of a right or straight one).
fn positive_below(key: &'static str, v: f64, limit: f64) -> Result<(), Invalid> {
    positive(key, v)?;
    if v < limit {
        Ok(())
    } else {
        Err((key, format!("must be below {limit}, got {v}")))
    }
}

impl CameraConfig {
    /// `[camera]`: image size, fields of view, range limits, intrinsics, source, rate.
    fn check(&self) -> Result<(), Invalid> {
        let c = self;
        if c.width == 0 || c.width as usize > rover_terrain_drivers::MAX_WIDTH {
            return Err((
                "camera.width",
                format!(
                    "must be 1..={}, got {}",
                    rover_terrain_drivers::MAX_WIDTH,
                    c.width
                ),
            ));
        }
        if c.height == 0 || c.height as usize > rover_terrain_drivers::MAX_HEIGHT {
            return Err((
                "camera.height",
                format!(
                    "must be 1..={}, got {}",
                    rover_terrain_drivers::MAX_HEIGHT,
                    c.height
                ),
            ));
        }
        for (key, fov) in [
            ("camera.hfov_deg", c.hfov_deg),
            ("camera.vfov_deg", c.vfov_deg),
        ] {
            positive_below(key, fov, 180.0)?;
        }
        positive("camera.min_range_m", c.min_range_m)?;
        positive("camera.max_range_m", c.max_range_m)?;
        if c.min_range_m >= c.max_range_m {
            return Err((
                "camera.min_range_m",
                format!(
                    "must be below camera.max_range_m ({} >= {})",
                    c.min_range_m, c.max_range_m
                ),
            ));
        }
        let pin = [
            ("camera.fx", c.fx),
            ("camera.fy", c.fy),
            ("camera.cx", c.cx),
            ("camera.cy", c.cy),
        ];
        let given = pin.iter().filter(|(_, v)| v.is_some()).count();
        if given != 0 && given != 4 {
            let missing = pin
                .iter()
                .find(|(_, v)| v.is_none())
                .map(|(k, _)| *k)
                .unwrap_or("camera.fx");
            return Err((
                missing,
                "pinhole intrinsics need all of fx, fy, cx, cy".into(),
            ));
        }
        for (key, v) in pin {
            if let Some(v) = v {
                finite(key, v)?;
            }
        }
        if let (Some(fx), Some(fy)) = (c.fx, c.fy) {
            positive("camera.fx", fx)?;
            positive("camera.fy", fy)?;
        }
        if let Some(src) = &c.source {
            if let Err(e) = src.parse::<rover_terrain_drivers::CameraSpec>() {
                return Err(("camera.source", e.to_string()));
            }
        }
        within("camera.fps", c.fps, 1, 240)?;
        positive("camera.depth_scale_mm", c.depth_scale_mm)?;
        Ok(())
    }
}

impl MountConfig {
    /// `[mount]`: finite offsets, a camera above the ground, angles within ±90°.
    fn check(&self) -> Result<(), Invalid> {
        let m = self;
        for (key, v) in [
            ("mount.x_m", m.x_m),
            ("mount.y_m", m.y_m),
            ("mount.roll_deg", m.roll_deg),
            ("mount.pitch_deg", m.pitch_deg),
            ("mount.yaw_deg", m.yaw_deg),
        ] {
            finite(key, v)?;
        }
        positive("mount.z_m", m.z_m)?;
        for (key, v) in [
            ("mount.roll_deg", m.roll_deg),
            ("mount.pitch_deg", m.pitch_deg),
            ("mount.yaw_deg", m.yaw_deg),
        ] {
            if v.abs() > 90.0 {
                return Err((key, format!("must be within ±90, got {v}")));
            }
        }
        Ok(())
    }
}

impl RoverConfig {
    /// Centre line of the left wheel track, metres (the right one's is its mirror):
    /// midway between the belly band's edge and the track's outer edge.
    pub fn track_centre_m(&self) -> f64 {
        0.5 * (self.belly_half_width_m + self.track_outer_m)
    }

    /// `[rover]`: positive sizes, slopes and tilt limits below 90°, tracks outside the belly band.
    fn check(&self) -> Result<(), Invalid> {
        let r = self;
        positive("rover.wheel_radius_m", r.wheel_radius_m)?;
        positive("rover.belly_clearance_m", r.belly_clearance_m)?;
        positive_below("rover.max_slope_deg", r.max_slope_deg, 90.0)?;
        positive("rover.belly_half_width_m", r.belly_half_width_m)?;
        positive("rover.track_outer_m", r.track_outer_m)?;
        if r.track_outer_m <= r.belly_half_width_m {
            return Err((
                "rover.track_outer_m",
                format!(
                    "must exceed rover.belly_half_width_m ({} <= {})",
                    r.track_outer_m, r.belly_half_width_m
                ),
            ));
        }
        positive("rover.wheelbase_m", r.wheelbase_m)?;
        for (key, v) in [
            ("rover.max_roll_deg", r.max_roll_deg),
            ("rover.max_pitch_deg", r.max_pitch_deg),
        ] {
            if let Some(v) = v {
                positive_below(key, v, 90.0)?;
            }
        }
        Ok(())
    }
}

impl AnalysisConfig {
    /// `[analysis]`: positive voxel and corridor, a height range, thresholds in range.
    fn check(&self) -> Result<(), Invalid> {
        let a = self;
        positive("analysis.voxel_m", a.voxel_m)?;
        positive("analysis.corridor_length_m", a.corridor_length_m)?;
        finite("analysis.z_min_m", a.z_min_m)?;
        finite("analysis.z_max_m", a.z_max_m)?;
        if a.z_min_m >= a.z_max_m {
            return Err((
                "analysis.z_min_m",
                format!(
                    "must be below analysis.z_max_m ({} >= {})",
                    a.z_min_m, a.z_max_m
                ),
            ));
        }
        positive("analysis.rise_threshold_m", a.rise_threshold_m)?;
        finite("analysis.diagonal_min_deg", a.diagonal_min_deg)?;
        if !(0.0..90.0).contains(&a.diagonal_min_deg) {
            return Err((
                "analysis.diagonal_min_deg",
                format!("must be within 0..90, got {}", a.diagonal_min_deg),
            ));
        }
        if a.min_points_per_cell == 0 {
            return Err(("analysis.min_points_per_cell", "must be at least 1".into()));
        }
        finite("analysis.min_seen_fraction", a.min_seen_fraction)?;
        if !(0.0..=1.0).contains(&a.min_seen_fraction) {
            return Err((
                "analysis.min_seen_fraction",
                format!("must be within 0..=1, got {}", a.min_seen_fraction),
            ));
        }
        if a.gap_min_cells == 0 {
            return Err(("analysis.gap_min_cells", "must be at least 1".into()));
        }
        finite("analysis.mixed_pixel_angle_deg", a.mixed_pixel_angle_deg)?;
        if !(0.0..45.0).contains(&a.mixed_pixel_angle_deg) {
            return Err((
                "analysis.mixed_pixel_angle_deg",
                format!("must be within 0..45, got {}", a.mixed_pixel_angle_deg),
            ));
        }
        Ok(())
    }
}

impl LinkConfig {
    /// `[link]`: a target that parses, a positive baud rate.
    fn check(&self) -> Result<(), Invalid> {
        if let Err(e) = self.target.parse::<crate::link::LinkTarget>() {
            return Err(("link.target", e.to_string()));
        }
        if self.baud == 0 {
            return Err(("link.baud", "must be positive".into()));
        }
        Ok(())
    }
}

impl ServiceConfig {
    /// `[service]`: timings and pool size in range, a known log level.
    fn check(&self) -> Result<(), Invalid> {
        let sv = self;
        within("service.frame_timeout_ms", sv.frame_timeout_ms, 10, 60_000)?;
        within("service.heartbeat_ms", sv.heartbeat_ms, 10, 10_000)?;
        within("service.stats_interval_s", sv.stats_interval_s, 1, 3600)?;
        within("service.pool_frames", sv.pool_frames, 3, 16)?;
        if sv.log_level.parse::<log::LevelFilter>().is_err() {
            return Err((
                "service.log_level",
                format!(
                    "must be off, error, warn, info, debug or trace, got {:?}",
                    sv.log_level
                ),
            ));
        }
        Ok(())
    }
}

/// `Ok` if `v` is within `lo..=hi`, else the key and the range it must be in.
fn within<T: PartialOrd + std::fmt::Display>(
    key: &'static str,
    v: T,
    lo: T,
    hi: T,
) -> Result<(), (&'static str, String)> {
    if v >= lo && v <= hi {
        Ok(())
    } else {
        Err((key, format!("must be {lo}..={hi}, got {v}")))
    }
}

/// The 1-based line where `section.key` is set in `text`, if it is set there.
fn find_key_line(text: &str, dotted: &str) -> Option<usize> {
    let (section, key) = dotted.split_once('.')?;
    let mut current = "";
    for (n, line) in text.lines().enumerate() {
        let t = line.trim();
        if let Some(rest) = t.strip_prefix('[') {
            current = rest.split(']').next().unwrap_or("").trim();
            continue;
        }
        if current == section {
            if let Some((k, _)) = t.split_once('=') {
                if k.trim() == key {
                    return Some(n + 1);
                }
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        Config::from_toml(text, "test.toml")
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn empty_file_is_the_default() {
        assert_eq!(Config::from_toml("", "x").unwrap(), Config::default());
    }

    #[test]
    fn subset_overrides_only_what_it_sets() {
        let c = Config::from_toml("[mount]\npitch_deg = 40\n", "x").unwrap();
        assert_eq!(c.mount.pitch_deg, 40.0);
        assert_eq!(c.mount.z_m, 0.8);
        assert_eq!(c.rover, RoverConfig::default());
    }

    #[test]
    fn bad_values_name_the_key_and_line() {
        let e = err("[camera]\nwidth = 640\nhfov_deg = 180\n");
        assert!(e.contains("line 3") && e.contains("camera.hfov_deg"), "{e}");
        let e = err("[analysis]\n\nvoxel_m = -0.05\n");
        assert!(
            e.contains("line 3") && e.contains("analysis.voxel_m") && e.contains("positive"),
            "{e}"
        );
        let e = err("[camera]\nmin_range_m = 5\nmax_range_m = 4\n");
        assert!(
            e.contains("camera.min_range_m") && e.contains("line 2"),
            "{e}"
        );
        let e = err("[rover]\nwheel_radius_m = 0\n");
        assert!(e.contains("rover.wheel_radius_m"), "{e}");
        let e = err("[camera]\nfx = 500\n");
        assert!(e.contains("pinhole"), "{e}");
        let e = err("[analysis]\nvoxel_m = 0.0001\n");
        assert!(e.contains("voxels"), "{e}");
        let e = err("[analysis]\nmin_seen_fraction = 1.5\n");
        assert!(e.contains("analysis.min_seen_fraction"), "{e}");
        for bad in ["45", "-1", "nan"] {
            let e = err(&format!("[analysis]\nmixed_pixel_angle_deg = {bad}\n"));
            assert!(e.contains("analysis.mixed_pixel_angle_deg"), "{bad}: {e}");
        }
        let off = Config::from_toml("[analysis]\nmixed_pixel_angle_deg = 0\n", "x").unwrap();
        assert_eq!(off.analysis.mixed_pixel_angle_deg, 0.0);
        let e = err("[camera]\nhfov_deg = nan\n");
        assert!(e.contains("finite"), "{e}");
        let e = err("[camera]\nsource = \"webcam:0\"\n");
        assert!(e.contains("camera.source") && e.contains("line 2"), "{e}");
        let e = err("[link]\ntarget = \"udp:1.2.3.4\"\n");
        assert!(e.contains("link.target") && e.contains("line 2"), "{e}");
        let e = err("[service]\nframe_timeout_ms = 0\n");
        assert!(e.contains("service.frame_timeout_ms"), "{e}");
        let e = err("[service]\npool_frames = 1\n");
        assert!(e.contains("service.pool_frames"), "{e}");
        let e = err("[service]\nlog_level = \"loud\"\n");
        assert!(e.contains("service.log_level"), "{e}");
        let e = err("[camera]\ndepth_scale_mm = -1\n");
        assert!(e.contains("camera.depth_scale_mm"), "{e}");
        let e = err("[rover]\nmax_roll_deg = 90\n");
        assert!(
            e.contains("rover.max_roll_deg") && e.contains("line 2"),
            "{e}"
        );
        let e = err("[rover]\nmax_pitch_deg = -5\n");
        assert!(e.contains("rover.max_pitch_deg"), "{e}");
        let e = err("[rover]\nwheelbase_m = 0\n");
        assert!(e.contains("rover.wheelbase_m"), "{e}");
        let c = Config::from_toml("[rover]\nmax_roll_deg = 12.5\n", "x").unwrap();
        assert_eq!(
            (c.rover.max_roll_deg, c.rover.max_pitch_deg),
            (Some(12.5), None)
        );
    }

    #[test]
    fn memory_keys_are_checked() {
        for (text, key) in [
            (
                "[memory]
max_travel_m = 0
",
                "memory.max_travel_m",
            ),
            (
                "[memory]
max_age_s = nan
",
                "memory.max_age_s",
            ),
            (
                "[memory]
min_frames = 0
",
                "memory.min_frames",
            ),
            (
                "[memory]
odometry_timeout_s = 60
",
                "memory.odometry_timeout_s",
            ),
            (
                "[memory]
max_speed_mps = -1
",
                "memory.max_speed_mps",
            ),
            (
                "[memory]
max_turn_dps = inf
",
                "memory.max_turn_dps",
            ),
            (
                "[memory]
standing_hold_s = -0.5
",
                "memory.standing_hold_s",
            ),
            (
                "[memory]
standing_hold_s = nan
",
                "memory.standing_hold_s",
            ),
            (
                "[memory]
standing_hold_s = 31
",
                "memory.standing_hold_s",
            ),
            (
                "[ros]
base_frame = \"\"
",
                "ros.base_frame",
            ),
            (
                "[ros]
camera_frame = \"base_link\"
",
                "ros.camera_frame",
            ),
            (
                "[memory]
behind_m = 0
",
                "memory.behind_m",
            ),
        ] {
            let e = err(text);
            assert!(e.contains(key), "{text}: {e}");
        }
        let c = Config::from_toml(
            "[memory]
enabled = false
",
            "x",
        )
        .unwrap();
        assert!(!c.memory.enabled);
        assert!(Config::default().memory.enabled);
    }

    #[test]
    fn each_section_checks_its_own_keys() {
        let key = |r: Result<(), Invalid>| r.unwrap_err().0;
        let d = Config::default();
        assert!(d.camera.check().is_ok() && d.mount.check().is_ok());
        assert!(d.rover.check().is_ok() && d.analysis.check().is_ok());
        assert!(d.link.check().is_ok() && d.service.check().is_ok());
        let mut c = d.camera.clone();
        c.fx = Some(400.0);
        assert_eq!(key(c.check()), "camera.fy");
        let mut m = d.mount.clone();
        m.yaw_deg = 91.0;
        assert_eq!(key(m.check()), "mount.yaw_deg");
        let mut r = d.rover.clone();
        r.track_outer_m = 0.1;
        assert_eq!(key(r.check()), "rover.track_outer_m");
        let mut a = d.analysis.clone();
        a.z_max_m = a.z_min_m;
        assert_eq!(key(a.check()), "analysis.z_min_m");
        let mut l = d.link.clone();
        l.baud = 0;
        assert_eq!(key(l.check()), "link.baud");
        let mut sv = d.service.clone();
        sv.pool_frames = 40;
        assert_eq!(key(sv.check()), "service.pool_frames");
        // Across sections: a grid too big for the memory it is given.
        let mut g = d.clone();
        g.analysis.voxel_m = 0.001;
        assert_eq!(key(g.check_grid()), "analysis.voxel_m");
    }

    #[test]
    fn unknown_keys_wrong_types_and_syntax_errors_name_the_place() {
        let e = err("[camera]\nwidht = 640\n");
        assert!(e.contains("widht") && e.contains("line 2"), "{e}");
        let e = err("[camera]\nwidth = \"wide\"\n");
        assert!(e.contains("width") && e.contains("line 2"), "{e}");
        let e = err("[camera\n");
        assert!(e.contains("line 1"), "{e}");
        let e = err("[sonar]\nx = 1\n");
        assert!(e.contains("sonar"), "{e}");
    }

    #[test]
    fn the_documented_config_file_is_valid_and_is_the_default() {
        let text = include_str!("../config/rover-terrain.toml");
        assert_eq!(
            Config::from_toml(text, "config/rover-terrain.toml").unwrap(),
            Config::default()
        );
    }
}
