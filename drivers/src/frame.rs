/// Largest accepted frame width in pixels; anything wider is rejected as absurd before
/// any buffer is sized from it.
pub const MAX_WIDTH: usize = 4096;
/// Largest accepted frame height in pixels.
pub const MAX_HEIGHT: usize = 4096;

/// One depth image: row-major `u16` millimetres along the optical axis, `0` = no return.
///
/// The pixel buffer is allocated once (see [`DepthFrame::with_capacity`]) and reused:
/// refilling a frame of the same or smaller size never allocates.
#[derive(Debug, Clone, Default)]
pub struct DepthFrame {
    width: usize,
    height: usize,
    depth_mm: Vec<u16>,
    /// Sequence number given by the source, counting from 0.
    pub seq: u64,
    /// Capture time in seconds, in the source's own clock (a recording's timestamps,
    /// or seconds since the source started).
    pub timestamp_s: f64,
    /// The motor controller's odometry message recorded with this frame (the 8
    /// bytes of PROTOCOL.md's odometry layout), for replayed drives; `None` from live
    /// cameras and from recordings without odometry.
    pub odometry: Option<[u8; 8]>,
}

impl DepthFrame {
    /// An empty frame whose buffer can hold `width × height` pixels without allocating.
    pub fn with_capacity(width: usize, height: usize) -> Self {
        DepthFrame {
            width: 0,
            height: 0,
            depth_mm: Vec::with_capacity(width.min(MAX_WIDTH) * height.min(MAX_HEIGHT)),
            seq: 0,
            timestamp_s: 0.0,
            odometry: None,
        }
    }

    /// A frame filled from a slice (tests, generated scenes).
    ///
    /// # Panics
    /// If `depth_mm.len() != width * height`.
    pub fn from_pixels(width: usize, height: usize, depth_mm: Vec<u16>) -> Self {
        assert_eq!(
            depth_mm.len(),
            width * height,
            "pixel count must be width*height"
        );
        DepthFrame {
            width,
            height,
            depth_mm,
            seq: 0,
            timestamp_s: 0.0,
            odometry: None,
        }
    }

    /// Resize to `width × height` (all pixels zero) and return the pixels to fill.
    /// Allocates only if the buffer's capacity is too small. The caller has checked
    /// the size against [`MAX_WIDTH`]/[`MAX_HEIGHT`].
    pub fn reshape(&mut self, width: usize, height: usize) -> &mut [u16] {
        debug_assert!(width <= MAX_WIDTH && height <= MAX_HEIGHT);
        self.width = width;
        self.height = height;
        self.depth_mm.clear();
        self.depth_mm.resize(width * height, 0);
        &mut self.depth_mm
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The pixels, row-major, millimetres, `0` = no return.
    pub fn pixels(&self) -> &[u16] {
        &self.depth_mm
    }

    /// The pixels, mutable (noise models, fault injection).
    pub fn pixels_mut(&mut self) -> &mut [u16] {
        &mut self.depth_mm
    }
}

/// One colour image: row-major 8-bit RGB, 3 bytes a pixel. Like [`DepthFrame`], its
/// buffer is allocated once and reused.
#[derive(Debug, Clone, Default)]
pub struct ColourFrame {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
    /// Sequence number given by the source.
    pub seq: u64,
    /// Capture time in seconds, in the source's own clock.
    pub timestamp_s: f64,
}

impl ColourFrame {
    /// An empty frame whose buffer holds `width × height` pixels without allocating.
    pub fn with_capacity(width: usize, height: usize) -> Self {
        ColourFrame {
            rgb: Vec::with_capacity(width.min(MAX_WIDTH) * height.min(MAX_HEIGHT) * 3),
            ..ColourFrame::default()
        }
    }

    /// Resize to `width × height` (all black) and return the bytes to fill. The
    /// caller has checked the size against [`MAX_WIDTH`]/[`MAX_HEIGHT`].
    pub fn reshape(&mut self, width: usize, height: usize) -> &mut [u8] {
        debug_assert!(width <= MAX_WIDTH && height <= MAX_HEIGHT);
        self.width = width;
        self.height = height;
        self.rgb.clear();
        self.rgb.resize(width * height * 3, 0);
        &mut self.rgb
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The pixels, row-major `[r, g, b]` bytes.
    pub fn rgb(&self) -> &[u8] {
        &self.rgb
    }
}
