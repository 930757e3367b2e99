//! One analysed frame as Foxglove's well-known messages (protobuf, from the `foxglove`
//! crate): the voxel centroids as a `PointCloud` coloured like `cloud.pcd`, the ground
//! cells as a `Grid` (height, view and class layers, coloured like `topdown.png`), the
//! toe line and hazards as a `SceneUpdate`, and the camera's mount as a
//! `FrameTransform`. Pure functions of the [`Scene`]: the same frame gives the same
//! bytes.

use foxglove::messages::{
    line_primitive, packed_element_field::NumericType, Color, CubePrimitive, FrameTransform, Grid,
    LinePrimitive, PackedElementField, Point3, PointCloud, Pose, Quaternion, SceneEntity,
    SceneUpdate, TextPrimitive, Timestamp, Vector2, Vector3,
};
use nalgebra::{Rotation3, UnitQuaternion};

use crate::inspect::{Class, Scene};
use crate::projection::camera_to_rover;

/// The TF frame names the messages are in.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Frames {
    /// The rover body frame (REP 103: x forward, y left, z up), e.g. `base_link`.
    pub base: String,
    /// The depth camera's optical frame (z forward, x right, y down).
    pub camera: String,
}

/// A timestamp `seconds` after the epoch (negative and non-finite become 0).
pub fn timestamp(seconds: f64) -> Timestamp {
    let s = if seconds.is_finite() {
        seconds.clamp(0.0, f64::from(u32::MAX))
    } else {
        0.0
    };
    let sec = s.floor();
    Timestamp::new(sec as u32, (((s - sec) * 1e9) as u32).min(999_999_999))
}

/// Packed fields, each right after the last (float32 4 bytes, uint8 1), then `red`,
/// `green`, `blue` and `alpha` (uint8).
fn fields_then_rgba(leading: &[(&str, NumericType)]) -> Vec<PackedElementField> {
    let rgba = ["red", "green", "blue", "alpha"].map(|c| (c, NumericType::Uint8));
    let mut offset = 0;
    leading
        .iter()
        .chain(&rgba)
        .map(|&(name, kind)| {
            let f = PackedElementField {
                name: name.into(),
                offset,
                r#type: kind as i32,
            };
            offset += if kind == NumericType::Float32 { 4 } else { 1 };
            f
        })
        .collect()
}

fn identity() -> Pose {
    Pose {
        position: Some(Vector3 {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        }),
        orientation: Some(Quaternion {
            x: 0.0,
            y: 0.0,
            z: 0.0,
            w: 1.0,
        }),
    }
}

fn colour(rgb: [u8; 3], a: f64) -> Color {
    Color {
        r: f64::from(rgb[0]) / 255.0,
        g: f64::from(rgb[1]) / 255.0,
        b: f64::from(rgb[2]) / 255.0,
        a,
    }
}

/// Bytes per point of [`cloud`]: x, y, z (float32, metres) and red, green, blue,
/// alpha (uint8).
pub const CLOUD_STRIDE: usize = 16;

/// The voxel centroids (rover frame, metres), one point per occupied voxel, in the
/// order and colours of `cloud.pcd` ([`Class::rgb`]).
pub fn cloud(scene: &Scene<'_>, stamp: Timestamp, frames: &Frames) -> PointCloud {
    let mut data = Vec::with_capacity(scene.voxels.len() * CLOUD_STRIDE);
    for v in scene.voxels {
        for f in [v.x, v.y, v.z] {
            data.extend_from_slice(&f.to_le_bytes());
        }
        let [r, g, b] = scene.class_at(v.x, v.y).rgb();
        data.extend_from_slice(&[r, g, b, 255]);
    }
    PointCloud {
        timestamp: Some(stamp),
        frame_id: frames.base.clone(),
        pose: Some(identity()),
        point_stride: CLOUD_STRIDE as u32,
        fields: fields_then_rgba(&[
            ("x", NumericType::Float32),
            ("y", NumericType::Float32),
            ("z", NumericType::Float32),
        ]),
        data: data.into(),
    }
}

