//! `rslam perturb --input` of an `rgbd-imu` output (a TUM dataset with `imu0/` beside it): its
//! frames go through the dataset path like any TUM input, and its inertial files
//! (`imu0/data.csv`, `imu0/sensor.yaml`, `state_groundtruth_estimate0/data.csv`,
//! `orbslam3_rgbd_inertial.yaml`) are copied unchanged, so the copy is still an RGB-D-inertial
//! dataset. The frames keep their capture times, so the IMU still matches them; `fast`, which
//! re-stamps the frames, and IMU items (not built for this layout yet) are refused.

use std::path::Path;

use rslam_core::dataset::euroc::{GROUND_TRUTH_DIR, IMU_DIR};
use rslam_core::read_text_file;
use rslam_perturb::PerturbSpec;

use super::rgbd_imu_render::ORBSLAM3_RGBD_INERTIAL_FILE;
use crate::PipelineError;

/// The inertial files of the `rgbd-imu` dataset at `root` (relative path, text) for its
/// perturbed copy; empty when it has no `imu0/data.csv`.
pub fn recorded_inertial_files(
    root: &Path,
    spec: &PerturbSpec,
) -> Result<Vec<(String, String)>, PipelineError> {
    let imu_csv = format!("{IMU_DIR}/data.csv");
    if !root.join(&imu_csv).is_file() {
        return Ok(Vec::new());
    }
    let refused = spec
        .fast
        .map(|k| format!("fast:{k}"))
        .or_else(|| spec.imu.items().first().map(|item| item.to_string()));
    if let Some(item) = refused {
        return Err(PipelineError::option(
            "--perturb",
            format!(
                "'{item}': {} has an IMU (imu0/); on this layout only frame corruptions and misalign keep the copy consistent with it (fast re-stamps the frames; IMU items need a EuRoC input or `rslam render --rig rgbd-imu`)",
                root.display()
            ),
        ));
    }
    let relatives = [
        imu_csv,
        format!("{IMU_DIR}/sensor.yaml"),
        format!("{GROUND_TRUTH_DIR}/data.csv"),
        ORBSLAM3_RGBD_INERTIAL_FILE.to_string(),
    ];
    let mut files = Vec::new();
    for relative in relatives {
        let path = root.join(&relative);
        if path.is_file() {
            let text = read_text_file(&path, "a file of the rgbd-imu layout")?;
            files.push((relative, text));
        }
    }
    Ok(files)
}
