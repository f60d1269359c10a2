//! The IMU readings and ground-truth states of a rig along its motion: synthesised at the IMU's
//! rate with its noise, then the spec's IMU items applied.

use rslam_core::dataset::euroc::{EurocImu, GroundTruthState, ImuSample as ImuRow};
use rslam_core::SplineSe3;
use rslam_perturb::imu::{ImuOrigin, ImuReport};

use super::imu_items::perturb_imu_stream;
use super::motion::{ground_truth_rows, imu_rows, imu_samples};
use super::seeds::imu_seed;
use crate::scene_job::SceneJob;
use crate::PipelineError;

/// The rows of imu0/data.csv and of the ground truth, IMU items applied.
pub(super) struct ImuStreams {
    pub imu: Vec<ImuRow>,
    pub ground_truth: Vec<GroundTruthState>,
    /// What the IMU items drew, for the manifest.
    pub report: Option<ImuReport>,
}

/// `imu` (the rig's IMU as mounted) synthesised along the spline with
/// [`imu_seed`]`(scene.seed)` (its noise scaled by `imu_noise`), the ground truth at its samples
/// (at `cam0_times` without an IMU), then the other IMU items, drawn from the job's seed. The
/// IMU is cheap beside the frames: made before them so that the manifest can say what was drawn.
pub(super) fn imu_and_ground_truth(
    scene: &SceneJob,
    imu: Option<&EurocImu>,
    spline: &SplineSe3,
    cam0_times: &[f64],
) -> Result<ImuStreams, PipelineError> {
    let spec = &scene.spec;
    let imu_seed = imu_seed(scene.seed);
    let Some(imu) = imu else {
        return Ok(ImuStreams {
            imu: Vec::new(),
            ground_truth: ground_truth_rows(spline, &[], cam0_times)?,
            report: None,
        });
    };
    let samples = imu_samples(spline, imu, spec.imu.synthesis_noise(imu.noise()), imu_seed)?;
    let rows = imu_rows(&samples)?;
    let ground_truth = ground_truth_rows(spline, &samples, cam0_times)?;
    if spec.imu.is_empty() {
        return Ok(ImuStreams {
            imu: rows,
            ground_truth,
            report: None,
        });
    }
    let perturbed = perturb_imu_stream(
        spec,
        &rows,
        &ground_truth,
        imu.rate_hz,
        ImuOrigin::Synthesised,
        scene.seed,
    )?;
    Ok(ImuStreams {
        imu: perturbed.samples,
        ground_truth: perturbed.ground_truth,
        report: Some(perturbed.report),
    })
}
