//! A rig's calibration perturbations (`baseline`, `extrinsic_rot`, `extrinsic_trans`; see
//! [`rslam_perturb::calibration`]): where each sensor really is, what the calibration files
//! state, and the manifest's record of both.
//!
//! Items apply in the order written, rendered ones to the actual rig and `@calibration` ones to
//! the written rig, both starting from the nominal rig. `@dynamic` items move a camera per frame
//! on top of the actual rig: on frame k, `T_BS(k) = B_k · Δ_k`, where `B_k` is the actual `T_BS`
//! (for cam1 moved by `baseline@dynamic`'s δ_k along cam0's x axis) and `Δ_k` the product of the
//! camera's `extrinsic_*@dynamic` draws for frame k, in the order written. Camera `i` draws with
//! [`camera_seed`]`(seed, i)`, the IMU with [`imu_seed`]`(seed)`; `baseline` moves cam1 and
//! draws with cam1's seed.

use rslam_core::dataset::euroc::{EurocCamera, IMU_DIR};
use rslam_core::Pose;
use rslam_perturb::calibration::{move_along_baseline, CalibrationItem, CalibrationMode, BASELINE};
use rslam_perturb::{PerturbError, PerturbSpec};
use serde_json::{json, Value};

use super::preset::Rig;
use super::seeds::{camera_seed, imu_seed};

/// What the `@dynamic` items drew on every frame, beside the manifest.
pub const PER_FRAME_FILE: &str = "calibration_per_frame.csv";

/// The rig as mounted and as calibrated.
#[derive(Clone, Debug)]
pub struct PerturbedRig {
    /// Where the sensors are: frames and IMU readings are made with it (the cameras before their
    /// `@dynamic` moves, which [`PerturbedRig::body_from_camera`] adds per frame).
    pub actual: Rig,
    /// What the calibration files state.
    pub written: Rig,
    /// The `@dynamic` items, in the order written.
    dynamic: Vec<CalibrationItem>,
    /// The job's seed, for the cameras' per-frame draws.
    seed: u64,
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
            dynamic: Vec::new(),
            seed,
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
            if item.dynamic {
                let clocks = |c: (&EurocCamera, &i64)| (c.0.rate_hz, *c.1);
                let mut cameras = nominal.cameras.iter().zip(&nominal.time_offsets_ns);
                let first = cameras.next().map(clocks);
                if cameras.any(|c| Some(clocks(c)) != first) {
                    return Err(PerturbError::spec(
                        item.to_string(),
                        "its per-frame draws are listed by frame for every camera at once; the rig's cameras differ in rate or time offset".to_string(),
                    ));
                }
                rig.dynamic.push(item.clone());
                continue;
            }
            let target = match item.mode {
                CalibrationMode::Rendered => &mut rig.actual,
                CalibrationMode::Calibration => &mut rig.written,
            };
            if item.name == BASELINE {
                let delta = item.baseline_offset(camera_seed(seed, 1), 0);
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

    /// δ of `baseline@dynamic` on cam1's frame `frame`; `None` without it.
    fn dynamic_baseline_offset(&self, frame: usize) -> Option<f64> {
        let item = self.dynamic.iter().find(|item| item.name == BASELINE)?;
        Some(item.baseline_offset(camera_seed(self.seed, 1), frame as u32))
    }

    /// Camera `index`'s `Δ_k` on its frame `frame`: the product of its `extrinsic_*@dynamic`
    /// draws; `None` when none moves it.
    fn dynamic_extrinsic(&self, index: usize, frame: usize) -> Option<Pose> {
        let name = &self.actual.cameras[index].name;
        let seed = camera_seed(self.seed, index);
        self.dynamic
            .iter()
            .filter(|item| item.name != BASELINE && item.moves(name))
            .map(|item| item.extrinsic_offset(seed, frame as u32))
            .reduce(|a, b| a.compose(&b))
    }

    /// Camera `index`'s actual `T_BS` on its frame `frame`.
    pub fn body_from_camera(&self, index: usize, frame: usize) -> Pose {
        let mut camera = self.actual.cameras[index].body_from_camera;
        if let Some(delta) = self.dynamic_baseline_offset(frame).filter(|_| index == 1) {
            let cam0 = self.actual.cameras[0].body_from_camera;
            camera = move_along_baseline(&cam0, &camera, delta);
        }
        match self.dynamic_extrinsic(index, frame) {
            Some(delta) => camera.compose(&delta),
            None => camera,
        }
    }

    /// The manifest's `calibration`: each sensor's actual and written `T_BS` (row-major; a
    /// camera's actual one before its `@dynamic` moves), with two cameras the baseline along
    /// cam0's x axis, nominal, actual and written, and the δ drawn; with `@dynamic` items, those
    /// items (`dynamic`) and the file with their draws (`per_frame`).
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
        if self.dynamic.iter().any(|item| item.name == BASELINE) {
            record["baseline_mode"] = json!("dynamic");
        }
        if !self.dynamic.is_empty() {
            let items: Vec<String> = self.dynamic.iter().map(ToString::to_string).collect();
            record["dynamic"] = json!(items);
            record["per_frame"] = json!(PER_FRAME_FILE);
        }
        record
    }

