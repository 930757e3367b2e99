//! The voxel centroids as point clouds: PCD (PCL's format, binary) and PLY (ASCII).

use std::fmt::Write;

use super::Scene;

/// The PCD file (version 0.7, `DATA binary`): fields `x y z` (float, metres, rover
/// frame) and `rgb` (PCL's packed `0x00RRGGBB` as a 4-byte unsigned), one point per
/// occupied voxel, coloured by [`super::Class`].
pub fn pcd(scene: &Scene<'_>) -> Vec<u8> {
    let n = scene.voxels.len();
    let mut out = format!(
        "# .PCD v0.7 - Point Cloud Data file format\n\
         # rover-terrain voxel centroids, rover frame (x forward, y left, z up), metres\n\
         VERSION 0.7\n\
         FIELDS x y z rgb\n\
         SIZE 4 4 4 4\n\
         TYPE F F F U\n\
         COUNT 1 1 1 1\n\
         WIDTH {n}\n\
         HEIGHT 1\n\
         VIEWPOINT 0 0 0 1 0 0 0\n\
         POINTS {n}\n\
         DATA binary\n"
    )
    .into_bytes();
    out.reserve(n * 16);
    for v in scene.voxels {
        let [r, g, b] = scene.class_at(v.x, v.y).rgb();
        let packed = (u32::from(r) << 16) | (u32::from(g) << 8) | u32::from(b);
        for f in [v.x, v.y, v.z] {
            out.extend_from_slice(&f.to_le_bytes());
        }
        out.extend_from_slice(&packed.to_le_bytes());
    }
    out
}

/// The PLY file (ASCII 1.0): `x y z` float and `red green blue` uchar per voxel.
pub fn ply(scene: &Scene<'_>) -> Vec<u8> {
    let n = scene.voxels.len();
    let mut s = format!(
        "ply\nformat ascii 1.0\n\
         comment rover-terrain voxel centroids, rover frame (x forward, y left, z up), metres\n\
         element vertex {n}\n\
         property float x\nproperty float y\nproperty float z\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\n\
         end_header\n"
    );
    for v in scene.voxels {
        let [r, g, b] = scene.class_at(v.x, v.y).rgb();
        let _ = writeln!(s, "{} {} {} {r} {g} {b}", v.x, v.y, v.z);
    }
    s.into_bytes()
}

/// One point read back from a PCD file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PcdPoint {
    /// Forward, metres.
    pub x: f32,
    /// Left, metres.
    pub y: f32,
    /// Up, metres.
    pub z: f32,
    /// Colour, `[r, g, b]`.
    pub rgb: [u8; 3],
}

/// Read a PCD file as [`pcd`] writes it (and as PCL writes `x y z rgb` clouds:
/// binary or ASCII data). Errors say what is wrong.
pub fn read_pcd(bytes: &[u8]) -> Result<Vec<PcdPoint>, String> {
    let mut pos = 0;
    let mut points = None;
    let mut fields = String::new();
    let mut binary = None;
    while binary.is_none() {
        let end = bytes[pos..]
            .iter()
            .position(|&b| b == b'\n')
            .ok_or("header ends before DATA")?;
        let line = std::str::from_utf8(&bytes[pos..pos + end]).map_err(|_| "header is not text")?;
        pos += end + 1;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("FIELDS") => fields = words.collect::<Vec<_>>().join(" "),
            Some("POINTS") => {
                points = Some(
                    words
                        .next()
                        .and_then(|n| n.parse::<usize>().ok())
                        .ok_or("bad POINTS")?,
                )
            }
            Some("DATA") => binary = Some(words.next() == Some("binary")),
            _ => {}
        }
    }
    if fields != "x y z rgb" {
        return Err(format!("fields {fields:?}, expected \"x y z rgb\""));
    }
    let n = points.ok_or("no POINTS line")?;
    let unpack = |c: u32| [(c >> 16) as u8, (c >> 8) as u8, c as u8];
    if binary == Some(true) {
        let data = &bytes[pos..];
        if data.len() != n * 16 {
            return Err(format!("{} data bytes for {n} points", data.len()));
        }
        Ok(data
            .chunks_exact(16)
            .map(|p| {
                let f = |i: usize| f32::from_le_bytes([p[i], p[i + 1], p[i + 2], p[i + 3]]);
                let c = u32::from_le_bytes([p[12], p[13], p[14], p[15]]);
                PcdPoint {
                    x: f(0),
                    y: f(4),
                    z: f(8),
                    rgb: unpack(c),
                }
            })
            .collect())
    } else {
        let text = std::str::from_utf8(&bytes[pos..]).map_err(|_| "data is not text")?;
        let pts: Result<Vec<PcdPoint>, String> = text
            .lines()
            .filter(|l| !l.trim().is_empty())
            .map(|l| {
                let w: Vec<&str> = l.split_whitespace().collect();
                if w.len() != 4 {
                    return Err(format!("line {l:?} has {} values", w.len()));
                }
                let f = |i: usize| w[i].parse::<f32>().map_err(|e| e.to_string());
                // PCL writes rgb as an unsigned integer or as the packed float.
                let c = w[3]
                    .parse::<u32>()
                    .or_else(|_| w[3].parse::<f32>().map(f32::to_bits))
                    .map_err(|e| e.to_string())?;
                Ok(PcdPoint {
                    x: f(0)?,
                    y: f(1)?,
                    z: f(2)?,
                    rgb: unpack(c),
                })
            })
            .collect();
        let pts = pts?;
        if pts.len() != n {
            return Err(format!("{} points for POINTS {n}", pts.len()));
        }
        Ok(pts)
    }
}