/// What the grid's `view` layer says of a cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum View {
    /// Seen: enough points.
    Seen = 0,
    /// Should have been seen (in view, not hidden), and was not.
    Unseen = 1,
    /// Out of view, shadowed or past the horizon: nothing to expect.
    NotExpected = 2,
}

/// Bytes per cell of [`grid`]: `height` (float32, metres, the cell's highest point;
/// NaN where unseen), `view` ([`View`], uint8), `class` (0 ground, 1 feature face, 2
/// hazard, uint8; [`Class`]), then `red`, `green`, `blue`, `alpha` (uint8): hazard
/// red, feature orange, seen ground green, unseen-but-expected grey, the rest clear.
pub const GRID_STRIDE: usize = 10;

/// The ground grid, rover frame: columns along x (forward), rows along y (left),
/// the corner nearest the origin at the grid's origin.
pub fn grid(scene: &Scene<'_>, stamp: Timestamp, frames: &Frames) -> Grid {
    let s = scene.spec;
    let mut data = Vec::with_capacity(s.nx * s.ny * GRID_STRIDE);
    for iy in 0..s.ny {
        for ix in 0..s.nx {
            let i = s.cell(ix, iy);
            let (x, y) = (s.x_centre(ix), s.y_centre(iy));
            let view = if scene.seen(i) {
                View::Seen
            } else if scene.expected[i] {
                View::Unseen
            } else {
                View::NotExpected
            };
            let class = scene.class_at(x, y);
            let height = if view == View::Seen {
                scene.cells[i].top
            } else {
                f32::NAN
            };
            let (rgb, a) = match (class, view) {
                (Class::Hazard, _) => (class.rgb(), 200),
                (Class::Feature, View::Seen) => (class.rgb(), 200),
                (_, View::Seen) => (class.rgb(), 160),
                (_, View::Unseen) => ([90, 90, 90], 200),
                (_, View::NotExpected) => ([0, 0, 0], 0),
            };
            data.extend_from_slice(&height.to_le_bytes());
            data.push(view as u8);
            data.push(match class {
                Class::Ground => 0,
                Class::Feature => 1,
                Class::Hazard => 2,
            });
            data.extend_from_slice(&[rgb[0], rgb[1], rgb[2], a]);
        }
    }
    let mut pose = identity();
    pose.position = Some(Vector3 {
        x: f64::from(s.origin[0]),
        y: f64::from(s.origin[1]),
        z: 0.0,
    });
    Grid {
        timestamp: Some(stamp),
        frame_id: frames.base.clone(),
        pose: Some(pose),
        column_count: s.nx as u32,
        cell_size: Some(Vector2 {
            x: f64::from(s.voxel_m),
            y: f64::from(s.voxel_m),
        }),
        row_stride: (s.nx * GRID_STRIDE) as u32,
        cell_stride: GRID_STRIDE as u32,
        fields: fields_then_rgba(&[
            ("height", NumericType::Float32),
            ("view", NumericType::Uint8),
            ("class", NumericType::Uint8),
        ]),
        data: data.into(),
    }
}

/// The entity id of the verdict's drawing: each frame's update replaces the last.
pub const ENTITY_ID: &str = "verdict";

