//! Ideal IMU readings: what a perfect gyroscope and accelerometer rigidly mounted on the moving
//! body would measure.

use glam::{DMat3, DVec3};

use crate::{CoreError, Pose, SplineSe3};

/// Gravity in the world frame, m/s², for rslam's z-up worlds.
pub const GRAVITY_WORLD: DVec3 = DVec3::new(0.0, 0.0, -9.81);

/// One gyroscope and accelerometer reading, both in the IMU's own axes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImuReading {
    /// Angular velocity, rad/s.
    pub gyroscope: DVec3,
    /// Specific force (acceleration minus gravity), m/s²: +9.81 up when at rest.
    pub accelerometer: DVec3,
}

/// The ideal reading at `t` of an IMU mounted at `body_from_imu`: ω_I, and
/// `a_I = R_WIᵀ (a_WI − g_W)` with a_WI the acceleration of the IMU's origin.
///
/// The IMU's own motion is evaluated exactly, as the spline's derivatives right-multiplied by the
/// constant extrinsic (`world_from_imu = world_from_body ∘ body_from_imu`), rather than by adding
/// the lever-arm terms ω×(ω×r) + α×r to the body's acceleration; the two agree (a spline test
/// checks it).
pub fn ideal_reading(
    spline: &SplineSe3,
    t: f64,
    body_from_imu: &Pose,
    gravity_world: DVec3,
) -> Result<ImuReading, CoreError> {
    let imu = spline.evaluate_frame(t, body_from_imu)?;
    let imu_from_world = DMat3::from_quat(imu.world_from_body.rotation).transpose();
    Ok(ImuReading {
        gyroscope: imu.angular_velocity_body,
        accelerometer: imu_from_world * (imu.linear_acceleration_world - gravity_world),
    })
}
