//! Kinect v1 through libfreenect (feature `freenect`), over our own FFI
//! (`libfreenect-sys`).
//!
//! Depth arrives in libfreenect's depth callback, inside `freenect_process_events`,
//! which only [`FreenectCamera::next_frame`] calls; the callback copies the frame out
//! of libfreenect's buffer before returning, so nothing of ours points into
//! libfreenect's memory after the call (the defect of the `freenectrs` crate).
//!
//! Units: with a Kinect, the stream is `FREENECT_DEPTH_MM` (libfreenect converts with
//! the device's own registration). When `FAKENECT_PATH` is set, the process runs on
//! libfreenect's replay library (`LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu/fakenect`),
//! whose Debian version replays raw 11-bit disparity only; the camera then streams
//! `FREENECT_DEPTH_11BIT` and converts exactly as the fake camera does (the session's
//! `device.json`, else the standard Kinect v1 fit), so both give the same millimetres.

use std::ffi::CStr;
use std::os::raw::{c_char, c_int, c_void};
use std::path::Path;
use std::time::{Duration, Instant};

use libfreenect_sys as ffi;

use crate::fakenect::{RawToMm, Registration, TiltState};
use crate::{DepthCamera, DepthFrame, DriverError, FrameStatus};

/// Kinect v1 depth image size.
const W: usize = 640;
const H: usize = 480;
/// How long `next_frame` waits for a frame before reporting a timeout.
pub const FRAME_TIMEOUT: Duration = Duration::from_secs(2);

/// What the depth callback fills; owned by the camera, lent to libfreenect as the
/// device's user pointer.
struct Shared {
    buf: Vec<u16>,
    fresh: bool,
    timestamp: u32,
    /// The last colour frame (RGB, 640×480×3), and whether one arrived.
    rgb: Vec<u8>,
    have_rgb: bool,
}

/// A Kinect v1 depth camera.
pub struct FreenectCamera {
    ctx: *mut ffi::freenect_context,
    dev: *mut ffi::freenect_device,
    /// Owned (from `Box::into_raw`, freed in `Drop`) and lent to libfreenect as the
    /// device's user pointer; only ever accessed through this pointer, because the
    /// callback writes to it behind the compiler's back.
    shared: std::ptr::NonNull<Shared>,
    to_mm: Option<RawToMm>,
    index: u32,
    seq: u64,
    started: bool,
    t0: Instant,
}

unsafe extern "C" fn on_depth(dev: *mut ffi::freenect_device, depth: *mut c_void, timestamp: u32) {
    // Safety: the user pointer is the camera's `Box<Shared>`, set before the stream
    // starts and valid until the device is closed; the callback only runs inside
    // `freenect_process_events`, called from `next_frame` while `self` is borrowed
    // mutably, so nothing else touches `Shared` meanwhile. libfreenect hands a buffer of
    // one 640×480 frame of native-endian u16 (both modes we set have 16 bits per
    // pixel), but not necessarily aligned for u16: fakenect's points just past the PGM
    // header. So it is read as bytes, which need no alignment.
    unsafe {
        let shared = &mut *(ffi::freenect_get_user(dev) as *mut Shared);
        if depth.is_null() {
            return;
        }
        let src = std::slice::from_raw_parts(depth as *const u8, shared.buf.len() * 2);
        for (d, pair) in shared.buf.iter_mut().zip(src.chunks_exact(2)) {
            *d = u16::from_ne_bytes([pair[0], pair[1]]);
        }
        shared.fresh = true;
        shared.timestamp = timestamp;
    }
}

unsafe extern "C" fn on_video(dev: *mut ffi::freenect_device, video: *mut c_void, _timestamp: u32) {
    // Safety: as in `on_depth`: the user pointer is our `Shared`, touched only inside
    // `freenect_process_events` called from `next_frame`; the buffer holds one RGB
    // frame (the mode we set) valid for this call, read as bytes and copied out.
    unsafe {
        let shared = &mut *(ffi::freenect_get_user(dev) as *mut Shared);
        if video.is_null() {
            return;
        }
        let src = std::slice::from_raw_parts(video as *const u8, shared.rgb.len());
        shared.rgb.copy_from_slice(src);
        shared.have_rgb = true;
    }
}

unsafe extern "C" fn on_log(_ctx: *mut ffi::freenect_context, level: c_int, msg: *const c_char) {
    if msg.is_null() {
        return;
    }
    // Safety: libfreenect passes a NUL-terminated message valid for the call.
    let text = unsafe { CStr::from_ptr(msg) }.to_string_lossy();
    let text = text.trim_end();
    match level {
        0..=1 => log::error!("libfreenect: {text}"),
        2 => log::warn!("libfreenect: {text}"),
        3..=4 => log::info!("libfreenect: {text}"),
        _ => log::debug!("libfreenect: {text}"),
    }
}