/// The verdict drawn on the ground: the feature's toe line (orange) across its span,
/// a red box 25 cm deep at each hazard's near edge on its side with its kind as a
/// label, and the decision as a label over the rover.
pub fn scene_update(scene: &Scene<'_>, stamp: Timestamp, frames: &Frames) -> SceneUpdate {
    let v = scene.verdict;
    let mut lines = Vec::new();
    if let Some(((lo, hi), toe)) = scene.toe_line() {
        let points = [lo, hi]
            .iter()
            .map(|&y| Point3 {
                x: f64::from(toe(y)),
                y: f64::from(y),
                z: 0.02,
            })
            .collect();
        lines.push(LinePrimitive {
            r#type: line_primitive::Type::LineStrip as i32,
            pose: Some(identity()),
            thickness: 0.03,
            scale_invariant: false,
            points,
            color: Some(colour(crate::inspect::FEATURE_RGB, 1.0)),
            colors: Vec::new(),
            indices: Vec::new(),
        });
    }
    let r = &scene.config.rover;
    let half_band = ((r.track_outer_m - r.belly_half_width_m) / 2.0).max(0.05);
    let mut cubes = Vec::new();
    let mut texts = Vec::new();
    for h in &v.hazards {
        let y = f64::from(scene.side_centre(h.side));
        let x = f64::from(h.distance_m) + f64::from(crate::inspect::HAZARD_DEPTH_M) / 2.0;
        let mut pose = identity();
        pose.position = Some(Vector3 { x, y, z: 0.05 });
        cubes.push(CubePrimitive {
            pose: Some(pose),
            size: Some(Vector3 {
                x: f64::from(crate::inspect::HAZARD_DEPTH_M),
                y: 2.0 * half_band,
                z: 0.1,
            }),
            color: Some(colour(crate::inspect::HAZARD_RGB, 0.6)),
        });
        pose.position = Some(Vector3 { x, y, z: 0.3 });
        texts.push(TextPrimitive {
            pose: Some(pose),
            billboard: true,
            font_size: 14.0,
            scale_invariant: true,
            color: Some(colour([255, 255, 255], 1.0)),
            text: format!("{:?} {:.2} m", h.kind, h.distance_m).to_lowercase(),
        });
    }
    let mut over = identity();
    over.position = Some(Vector3 {
        x: 0.0,
        y: 0.0,
        z: 0.8,
    });
    texts.push(TextPrimitive {
        pose: Some(over),
        billboard: true,
        font_size: 18.0,
        scale_invariant: true,
        color: Some(colour([255, 255, 255], 1.0)),
        text: match v.feature.map(|f| f.workcase) {
            Some(wc) => format!("{:?} (workcase {wc})", v.decision).to_lowercase(),
            None => format!("{:?}", v.decision).to_lowercase(),
        },
    });
    SceneUpdate {
        deletions: Vec::new(),
        entities: vec![SceneEntity {
            timestamp: Some(stamp),
            frame_id: frames.base.clone(),
            id: ENTITY_ID.into(),
            lifetime: None,
            frame_locked: true,
            metadata: Vec::new(),
            arrows: Vec::new(),
            cubes,
            spheres: Vec::new(),
            cylinders: Vec::new(),
            lines,
            triangles: Vec::new(),
            texts,
            models: Vec::new(),
        }],
    }
}

/// The camera's optical frame in the rover frame: the mount's position and the
/// rotation taking optical-frame vectors to rover-frame vectors (the one the point
/// cloud is built with).
pub fn camera_transform(
    config: &crate::Config,
    stamp: Timestamp,
    frames: &Frames,
) -> FrameTransform {
    let m = camera_to_rover(config);
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m));
    let mnt = &config.mount;
    FrameTransform {
        timestamp: Some(stamp),
        parent_frame_id: frames.base.clone(),
        child_frame_id: frames.camera.clone(),
        translation: Some(Vector3 {
            x: mnt.x_m,
            y: mnt.y_m,
            z: mnt.z_m,
        }),
        rotation: Some(Quaternion {
            x: q.i,
            y: q.j,
            z: q.k,
            w: q.w,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packed_fields_follow_each_other_and_end_at_the_strides() {
        let f = fields_then_rgba(&[("x", NumericType::Float32), ("v", NumericType::Uint8)]);
        let at: Vec<(&str, u32)> = f.iter().map(|f| (f.name.as_str(), f.offset)).collect();
        assert_eq!(
            at,
            [
                ("x", 0),
                ("v", 4),
                ("red", 5),
                ("green", 6),
                ("blue", 7),
                ("alpha", 8)
            ]
        );
        assert_eq!(timestamp(12.25), Timestamp::new(12, 250_000_000));
        assert_eq!(timestamp(f64::NAN), Timestamp::new(0, 0));
        assert_eq!(timestamp(-3.0), Timestamp::new(0, 0));
    }
}
