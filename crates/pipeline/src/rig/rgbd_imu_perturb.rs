//! A perturbed copy of an `rgbd-imu` output (a TUM dataset with `imu0/` beside it): its
//! frames go through the dataset path like any TUM input, and its inertial files
//! (`imu0/data.csv`, `imu0/sensor.yaml`, `state_groundtruth_estimate0/data.csv`,
//! `orbslam3_rgbd_inertial.yaml`) go with them, so the copy is still an RGB-D-inertial dataset.
//! The frames keep their capture times, so the IMU still matches them. The IMU items that act on
//! the IMU stream apply to `imu0/data.csv` (and the true biases of the ground truth) as for a
//! recorded EuRoC IMU; every other inertial file is copied byte for byte. `fast` and
//! `cam_imu_offset`, which re-stamp the frames, are refused where the job is planned
//! ([`crate::settings::recorded_dataset`]).

use std::path::Path;

use rslam_core::dataset::euroc::{
    ground_truth_csv, imu_csv, read_inertial, GROUND_TRUTH_DIR, IMU_DIR,
};
use rslam_core::read_text_file;
use rslam_perturb::imu::{ImuOrigin, ImuReport};
use rslam_perturb::PerturbSpec;

use super::imu_items::perturb_imu_stream;
use super::rgbd_imu_render::ORBSLAM3_RGBD_INERTIAL_FILE;
use crate::PipelineError;

/// The inertial files of a perturbed copy, and what the IMU items drew.
#[derive(Debug, Default)]
pub struct RecordedInertial {
    /// Relative path and text of each file.
    pub files: Vec<(String, String)>,
    /// `None` without IMU items.
    pub report: Option<ImuReport>,
}

/// The inertial files of the `rgbd-imu` dataset at `root` for its perturbed copy, the spec's IMU
/// items applied (draws keyed by `seed`); empty when it has no `imu0/`.
pub fn recorded_inertial_files(
    root: &Path,
    spec: &PerturbSpec,
    seed: u64,
) -> Result<RecordedInertial, PipelineError> {
    let (Some(imu), ground_truth) = read_inertial(root)? else {
        return Ok(RecordedInertial::default());
    };
    let imu_file = format!("{IMU_DIR}/data.csv");
    let truth_file = format!("{GROUND_TRUTH_DIR}/data.csv");
    let mut files = Vec::new();
    let mut report = None;
    if !spec.imu.is_empty() {
        let perturbed = perturb_imu_stream(
            spec,
            &imu.samples,
            ground_truth.as_deref().unwrap_or_default(),
            imu.imu.rate_hz,
            ImuOrigin::Recorded(imu.imu.noise()),
            seed,
        )?;
        if perturbed.samples_changed {
            files.push((imu_file.clone(), imu_csv(&perturbed.samples)));
        }
        if perturbed.ground_truth_changed {
            files.push((
                truth_file.clone(),
                ground_truth_csv(&perturbed.ground_truth),
            ));
        }
        report = Some(perturbed.report);
    }
    let copied = [
        imu_file,
        format!("{IMU_DIR}/sensor.yaml"),
        truth_file,
        ORBSLAM3_RGBD_INERTIAL_FILE.to_string(),
    ];
    for relative in copied {
        let path = root.join(&relative);
        if path.is_file() && !files.iter().any(|(written, _)| *written == relative) {
            let text = read_text_file(&path, "a file of the rgbd-imu layout")?;
            files.push((relative, text));
        }
    }
    Ok(RecordedInertial { files, report })
}
