//! A EuRoC (ASL) folder as `rslam_core::dataset::euroc::read_euroc` reads it: a camera's
//! sensor.yaml and data.csv, the IMU's sensor.yaml and data.csv, the ground truth's data.csv.
//! Each target's file replaces one file of a small valid MH_01_easy-style sequence.

use std::path::Path;

use rslam_core::dataset::encode_grey_png;
use rslam_core::dataset::euroc::{read_euroc, EurocDataset};
use rslam_core::RgbImage;

use crate::Scratch;

pub const CAMERA_YAML: &str = "mav0/cam0/sensor.yaml";
pub const CAMERA_CSV: &str = "mav0/cam0/data.csv";
pub const IMU_YAML: &str = "mav0/imu0/sensor.yaml";
pub const IMU_CSV: &str = "mav0/imu0/data.csv";
pub const GROUND_TRUTH_CSV: &str = "mav0/state_groundtruth_estimate0/data.csv";

/// The frame data.csv names: 752×480 grey, the resolution of the seeds' sensor.yaml.
const FRAME: &str = "1403636579763555584.png";

/// Every file the reader needs, valid: each target's first seed (one camera, the IMU, the
/// ground truth); the target's file then replaces one of them.
pub fn prepare(dir: &Path) -> std::io::Result<()> {
    for (target, file) in [
        ("euroc_camera_yaml", CAMERA_YAML),
        ("euroc_camera_csv", CAMERA_CSV),
        ("euroc_imu_yaml", IMU_YAML),
        ("euroc_imu", IMU_CSV),
        ("euroc_groundtruth", GROUND_TRUTH_CSV),
    ] {
        let seeds = crate::corpus::seeds(target).map_err(std::io::Error::other)?;
        let path = dir.join(file);
        std::fs::create_dir_all(path.parent().expect("a file inside mav0"))?;
        std::fs::write(path, &seeds[0])?;
    }
    let data = dir.join("mav0/cam0/data");
    std::fs::create_dir_all(&data)?;
    let png = encode_grey_png(&RgbImage::new(752, 480)).map_err(std::io::Error::other)?;
    std::fs::write(data.join(FRAME), png)
}

pub fn camera_yaml(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(CAMERA_YAML, input)?;
    read(&scratch.dir)
}

pub fn camera_csv(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(CAMERA_CSV, input)?;
    read(&scratch.dir)
}

pub fn imu_yaml(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(IMU_YAML, input)?;
    read(&scratch.dir)
}

pub fn imu(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(IMU_CSV, input)?;
    read(&scratch.dir)
}

pub fn ground_truth(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(GROUND_TRUTH_CSV, input)?;
    read(&scratch.dir)
}

/// An accepted sequence has usable cameras, frames inside their camera folder in strictly
/// increasing time, finite IMU readings and finite unit-quaternion ground truth, both in
/// strictly increasing time.
pub(super) fn read(root: &Path) -> Result<(), String> {
    let dataset: EurocDataset = read_euroc(root).map_err(|e| e.to_string())?;
    for camera in &dataset.cameras {
        if let Err(problem) = camera.camera.intrinsics.check() {
            panic!("accepted camera {:?}: {problem}", camera.camera.intrinsics);
        }
        let rate = camera.camera.rate_hz;
        assert!(rate.is_finite() && rate > 0.0, "accepted rate {rate}");
        let folder = dataset.mav_dir.join(&camera.camera.name).join("data");
        for frame in &camera.frames {
            assert!(
                frame.path.parent() == Some(folder.as_path()),
                "accepted frame {} outside {}",
                frame.path.display(),
                folder.display()
            );
        }
        increasing(camera.frames.iter().map(|f| f.t_ns), "frame");
    }
    if let Some(imu) = &dataset.imu {
        for sample in &imu.samples {
            assert!(
                sample.gyro.is_finite() && sample.accel.is_finite(),
                "accepted IMU sample {sample:?}"
            );
        }
        increasing(imu.samples.iter().map(|s| s.t_ns), "IMU sample");
    }
    if let Some(states) = &dataset.ground_truth {
        for state in states {
            let pose = &state.world_from_body;
            assert!(
                pose.translation.is_finite()
                    && pose.rotation.is_finite()
                    && (pose.rotation.length() - 1.0).abs() < 1e-6,
                "accepted ground-truth pose {pose:?}"
            );
            assert!(
                state.velocity.is_finite()
                    && state.gyro_bias.is_finite()
                    && state.accel_bias.is_finite(),
                "accepted ground-truth state {state:?}"
            );
        }
        increasing(states.iter().map(|s| s.t_ns), "ground-truth state");
    }
    Ok(())
}

fn increasing(times: impl Iterator<Item = u64>, what: &str) {
    let mut last = None;
    for t in times {
        assert!(
            last.is_none_or(|l| l < t),
            "accepted {what} at {t} ns after {last:?}"
        );
        last = Some(t);
    }
}
