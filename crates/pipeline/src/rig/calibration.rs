//! A rig's calibration perturbations (`baseline`, `extrinsic_rot`, `extrinsic_trans`; see
//! [`rslam_perturb::calibration`]): where each sensor really is, what the calibration files
//! state, and the manifest's record of both.
//!
//! Items apply in the order written, rendered ones to the actual rig and `@calibration` ones to
//! the written rig, both starting from the nominal rig. Camera `i` draws with
//! [`camera_seed`]`(seed, i)`, the IMU with [`imu_seed`]`(seed)`; `baseline` moves cam1 and
//! draws with cam1's seed.

use rslam_core::dataset::euroc::IMU_DIR;
use rslam_core::Pose;
use rslam_perturb::calibration::{move_along_baseline, CalibrationItem, CalibrationMode, BASELINE};
use rslam_perturb::{PerturbError, PerturbSpec};
use serde_json::{json, Value};

use super::euroc_render::{camera_seed, imu_seed};
use super::preset::Rig;

/// Per cam1 frame under `baseline@dynamic`: its δ and cam1's actual baseline, beside the
/// manifest.
pub const PER_FRAME_FILE: &str = "calibration_per_frame.csv";

/// The rig as mounted and as calibrated.
#[derive(Clone, Debug)]
pub struct PerturbedRig {
    /// Where the sensors are: frames and IMU readings are made with it (cam1 before a
    /// `baseline@dynamic` offset, which [`PerturbedRig::body_from_camera`] adds per frame).
    pub actual: Rig,
    /// What the calibration files state.
    pub written: Rig,
    /// `baseline@dynamic`, with cam1's seed.
    dynamic_baseline: Option<(CalibrationItem, u64)>,
    /// δ of a per-sequence `baseline` and its mode.
    baseline_offset: Option<(f64, CalibrationMode)>,
}

/// The sensors of `rig` as a spec names them: its cameras, then `imu0` when it has an IMU.
pub fn sensor_names(rig: &Rig) -> Vec<&str> {
    let cameras = rig.cameras.iter().map(|c| c.name.as_str());
    cameras.chain(rig.imu.as_ref().map(|_| IMU_DIR)).collect()
}

/// Distance from cam0 to cam1 along cam0's x axis, metres: a rectified pair's baseline.
fn baseline_m(body_from_cam0: &Pose, body_from_cam1: &Pose) -> f64 {
    body_from_cam0
        .inverse()
        .compose(body_from_cam1)
        .translation
        .x
}

impl PerturbedRig {
    /// Applies the spec's calibration items to `nominal`; refuses an item addressed to a sensor
    /// the rig lacks, and `baseline` on a rig with fewer than two cameras.
    pub fn new(nominal: &Rig, spec: &PerturbSpec, seed: u64) -> Result<Self, PerturbError> {
        if let Some(problem) = spec.unknown_sensor(&sensor_names(nominal)) {
            return Err(problem);
        }
        let mut rig = Self {
            actual: nominal.clone(),
            written: nominal.clone(),
            dynamic_baseline: None,
            baseline_offset: None,
        };
        for item in &spec.calibration {
            if item.name == BASELINE && nominal.cameras.len() < 2 {
                return Err(PerturbError::spec(
                    item.to_string(),
                    format!(
                        "needs two cameras (cam0, cam1); there are {}",
                        nominal.cameras.len()
                    ),
                ));
            }
            let target = match item.mode {
                CalibrationMode::Rendered => &mut rig.actual,
                CalibrationMode::Calibration => &mut rig.written,
            };
            if item.name == BASELINE {
                let cam1_seed = camera_seed(seed, 1);
                if item.dynamic {
                    rig.dynamic_baseline = Some((item.clone(), cam1_seed));
                    continue;
                }
                let delta = item.baseline_offset(cam1_seed, 0);
                let cam0 = target.cameras[0].body_from_camera;
                let cam1 = &mut target.cameras[1].body_from_camera;
                *cam1 = move_along_baseline(&cam0, cam1, delta);
                rig.baseline_offset = Some((delta, item.mode));
                continue;
            }
            for (i, camera) in target.cameras.iter_mut().enumerate() {
                if item.moves(&camera.name) {
                    camera.body_from_camera =
                        item.apply_extrinsic(&camera.body_from_camera, camera_seed(seed, i));
                }
            }
            if let Some(imu) = target.imu.as_mut().filter(|_| item.moves(IMU_DIR)) {
                imu.body_from_imu = item.apply_extrinsic(&imu.body_from_imu, imu_seed(seed));
            }
        }
        Ok(rig)
    }

