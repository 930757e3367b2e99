//! PCL itself reads our `cloud.pcd` (feature `pcl-check`, which needs Debian's
//! `pcl-tools`: `apt-get install pcl-tools`; CI installs it): PCL's own converter
//! loads the binary file and writes it as ASCII, and that reads back to the same
//! points.
#![cfg(feature = "pcl-check")]

use std::process::Command;

use rover_terrain::inspect::cloud::read_pcd;

#[test]
fn pcl_loads_cloud_pcd() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rover-terrain"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["inspect", "fixtures/scenes/belly_block_40cm.png", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(out.status.success());
    let ascii = dir.path().join("ascii.pcd");
    let pcl = Command::new("pcl_convert_pcd_ascii_binary")
        .arg(dir.path().join("cloud.pcd"))
        .arg(&ascii)
        .arg("0")
        .output()
        .expect("pcl_convert_pcd_ascii_binary (apt-get install pcl-tools)");
    let said = format!(
        "{}{}",
        String::from_utf8_lossy(&pcl.stdout),
        String::from_utf8_lossy(&pcl.stderr)
    );
    assert!(pcl.status.success() && ascii.is_file(), "{said}");
    let ours = read_pcd(&std::fs::read(dir.path().join("cloud.pcd")).unwrap()).unwrap();
    let theirs = read_pcd(&std::fs::read(&ascii).unwrap()).unwrap();
    assert!(said.contains(&format!("{} points", ours.len())), "{said}");
    assert_eq!(theirs.len(), ours.len());
    for (a, b) in ours.iter().zip(&theirs) {
        assert_eq!(a.rgb, b.rgb);
        for (p, q) in [(a.x, b.x), (a.y, b.y), (a.z, b.z)] {
            assert!((p - q).abs() <= 1e-5 * p.abs().max(1.0), "{p} vs {q}");
        }
    }
}
