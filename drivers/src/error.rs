use std::path::PathBuf;

/// Everything a depth source can fail with. Each variant names the file or device.
#[derive(Debug, thiserror::Error)]
pub enum DriverError {
    /// The file could not be opened or read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the OS said.
        source: std::io::Error,
    },
    /// The file was read but its content is not a valid depth frame or session.
    #[error("{path}: {what}")]
    Malformed {
        /// The file.
        path: PathBuf,
        /// What is wrong with it, in words.
        what: String,
    },
    /// A directory or session holds no depth frame at all.
    #[error("{path}: no depth frames found (expected .pgm/.png images or a fakenect INDEX.txt)")]
    Empty {
        /// The directory.
        path: PathBuf,
    },
    /// A file listed in a fakenect `INDEX.txt` does not exist.
    #[error("{path}: listed in {index} but missing")]
    MissingFile {
        /// The missing frame file.
        path: PathBuf,
        /// The index that lists it.
        index: PathBuf,
    },
    /// No camera at all, or not the one asked for.
    #[error("{0}")]
    NoDevice(String),
    /// The camera stopped delivering (unplugged, USB error, recording ended).
    #[error("camera disconnected: {0}")]
    Disconnected(String),
    /// No frame within the camera's timeout.
    #[error("no frame from {camera} within {timeout_ms} ms")]
    Timeout {
        /// The camera.
        camera: String,
        /// The timeout, ms.
        timeout_ms: u64,
    },
    /// A camera argument that names no known camera.
    #[error("camera {spec:?}: {why}")]
    BadSpec {
        /// The argument as given.
        spec: String,
        /// What is wrong.
        why: String,
    },
    /// The input path does not exist or is neither a file nor a directory.
    #[error("{path}: no such file or directory")]
    NotFound {
        /// The path as given.
        path: PathBuf,
    },
}

impl DriverError {
    pub(crate) fn malformed(path: &std::path::Path, what: impl Into<String>) -> Self {
        DriverError::Malformed {
            path: path.to_path_buf(),
            what: what.into(),
        }
    }

    pub(crate) fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        DriverError::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}
