//! The rig's motion: the body's path from cam0's, its spline, when each sensor samples it, and
//! the IMU and ground-truth rows of the EuRoC layout.

use rslam_core::dataset::euroc::{
    nanoseconds_from_seconds, EurocImu, GroundTruthState, ImuSample as ImuRow,
};
use rslam_core::imu::{synthesize_imu, ImuNoise, ImuSample, ImuSynthesis};
use rslam_core::{Pose, SplineSe3, Trajectory};

use crate::PipelineError;

/// The body's path when `cam0_path` is the path of a camera at `body_from_cam0`:
/// `world_from_body = world_from_cam0 ∘ body_from_cam0⁻¹`, at the same times.
pub fn body_path(cam0_path: &Trajectory, body_from_cam0: &Pose) -> Trajectory {
    let cam0_from_body = body_from_cam0.inverse();
    Trajectory::new(
        cam0_path.timestamps.clone(),
        cam0_path
            .poses
            .iter()
            .map(|world_from_cam0| world_from_cam0.compose(&cam0_from_body))
            .collect(),
    )
}

/// Sample times of a sensor at `rate_hz` over the spline's valid range: `start + k / rate_hz`,
/// both ends included when they fall on the grid (a microsecond of slack for rounding).
pub fn sample_times(spline: &SplineSe3, rate_hz: f64) -> Vec<f64> {
    let range = spline.valid_range();
    let steps = ((range.end - range.start) * rate_hz + 1e-6)
        .floor()
        .max(-1.0);
    (0..=steps as i64)
        .map(|k| (range.start + k as f64 / rate_hz).min(range.end))
        .collect()
}

/// Camera poses at `times`: `world_from_body(t_k) ∘ body_from_camera(k)` for frame k (the
/// camera's placement may change from frame to frame: `baseline@dynamic`).
pub fn camera_poses(
    spline: &SplineSe3,
    body_from_camera: impl Fn(usize) -> Pose,
    times: &[f64],
) -> Result<Vec<Pose>, PipelineError> {
    times
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            let state = spline.evaluate(t)?;
            Ok(state.world_from_body.compose(&body_from_camera(k)))
        })
        .collect()
}

/// IMU samples along the spline with the sensor.yaml's noise and placement, seeded by `seed`.
pub fn imu_samples(
    spline: &SplineSe3,
    imu: &EurocImu,
    seed: u64,
) -> Result<Vec<ImuSample>, PipelineError> {
    let options = ImuSynthesis {
        rate_hz: imu.rate_hz,
        body_from_imu: imu.body_from_imu,
        noise: ImuNoise {
            gyroscope_noise_density: imu.gyroscope_noise_density,
            gyroscope_random_walk: imu.gyroscope_random_walk,
            accelerometer_noise_density: imu.accelerometer_noise_density,
            accelerometer_random_walk: imu.accelerometer_random_walk,
        },
        seed,
        ..ImuSynthesis::default()
    };
    Ok(synthesize_imu(spline, &options)?)
}

/// `t` seconds as whole nanoseconds (rounded), or an error naming the time.
pub fn nanoseconds(t: f64) -> Result<u64, PipelineError> {
    nanoseconds_from_seconds(t).ok_or_else(|| {
        PipelineError::option(
            "--traj",
            format!("time {t} s: expected a finite time from 0 to about 1.8e10 s"),
        )
    })
}

/// `imu0/data.csv` rows: the measured (noisy, biased) readings, stamped in nanoseconds.
pub fn imu_rows(samples: &[ImuSample]) -> Result<Vec<ImuRow>, PipelineError> {
    samples
        .iter()
        .map(|s| {
            Ok(ImuRow {
                t_ns: nanoseconds(s.timestamp)?,
                gyro: s.measured.gyroscope,
                accel: s.measured.accelerometer,
            })
        })
        .collect()
}

/// Ground-truth rows at the IMU's sample times (the true biases of each sample), or at `times`
/// with zero biases when the rig has no IMU: the body's pose and its velocity in the world.
pub fn ground_truth_rows(
    spline: &SplineSe3,
    imu: &[ImuSample],
    times: &[f64],
) -> Result<Vec<GroundTruthState>, PipelineError> {
    let row = |t: f64, gyro_bias, accel_bias| -> Result<GroundTruthState, PipelineError> {
        let state = spline.evaluate(t)?;
        Ok(GroundTruthState {
            t_ns: nanoseconds(t)?,
            world_from_body: state.world_from_body,
            velocity: state.linear_velocity_world,
            gyro_bias,
            accel_bias,
        })
    };
    if imu.is_empty() {
        times
            .iter()
            .map(|&t| row(t, glam::DVec3::ZERO, glam::DVec3::ZERO))
            .collect()
    } else {
        imu.iter()
            .map(|s| row(s.timestamp, s.bias.gyroscope, s.bias.accelerometer))
            .collect()
    }
}
