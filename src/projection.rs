//! Depth pixel → rover-frame point: the camera model (the paper's FOV model, eq. 1-4
//! with eq. 4 corrected to use the vertical FOV, or pinhole intrinsics) and the
//! camera's mount pose, folded into per-column and per-row lookup tables.
//!
//! For a pixel (u, v) with optical depth Z (metres), the camera-frame point is
//! `(kx[u]·Z, ky[v]·Z, Z)` (X right, Y up, Z forward) with
//! - FOV model: `kx[u] = (u/W − 0.5)·2·tan(hfov/2)`, `ky[v] = (0.5 − v/H)·2·tan(vfov/2)`;
//! - pinhole: `kx[u] = (u − cx)/fx`, `ky[v] = −(v − cy)/fy`.
//!
//! In the rover frame (REP 103: x forward, y left, z up) it is `t + Z·M·(kx, ky, 1)`
//! where `M = R(roll, pitch, yaw)·B`, `B` takes optical axes to body axes
//! (x = Z, y = −X, z = Y), and `t` is the camera position. Because `M·(kx, ky, 1) =
//! kx·M₀ + ky·M₁ + M₂`, one table of `kx·M₀` per column and one of `ky·M₁ + M₂` per row
//! give every pixel's ray with three additions.

use nalgebra::{Matrix3, Rotation3, Vector3};

use crate::config::Config;

/// The camera model and mount folded into per-column and per-row ray tables.
#[derive(Debug, Clone)]
pub struct Projector {
    width: usize,
    height: usize,
    /// Per column u: `kx[u]·M₀`, rover frame, per metre of depth.
    col: Vec<[f32; 3]>,
    /// Per row v: `ky[v]·M₁ + M₂`, rover frame, per metre of depth.
    row: Vec<[f32; 3]>,
    /// Camera position in the rover frame, metres.
    origin: [f32; 3],
    /// `M`, camera optical frame → rover frame.
    m: Matrix3<f64>,
    kx: Vec<f64>,
    ky: Vec<f64>,
}

impl Projector {
    /// Build the tables for `width × height` images from the camera and mount config.
    pub fn new(config: &Config, width: usize, height: usize) -> Self {
        let cam = &config.camera;
        let (kx, ky): (Vec<f64>, Vec<f64>) = match config.pinhole() {
            Some((fx, fy, cx, cy)) => {
                // Intrinsics are given for the configured size; scale to this one.
                let sx = width as f64 / f64::from(cam.width);
                let sy = height as f64 / f64::from(cam.height);
                (
                    (0..width)
                        .map(|u| (u as f64 - cx * sx) / (fx * sx))
                        .collect(),
                    (0..height)
                        .map(|v| -(v as f64 - cy * sy) / (fy * sy))
                        .collect(),
                )
            }
            None => {
                let tx = 2.0 * (cam.hfov_deg.to_radians() / 2.0).tan();
                let ty = 2.0 * (cam.vfov_deg.to_radians() / 2.0).tan();
                (
                    (0..width)
                        .map(|u| (u as f64 / width as f64 - 0.5) * tx)
                        .collect(),
                    (0..height)
                        .map(|v| (0.5 - v as f64 / height as f64) * ty)
                        .collect(),
                )
            }
        };
        let m = camera_to_rover(config);
        let (m0, m1, m2) = (m.column(0), m.column(1), m.column(2));
        let f3 = |v: Vector3<f64>| [v.x as f32, v.y as f32, v.z as f32];
        let col = kx.iter().map(|&k| f3(m0 * k)).collect();
        let row = ky.iter().map(|&k| f3(m1 * k + m2)).collect();
        let mnt = &config.mount;
        Projector {
            width,
            height,
            col,
            row,
            origin: [mnt.x_m as f32, mnt.y_m as f32, mnt.z_m as f32],
            m,
            kx,
            ky,
        }
    }

    /// Image width the tables are built for, pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Image height the tables are built for, pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Whether continuous image position (u, v), pixels (as [`Projector::project`]
    /// gives it), lies inside the image, half a pixel clear of its edges.
    pub fn in_image(&self, u: f64, v: f64) -> bool {
        let (w, h) = (self.width as f64, self.height as f64);
        u >= 0.5 && v >= 0.5 && u <= w - 1.5 && v <= h - 1.5
    }

    /// The angle between neighbouring pixels' rays at the image centre, along a row
    /// and along a column: `[u, v]`, radians.
    pub fn pixel_angle(&self) -> [f64; 2] {
        let step = |t: &[f64]| {
            if t.len() > 1 {
                (t[1] - t[0]).abs()
            } else {
                0.0
            }
        };
        [step(&self.kx), step(&self.ky)]
    }

    /// Per-column ray parts (`kx[u]·M₀`), rover frame.
    pub fn col_table(&self) -> &[[f32; 3]] {
        &self.col
    }

