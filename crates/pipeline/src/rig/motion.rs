//! The rig's motion: the body's path from cam0's, its spline, when each sensor samples it, and
//! the IMU and ground-truth rows of the EuRoC layout.
//!
//! The spec's motion items act on the path before the spline: `rot`/`trans` deviate cam0's path
//! (the deviated path is the new ground truth, as for one camera), `fast:K` plays it K times
//! faster (its stamps divided by K). Every sensor then samples the changed motion at its own
//! rate, so the IMU feels what the cameras see: under `fast:K` a camera at the path's rate gets
//! the path's frames 0, K, 2K, … (docs/src/perturbations.md §6) and the IMU K× the angular velocity and
//! K² the acceleration.

use rslam_core::dataset::euroc::{
    nanoseconds_from_seconds, EurocImu, GroundTruthState, ImuSample as ImuRow,
};
use rslam_core::imu::{synthesize_imu, ImuNoise, ImuSample, ImuSynthesis};
use rslam_core::{CoreError, Pose, SplineSe3, Trajectory};

use crate::{JobPart, PipelineError};

/// The path the body follows in a rig render: cam0's `path` (the deviated one, stamped at the
/// job's rate as `stamps`) played `speed_up` times faster ([`crate::plan::speed_up`]), carried to
/// the body:
/// `world_from_body = world_from_cam0 ∘ body_from_cam0⁻¹`.
pub fn body_path(
    stamps: &[f64],
    path: &[Pose],
    speed_up: u32,
    body_from_cam0: &Pose,
) -> Trajectory {
    let speed_up = f64::from(speed_up);
    let cam0_from_body = body_from_cam0.inverse();
    Trajectory::new(
        stamps.iter().map(|t| t / speed_up).collect(),
        path.iter()
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

/// IMU samples along the spline at the sensor.yaml's rate and placement, with `noise` (the
/// sensor.yaml's, or scaled by `imu_noise`), seeded by `seed`.
pub fn imu_samples(
    spline: &SplineSe3,
    imu: &EurocImu,
    noise: ImuNoise,
    seed: u64,
) -> Result<Vec<ImuSample>, PipelineError> {
    let options = ImuSynthesis {
        rate_hz: imu.rate_hz,
        body_from_imu: imu.body_from_imu,
        noise,
        seed,
        ..ImuSynthesis::default()
    };
    Ok(synthesize_imu(spline, &options)?)
}

/// `t` seconds as whole nanoseconds (rounded), or an error naming the time.
pub fn nanoseconds(t: f64) -> Result<u64, PipelineError> {
    nanoseconds_from_seconds(t).ok_or_else(|| {
        PipelineError::option(
            JobPart::Trajectory,
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

/// The body's motion through its path.
pub(super) fn motion_spline(body: &Trajectory) -> Result<SplineSe3, PipelineError> {
    SplineSe3::from_trajectory(body).map_err(|e| match e {
        CoreError::SplineTooShort { poses } => PipelineError::option(
            JobPart::Frames,
            format!("{poses} poses: a rig's motion spline needs at least 4"),
        ),
        other => other.into(),
    })
}

#[cfg(test)]
mod tests {
    use glam::{DQuat, DVec3};
    use rslam_perturb::PerturbSpec;

    use super::*;

    /// `imu_noise:K` scales the synthesis noise: with the same seed, every reading's error
    /// (white noise and walked bias alike) is K times the nominal one, exactly up to rounding.
    #[test]
    fn imu_noise_scales_every_synthesised_error_by_k() {
        let poses = (0..8)
            .map(|i| {
                let t = i as f64 * 0.1;
                Pose::new(
                    DQuat::from_rotation_z(0.3 * t) * DQuat::from_rotation_x(0.1 * t),
                    DVec3::new(t, 0.5 * t * t, 0.1),
                )
            })
            .collect();
        let spline = SplineSe3::from_control_poses(0.0, 0.1, poses).unwrap();
        let imu = EurocImu::adis16448();
        let with = |text: &str| {
            let noise = PerturbSpec::parse(text)
                .unwrap()
                .imu
                .synthesis_noise(imu.noise());
            imu_samples(&spline, &imu, noise, 42).unwrap()
        };
        let (clean, nominal, tripled) = (
            with("imu_noise:0"),
            with("imu_noise:1"),
            with("imu_noise:3"),
        );
        assert!(clean.len() > 50);
        for ((c, n), t) in clean.iter().zip(&nominal).zip(&tripled) {
            assert_eq!(c.measured, c.truth, "K = 0 is a perfect IMU");
            let error = |s: &ImuSample| {
                (
                    s.measured.gyroscope - c.truth.gyroscope,
                    s.measured.accelerometer - c.truth.accelerometer,
                )
            };
            let ((gn, an), (gt, at)) = (error(n), error(t));
            assert!((gt - 3.0 * gn).length() < 1e-12 * (1.0 + gn.length()));
            assert!((at - 3.0 * an).length() < 1e-12 * (1.0 + an.length()));
            assert!((t.bias.gyroscope - 3.0 * n.bias.gyroscope).length() < 1e-15);
        }
        assert!(nominal[1].measured != nominal[1].truth);
    }
}
