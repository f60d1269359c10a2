//! Reads a EuRoC dataset back: rslam's own or a published one (MH_01_easy and the rest), which
//! has no rslam manifest and more folders (`leica0`, `body.yaml`) that are not read; or TUM-VI's
//! EuRoC-style export (its calibration in `dso/`, see [`super::tum_vi`]), told by a first camera
//! without sensor.yaml.

use std::path::{Path, PathBuf};

use super::csv::{read_camera_csv, read_ground_truth_csv, read_imu_csv};
use super::sensor_yaml::{read_camera_yaml, read_imu_yaml};
use super::tum_vi::{self, TumViCalibration};
use super::writer::{GROUND_TRUTH_DIR, IMU_DIR, MAV_DIR};
use super::{CameraColour, EurocCamera, EurocFrame, EurocImu, GroundTruthState, ImuSample};
use crate::dataset::codec::read_image_colour_type;
use crate::limits::MAX_EUROC_CAMERAS;
use crate::CoreError;

/// One camera and its frames, in time order.
#[derive(Clone, Debug, PartialEq)]
pub struct EurocCameraFrames {
    pub camera: EurocCamera,
    pub frames: Vec<EurocFrame>,
}

/// The IMU and its samples, in time order.
#[derive(Clone, Debug, PartialEq)]
pub struct EurocImuSamples {
    pub imu: EurocImu,
    pub samples: Vec<ImuSample>,
}

/// A EuRoC dataset as read.
#[derive(Clone, Debug, PartialEq)]
pub struct EurocDataset {
    /// The `mav0` folder.
    pub mav_dir: PathBuf,
    /// `cam0`, `cam1`, … in the order of their number.
    pub cameras: Vec<EurocCameraFrames>,
    /// `imu0`, when there is one.
    pub imu: Option<EurocImuSamples>,
    /// `state_groundtruth_estimate0/data.csv`, when there is one (EuRoC's test sequences have
    /// none, nor has TUM-VI).
    pub ground_truth: Option<Vec<GroundTruthState>>,
    /// TUM-VI's calibration, for its export; `None` for EuRoC's layout.
    pub tum_vi: Option<TumViCalibration>,
}

/// The number of a camera folder `cam<N>`.
fn camera_number(name: &str) -> Option<usize> {
    let digits = name.strip_prefix("cam")?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
}

/// Reads the EuRoC dataset at `root` (the folder holding `mav0/`, or `mav0/` itself): every
/// `cam<N>` folder with its sensor.yaml and data.csv (each listed image must exist), `imu0` and
/// the ground truth where present. A camera's colour is told from its first frame's header.
pub fn read_euroc(root: &Path) -> Result<EurocDataset, CoreError> {
    read_euroc_with(root, false)
}

/// [`read_euroc`] of a dataset whose frames were deleted after use: the frames' times without
/// their images, each camera's colour unknown (grey, as for a camera without frames). For what
/// needs no image, such as culling to the cameras' views.
pub fn read_euroc_without_frames(root: &Path) -> Result<EurocDataset, CoreError> {
    read_euroc_with(root, true)
}