    /// δ of `baseline@dynamic` on cam1's frame `frame`; 0 without it.
    fn dynamic_offset(&self, frame: usize) -> f64 {
        self.dynamic_baseline.as_ref().map_or(0.0, |(item, seed)| {
            item.baseline_offset(*seed, frame as u32)
        })
    }

    /// Camera `index`'s actual `T_BS` on its frame `frame`.
    pub fn body_from_camera(&self, index: usize, frame: usize) -> Pose {
        let camera = self.actual.cameras[index].body_from_camera;
        if index != 1 || self.dynamic_baseline.is_none() {
            return camera;
        }
        let cam0 = self.actual.cameras[0].body_from_camera;
        move_along_baseline(&cam0, &camera, self.dynamic_offset(frame))
    }

    /// The manifest's `calibration`: each sensor's actual and written `T_BS` (row-major; cam1's
    /// actual one before a per-frame offset), and with two cameras the baseline along cam0's x
    /// axis, nominal, actual and written, and the δ drawn.
    pub fn record(&self, nominal: &Rig) -> Value {
        let pose = |p: &Pose| p.to_row_major().to_vec();
        let mut sensors: Vec<Value> = nominal
            .cameras
            .iter()
            .zip(&self.actual.cameras)
            .zip(&self.written.cameras)
            .map(|((n, a), w)| {
                json!({
                    "name": n.name,
                    "nominal_T_BS": pose(&n.body_from_camera),
                    "true_T_BS": pose(&a.body_from_camera),
                    "written_T_BS": pose(&w.body_from_camera),
                })
            })
            .collect();
        if let (Some(n), Some(a), Some(w)) = (&nominal.imu, &self.actual.imu, &self.written.imu) {
            sensors.push(json!({
                "name": IMU_DIR,
                "nominal_T_BS": pose(&n.body_from_imu),
                "true_T_BS": pose(&a.body_from_imu),
                "written_T_BS": pose(&w.body_from_imu),
            }));
        }
        let mut record = json!({ "sensors": sensors });
        if let ([n0, n1, ..], [a0, a1, ..], [w0, w1, ..]) = (
            nominal.cameras.as_slice(),
            self.actual.cameras.as_slice(),
            self.written.cameras.as_slice(),
        ) {
            record["baseline_m"] = json!({
                "nominal": baseline_m(&n0.body_from_camera, &n1.body_from_camera),
                "true": baseline_m(&a0.body_from_camera, &a1.body_from_camera),
                "written": baseline_m(&w0.body_from_camera, &w1.body_from_camera),
            });
        }
        if let Some((delta, mode)) = self.baseline_offset {
            record["baseline_offset_m"] = json!(delta);
            record["baseline_mode"] = json!(mode);
        }
        if self.dynamic_baseline.is_some() {
            record["baseline_mode"] = json!("dynamic");
            record["per_frame"] = json!(PER_FRAME_FILE);
        }
        record
    }

