//! Raw FFI to libfreenect 0.5 (`libfreenect.h`), only what rover-terrain uses.
//!
//! Written by hand (the registry has no maintained sys crate; `freenectrs` hands out a
//! slice into libfreenect's frame buffer that outlives it). Every function is declared
//! exactly as in the header; `freenect_frame_mode` and `freenect_raw_tilt_state` are
//! `#[repr(C)]` copies of the header's structs, checked by size in the tests.
#![allow(non_camel_case_types)]
#![deny(missing_docs)]

use std::os::raw::{c_char, c_double, c_int, c_void};

/// Opaque library context.
#[repr(C)]
pub struct freenect_context {
    _private: [u8; 0],
}

/// Opaque device handle.
#[repr(C)]
pub struct freenect_device {
    _private: [u8; 0],
}

/// `freenect_resolution`: VGA.
pub const FREENECT_RESOLUTION_MEDIUM: c_int = 1;
/// `freenect_depth_format`: raw 11-bit disparity, one `u16` per pixel.
pub const FREENECT_DEPTH_11BIT: c_int = 0;
/// `freenect_depth_format`: millimetres, not registered to the RGB image.
pub const FREENECT_DEPTH_MM: c_int = 5;
/// `freenect_device_flags`: the motor and accelerometer.
pub const FREENECT_DEVICE_MOTOR: c_int = 0x01;
/// `FREENECT_VIDEO_RGB`: 8-bit RGB, 3 bytes a pixel.
pub const FREENECT_VIDEO_RGB: c_int = 0;
/// `freenect_device_flags`: the cameras.
pub const FREENECT_DEVICE_CAMERA: c_int = 0x02;
/// Accelerometer counts per g.
pub const FREENECT_COUNTS_PER_G: c_int = 819;
/// `freenect_loglevel` values, FATAL (0) to FLOOD (7).
pub const FREENECT_LOG_WARNING: c_int = 2;
/// Log level INFO.
pub const FREENECT_LOG_INFO: c_int = 4;

/// `freenect_frame_mode`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct freenect_frame_mode {
    /// Internal id.
    pub reserved: u32,
    /// `freenect_resolution`.
    pub resolution: c_int,
    /// `freenect_video_format` or `freenect_depth_format` (a union of ints).
    pub format: i32,
    /// Bytes in one frame.
    pub bytes: i32,
    /// Width, pixels.
    pub width: i16,
    /// Height, pixels.
    pub height: i16,
    /// Bits of data per pixel.
    pub data_bits_per_pixel: i8,
    /// Bits of padding per pixel.
    pub padding_bits_per_pixel: i8,
    /// Frame rate, Hz.
    pub framerate: i8,
    /// Non-zero when the mode is valid.
    pub is_valid: i8,
}

/// `freenect_raw_tilt_state`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct freenect_raw_tilt_state {
    /// Raw accelerometer X.
    pub accelerometer_x: i16,
    /// Raw accelerometer Y.
    pub accelerometer_y: i16,
    /// Raw accelerometer Z.
    pub accelerometer_z: i16,
    /// Raw tilt motor angle.
    pub tilt_angle: i8,
    /// `freenect_tilt_status_code`.
    pub tilt_status: c_int,
}

/// Depth callback: the frame buffer is libfreenect's and valid only during the call.
pub type freenect_depth_cb =
    Option<unsafe extern "C" fn(dev: *mut freenect_device, depth: *mut c_void, timestamp: u32)>;
/// Video callback: the frame buffer is libfreenect's and valid only during the call.
pub type freenect_video_cb =
    Option<unsafe extern "C" fn(dev: *mut freenect_device, video: *mut c_void, timestamp: u32)>;
/// Log callback: an already formatted message.
pub type freenect_log_cb =
    Option<unsafe extern "C" fn(ctx: *mut freenect_context, level: c_int, msg: *const c_char)>;

/// `struct timeval` for `freenect_process_events_timeout`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct timeval {
    /// Seconds.
    pub tv_sec: std::os::raw::c_long,
    /// Microseconds.
    pub tv_usec: std::os::raw::c_long,
}

