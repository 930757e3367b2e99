use std::path::{Path, PathBuf};

use crate::fakenect::Session;
use crate::image::{read_depth_image, ImageKind};
use crate::{DepthCamera, DepthFrame, DriverError, FrameStatus};

/// Frame period assumed for plain image sequences, seconds (a Kinect's 30 Hz).
pub const IMAGE_SEQUENCE_PERIOD_S: f64 = 1.0 / 30.0;

#[derive(Debug)]
enum Source {
    Images(Vec<PathBuf>),
    Session(Session),
}

/// The file-backed camera: replays one depth image, a directory of images (in name
/// order), or a libfreenect `fakenect` session, as fast as it is asked.
///
/// Deterministic: the same input gives the same frames, sequence numbers and
/// timestamps every time.
#[derive(Debug)]
pub struct FakeCamera {
    source: Source,
    label: String,
    next: usize,
    seq: u64,
    looping: bool,
    scratch: Vec<u8>,
    last: Option<usize>,
}

impl FakeCamera {
    /// Open `path`: a `.pgm`/`.png` file, a directory of them, or a fakenect session
    /// directory (one with `INDEX.txt`). Every frame file is checked to exist now;
    /// frame contents are checked as each frame is read.
    pub fn open(path: &Path) -> Result<Self, DriverError> {
        let source = if path.is_file() {
            if ImageKind::of(path).is_none() {
                return Err(DriverError::Malformed {
                    path: path.to_path_buf(),
                    what: "unknown image type (expected .pgm or .png)".into(),
                });
            }
            Source::Images(vec![path.to_path_buf()])
        } else if path.is_dir() {
            if Session::is_session(path) {
                Source::Session(Session::open(path)?)
            } else {
                let entries = std::fs::read_dir(path).map_err(|e| DriverError::Io {
                    path: path.to_path_buf(),
                    source: e,
                })?;
                let mut images = Vec::new();
                for entry in entries {
                    let entry = entry.map_err(|e| DriverError::Io {
                        path: path.to_path_buf(),
                        source: e,
                    })?;
                    let p = entry.path();
                    if p.is_file() && ImageKind::of(&p).is_some() {
                        images.push(p);
                    }
                }
                if images.is_empty() {
                    return Err(DriverError::Empty {
                        path: path.to_path_buf(),
                    });
                }
                images.sort();
                Source::Images(images)
            }
        } else {
            return Err(DriverError::NotFound {
                path: path.to_path_buf(),
            });
        };
        Ok(FakeCamera {
            source,
            label: format!("fake:{}", path.display()),
            next: 0,
            seq: 0,
            looping: false,
            scratch: Vec::new(),
            last: None,
        })
    }

    /// Start again from the first frame after the last one, instead of ending.
    pub fn looping(mut self, looping: bool) -> Self {
        self.looping = looping;
        self
    }

    /// Number of depth frames in one pass.
    pub fn len(&self) -> usize {
        match &self.source {
            Source::Images(v) => v.len(),
            Source::Session(s) => s.depth_entries().len(),
        }
    }

    /// Whether there are no frames (never true for an opened camera).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The file of the frame last delivered.
    pub fn last_path(&self) -> Option<&Path> {
        let i = self.last?;
        Some(match &self.source {
            Source::Images(v) => &v[i],
            Source::Session(s) => &s.depth_entries()[i].path,
        })
    }
}

impl DepthCamera for FakeCamera {
    fn start(&mut self) -> Result<(), DriverError> {
        Ok(())
    }

    fn stop(&mut self) -> Result<(), DriverError> {
        Ok(())
    }

    fn next_frame(&mut self, frame: &mut DepthFrame) -> Result<FrameStatus, DriverError> {
        if self.next >= self.len() {
            if !self.looping {
                return Ok(FrameStatus::EndOfStream);
            }
            self.next = 0;
        }
        let i = self.next;
        self.next += 1;
        self.last = Some(i);
        match &self.source {
            Source::Images(v) => {
                read_depth_image(&v[i], &mut self.scratch, frame)?;
                frame.timestamp_s = self.seq as f64 * IMAGE_SEQUENCE_PERIOD_S;
            }
            Source::Session(s) => s.read_depth(i, &mut self.scratch, frame)?,
        }
        frame.seq = self.seq;
        self.seq += 1;
        Ok(FrameStatus::Frame)
    }

    fn describe(&self) -> String {
        self.label.clone()
    }

