//! Reading back what `rslam render` / `rslam perturb` wrote, for assertions.

use std::collections::BTreeMap;
use std::path::Path;

use rslam_core::dataset::{decode_depth_png, read_rgb, Manifest};
use rslam_core::trajectory_io::{read_trajectory, TrajectoryFormat};
use rslam_core::{DepthImage, Pose, RgbImage, Trajectory};

/// Files in `dir` whose names start with `prefix`, sorted.
pub fn files(dir: &Path, prefix: &str) -> Vec<std::path::PathBuf> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.file_name().unwrap().to_string_lossy().starts_with(prefix))
        .collect();
    v.sort();
    v
}

pub fn manifest(root: &Path) -> Manifest {
    Manifest::read(root).expect("rslam.json")
}

pub fn replica_trajectory(root: &Path) -> Trajectory {
    read_trajectory(&root.join("traj.txt"), Some(TrajectoryFormat::Replica))
        .expect("traj.txt")
        .trajectory
}

pub fn tum_trajectory(root: &Path) -> Trajectory {
    read_trajectory(&root.join("groundtruth.txt"), Some(TrajectoryFormat::Tum))
        .expect("groundtruth.txt")
        .trajectory
}

pub fn replica_depth(root: &Path, i: usize) -> DepthImage {
    decode_depth_png(&root.join(format!("results/depth{i:06}.png")), 6553.5).expect("depth png")
}

pub fn replica_rgb(root: &Path, i: usize) -> RgbImage {
    read_rgb(&root.join(format!("results/frame{i:06}.jpg"))).expect("frame jpg")
}

/// Non-comment lines of a text file.
pub fn lines(path: &Path) -> Vec<String> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(str::to_string)
        .collect()
}

/// Poses equal to within what a text file with 6 decimals (TUM) or full precision keeps.
pub fn assert_poses_close(actual: &[Pose], expected: &[Pose], tolerance: f64) {
    assert_eq!(actual.len(), expected.len(), "pose count");
    for (i, (a, e)) in actual.iter().zip(expected).enumerate() {
        let dt = (a.translation - e.translation).length();
        // Twice the vector part of the relative quaternion: the angle, precise for small angles.
        let dr = 2.0 * (a.rotation * e.rotation.inverse()).xyz().length();
        assert!(
            dt < tolerance && dr < tolerance,
            "pose {i}: Δt {dt}, Δrot {dr} rad"
        );
    }
}

/// Every file under `root`, relative path → bytes.
pub fn tree(root: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut pending = vec![root.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else {
                let relative = path.strip_prefix(root).unwrap().display().to_string();
                out.insert(relative, std::fs::read(&path).unwrap());
            }
        }
    }
    out
}

pub fn assert_same_tree(a: &Path, b: &Path) {
    let (a, b) = (tree(a), tree(b));
    assert_eq!(
        a.keys().collect::<Vec<_>>(),
        b.keys().collect::<Vec<_>>(),
        "same files"
    );
    for (name, bytes) in &a {
        assert!(bytes == &b[name], "{name} differs");
    }
}

/// Each of `files` (relative paths) has the same bytes under `a` and `b`.
pub fn assert_same_files(a: &Path, b: &Path, files: &[&str]) {
    for file in files {
        let read = |root: &Path| std::fs::read(root.join(file)).unwrap();
        assert!(read(a) == read(b), "{file}: not the same bytes");
    }
}

/// The mean linear brightness of an sRGB image file (what the controller steers).
pub fn mean_linear(path: &std::path::Path) -> f64 {
    let image = image::open(path).unwrap().to_rgb8();
    let linear = |v: u8| {
        let c = v as f64 / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    let values = image.as_raw();
    values.iter().map(|&v| linear(v)).sum::<f64>() / values.len() as f64
}
