//! A recorded ROS 2 bag as `rslam perturb --input BAG` reads it: the MCAP storage file of a
//! rosbag2 folder, every message read and the cameras and IMU topics found
//! (`rslam_core::dataset::ros2::RecordedBagCameras`).

use std::path::Path;

use rslam_core::dataset::ros2::{RecordedBag, RecordedBagCameras};

use crate::Scratch;

pub const STORAGE: &str = "bag_0.mcap";

/// The folder's `metadata.yaml` (its content is not read).
pub fn prepare(dir: &Path) -> std::io::Result<()> {
    std::fs::write(dir.join("metadata.yaml"), "rosbag2_bagfile_information:\n")
}

pub fn storage(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(STORAGE, input)?;
    let bag = RecordedBag::open(&scratch.dir).map_err(|e| e.to_string())?;
    let recorded = RecordedBagCameras::read(bag).map_err(|e| e.to_string())?;
    assert!(!recorded.cameras.is_empty());
    for camera in &recorded.cameras {
        let frames = camera.frames().messages.len();
        assert!(frames >= 2 && camera.rate_hz.is_finite() && camera.rate_hz > 0.0);
        if let Some(depth) = &camera.depth {
            assert_eq!(depth.messages.len(), frames);
        }
        assert!(recorded.is_perturbed(camera.frames().index));
    }
    for imu in &recorded.imus {
        if let Ok(samples) = imu.samples() {
            assert!(samples.windows(2).all(|w| w[0].t_ns < w[1].t_ns));
        }
        if let Ok(rate_hz) = imu.rate_hz() {
            assert!(rate_hz.is_finite() && rate_hz > 0.0);
            let noise = imu.stated_noise(rate_hz);
            assert!(noise.is_none_or(|n| n.gyroscope_noise_density.is_finite()));
        }
    }
    Ok(())
}