    fn last_source(&self) -> Option<&Path> {
        self.last_path()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fakenect::{Registration, SessionWriter};
    use crate::image::encode_png_depth;

    #[test]
    fn image_directory_in_name_order_then_end() {
        let dir = tempfile::tempdir().unwrap();
        for (name, v) in [("b.png", 2u16), ("a.png", 1), ("c.txt", 9)] {
            let f = DepthFrame::from_pixels(2, 1, vec![v, v]);
            std::fs::write(dir.path().join(name), encode_png_depth(&f)).unwrap();
        }
        let mut cam = FakeCamera::open(dir.path()).unwrap();
        assert_eq!(cam.len(), 2);
        let mut f = DepthFrame::with_capacity(2, 1);
        assert_eq!(cam.next_frame(&mut f).unwrap(), FrameStatus::Frame);
        assert_eq!((f.pixels()[0], f.seq), (1, 0));
        assert_eq!(cam.next_frame(&mut f).unwrap(), FrameStatus::Frame);
        assert_eq!((f.pixels()[0], f.seq), (2, 1));
        assert_eq!(cam.next_frame(&mut f).unwrap(), FrameStatus::EndOfStream);
    }

    #[test]
    fn looping_restarts_and_keeps_counting() {
        let dir = tempfile::tempdir().unwrap();
        let f = DepthFrame::from_pixels(1, 1, vec![5]);
        std::fs::write(dir.path().join("a.png"), encode_png_depth(&f)).unwrap();
        let mut cam = FakeCamera::open(&dir.path().join("a.png"))
            .unwrap()
            .looping(true);
        let mut f = DepthFrame::default();
        for seq in 0..3 {
            assert_eq!(cam.next_frame(&mut f).unwrap(), FrameStatus::Frame);
            assert_eq!(f.seq, seq);
        }
    }

    #[test]
    fn empty_missing_and_unknown_inputs_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let e = FakeCamera::open(dir.path()).unwrap_err();
        assert!(matches!(e, DriverError::Empty { .. }), "{e}");
        let e = FakeCamera::open(&dir.path().join("nope")).unwrap_err();
        assert!(matches!(e, DriverError::NotFound { .. }), "{e}");
        std::fs::write(dir.path().join("x.jpg"), b"jpeg").unwrap();
        let e = FakeCamera::open(&dir.path().join("x.jpg")).unwrap_err();
        assert!(e.to_string().contains("x.jpg"), "{e}");
    }

    #[test]
    fn session_replays_in_millimetres_with_recorded_times() {
        let dir = tempfile::tempdir().unwrap();
        let reg = Registration::LIBFREENECT_DEFAULT;
        let mut w = SessionWriter::create(dir.path(), Some(reg)).unwrap();
        let mut frame =
            DepthFrame::from_pixels(4, 2, vec![0, 800, 1000, 1500, 2000, 2500, 3000, 0]);
        w.write_depth(&frame, 100.5, 7).unwrap();
        frame.pixels_mut()[0] = 900;
        w.write_depth(&frame, 100.6, 8).unwrap();

        let mut cam = FakeCamera::open(dir.path()).unwrap();
        assert_eq!(cam.len(), 2);
        let mut f = DepthFrame::default();
        cam.next_frame(&mut f).unwrap();
        assert_eq!(f.timestamp_s, 100.5);
        assert_eq!(f.pixels()[0], 0, "no data stays no data");
        for (got, want) in f.pixels().iter().zip(frame.pixels()).skip(1) {
            if *want == 0 {
                assert_eq!(*got, 0);
            } else {
                // Within one disparity step of the Kinect at that range.
                let step = 1.0e-5 * f64::from(*want).powi(2) + 3.0;
                assert!(
                    (f64::from(*got) - f64::from(*want)).abs() <= step,
                    "{got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn session_with_missing_file_names_it() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("INDEX.txt"), "d-1.000000-1.pgm\n").unwrap();
        let e = FakeCamera::open(dir.path()).unwrap_err().to_string();
        assert!(
            e.contains("d-1.000000-1.pgm") && e.contains("INDEX.txt"),
            "{e}"
        );
    }

    #[test]
    fn session_with_bad_index_line_or_truncated_frame() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("INDEX.txt"), "garbage line\n").unwrap();
        let e = FakeCamera::open(dir.path()).unwrap_err().to_string();
        assert!(e.contains("line 1"), "{e}");

        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("INDEX.txt"), "d-1.0-1.pgm\n").unwrap();
        std::fs::write(
            dir.path().join("d-1.0-1.pgm"),
            b"P5 640 480 65535\n\x01\x02",
        )
        .unwrap();
        let mut cam = FakeCamera::open(dir.path()).unwrap();
        let e = cam
            .next_frame(&mut DepthFrame::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("d-1.0-1.pgm") && e.contains("truncated"), "{e}");
    }

    #[test]
    fn session_with_only_colour_frames_is_empty() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("INDEX.txt"), "r-1.0-1.ppm\n").unwrap();
        std::fs::write(dir.path().join("r-1.0-1.ppm"), b"P6 1 1 255\n\0\0\0").unwrap();
        let e = FakeCamera::open(dir.path()).unwrap_err();
        assert!(matches!(e, DriverError::Empty { .. }), "{e}");
    }
}