fn read_euroc_with(root: &Path, images_deleted: bool) -> Result<EurocDataset, CoreError> {
    let mav_dir = if root.join(MAV_DIR).is_dir() {
        root.join(MAV_DIR)
    } else if root.file_name().is_some_and(|n| n == MAV_DIR) && root.is_dir() {
        root.to_path_buf()
    } else {
        return Err(CoreError::bad_file(
            root,
            "not a EuRoC dataset: expected a mav0/ folder with cam0/, cam1/, imu0/ …",
        ));
    };
    let mut numbered: Vec<(usize, String)> = Vec::new();
    for entry in std::fs::read_dir(&mav_dir).map_err(|e| CoreError::io(&mav_dir, e))? {
        let entry = entry.map_err(|e| CoreError::io(&mav_dir, e))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if let Some(number) = camera_number(&name).filter(|_| entry.path().is_dir()) {
            numbered.push((number, name));
        }
    }
    if numbered.len() > MAX_EUROC_CAMERAS {
        return Err(CoreError::bad_file(
            &mav_dir,
            format!(
                "{} camera folders, over the limit of {MAX_EUROC_CAMERAS}",
                numbered.len()
            ),
        ));
    }
    numbered.sort();
    let tum_vi = match numbered.first() {
        Some((_, first)) if !mav_dir.join(first).join("sensor.yaml").is_file() => Some(
            tum_vi::read_calibration(&mav_dir, &mav_dir.join(first).join("sensor.yaml"))?,
        ),
        _ => None,
    };
    let cameras = numbered
        .iter()
        .map(|(_, name)| read_camera(&mav_dir, name, tum_vi.as_ref(), images_deleted))
        .collect::<Result<Vec<_>, _>>()?;
    let (imu, ground_truth) = read_inertial_calibrated(&mav_dir, |imu_dir| match &tum_vi {
        None => read_imu_yaml(&imu_dir.join("sensor.yaml")),
        Some(calibration) => tum_vi::imu(calibration),
    })?;
    if cameras.is_empty() && imu.is_none() {
        return Err(CoreError::bad_file(
            &mav_dir,
            "no camera (cam0/ …) and no IMU (imu0/); expected at least one sensor folder",
        ));
    }
    Ok(EurocDataset {
        mav_dir,
        cameras,
        imu,
        ground_truth,
        tum_vi,
    })
}

/// The IMU (`imu0/`, when that folder exists) and the ground truth
/// (`state_groundtruth_estimate0/data.csv`, when that file exists) under `dir`: `mav0/` of a
/// EuRoC dataset, or the root of an `rgbd-imu` one, which has them beside its TUM files.
pub fn read_inertial(
    dir: &Path,
) -> Result<(Option<EurocImuSamples>, Option<Vec<GroundTruthState>>), CoreError> {
    read_inertial_calibrated(dir, |imu_dir| read_imu_yaml(&imu_dir.join("sensor.yaml")))
}

/// [`read_inertial`] with the IMU's calibration from `calibration(imu_dir)` (TUM-VI's is not in
/// a sensor.yaml).
fn read_inertial_calibrated(
    dir: &Path,
    calibration: impl FnOnce(&Path) -> Result<EurocImu, CoreError>,
) -> Result<(Option<EurocImuSamples>, Option<Vec<GroundTruthState>>), CoreError> {
    let imu_dir = dir.join(IMU_DIR);
    let imu = if imu_dir.is_dir() {
        Some(EurocImuSamples {
            imu: calibration(&imu_dir)?,
            samples: read_imu_csv(&imu_dir.join("data.csv"))?,
        })
    } else {
        None
    };
    let gt_csv = dir.join(GROUND_TRUTH_DIR).join("data.csv");
    let ground_truth = if gt_csv.is_file() {
        Some(read_ground_truth_csv(&gt_csv)?)
    } else {
        None
    };
    Ok((imu, ground_truth))
}

fn read_camera(
    mav_dir: &Path,
    name: &str,
    tum_vi: Option<&TumViCalibration>,
    images_deleted: bool,
) -> Result<EurocCameraFrames, CoreError> {
    let dir = mav_dir.join(name);
    let csv = dir.join("data.csv");
    let (mut camera, frames) = match tum_vi {
        None => {
            let camera = read_camera_yaml(&dir.join("sensor.yaml"), name)?;
            let frames = read_camera_csv(&csv, &dir.join("data"), images_deleted)?;
            (camera, frames)
        }
        Some(calibration) => {
            let frames = read_camera_csv(&csv, &dir.join("data"), images_deleted)?;
            (tum_vi::camera(calibration, name, &csv, &frames)?, frames)
        }
    };
    if let Some(first) = frames.first().filter(|_| !images_deleted) {
        let colour_type = read_image_colour_type(&first.path)?;
        camera.colour = if colour_type.has_color() {
            CameraColour::Rgb
        } else if colour_type.bytes_per_pixel() > colour_type.channel_count() {
            CameraColour::Grey16
        } else {
            CameraColour::Grey
        };
    }
    Ok(EurocCameraFrames { camera, frames })
}