    /// Per-row ray parts (`ky[v]·M₁ + M₂`), rover frame.
    pub fn row_table(&self) -> &[[f32; 3]] {
        &self.row
    }

    /// Camera position in the rover frame, metres.
    pub fn origin(&self) -> [f32; 3] {
        self.origin
    }

    /// The rover-frame ray of pixel (u, v) per metre of optical depth, in f64
    /// (for the scene renderer and for tests).
    pub fn ray(&self, u: usize, v: usize) -> Vector3<f64> {
        self.m * Vector3::new(self.kx[u], self.ky[v], 1.0)
    }

    /// The rover-frame point of pixel (u, v) at optical depth `z_m`, metres.
    pub fn point(&self, u: usize, v: usize, z_m: f64) -> Vector3<f64> {
        let o = self.origin;
        Vector3::new(f64::from(o[0]), f64::from(o[1]), f64::from(o[2])) + self.ray(u, v) * z_m
    }

    /// Where a rover-frame point falls in the image: (u, v) in pixels (continuous,
    /// same convention as the tables) and its optical depth, metres; `None` behind
    /// the camera.
    pub fn project(&self, p: Vector3<f64>) -> Option<(f64, f64, f64)> {
        let o = self.origin;
        let rel = p - Vector3::new(f64::from(o[0]), f64::from(o[1]), f64::from(o[2]));
        let c = self.m.transpose() * rel; // optical frame: X right, Y up, Z forward
        if c.z <= 1e-9 {
            return None;
        }
        let (kx, ky) = (c.x / c.z, c.y / c.z);
        // Invert the linear tables using their first element and step.
        let inv = |k: f64, t: &[f64]| {
            let step = if t.len() > 1 { t[1] - t[0] } else { 1.0 };
            (k - t[0]) / step
        };
        Some((inv(kx, &self.kx), inv(ky, &self.ky), c.z))
    }
}

