//! What a TUM-VI export's perturbed copy holds beyond the EuRoC layout's files: its motion-capture
//! ground truth (`mav0/mocap0/data.csv`) copied byte for byte, `dso/camchain.yaml` rewritten
//! where the written calibration moved a sensor (the moved cameras' `T_cam_imu` and every
//! `T_cn_cnm1` they take part in; all of them when the IMU moved) or else copied, and every other
//! file of `dso/` copied byte for byte, except DSO's copy of imu0's readings (`dso/imu.txt`) when
//! IMU items changed them: it would contradict `imu0/data.csv`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rslam_core::dataset::euroc::{
    EurocDataset, EurocWriter, TumViCalibration, CAMCHAIN_FILE, MAV_DIR, MOCAP_DIR,
    TUM_VI_CALIBRATION_DIR,
};
use rslam_core::{CoreError, Pose};
use serde_json::{json, Value};

use super::preset::Rig;
use crate::PipelineError;

/// DSO's copy of the IMU readings in `dso/`.
const DSO_IMU_FILE: &str = "imu.txt";

/// The TUM-VI files of one perturbed copy, settled before anything is written.
pub struct TumViFiles {
    /// `mav0/mocap0/data.csv`, when the input has one.
    mocap: Option<PathBuf>,
    /// camchain.yaml's text with the moved cameras, `None` when no sensor moved (copied).
    camchain: Option<String>,
    /// The cameras whose `T_cam_imu` is rewritten.
    moved: Vec<String>,
    /// Files of `dso/` to copy: relative path in the output (`dso/…`) and source.
    copies: Vec<(String, PathBuf)>,
    /// Entries of `dso/` not copied, with why.
    left_out: Vec<(String, &'static str)>,
}

/// Every entry under `dir` (recursively), relative to it with `/`, sorted; directories are
/// walked, symbolic links are not followed.
fn entries(dir: &Path, prefix: &str, out: &mut Vec<(String, PathBuf)>) -> Result<(), CoreError> {
    let mut list: Vec<_> = std::fs::read_dir(dir)
        .map_err(|e| CoreError::io(dir, e))?
        .collect::<Result<_, _>>()
        .map_err(|e| CoreError::io(dir, e))?;
    list.sort_by_key(|e| e.file_name());
    for entry in list {
        let path = entry.path();
        let relative = format!("{prefix}/{}", entry.file_name().to_string_lossy());
        let kind = std::fs::symlink_metadata(&path)
            .map_err(|e| CoreError::io(&path, e))?
            .file_type();
        if kind.is_dir() {
            entries(&path, &relative, out)?;
        } else {
            out.push((relative, path));
        }
    }
    Ok(())
}

impl TumViFiles {
    /// The files for `dataset` (read with `calibration`) whose written rig is `written` (the
    /// recorded rig under the `@calibration` items); `imu_changed` when IMU items changed imu0's
    /// readings.
    pub fn plan(
        dataset: &EurocDataset,
        calibration: &TumViCalibration,
        written: &Rig,
        imu_changed: bool,
    ) -> Result<Self, PipelineError> {
        let body_from_imu = written
            .imu
            .as_ref()
            .map_or(Pose::IDENTITY, |i| i.body_from_imu);
        let imu_moved = body_from_imu != Pose::IDENTITY;
        let mut camera_from_imu = BTreeMap::new();
        for (recorded, written) in dataset.cameras.iter().zip(&written.cameras) {
            if imu_moved || recorded.camera.body_from_camera != written.body_from_camera {
                let pose = written.body_from_camera.inverse().compose(&body_from_imu);
                camera_from_imu.insert(written.name.clone(), pose);
            }
        }
        let camchain =
            (!camera_from_imu.is_empty()).then(|| calibration.camchain.rewritten(&camera_from_imu));
        let mut found = Vec::new();
        entries(&calibration.dso_dir, TUM_VI_CALIBRATION_DIR, &mut found)?;
        let mut copies = Vec::new();
        let mut left_out = Vec::new();
        let camchain_file = format!("{TUM_VI_CALIBRATION_DIR}/{CAMCHAIN_FILE}");
        let imu_file = format!("{TUM_VI_CALIBRATION_DIR}/{DSO_IMU_FILE}");
        for (relative, path) in found {
            if relative == camchain_file && camchain.is_some() {
                continue;
            }
            if !std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file()) {
                left_out.push((relative, "not a plain file (a link)"));
            } else if relative == imu_file && imu_changed {
                left_out.push((
                    relative,
                    "repeats imu0/data.csv's readings, which the IMU items changed",
                ));
            } else {
                copies.push((relative, path));
            }
        }
        let mocap = dataset.mav_dir.join(MOCAP_DIR).join("data.csv");
        Ok(Self {
            mocap: mocap.is_file().then_some(mocap),
            camchain,
            moved: camera_from_imu.into_keys().collect(),
            copies,
            left_out,
        })
    }

    /// What the manifest records of them.
    pub fn record(&self) -> Value {
        json!({
            "ground_truth": self.mocap.as_ref().map(|_| format!("{MAV_DIR}/{MOCAP_DIR}/data.csv (copied)")),
            "camchain": if self.camchain.is_some() { "rewritten" } else { "copied" },
            "camchain_moved": self.moved,
            "copied": self.copies.iter().map(|(relative, _)| relative).collect::<Vec<_>>(),
            "left_out": self.left_out.iter().map(|(relative, why)| json!({"file": relative, "why": why})).collect::<Vec<_>>(),
        })
    }

    pub fn write(&self, writer: &EurocWriter) -> Result<(), PipelineError> {
        let read = |path: &Path| std::fs::read(path).map_err(|e| CoreError::io(path, e));
        if let Some(mocap) = &self.mocap {
            writer.copy_sensor_file(MOCAP_DIR, "data.csv", &read(mocap)?)?;
        }
        if let Some(text) = &self.camchain {
            let relative = format!("{TUM_VI_CALIBRATION_DIR}/{CAMCHAIN_FILE}");
            writer.copy_file(&relative, text.as_bytes())?;
        }
        for (relative, path) in &self.copies {
            writer.copy_file(relative, &read(path)?)?;
        }
        Ok(())
    }
}