    /// [`PER_FRAME_FILE`] for the frames stamped `times_ns` (the rig's cameras share their
    /// frame times), when an item is `@dynamic`: `frame,t_ns`, then under `baseline@dynamic`
    /// `baseline_offset_m` (δ_k), with two cameras `baseline_true_m` (cam1 along cam0's x axis
    /// on that frame), and for each camera an `extrinsic_*@dynamic` item moves, its `Δ_k` as
    /// `camN_rot_{x,y,z}_deg` (rotation vector, degrees) and `camN_trans_{x,y,z}_m` (metres),
    /// both in the camera's frame.
    pub fn per_frame_csv(&self, times_ns: &[u64]) -> Option<String> {
        if self.dynamic.is_empty() {
            return None;
        }
        let moved: Vec<(usize, &str)> = self
            .actual
            .cameras
            .iter()
            .enumerate()
            .filter(|(i, _)| self.dynamic_extrinsic(*i, 0).is_some())
            .map(|(i, camera)| (i, camera.name.as_str()))
            .collect();
        let two_cameras = self.actual.cameras.len() >= 2;
        let mut header = vec!["frame".to_string(), "t_ns".to_string()];
        if self.dynamic_baseline_offset(0).is_some() {
            header.push("baseline_offset_m".into());
        }
        if two_cameras {
            header.push("baseline_true_m".into());
        }
        for (_, name) in &moved {
            for quantity in ["rot", "trans"] {
                let unit = if quantity == "rot" { "deg" } else { "m" };
                header
                    .extend(["x", "y", "z"].map(|axis| format!("{name}_{quantity}_{axis}_{unit}")));
            }
        }
        let mut csv = header.join(",") + "\n";
        for (frame, t_ns) in times_ns.iter().enumerate() {
            let mut row = vec![frame.to_string(), t_ns.to_string()];
            row.extend(
                self.dynamic_baseline_offset(frame)
                    .map(|d| format!("{d:e}")),
            );
            if two_cameras {
                let baseline = baseline_m(
                    &self.body_from_camera(0, frame),
                    &self.body_from_camera(1, frame),
                );
                row.push(format!("{baseline:e}"));
            }
            for (i, _) in &moved {
                let delta = self.dynamic_extrinsic(*i, frame).unwrap_or(Pose::IDENTITY);
                let rotation = delta.rotation.to_scaled_axis() * 180.0 / std::f64::consts::PI;
                let values = rotation
                    .to_array()
                    .into_iter()
                    .chain(delta.translation.to_array());
                row.extend(values.map(|v| format!("{v:e}")));
            }
            csv.push_str(&(row.join(",") + "\n"));
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
    fn per_frame_draws_need_cameras_on_one_clock() {
        let mut rig = Rig::stereo_imu();
        rig.time_offsets_ns[1] = 2_500_000;
        let spec = PerturbSpec::parse("cam1:extrinsic_rot:1@dynamic").unwrap();
        let err = PerturbedRig::new(&rig, &spec, 0).err().unwrap().to_string();
        assert!(err.contains("differ in rate or time offset"), "{err}");
        rig.time_offsets_ns[1] = 0;
        rig.cameras[1].rate_hz = 10.0;
        assert!(PerturbedRig::new(&rig, &spec, 0).is_err());
        let once = PerturbSpec::parse("cam1:extrinsic_rot:1").unwrap();
        PerturbedRig::new(&rig, &once, 0).unwrap();
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

    /// The CSV's rows as numbers by column name.
    fn csv_columns(csv: &str) -> Vec<(String, Vec<f64>)> {
        let mut lines = csv.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let rows: Vec<Vec<f64>> = lines
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect();
        header
            .iter()
            .enumerate()
            .map(|(c, name)| (name.to_string(), rows.iter().map(|r| r[c]).collect()))
            .collect()
    }

    fn column<'a>(columns: &'a [(String, Vec<f64>)], name: &str) -> &'a [f64] {
        &columns.iter().find(|(n, _)| n == name).unwrap().1
    }

    #[test]
    fn dynamic_extrinsics_move_each_frame_by_the_draws_the_csv_lists() {
        let nominal = Rig::stereo_imu();
        const MOVING: &str =
            "cam1:extrinsic_rot:0.5@dynamic,cam1:extrinsic_trans:0.01@dynamic,cam0:extrinsic_rot:0.2@dynamic";
        let rig = perturbed(MOVING, 4);
        assert_eq!(rig.actual, nominal, "nothing moves per sequence");
        assert_eq!(rig.written, nominal);
        let times: Vec<u64> = (0..10).map(|k| 1_000 + 50_000_000 * k).collect();
        let csv = rig.per_frame_csv(&times).unwrap();
        let header = csv.lines().next().unwrap();
        assert_eq!(
            header,
            "frame,t_ns,baseline_true_m,\
             cam0_rot_x_deg,cam0_rot_y_deg,cam0_rot_z_deg,cam0_trans_x_m,cam0_trans_y_m,cam0_trans_z_m,\
             cam1_rot_x_deg,cam1_rot_y_deg,cam1_rot_z_deg,cam1_trans_x_m,cam1_trans_y_m,cam1_trans_z_m"
        );
        let columns = csv_columns(&csv);
        assert_eq!(column(&columns, "t_ns")[3], times[3] as f64);
        for (i, camera) in nominal.cameras.iter().enumerate() {
            let name = &camera.name;
            let get = |q: &str, k: usize| {
                glam::DVec3::from_array(["x", "y", "z"].map(|a| {
                    column(
                        &columns,
                        &format!("{name}_{q}_{a}_{}", if q == "rot" { "deg" } else { "m" }),
                    )[k]
                }))
            };
            for k in 0..times.len() {
                // The listed Δ_k, applied to the nominal T_BS, is the pose frame k is made with.
                let rotation =
                    glam::DQuat::from_scaled_axis(get("rot", k) * std::f64::consts::PI / 180.0);
                let listed = camera
                    .body_from_camera
                    .compose(&Pose::new(rotation, get("trans", k)));
                let used = rig.body_from_camera(i, k);
                assert!(
                    used.rotation.abs_diff_eq(listed.rotation, 1e-12),
                    "{name} frame {k}"
                );
                assert!((used.translation - listed.translation).length() < 1e-12);
                assert_ne!(used, camera.body_from_camera, "{name} frame {k} moved");
            }
            assert_ne!(
                get("rot", 0),
                get("rot", 1),
                "{name}: a new draw on every frame"
            );
        }
        // cam0 only turns; the true baseline is between the cameras as placed on that frame.
        assert_eq!(column(&columns, "cam0_trans_x_m")[5], 0.0);
        let expected = baseline_m(&rig.body_from_camera(0, 5), &rig.body_from_camera(1, 5));
        assert!((column(&columns, "baseline_true_m")[5] - expected).abs() < 1e-12);
        // Frame k's draw does not depend on how many frames there are.
        let short = rig.per_frame_csv(&times[..4]).unwrap();
        assert!(csv.starts_with(&short), "{short}");
        // The same seed draws the same, another seed another.
        assert_eq!(
            perturbed(MOVING, 4).per_frame_csv(&times),
            Some(csv.clone())
        );
        assert_ne!(perturbed(MOVING, 5).per_frame_csv(&times), Some(csv));
        let record = rig.record(&nominal);
        assert_eq!(record["per_frame"], PER_FRAME_FILE);
        assert_eq!(
            record["dynamic"],
            json!([
                "cam1:extrinsic_rot:0.5@dynamic",
                "cam1:extrinsic_trans:0.01@dynamic",
                "cam0:extrinsic_rot:0.2@dynamic"
            ])
        );
        assert!(record.get("baseline_mode").is_none());
    }

    #[test]
    fn a_dynamic_baseline_and_a_dynamic_shift_add_up_on_top_of_the_per_sequence_rig() {
        let nominal = Rig::stereo_imu();
        let rig = perturbed(
            "extrinsic_rot:1,baseline:0.01@dynamic,cam1:extrinsic_trans:0.01@dynamic",
            8,
        );
        assert_ne!(rig.actual.cameras, nominal.cameras, "rotated per sequence");
        let csv = rig.per_frame_csv(&[0, 1, 2]).unwrap();
        assert!(
            csv.starts_with("frame,t_ns,baseline_offset_m,baseline_true_m,cam1_rot_x_deg,"),
            "{csv}"
        );
        let columns = csv_columns(&csv);
        for k in 0..3 {
            let actual = rig.actual.cameras[1].body_from_camera;
            let cam0 = rig.actual.cameras[0].body_from_camera;
            let shifted =
                move_along_baseline(&cam0, &actual, column(&columns, "baseline_offset_m")[k]);
            let t = glam::DVec3::from_array(
                ["x", "y", "z"].map(|a| column(&columns, &format!("cam1_trans_{a}_m"))[k]),
            );
            let expected = shifted.compose(&Pose::new(glam::DQuat::IDENTITY, t));
            let used = rig.body_from_camera(1, k);
            assert!(
                (used.translation - expected.translation).length() < 1e-12,
                "frame {k}"
            );
            assert_eq!(rig.body_from_camera(0, k), cam0, "cam0 has no dynamic item");
            let true_b = baseline_m(&cam0, &used);
            assert!((column(&columns, "baseline_true_m")[k] - true_b).abs() < 1e-12);
        }
        assert_eq!(rig.record(&nominal)["baseline_mode"], "dynamic");
    }

    #[test]
    fn unknown_sensors_and_a_one_camera_baseline_are_refused() {
        let spec = PerturbSpec::parse("cam2:extrinsic_rot:1").unwrap();
        let err = PerturbedRig::new(&Rig::stereo(), &spec, 0)
            .unwrap_err()
            .to_string();
        assert_eq!(
            err,
            "spec item 'cam2:extrinsic_rot:1': no sensor 'cam2' here; the sensors are cam0, cam1"
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
