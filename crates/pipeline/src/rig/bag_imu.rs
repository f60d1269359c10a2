//! The spec's IMU items on a recorded bag's `sensor_msgs/Imu` topics: each topic is a stream of
//! its own (its rate the median step of its stamps, its draws keyed by the job's IMU seed and
//! the topic's place), perturbed as a recorded EuRoC IMU is, and written back message for
//! message ([`RecordedImu::rewritten`]). A bag carries no ground-truth biases to update, and
//! states its IMU's noise only as each reading's covariance: `imu_noise:K` scales that white
//! noise and adds no bias random walk, which the bag does not state.

use rslam_core::dataset::ros2::{Imu, LogTimes, RecordedBagCameras, RecordedImu};
use rslam_core::imu::ImuNoise;
use rslam_perturb::imu::ImuOrigin;
use rslam_perturb::PerturbSpec;

use super::imu_items::perturb_imu_stream;
use super::seeds::{camera_seed, imu_seed};
use crate::PipelineError;

/// A bag's IMU topics after the spec: per topic changed, its index among the bag's topics and
/// its messages; and what the items drew, per topic, for the manifest.
pub(crate) struct BagImus {
    pub messages: Vec<(usize, Vec<(Imu, LogTimes)>)>,
    pub report: Option<serde_json::Value>,
}

/// The IMU items of `spec` applied to each IMU topic of `recorded` (none without IMU items).
pub(crate) fn perturb_bag_imus(
    recorded: &RecordedBagCameras,
    spec: &PerturbSpec,
    seed: u64,
) -> Result<BagImus, PipelineError> {
    let mut imus = BagImus {
        messages: Vec::new(),
        report: None,
    };
    if !spec.imu.changes_imu() {
        return Ok(imus);
    }
    let mut report = serde_json::Map::new();
    for (k, imu) in recorded.imus.iter().enumerate() {
        let bad = |message: String| PipelineError::Input {
            path: recorded.bag.folder.clone(),
            message,
        };
        let samples = imu.samples().map_err(bad)?;
        let rate_hz = imu.rate_hz().map_err(bad)?;
        let perturbed = perturb_imu_stream(
            spec,
            &samples,
            &[],
            rate_hz,
            ImuOrigin::Recorded(recorded_noise(imu, spec, rate_hz).map_err(bad)?),
            camera_seed(imu_seed(seed), k),
        )?;
        let messages = perturbed
            .samples
            .iter()
            .zip(&perturbed.input_index)
            .map(|(sample, &input)| imu.rewritten(input, sample))
            .collect();
        imus.messages.push((imu.index, messages));
        let drawn = serde_json::to_value(perturbed.report)
            .map_err(|e| PipelineError::Worker(format!("IMU report for the manifest: {e}")))?;
        report.insert(imu.name.clone(), drawn);
    }
    imus.report = Some(report.into());
    Ok(imus)
}

/// The noise `imu_noise` scales: what the topic's covariances state. Without `imu_noise` none is
/// needed.
fn recorded_noise(imu: &RecordedImu, spec: &PerturbSpec, rate_hz: f64) -> Result<ImuNoise, String> {
    match (spec.imu.noise_scale, imu.stated_noise(rate_hz)) {
        (None, _) => Ok(ImuNoise::ZERO),
        (Some(_), Some(noise)) => Ok(noise),
        (Some(k), None) => Err(format!(
            "imu_noise:{k}: topic {} states no noise (its angular velocity and linear acceleration covariances are 0, unknown by REP 145), so there is no recorded noise to scale",
            imu.name
        )),
    }
}
