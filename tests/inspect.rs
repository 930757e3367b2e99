//! `inspect`: the pictures exist at their documented sizes, the clouds hold one point
//! per voxel with the right colours, the PCD reads back to the pipeline's voxels, and
//! hazards are drawn where they are.

use std::path::{Path, PathBuf};
use std::process::Command;

use rover_terrain::inspect::cloud::read_pcd;
use rover_terrain::inspect::{side, topdown, Scene, FEATURE_RGB, GROUND_RGB, HAZARD_RGB};
use rover_terrain::{Config, Pipeline};
use rover_terrain_drivers::{DepthCamera, DepthFrame, FakeCamera};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn inspect(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_rover-terrain"))
        .current_dir(root())
        .arg("inspect")
        .args(args)
        .output()
        .unwrap()
}

fn png_size(path: &Path) -> (u32, u32) {
    let file = std::fs::File::open(path).unwrap();
    let reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap();
    (reader.info().width, reader.info().height)
}

fn png_pixel(path: &Path, x: u32, y: u32) -> [u8; 3] {
    let file = std::fs::File::open(path).unwrap();
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    let i = (y as usize * info.width as usize + x as usize) * 3;
    [buf[i], buf[i + 1], buf[i + 2]]
}

/// The fixture through the pipeline, as `inspect` sees it.
fn analysed(name: &str) -> (Pipeline, rover_terrain::Verdict) {
    let mut cam = FakeCamera::open(&root().join("fixtures/scenes").join(name)).unwrap();
    let mut f = DepthFrame::default();
    cam.next_frame(&mut f).unwrap();
    let mut p = Pipeline::new(Config::default()).unwrap();
    let v = p.process(&f).unwrap().clone();
    (p, v)
}

fn write_set(name: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("set");
    let o = inspect(&[
        &format!("fixtures/scenes/{name}"),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (dir, out)
}

#[test]
fn a_frame_gives_five_files_of_the_documented_sizes_and_counts() {
    let (_tmp, out) = write_set("diagonal_left.png");
    let (pipeline, verdict) = analysed("diagonal_left.png");
    let spec = pipeline.grid().spec();
    assert_eq!(png_size(&out.join("depth.png")), (640, 480));
    assert_eq!(
        png_size(&out.join("topdown.png")),
        topdown::size(spec.nx, spec.ny)
    );
    assert_eq!(topdown::size(spec.nx, spec.ny), (752, 830), "as documented");
    assert_eq!(png_size(&out.join("side.png")), (side::WIDTH, side::HEIGHT));

    let voxels = pipeline.grid().voxels();
    assert_eq!(voxels.len(), verdict.voxels as usize);
    let pcd = std::fs::read(out.join("cloud.pcd")).unwrap();
    let header = String::from_utf8_lossy(&pcd[..300]);
    assert!(
        header.contains(&format!("POINTS {}\n", voxels.len())),
        "{header}"
    );
    assert!(header.contains(&format!("WIDTH {}\n", voxels.len())));
    let ply = std::fs::read_to_string(out.join("cloud.ply")).unwrap();
    assert!(ply.contains(&format!("element vertex {}\n", voxels.len())));
    let body = ply.split("end_header\n").nth(1).unwrap();
    assert_eq!(body.lines().count(), voxels.len());

    // Golden: the PCD reads back to exactly the pipeline's voxels, coloured by class.
    let points = read_pcd(&pcd).unwrap();
    assert_eq!(points.len(), voxels.len());
    let scene = Scene::of(&pipeline, &verdict);
    for (p, v) in points.iter().zip(voxels) {
        assert_eq!((p.x, p.y, p.z), (v.x, v.y, v.z));
        assert_eq!(p.rgb, scene.class_at(v.x, v.y).rgb());
    }
    // A diagonal ramp on the left: its face is amber, the flat ground is not.
    let amber = points.iter().filter(|p| p.rgb == FEATURE_RGB).count();
    assert!(amber > 100, "{amber} points on the ramp's face");
    assert!(points.iter().any(|p| p.rgb == GROUND_RGB));
    assert!(
        points
            .iter()
            .filter(|p| p.rgb == FEATURE_RGB)
            .all(|p| p.y > 0.0),
        "the face is on the left"
    );
    // The PLY's first vertex is the PCD's first point.
    let first: Vec<f32> = body
        .lines()
        .next()
        .unwrap()
        .split(' ')
        .take(3)
        .map(|w| w.parse().unwrap())
        .collect();
    assert_eq!(first, vec![points[0].x, points[0].y, points[0].z]);
}

#[test]
fn a_hazard_is_drawn_where_it_is_and_its_voxels_are_red() {
    let (_tmp, out) = write_set("track_block.png");
    let (pipeline, verdict) = analysed("track_block.png");
    let h = verdict.hazards.first().expect("the block is a hazard");
    let scene = Scene::of(&pipeline, &verdict);
    let (x, y) = topdown::to_pixel(
        pipeline.grid().spec(),
        h.distance_m,
        scene.side_centre(h.side),
    );
    assert_eq!(
        png_pixel(&out.join("topdown.png"), x as u32, y as u32),
        [230, 30, 30],
        "the hazard marker sits at {:.2} m on the {:?} side",
        h.distance_m,
        h.side
    );
    let points = read_pcd(&std::fs::read(out.join("cloud.pcd")).unwrap()).unwrap();
    assert!(points.iter().any(|p| p.rgb == HAZARD_RGB));
    // No data is black in depth.png: the sky above the horizon has none.
    let flat = {
        let (_t, o) = write_set("all_zero.png");
        png_pixel(&o.join("depth.png"), 320, 240)
    };
    assert_eq!(flat, [0, 0, 0]);
}

#[test]
fn every_n_frames_of_a_sequence_gets_its_own_set() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("seq");
    let o = inspect(&[
        "--camera",
        "fake:fixtures/fakenect/ramp-step",
        "--every",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut dirs: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    dirs.sort();
    assert_eq!(dirs, ["frame-000000", "frame-000002"]);
    for d in dirs {
        assert!(out.join(d).join("topdown.png").is_file());
    }
    let o = inspect(&["fixtures/scenes/flat.png", "--out", "x", "--every", "0"]);
    assert_eq!(o.status.code(), Some(1));
    let o = inspect(&["no/such.png", "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no/such.png"));
}