extern "C" {
    /// Create a context (`usb_ctx` may be null).
    pub fn freenect_init(ctx: *mut *mut freenect_context, usb_ctx: *mut c_void) -> c_int;
    /// Destroy a context.
    pub fn freenect_shutdown(ctx: *mut freenect_context) -> c_int;
    /// Set the log level.
    pub fn freenect_set_log_level(ctx: *mut freenect_context, level: c_int);
    /// Set the log callback.
    pub fn freenect_set_log_callback(ctx: *mut freenect_context, cb: freenect_log_cb);
    /// Choose motor and/or camera.
    pub fn freenect_select_subdevices(ctx: *mut freenect_context, subdevs: c_int);
    /// Handle USB events (calls the callbacks).
    pub fn freenect_process_events(ctx: *mut freenect_context) -> c_int;
    /// Number of Kinects attached.
    pub fn freenect_num_devices(ctx: *mut freenect_context) -> c_int;
    /// Open device `index`.
    pub fn freenect_open_device(
        ctx: *mut freenect_context,
        dev: *mut *mut freenect_device,
        index: c_int,
    ) -> c_int;
    /// Close a device.
    pub fn freenect_close_device(dev: *mut freenect_device) -> c_int;
    /// Attach a user pointer to a device.
    pub fn freenect_set_user(dev: *mut freenect_device, user: *mut c_void);
    /// The user pointer of a device.
    pub fn freenect_get_user(dev: *mut freenect_device) -> *mut c_void;
    /// Set the depth callback.
    pub fn freenect_set_depth_callback(dev: *mut freenect_device, cb: freenect_depth_cb);
    /// Find a depth mode.
    pub fn freenect_find_depth_mode(res: c_int, fmt: c_int) -> freenect_frame_mode;
    /// Set the depth mode.
    pub fn freenect_set_depth_mode(dev: *mut freenect_device, mode: freenect_frame_mode) -> c_int;
    /// Start the depth stream.
    pub fn freenect_start_depth(dev: *mut freenect_device) -> c_int;
    /// Stop the depth stream.
    pub fn freenect_stop_depth(dev: *mut freenect_device) -> c_int;
    /// Set the video callback.
    pub fn freenect_set_video_callback(dev: *mut freenect_device, cb: freenect_video_cb);
    /// Find a video mode.
    pub fn freenect_find_video_mode(res: c_int, fmt: c_int) -> freenect_frame_mode;
    /// Set the video mode.
    pub fn freenect_set_video_mode(dev: *mut freenect_device, mode: freenect_frame_mode) -> c_int;
    /// Start the video stream.
    pub fn freenect_start_video(dev: *mut freenect_device) -> c_int;
    /// Stop the video stream.
    pub fn freenect_stop_video(dev: *mut freenect_device) -> c_int;
    /// Read the tilt state from the device.
    pub fn freenect_update_tilt_state(dev: *mut freenect_device) -> c_int;
    /// The last tilt state read.
    pub fn freenect_get_tilt_state(dev: *mut freenect_device) -> *mut freenect_raw_tilt_state;
    /// Accelerometer in m/s².
    pub fn freenect_get_mks_accel(
        state: *mut freenect_raw_tilt_state,
        x: *mut c_double,
        y: *mut c_double,
        z: *mut c_double,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn structs_have_the_header_layout() {
        // uint32 + enum + union(int32) + int32 + 2×int16 + 4×int8 = 24 bytes.
        assert_eq!(std::mem::size_of::<freenect_frame_mode>(), 24);
        // 3×int16 + int8 (+1 pad) + enum = 12 bytes.
        assert_eq!(std::mem::size_of::<freenect_raw_tilt_state>(), 12);
    }

    #[test]
    fn the_library_links_and_finds_its_depth_modes() {
        // Safety: a pure lookup in libfreenect's static mode table.
        let m =
            unsafe { freenect_find_depth_mode(FREENECT_RESOLUTION_MEDIUM, FREENECT_DEPTH_11BIT) };
        assert_eq!(
            (m.is_valid, m.width, m.height, m.bytes),
            (1, 640, 480, 640 * 480 * 2)
        );
        // Safety: as above.
        let v = unsafe { freenect_find_video_mode(FREENECT_RESOLUTION_MEDIUM, FREENECT_VIDEO_RGB) };
        assert_eq!(
            (v.is_valid, v.width, v.height, v.bytes),
            (1, 640, 480, 640 * 480 * 3)
        );
    }
}