/// The rotation taking camera optical-frame vectors to rover-frame vectors.
pub fn camera_to_rover(config: &Config) -> Matrix3<f64> {
    let mnt = &config.mount;
    // REP 103 right-handed rotations: positive pitch about +y turns +x toward −z,
    // i.e. looks down; positive roll lifts the left side; positive yaw looks left.
    let r = Rotation3::from_euler_angles(
        mnt.roll_deg.to_radians(),
        mnt.pitch_deg.to_radians(),
        mnt.yaw_deg.to_radians(),
    );
    #[rustfmt::skip]
    let b = Matrix3::new(
        0.0, 0.0, 1.0, // x_body = Z_optical
        -1.0, 0.0, 0.0, // y_body = −X_optical
        0.0, 1.0, 0.0, // z_body = Y_optical
    );
    r.matrix() * b
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn centre_pixel_of_level_camera_looks_forward() {
        let mut c = Config::default();
        c.mount.pitch_deg = 0.0;
        let p = Projector::new(&c, 640, 480);
        let r = p.ray(320, 240);
        assert!(close(r.x, 1.0, 1e-12) && close(r.y, 0.0, 1e-12) && close(r.z, 0.0, 1e-12));
        // Left image edge (u = 0) is to the left (+y) per eq. 2-3.
        let l = p.ray(0, 240);
        assert!(close(l.y, (57f64.to_radians() / 2.0).tan(), 1e-12), "{l}");
        // Top row (v = 0) is up, using the *vertical* FOV (eq. 4 corrected).
        let t = p.ray(320, 0);
        assert!(close(t.z, (43f64.to_radians() / 2.0).tan(), 1e-12), "{t}");
    }

    #[test]
    fn pitched_camera_sees_the_ground_where_trigonometry_says() {
        let c = Config::default(); // 0.8 m high, pitched 30° down
        let p = Projector::new(&c, 640, 480);
        // The centre ray hits the ground at 0.8 / tan(30°).
        let r = p.ray(320, 240);
        let z = 0.8 / -r.z;
        let hit = p.point(320, 240, z);
        assert!(close(hit.x, 0.8 / 30f64.to_radians().tan(), 1e-9), "{hit}");
        assert!(close(hit.y, 0.0, 1e-12));
    }

    /// The ground point (x, y) that pixel (u, v) sees, by hand: the optical ray
    /// (kx, ky, 1) in the body axes, turned by roll about x, then pitch about y
    /// (positive looks down), then yaw about z (URDF `rpy`), from height `h`.
    fn hand_ground(kx: f64, ky: f64, [r, p, y]: [f64; 3], h: f64) -> (f64, f64) {
        let (x0, y0, z0) = (1.0, -kx, ky);
        let (y1, z1) = (y0 * r.cos() - z0 * r.sin(), y0 * r.sin() + z0 * r.cos());
        let (x2, z2) = (x0 * p.cos() + z1 * p.sin(), -x0 * p.sin() + z1 * p.cos());
        let (x3, y3) = (x2 * y.cos() - y1 * y.sin(), x2 * y.sin() + y1 * y.cos());
        let t = h / -z2;
        (t * x3, t * y3)
    }

    #[test]
    fn roll_pitch_and_yaw_turn_the_rays_as_the_config_says() {
        let mut c = Config::default();
        c.mount.z_m = 0.9;
        c.mount.pitch_deg = 35.0;
        let (tx, ty) = (
            (57f64 / 2.0).to_radians().tan(),
            (43f64 / 2.0).to_radians().tan(),
        );
        for (roll, yaw) in [(10.0, 0.0), (-10.0, 0.0), (0.0, 10.0), (7.0, -9.0)] {
            c.mount.roll_deg = roll;
            c.mount.yaw_deg = yaw;
            let p = Projector::new(&c, 640, 480);
            let angles = [roll, 35.0f64, yaw].map(f64::to_radians);
            for (u, v) in [(0, 479), (639, 479), (320, 240), (100, 300), (600, 420)] {
                let (kx, ky) = (
                    (u as f64 / 640.0 - 0.5) * 2.0 * tx,
                    (0.5 - v as f64 / 480.0) * 2.0 * ty,
                );
                let (x, y) = hand_ground(kx, ky, angles, 0.9);
                let r = p.ray(u, v);
                let hit = p.point(u, v, 0.9 / -r.z);
                assert!(
                    close(hit.x, x, 1e-9) && close(hit.y, y, 1e-9),
                    "{roll} {yaw} ({u},{v}): {hit} vs ({x}, {y})"
                );
            }
        }
        // The signs in words: rolled left side up, the bottom row's right end sees the
        // ground nearer than its left end; yawed left, the centre looks left.
        c.mount.roll_deg = 10.0;
        c.mount.yaw_deg = 0.0;
        let p = Projector::new(&c, 640, 480);
        let ground = |u, v| p.point(u, v, 0.9 / -p.ray(u, v).z);
        assert!(ground(639, 479).x < ground(0, 479).x - 0.05);
        c.mount.roll_deg = 0.0;
        c.mount.yaw_deg = 10.0;
        let p = Projector::new(&c, 640, 480);
        let centre = p.point(320, 240, 0.9 / -p.ray(320, 240).z);
        assert!(
            close(centre.y / centre.x, 10f64.to_radians().tan(), 1e-9),
            "{centre}"
        );
    }

    #[test]
    fn an_off_centre_principal_point_is_the_pixel_that_looks_along_the_axis() {
        let mut c = Config::default();
        c.mount.pitch_deg = 0.0;
        c.camera.width = 848;
        c.camera.fx = Some(425.0);
        c.camera.fy = Some(426.0);
        c.camera.cx = Some(430.0);
        c.camera.cy = Some(236.0);
        let p = Projector::new(&c, 848, 480);
        let r = p.ray(430, 236);
        assert!(close(r.y, 0.0, 1e-12) && close(r.z, 0.0, 1e-12), "{r}");
        // 425 pixels right of cx is 45° right; 426 below cy is 45° down.
        let r = p.ray(430 + 415, 236);
        assert!(close(r.y, -415.0 / 425.0, 1e-12), "{r}");
        let r = p.ray(430, 236 + 213);
        assert!(close(r.z, -213.0 / 426.0, 1e-12), "{r}");
    }

    #[test]
    fn project_inverts_point() {
        let mut c = Config::default();
        c.mount.roll_deg = 3.0;
        c.mount.yaw_deg = -5.0;
        c.mount.y_m = 0.1;
        let p = Projector::new(&c, 640, 480);
        let q = p.point(100, 400, 1.7);
        let (u, v, z) = p.project(q).unwrap();
        assert!(close(u, 100.0, 1e-9) && close(v, 400.0, 1e-9) && close(z, 1.7, 1e-9));
    }

    #[test]
    fn pinhole_matches_fov_model_when_equivalent() {
        let mut c = Config::default();
        let fov = Projector::new(&c, 640, 480);
        let fx = 320.0 / (57f64.to_radians() / 2.0).tan();
        let fy = 240.0 / (43f64.to_radians() / 2.0).tan();
        c.camera.fx = Some(fx);
        c.camera.fy = Some(fy);
        c.camera.cx = Some(320.0);
        c.camera.cy = Some(240.0);
        let pin = Projector::new(&c, 640, 480);
        for (u, v) in [(0, 0), (639, 479), (320, 100)] {
            assert!((fov.ray(u, v) - pin.ray(u, v)).norm() < 1e-12);
        }
    }

    #[test]
    fn tables_agree_with_the_f64_ray() {
        let c = Config::default();
        let p = Projector::new(&c, 64, 48);
        for (u, v) in [(0, 0), (63, 47), (10, 30)] {
            let r = p.ray(u, v);
            for k in 0..3 {
                let t = p.col_table()[u][k] + p.row_table()[v][k];
                assert!(close(f64::from(t), r[k], 1e-6));
            }
        }
    }
}