    /// [`PER_FRAME_FILE`] for cam1's frames stamped `cam1_times_ns`, under `baseline@dynamic`:
    /// `frame,t_ns,baseline_offset_m,baseline_true_m`.
    pub fn per_frame_csv(&self, cam1_times_ns: &[u64]) -> Option<String> {
        self.dynamic_baseline.as_ref()?;
        let cam0 = self.actual.cameras[0].body_from_camera;
        let mut csv = String::from("frame,t_ns,baseline_offset_m,baseline_true_m\n");
        for (frame, t_ns) in cam1_times_ns.iter().enumerate() {
            let baseline = baseline_m(&cam0, &self.body_from_camera(1, frame));
            csv.push_str(&format!(
                "{frame},{t_ns},{:e},{baseline:e}\n",
                self.dynamic_offset(frame)
            ));
        }
        Some(csv)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rig::STEREO_BASELINE_M;

    fn perturbed(text: &str, seed: u64) -> PerturbedRig {
        PerturbedRig::new(&Rig::stereo_imu(), &PerturbSpec::parse(text).unwrap(), seed).unwrap()
    }

    #[test]
    fn rendered_items_move_the_actual_rig_and_calibration_items_the_written_one() {
        let nominal = Rig::stereo_imu();
        let rendered = perturbed("baseline:0.01", 3);
        assert_eq!(rendered.written, nominal);
        let delta = rendered.record(&nominal)["baseline_offset_m"]
            .as_f64()
            .unwrap();
        assert!(delta != 0.0);
        let true_b = baseline_m(
            &rendered.actual.cameras[0].body_from_camera,
            &rendered.actual.cameras[1].body_from_camera,
        );
        assert!((true_b - (STEREO_BASELINE_M + delta)).abs() < 1e-12);
        assert_eq!(rendered.actual.cameras[0], nominal.cameras[0]);

        let calibration = perturbed("baseline:0.01@calibration", 3);
        assert_eq!(calibration.actual, nominal);
        assert_eq!(
            calibration.written.cameras[1].body_from_camera,
            rendered.actual.cameras[1].body_from_camera,
            "the same draw in either mode"
        );
    }

    #[test]
    fn extrinsic_items_move_the_named_sensor_or_every_camera() {
        let nominal = Rig::stereo_imu();
        let imu = perturbed("imu0:extrinsic_rot:1@calibration", 0);
        assert_eq!(imu.written.cameras, nominal.cameras);
        assert_ne!(imu.written.imu, nominal.imu);
        let every = perturbed("extrinsic_trans:0.01", 0);
        assert_eq!(every.actual.imu, nominal.imu);
        for (a, n) in every.actual.cameras.iter().zip(&nominal.cameras) {
            assert_ne!(a.body_from_camera, n.body_from_camera, "{}", a.name);
        }
        let offsets: Vec<_> = every
            .actual
            .cameras
            .iter()
            .zip(&nominal.cameras)
            .map(|(a, n)| a.body_from_camera.translation - n.body_from_camera.translation)
            .collect();
        assert_ne!(offsets[0], offsets[1], "each camera draws its own");
    }

    #[test]
    fn dynamic_baseline_draws_per_frame_with_the_stated_sigma() {
        let sigma = 0.01;
        let rig = perturbed(&format!("baseline:{sigma}@dynamic"), 11);
        let n = 4000;
        let baselines: Vec<f64> = (0..n)
            .map(|k| {
                baseline_m(
                    &rig.actual.cameras[0].body_from_camera,
                    &rig.body_from_camera(1, k),
                )
            })
            .collect();
        let offsets: Vec<f64> = baselines.iter().map(|b| b - STEREO_BASELINE_M).collect();
        let mean = offsets.iter().sum::<f64>() / n as f64;
        let std = (offsets.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt();
        assert!(mean.abs() < 4.0 * sigma / (n as f64).sqrt(), "mean {mean}");
        assert!((std / sigma - 1.0).abs() < 0.05, "std {std}");
        // Neighbouring frames are independent draws: lag-1 correlation near 0.
        let lag1 = offsets
            .windows(2)
            .map(|w| (w[0] - mean) * (w[1] - mean))
            .sum::<f64>()
            / ((n - 1) as f64 * std * std);
        assert!(lag1.abs() < 0.05, "lag-1 correlation {lag1}");
        // cam0 stays, the written rig is nominal.
        assert_eq!(
            rig.body_from_camera(0, 5),
            rig.actual.cameras[0].body_from_camera
        );
        assert_eq!(rig.written, Rig::stereo_imu());
        let csv = rig.per_frame_csv(&[10, 20]).unwrap();
        let row: Vec<&str> = csv.lines().nth(2).unwrap().split(',').collect();
        assert_eq!(row[..2], ["1", "20"]);
        let offset: f64 = row[2].parse().unwrap();
        assert!((offset - offsets[1]).abs() < 1e-12);
    }

    #[test]
    fn unknown_sensors_and_a_one_camera_baseline_are_refused() {
        let spec = PerturbSpec::parse("cam2:extrinsic_rot:1").unwrap();
        let err = PerturbedRig::new(&Rig::stereo(), &spec, 0)
            .unwrap_err()
            .to_string();
        assert_eq!(
            err,
            "--perturb item 'cam2:extrinsic_rot:1': no sensor 'cam2' here; the sensors are cam0, cam1"
        );
        let spec = PerturbSpec::parse("imu0:extrinsic_rot:1").unwrap();
        let err = PerturbedRig::new(&Rig::stereo(), &spec, 0)
            .unwrap_err()
            .to_string();
        assert!(err.contains("no sensor 'imu0'"), "{err}");
        let mut mono = Rig::stereo();
        mono.cameras.truncate(1);
        let spec = PerturbSpec::parse("baseline:0.01").unwrap();
        let err = PerturbedRig::new(&mono, &spec, 0).unwrap_err().to_string();
        assert!(
            err.contains("needs two cameras (cam0, cam1); there are 1"),
            "{err}"
        );
    }
}
