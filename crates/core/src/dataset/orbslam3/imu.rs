//! The IMU keys of ORB-SLAM3 v1.0's inertial settings, shared by the stereo-inertial and the
//! RGB-D-inertial files.

use super::stereo::{opencv_matrix, real};
use crate::dataset::euroc::EurocImu;
use crate::Pose;

/// `IMU.T_b_c1` (camera `camera`'s pose in the IMU frame: inverse(T_BS imu0) · T_BS camera)
/// and the IMU's noise model and rate. ORB-SLAM3's `IMU.Noise*`/`*Walk` are continuous-time
/// densities as Kalibr's and EuRoC's sensor.yaml give them (ORB-SLAM3 scales them by √rate
/// itself).
pub(super) fn imu_part(camera: &str, body_from_camera: &Pose, imu: &EurocImu) -> String {
    let imu_from_camera = imu.body_from_imu.inverse().compose(body_from_camera);
    format!(
        "# {camera}'s pose in the IMU (body) frame: inverse(T_BS imu0) * T_BS {camera}.\n\
         {t_b_c1}\
         \n\
         # {comment}: continuous-time densities, as in imu0/sensor.yaml.\n\
         IMU.NoiseGyro: {noise_gyro}\n\
         IMU.NoiseAcc: {noise_acc}\n\
         IMU.GyroWalk: {gyro_walk}\n\
         IMU.AccWalk: {acc_walk}\n\
         IMU.Frequency: {rate}\n",
        t_b_c1 = opencv_matrix("IMU.T_b_c1", &imu_from_camera),
        comment = crate::printable(&imu.comment),
        noise_gyro = real(imu.gyroscope_noise_density),
        noise_acc = real(imu.accelerometer_noise_density),
        gyro_walk = real(imu.gyroscope_random_walk),
        acc_walk = real(imu.accelerometer_random_walk),
        rate = real(imu.rate_hz),
    )
}
