use rover_terrain_drivers::DriverError;

/// Everything the rover-terrain library can fail with.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The configuration is invalid; the message names the file, key and line.
    #[error("config: {message}")]
    Config {
        /// What is wrong, where.
        message: String,
    },
    /// A depth source failed (bad file, missing frame, ...).
    #[error(transparent)]
    Driver(#[from] DriverError),
    /// A frame's size is not what the camera is configured to deliver.
    #[error("frame {seq}: size {got_w}×{got_h}, but [camera] expects {want_w}×{want_h}")]
    FrameSize {
        /// The frame's sequence number.
        seq: u64,
        /// Its width, pixels.
        got_w: usize,
        /// Its height, pixels.
        got_h: usize,
        /// The configured width, pixels.
        want_w: usize,
        /// The configured height, pixels.
        want_h: usize,
    },
    /// The configuration is valid but cannot work (e.g. the camera sees no corridor).
    #[error("setup: {0}")]
    Setup(String),
    /// A fixture of the validation suite is malformed.
    #[error("fixture {path}: {message}")]
    Fixture {
        /// The fixture file.
        path: std::path::PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// A link to the motor controller failed or is misconfigured.
    #[error("link {target}: {message}")]
    Link {
        /// The link, as given (`serial:/dev/ttyUSB0`, ...).
        target: String,
        /// What went wrong.
        message: String,
    },
    /// Writing an output file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: std::path::PathBuf,
        /// What the OS said.
        source: std::io::Error,
    },
}