/// How many Kinects libfreenect sees.
pub fn count() -> Result<u32, DriverError> {
    let mut ctx = std::ptr::null_mut();
    // Safety: valid out-pointer, null USB context; the context is shut down below and
    // not used after.
    unsafe {
        if ffi::freenect_init(&mut ctx, std::ptr::null_mut()) < 0 || ctx.is_null() {
            return Err(DriverError::NoDevice(
                "libfreenect could not start (no USB access?)".into(),
            ));
        }
        ffi::freenect_set_log_callback(ctx, Some(on_log));
        let n = ffi::freenect_num_devices(ctx).max(0) as u32;
        ffi::freenect_shutdown(ctx);
        Ok(n)
    }
}

impl FreenectCamera {
    /// Open Kinect number `index`. Fails with [`DriverError::NoDevice`] when
    /// libfreenect cannot start or sees no such Kinect.
    pub fn open(index: u32) -> Result<Self, DriverError> {
        let replay = std::env::var_os("FAKENECT_PATH");
        // Decided before libfreenect is touched, so that an error here leaks nothing.
        let (format, to_mm) = match &replay {
            Some(path) => {
                let session = Path::new(path);
                let device = session.join("device.json");
                let table = if device.is_file() {
                    let text = std::fs::read_to_string(&device).map_err(|e| DriverError::Io {
                        path: device.clone(),
                        source: e,
                    })?;
                    RawToMm::from_registration(&Registration::from_device_json(&text, &device)?)
                } else {
                    RawToMm::standard()
                };
                (ffi::FREENECT_DEPTH_11BIT, Some(table))
            }
            None => (ffi::FREENECT_DEPTH_MM, None),
        };
        let mut ctx = std::ptr::null_mut();
        // Safety: `ctx` is a valid out-pointer; a null USB context asks libfreenect to
        // make its own.
        if unsafe { ffi::freenect_init(&mut ctx, std::ptr::null_mut()) } < 0 || ctx.is_null() {
            return Err(DriverError::NoDevice(
                "libfreenect could not start (no USB access?)".into(),
            ));
        }
        // Safety: `ctx` is the live context; the callback is a plain function.
        unsafe {
            ffi::freenect_set_log_callback(ctx, Some(on_log));
            ffi::freenect_set_log_level(ctx, ffi::FREENECT_LOG_WARNING);
            ffi::freenect_select_subdevices(
                ctx,
                ffi::FREENECT_DEVICE_MOTOR | ffi::FREENECT_DEVICE_CAMERA,
            );
        }
        let fail = |ctx, e: DriverError| {
            // Safety: `ctx` is live and nothing else uses it.
            unsafe { ffi::freenect_shutdown(ctx) };
            Err(e)
        };
        // Safety: live context.
        let n = unsafe { ffi::freenect_num_devices(ctx) };
        if n <= index as c_int {
            return fail(
                ctx,
                DriverError::NoDevice(format!(
                    "no Kinect at index {index}: libfreenect sees {} device(s)",
                    n.max(0)
                )),
            );
        }
        let mut dev = std::ptr::null_mut();
        // Safety: live context, valid out-pointer.
        if unsafe { ffi::freenect_open_device(ctx, &mut dev, index as c_int) } < 0 || dev.is_null()
        {
            return fail(
                ctx,
                DriverError::NoDevice(format!(
                    "cannot open Kinect {index} (in use, or no permission: see the udev rule)"
                )),
            );
        }
        let shared = std::ptr::NonNull::from(Box::leak(Box::new(Shared {
            buf: vec![0; W * H],
            fresh: false,
            timestamp: 0,
            rgb: vec![0; W * H * 3],
            have_rgb: false,
        })));
        // Safety: live device; the mode comes from libfreenect's own table; the user
        // pointer is the boxed `Shared`, which lives as long as the camera.
        unsafe {
            let mode = ffi::freenect_find_depth_mode(ffi::FREENECT_RESOLUTION_MEDIUM, format);
            if mode.is_valid == 0 || ffi::freenect_set_depth_mode(dev, mode) < 0 {
                ffi::freenect_close_device(dev);
                drop(Box::from_raw(shared.as_ptr()));
                return fail(
                    ctx,
                    DriverError::NoDevice(format!("Kinect {index} refuses the depth mode")),
                );
            }
            ffi::freenect_set_user(dev, shared.as_ptr() as *mut c_void);
            ffi::freenect_set_depth_callback(dev, Some(on_depth));
            // Colour is optional: without it, depth still works.
            let video = ffi::freenect_find_video_mode(
                ffi::FREENECT_RESOLUTION_MEDIUM,
                ffi::FREENECT_VIDEO_RGB,
            );
            if video.is_valid != 0 && ffi::freenect_set_video_mode(dev, video) >= 0 {
                ffi::freenect_set_video_callback(dev, Some(on_video));
            } else {
                log::warn!("Kinect {index}: no RGB video mode; depth only");
            }
        }
        Ok(FreenectCamera {
            ctx,
            dev,
            shared,
            to_mm,
            index,
            seq: 0,
            started: false,
            t0: Instant::now(),
        })
    }

