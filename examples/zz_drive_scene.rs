//! Temporary: render a drive towards a dumped scene from D metres back, as a recording.
use rover_terrain::sim::drive::write_recording;
use rover_terrain::sim::{render_from, Element, Pose, Terrain};
use rover_terrain::Config;
use rover_terrain_proto::Odometry;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let elements: Vec<Element> =
        serde_json::from_str(&std::fs::read_to_string(&a[1]).unwrap()).unwrap();
    let config: Config = toml::from_str(&std::fs::read_to_string(&a[2]).unwrap()).unwrap();
    let back: f64 = a[3].parse().unwrap();
    let step: f64 = a[4].parse().unwrap();
    let out = std::path::Path::new(&a[5]);
    let terrain = Terrain::new(elements);
    let end: f64 = a.get(6).map_or(0.0, |e| e.parse().unwrap());
    let n = ((back + end) / step).round() as usize;
    let mut drive = Vec::new();
    for k in 0..=n {
        let pose = Pose {
            x: -back + k as f64 * step,
            y: 0.0,
            heading: 0.0,
        };
        let odometry = Odometry::from_pose(k as u8, k as u64 * 100, k as f64 * step, 0.0, 0.0);
        let mut frame = render_from(&terrain, &config, pose);
        frame.seq = k as u64;
        frame.timestamp_s = k as f64 / 10.0;
        frame.odometry = Some(odometry.encode());
        drive.push((frame, pose, odometry));
    }
    write_recording(out, &drive).unwrap();
}
