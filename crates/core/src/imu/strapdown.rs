//! Strapdown dead reckoning: IMU readings integrated into pose and velocity, the check that
//! synthesised readings belong to the motion they came from.

use glam::{DQuat, DVec3};

use super::ImuSample;
use crate::Pose;

/// Where the IMU is and how fast it moves, in the world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InertialState {
    pub world_from_imu: Pose,
    /// m/s.
    pub velocity_world: DVec3,
}

/// The state after the measured readings of `samples`, starting from `start` at the first
/// sample's time (biases are not removed: pass noise-free or bias-corrected samples).
///
/// Second order, step by step between consecutive samples (trapezoidal): the orientation turns
/// by exp of the mean angular rate times Δt, the velocity follows the trapezoid rule on the world
/// acceleration `R f + g`, and the position is exact for an acceleration linear over the step.
pub fn dead_reckon(
    start: InertialState,
    samples: &[ImuSample],
    gravity_world: DVec3,
) -> InertialState {
    let (mut rotation, mut position, mut velocity) = (
        start.world_from_imu.rotation,
        start.world_from_imu.translation,
        start.velocity_world,
    );
    for pair in samples.windows(2) {
        let (from, to) = (&pair[0].measured, &pair[1].measured);
        let dt = pair[1].timestamp - pair[0].timestamp;
        let turn = DQuat::from_scaled_axis(0.5 * (from.gyroscope + to.gyroscope) * dt);
        let next = (rotation * turn).normalize();
        let a0 = rotation * from.accelerometer + gravity_world;
        let a1 = next * to.accelerometer + gravity_world;
        position += velocity * dt + (a0 / 3.0 + a1 / 6.0) * dt * dt;
        velocity += 0.5 * (a0 + a1) * dt;
        rotation = next;
    }
    InertialState {
        world_from_imu: Pose::new(rotation, position),
        velocity_world: velocity,
    }
}
