use crate::Pose;

/// Timestamped camera-to-world poses, in time order as read or generated.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trajectory {
    /// Seconds.
    pub timestamps: Vec<f64>,
    pub poses: Vec<Pose>,
}

impl Trajectory {
    pub fn new(timestamps: Vec<f64>, poses: Vec<Pose>) -> Self {
        assert_eq!(timestamps.len(), poses.len(), "one timestamp per pose");
        Self { timestamps, poses }
    }

    /// Poses stamped `i / rate_hz`.
    pub fn from_poses_at_rate(poses: Vec<Pose>, rate_hz: f64) -> Self {
        let timestamps = (0..poses.len()).map(|i| i as f64 / rate_hz).collect();
        Self { timestamps, poses }
    }

    pub fn len(&self) -> usize {
        self.poses.len()
    }

    pub fn is_empty(&self) -> bool {
        self.poses.is_empty()
    }

    /// Sum of distances between consecutive positions (evo's `path_length`).
    pub fn path_length(&self) -> f64 {
        self.poses
            .windows(2)
            .map(|w| (w[1].translation - w[0].translation).length())
            .sum()
    }
}