    /// The tilt state (accelerometer counts and motor), read now.
    pub fn read_tilt_state(&mut self) -> Option<TiltState> {
        // Safety: live device; the state pointer is libfreenect's and copied at once.
        unsafe {
            if ffi::freenect_update_tilt_state(self.dev) < 0 {
                return None;
            }
            let state = ffi::freenect_get_tilt_state(self.dev);
            if state.is_null() {
                return None;
            }
            let s = *state;
            Some(TiltState {
                accel: [s.accelerometer_x, s.accelerometer_y, s.accelerometer_z],
                tilt_angle: s.tilt_angle,
                tilt_status: s.tilt_status,
            })
        }
    }
}

impl DepthCamera for FreenectCamera {
    fn start(&mut self) -> Result<(), DriverError> {
        if !self.started {
            // Safety: live device with its callback and user pointer set.
            if unsafe { ffi::freenect_start_depth(self.dev) } < 0 {
                return Err(DriverError::Disconnected(format!(
                    "Kinect {} will not start its depth stream",
                    self.index
                )));
            }
            // Safety: as above; a Kinect (or a session) without colour just never
            // calls the video callback.
            if unsafe { ffi::freenect_start_video(self.dev) } < 0 {
                log::warn!(
                    "Kinect {}: colour stream did not start; depth only",
                    self.index
                );
            }
            self.started = true;
        }
        Ok(())
    }

    fn stop(&mut self) -> Result<(), DriverError> {
        if self.started {
            // Safety: live, started device.
            unsafe {
                ffi::freenect_stop_video(self.dev);
                ffi::freenect_stop_depth(self.dev);
            }
            self.started = false;
        }
        Ok(())
    }

    fn next_frame(&mut self, frame: &mut DepthFrame) -> Result<FrameStatus, DriverError> {
        self.start()?;
        let deadline = Instant::now() + FRAME_TIMEOUT;
        let shared = self.shared.as_ptr();
        // Safety (every access to `*shared` below): the pointer is ours and live; the
        // callback writes through the same pointer only inside
        // `freenect_process_events`, never concurrently with these reads.
        loop {
            if unsafe { (*shared).fresh } {
                break;
            }
            if Instant::now() > deadline {
                return Err(DriverError::Timeout {
                    camera: self.describe(),
                    timeout_ms: FRAME_TIMEOUT.as_millis() as u64,
                });
            }
            // Safety: live context; callbacks run inside this call (see `on_depth`).
            if unsafe { ffi::freenect_process_events(self.ctx) } < 0 {
                return Err(DriverError::Disconnected(format!(
                    "Kinect {}: libfreenect stopped processing events",
                    self.index
                )));
            }
        }
        let src: &Shared = unsafe {
            (*shared).fresh = false;
            &*shared
        };
        let pixels = frame.reshape(W, H);
        match &self.to_mm {
            Some(t) => {
                for (d, &raw) in pixels.iter_mut().zip(&src.buf) {
                    *d = t.convert(raw);
                }
            }
            None => pixels.copy_from_slice(&src.buf),
        }
        frame.seq = self.seq;
        self.seq += 1;
        frame.timestamp_s = self.t0.elapsed().as_secs_f64();
        Ok(FrameStatus::Frame)
    }

    fn next_colour(&mut self, frame: &mut crate::ColourFrame) -> Result<bool, DriverError> {
        // Safety: our live pointer; the callback writes only inside
        // `freenect_process_events`, which is not running now.
        let src: &Shared = unsafe { &*self.shared.as_ptr() };
        if !src.have_rgb {
            return Ok(false);
        }
        frame.reshape(W, H).copy_from_slice(&src.rgb);
        frame.seq = self.seq.saturating_sub(1);
        frame.timestamp_s = self.t0.elapsed().as_secs_f64();
        Ok(true)
    }

    fn tilt_state(&mut self) -> Option<TiltState> {
        self.read_tilt_state()
    }

    fn describe(&self) -> String {
        format!("freenect:{}", self.index)
    }
}

impl Drop for FreenectCamera {
    fn drop(&mut self) {
        let _ = self.stop();
        // Safety: the device and context are live and used by nothing else; after
        // this they are not used again.
        unsafe {
            ffi::freenect_close_device(self.dev);
            ffi::freenect_shutdown(self.ctx);
            // Nothing can call back any more: free the callback's buffer.
            drop(Box::from_raw(self.shared.as_ptr()));
        }
    }
}
