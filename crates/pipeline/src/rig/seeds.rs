//! How a rig's sensors draw their randomness from the job's seed: each camera its frame
//! corruptions, the IMU its noise.

use rslam_core::hash::splitmix64;

/// Camera `index`'s seed for its frame corruptions: the job's seed for cam0 (so cam0 is
/// corrupted as a one-camera render with that seed would be), then the next states of a
/// SplitMix64 stream from it, `seed + index · 0x9e3779b97f4a7c15` (wrapping), so that the noise
/// differs between cameras.
pub fn camera_seed(seed: u64, index: usize) -> u64 {
    seed.wrapping_add((index as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15))
}

/// The IMU noise's seed: `splitmix64(seed ^ 0x494d_5530)` ("IMU0"), unrelated to any camera's.
pub fn imu_seed(seed: u64) -> u64 {
    splitmix64(seed ^ 0x494d_5530)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camera_seeds_differ_and_cam0_keeps_the_job_seed() {
        assert_eq!(camera_seed(7, 0), 7);
        assert_ne!(camera_seed(7, 1), 7);
        assert_ne!(camera_seed(7, 1), camera_seed(7, 2));
        assert_ne!(imu_seed(7), camera_seed(7, 1));
        assert_eq!(
            camera_seed(u64::MAX, 1),
            u64::MAX.wrapping_add(0x9e37_79b9_7f4a_7c15)
        );
    }
}
