//! TUM-VI's EuRoC-style export (`dataset-room1_512_16/`; Schubert et al., IROS 2018): `mav0/`
//! as EuRoC has it but without sensor.yaml files; the calibration in `dso/` beside `mav0/`
//! (Kalibr's `camchain.yaml` and `imu_config.yaml`, and DSO's own files); the ground truth as
//! motion-capture poses of the IMU in `mav0/mocap0/data.csv` (no velocity, no biases). Its
//! frames are 16-bit grey PNGs.

use std::path::{Path, PathBuf};

use super::camchain::{read_camchain, Camchain};
use super::sensor_yaml::read_kalibr_imu_yaml;
use super::{CameraColour, EurocCamera, EurocFrame, EurocImu, RadialTangential};
use crate::CoreError;

/// TUM-VI's calibration folder, beside `mav0/`.
pub const TUM_VI_CALIBRATION_DIR: &str = "dso";
/// Kalibr's camera chain in [`TUM_VI_CALIBRATION_DIR`].
pub const CAMCHAIN_FILE: &str = "camchain.yaml";
/// Kalibr's IMU noise file in [`TUM_VI_CALIBRATION_DIR`].
pub const IMU_CONFIG_FILE: &str = "imu_config.yaml";

/// What a TUM-VI export has in place of sensor.yaml files.
#[derive(Clone, Debug, PartialEq)]
pub struct TumViCalibration {
    /// `dso/`, beside `mav0/`.
    pub dso_dir: PathBuf,
    pub camchain: Camchain,
}

/// `dso/` beside `mav_dir`.
fn calibration_dir(mav_dir: &Path) -> PathBuf {
    mav_dir
        .parent()
        .unwrap_or(Path::new("."))
        .join(TUM_VI_CALIBRATION_DIR)
}

/// The TUM-VI calibration of a dataset whose first camera has no `sensor.yaml` (at
/// `missing_yaml`); an error naming both files when there is no `dso/camchain.yaml` either.
pub(super) fn read_calibration(
    mav_dir: &Path,
    missing_yaml: &Path,
) -> Result<TumViCalibration, CoreError> {
    let dso_dir = calibration_dir(mav_dir);
    let camchain = dso_dir.join(CAMCHAIN_FILE);
    if !camchain.is_file() {
        return Err(CoreError::bad_file(
            missing_yaml,
            format!(
                "no such file, and no {} either: expected EuRoC's sensor.yaml in each camera folder or TUM-VI's {TUM_VI_CALIBRATION_DIR}/{CAMCHAIN_FILE} beside mav0/",
                camchain.display()
            ),
        ));
    }
    Ok(TumViCalibration {
        camchain: read_camchain(&camchain)?,
        dso_dir,
    })
}

/// The camera `name` (`cam0`) as camchain.yaml describes it, its rate told from its frames'
/// stamps (`csv` is their data.csv): the median interval, as camchain.yaml has no rate.
pub(super) fn camera(
    calibration: &TumViCalibration,
    name: &str,
    csv: &Path,
    frames: &[EurocFrame],
) -> Result<EurocCamera, CoreError> {
    let chain = &calibration.camchain;
    let Some(camera) = chain.camera(name) else {
        return Err(CoreError::bad_file(
            &chain.path,
            format!("no '{name}:' block for mav0/{name}/; expected one per camera folder"),
        ));
    };
    let mut intervals: Vec<u64> = frames.windows(2).map(|w| w[1].t_ns - w[0].t_ns).collect();
    intervals.sort_unstable();
    let Some(&median) = intervals.get(intervals.len() / 2) else {
        return Err(CoreError::bad_file(
            csv,
            format!(
                "{} frame(s): TUM-VI's {CAMCHAIN_FILE} gives no frame rate, and it cannot be told from fewer than two stamps",
                frames.len()
            ),
        ));
    };
    Ok(EurocCamera {
        name: name.to_string(),
        comment: camera.rostopic.clone(),
        body_from_camera: camera.camera_from_imu.inverse(),
        rate_hz: 1e9 / median as f64,
        intrinsics: camera.intrinsics,
        distortion: RadialTangential::NONE,
        colour: CameraColour::Grey16,
    })
}

/// imu0 as `dso/imu_config.yaml` describes it.
pub(super) fn imu(calibration: &TumViCalibration) -> Result<EurocImu, CoreError> {
    read_kalibr_imu_yaml(&calibration.dso_dir.join(IMU_CONFIG_FILE))
}
