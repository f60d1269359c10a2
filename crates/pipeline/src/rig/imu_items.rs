//! The spec's IMU items in the runs: applied to a rig's IMU stream and ground truth, and `cam_imu_offset` applied to the camera stamps (the cameras'
//! stamps move, not the IMU's: the IMU's clock is the body's, which the ground truth is in).

use rslam_core::dataset::euroc::{GroundTruthState, ImuSample};
use rslam_core::dataset::Manifest;
use rslam_perturb::imu::{shift_stamp, ImuOrigin, ImuReport, ImuStream, PerturbedImu};
use rslam_perturb::PerturbSpec;

use crate::{JobPart, PipelineError};

/// The spec's IMU items applied to `samples` and `ground_truth`, draws keyed by `seed`.
pub fn perturb_imu_stream(
    spec: &PerturbSpec,
    samples: &[ImuSample],
    ground_truth: &[GroundTruthState],
    rate_hz: f64,
    origin: ImuOrigin,
    seed: u64,
) -> Result<PerturbedImu, PipelineError> {
    let stream = ImuStream {
        samples,
        ground_truth,
        rate_hz,
        origin,
    };
    spec.imu
        .apply(&stream, seed)
        .map_err(|e| PipelineError::option(JobPart::Spec, e.to_string()))
}

/// `manifest` with what the IMU items drew under `extra.imu_perturbation` (nothing without
/// IMU items, so that other manifests stay as they were).
pub fn with_imu_report(
    mut manifest: Manifest,
    report: Option<&ImuReport>,
) -> Result<Manifest, PipelineError> {
    if let Some(report) = report {
        manifest.extra["imu_perturbation"] = serde_json::to_value(report)
            .map_err(|e| PipelineError::Worker(format!("IMU report for the manifest: {e}")))?;
    }
    Ok(manifest)
}

/// `camera`'s stamps as written: moved by `cam_imu_offset`, which must keep them at or above 0.
pub fn camera_stamps(
    spec: &PerturbSpec,
    camera: &str,
    times_ns: &[u64],
) -> Result<Vec<u64>, PipelineError> {
    let Some(offset) = spec.imu.cam_imu_offset_ns() else {
        return Ok(times_ns.to_vec());
    };
    times_ns
        .iter()
        .map(|&t| {
            shift_stamp(t, offset).ok_or_else(|| {
                PipelineError::option(
                    JobPart::Spec,
                    format!("'cam_imu_offset:{}': {camera}'s frame at {t} ns would be stamped before 0 ns", offset as f64 / 1e6),
                )
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_offset_moves_every_stamp_exactly_or_refuses() {
        let spec = PerturbSpec::parse("cam_imu_offset:-1.5").unwrap();
        let times = [1_500_000, 2_000_000_123];
        assert_eq!(
            camera_stamps(&spec, "cam0", &times).unwrap(),
            [0, 1_998_500_123]
        );
        let err = camera_stamps(&spec, "cam1", &[1_499_999])
            .unwrap_err()
            .to_string();
        assert_eq!(
            err,
            "spec: 'cam_imu_offset:-1.5': cam1's frame at 1499999 ns would be stamped before 0 ns"
        );
        let none = PerturbSpec::parse("imu_jitter:1").unwrap();
        assert_eq!(camera_stamps(&none, "cam0", &times).unwrap(), times);
    }
}
