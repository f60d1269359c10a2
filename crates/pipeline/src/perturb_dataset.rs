//! `rslam perturb` on a dataset (Replica or TUM layout): its frames decoded, perturbed and
//! written in the same layout, with `fast` and `misalign` re-planning the streams; an `rgbd-imu`
//! output keeps its inertial files ([`crate::rig::rgbd_imu_perturb`]).

use std::path::Path;

use rslam_core::dataset::euroc::IMU_DIR;
use rslam_core::dataset::{read_dataset, DatasetOverrides, DepthPng, Manifest, SourceDataset};
use rslam_core::{nearest_time, Pose, Trajectory};
use rslam_gpu::GpuContext;
use rslam_perturb::PerturbSpec;

use crate::dataset_run::{dataset_writing, DatasetOutput};
use crate::job::{Planned, Streams, Writing};
use crate::manifest::ManifestParts;
use crate::pipeline::Pipeline;
use crate::plan::{self, FramePlan, SourceTiming};
use crate::rig::rgbd_imu_perturb::recorded_inertial_files;
use crate::rig::with_imu_report;
use crate::source::RecordedSource;
use crate::{settings, PipelineError};

/// Largest |Δt| at which a ground-truth pose stands for a frame when re-stamping (TUM's 100 Hz
/// motion capture has one within 5 ms of every frame).
const GT_MATCH_MAX_DIFF_S: f64 = 0.02;

/// The plan of a recorded dataset under `spec`.
pub fn dataset_plan(dataset: &SourceDataset, spec: &PerturbSpec, seed: u64) -> FramePlan {
    let rgb_times: Vec<f64> = dataset.frames.iter().map(|f| f.rgb_time).collect();
    let depth_offsets: Vec<f64> = dataset
        .frames
        .iter()
        .map(|f| f.depth_time - f.rgb_time)
        .collect();
    FramePlan::recorded(
        &SourceTiming {
            rgb_times: &rgb_times,
            depth_offsets: &depth_offsets,
            rate_hz: dataset.rate_hz,
        },
        spec,
        seed,
    )
}

/// A dataset perturb, planned: the dataset read, the frame plan made, the inertial files of an
/// `rgbd-imu` output perturbed.
pub(crate) struct DatasetPerturb<'a> {
    spec: &'a PerturbSpec,
    seed: u64,
    dataset: SourceDataset,
    plan: FramePlan,
    ground_truth: Trajectory,
    sensor_files: Vec<(String, String)>,
    manifest: Manifest,
}

pub(crate) struct RecordedDataset<'a> {
    pub input: &'a Path,
    pub overrides: &'a DatasetOverrides,
    pub depth_png: DepthPng,
    pub spec: &'a PerturbSpec,
    pub seed: u64,
}

pub(crate) fn plan<'a>(
    job: RecordedDataset<'a>,
    command: &[String],
) -> Result<DatasetPerturb<'a>, PipelineError> {
    let dataset = read_dataset(job.input, job.overrides)?;
    let imu = job.input.join(IMU_DIR).is_dir();
    settings::check(
        job.spec,
        &settings::recorded_dataset(&dataset, job.input, imu),
    )?;
    let inertial = recorded_inertial_files(job.input, job.spec, job.seed)?;
    let plan = dataset_plan(&dataset, job.spec, job.seed);
    let ground_truth = output_ground_truth(&dataset, &plan, plan::restamps(job.spec));
    let manifest = ManifestParts {
        command,
        source: job.input.display().to_string(),
        source_hash: String::new(),
        format: Some(dataset.format),
        camera: Some(dataset.intrinsics),
        distortion: dataset.distortion,
        depth_png: job.depth_png,
        bag: Default::default(),
        rate_hz: dataset.rate_hz,
        seed: job.seed,
        spec: job.spec,
        plan: &plan,
        extra: serde_json::json!({}),
    }
    .build()?;
    let manifest = with_imu_report(manifest, inertial.report.as_ref())?;
    Ok(DatasetPerturb {
        spec: job.spec,
        seed: job.seed,
        dataset,
        plan,
        ground_truth,
        sensor_files: inertial.files,
        manifest,
    })
}

impl Planned for DatasetPerturb<'_> {
    fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    fn streams(&self) -> Streams {
        Streams::Frames(self.plan.len())
    }

    fn open<'a>(&'a self, ctx: &'a GpuContext) -> Result<Writing<'a>, PipelineError> {
        let dataset = &self.dataset;
        let source = RecordedSource::dataset(dataset);
        let pipeline = Pipeline::new(ctx, source, self.spec, self.seed)?;
        let output = DatasetOutput {
            format: dataset.format,
            camera: dataset.intrinsics,
            plan: &self.plan,
            ground_truth: &self.ground_truth,
            sensor_files: &self.sensor_files,
            bag_imu: None,
        };
        Ok(dataset_writing(ctx, pipeline, output, "perturbing"))
    }
}

/// The source's ground truth for the output frames. Without re-stamping it is kept whole (at its
/// own rate); with `fast` each kept frame takes the pose nearest its original capture time.
pub(crate) fn output_ground_truth(
    src: &SourceDataset,
    plan: &FramePlan,
    restamp: bool,
) -> Trajectory {
    let Some(gt) = &src.ground_truth else {
        return Trajectory::default();
    };
    if !restamp {
        return gt.clone();
    }
    let mut timestamps = Vec::new();
    let mut poses: Vec<Pose> = Vec::new();
    for (j, &s) in plan.rgb_source.iter().enumerate() {
        let captured = src.frames[s].rgb_time;
        if let Some(i) = nearest_time(gt.timestamps.iter().copied(), captured, GT_MATCH_MAX_DIFF_S)
        {
            timestamps.push(plan.frames[j].rgb_time);
            poses.push(gt.poses[i]);
        }
    }
    Trajectory::new(timestamps, poses)
}
