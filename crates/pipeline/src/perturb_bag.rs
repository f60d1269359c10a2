//! `rslam perturb` on a recorded ROS 2 bag: each camera's colour (and depth) messages decoded,
//! perturbed and written back in their encodings into a bag of the same topics, every other
//! message copied ([`rslam_core::dataset::ros2::RecordedBagCameras`]). The spec applies to every
//! camera (its depth items to the cameras with depth), its IMU items to every `sensor_msgs/Imu`
//! topic ([`crate::rig::perturb_bag_imus`]); `misalign` moves the depth stamps; `fast` and
//! `cam_imu_offset` are refused, since the copied topics keep their times. Like a bag rslam renders, it is written
//! from its first message on every run.

use std::path::Path;
use std::sync::Arc;

use rslam_core::dataset::ros2::{
    BagCompression, BagOptions, Imu, LogTimes, PerturbedBag, RecordedBag, RecordedBagCamera,
    RecordedBagCameras,
};
use rslam_core::dataset::{ContentWriter, DatasetFormat, DepthPng, Manifest};
use rslam_gpu::GpuContext;
use rslam_perturb::{PerturbError, PerturbSpec};

use crate::job::{Planned, Streams, Writing};
use crate::manifest::ManifestParts;
use crate::output_folder::Written;
use crate::pipeline::Pipeline;
use crate::plan::{FramePlan, SourceTiming};
use crate::rig::perturb_bag_imus;
use crate::rig::CameraFrames;
use crate::sink::{seal_bag, PerturbedBagSink};
use crate::source::BagSource;
use crate::{settings, PipelineError};

pub(crate) struct BagPerturb {
    seed: u64,
    recorded: Arc<RecordedBagCameras>,
    /// Per camera, in the order of `recorded.cameras`.
    runs: Vec<CameraRun>,
    /// The IMU topics the spec changed: index among the bag's topics, messages.
    imu_messages: Vec<(usize, Vec<(Imu, LogTimes)>)>,
    manifest: Manifest,
}

/// One camera's part: its spec, its frames' recorded colour and depth stamps (seconds), its plan.
struct CameraRun {
    spec: PerturbSpec,
    recorded_times: Vec<(f64, f64)>,
    plan: FramePlan,
}

pub(crate) fn plan(
    input: &Path,
    compression: BagCompression,
    spec: &PerturbSpec,
    seed: u64,
    command: &[String],
) -> Result<BagPerturb, PipelineError> {
    let recorded = RecordedBagCameras::read(RecordedBag::open(input)?)?;
    settings::check(spec, &settings::recorded_bag(&recorded))?;
    let has_colour = recorded.cameras.iter().any(|c| c.colour.is_some());
    if let (Some(item), false) = (spec.image.first(), has_colour) {
        return Err(PerturbError::spec(
            item.to_string(),
            format!(
                "an image item, and the bag {} has no colour topic",
                input.display()
            ),
        )
        .into());
    }
    let imus = perturb_bag_imus(&recorded, spec, seed)?;
    let runs: Vec<CameraRun> = recorded
        .cameras
        .iter()
        .map(|camera| camera_run(camera, spec, seed))
        .collect();
    let cam0 = &recorded.cameras[0];
    let cameras: Vec<serde_json::Value> = recorded
        .cameras
        .iter()
        .zip(&runs)
        .map(|(camera, run)| {
            serde_json::json!({
                "colour_topic": camera.colour.as_ref().map(|c| c.name.clone()),
                "depth_topic": camera.depth.as_ref().map(|d| d.name.clone()),
                "frames": run.plan.len(),
            })
        })
        .collect();
    let mut manifest = ManifestParts {
        command,
        source: input.display().to_string(),
        source_hash: String::new(),
        format: Some(DatasetFormat::Ros2),
        camera: Some(cam0.intrinsics),
        distortion: cam0.distortion,
        depth_png: DepthPng::default(),
        bag: BagOptions {
            compression,
            ..BagOptions::default()
        },
        rate_hz: cam0.rate_hz,
        seed,
        spec,
        plan: &runs[0].plan,
        extra: serde_json::json!({ "cameras": cameras }),
    }
    .build()?;
    if let Some(report) = imus.report {
        manifest.extra["imu_perturbation"] = report;
    }
    Ok(BagPerturb {
        seed,
        recorded: Arc::new(recorded),
        runs,
        imu_messages: imus.messages,
        manifest,
    })
}

/// A camera's run: the spec without its depth items where the camera has no depth, without its
/// image items where it has no colour (a depth camera of its own).
fn camera_run(camera: &RecordedBagCamera, spec: &PerturbSpec, seed: u64) -> CameraRun {
    let spec = match (&camera.colour, &camera.depth) {
        (Some(_), Some(_)) => spec.clone(),
        (Some(_), None) => spec.without_depth(),
        (None, _) => spec.without_image(),
    };
    let recorded_times: Vec<(f64, f64)> = camera
        .frames()
        .messages
        .iter()
        .enumerate()
        .map(|(i, frame)| {
            let rgb = frame.stamp.seconds();
            let depth = camera
                .depth
                .as_ref()
                .map_or(rgb, |d| d.messages[i].stamp.seconds());
            (rgb, depth)
        })
        .collect();
    let rgb_times: Vec<f64> = recorded_times.iter().map(|t| t.0).collect();
    let depth_offsets: Vec<f64> = recorded_times.iter().map(|t| t.1 - t.0).collect();
    let plan = FramePlan::recorded(
        &SourceTiming {
            rgb_times: &rgb_times,
            depth_offsets: &depth_offsets,
            rate_hz: camera.rate_hz,
        },
        &spec,
        seed,
    );
    CameraRun {
        spec,
        recorded_times,
        plan,
    }
}

impl Planned for BagPerturb {
    fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    fn streams(&self) -> Streams {
        if let [run] = &self.runs[..] {
            return Streams::Frames(run.plan.len());
        }
        let cameras = self
            .recorded
            .cameras
            .iter()
            .zip(&self.runs)
            .map(|(camera, run)| CameraFrames {
                name: camera.frames().name.clone(),
                frames: run.plan.len(),
            })
            .collect();
        Streams::Rig {
            cameras,
            imu_samples: 0,
        }
    }

    fn open<'a>(&'a self, ctx: &'a GpuContext) -> Result<Writing<'a>, PipelineError> {
        let pipelines = self
            .runs
            .iter()
            .enumerate()
            .map(|(i, run)| {
                let source = BagSource::new(self.recorded.clone(), i);
                Pipeline::new(ctx, source, &run.spec, self.seed)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Box::new(move |out, _found, manifest, progress| {
            let bag = Arc::new(PerturbedBag::create(
                out,
                self.recorded.clone(),
                &self.imu_messages,
                manifest.bag.compression,
            )?);
            let made = self
                .runs
                .iter()
                .map(|r| r.plan.needed_sources().len())
                .sum();
            progress.start(made, "perturbing");
            for (i, (mut pipeline, run)) in pipelines.into_iter().zip(&self.runs).enumerate() {
                let mut sink =
                    PerturbedBagSink::new(bag.clone(), i, &run.plan, &run.recorded_times);
                pipeline.run(ctx, &run.plan.needed_sources(), progress, &mut sink)?;
                sink.finish()?;
            }
            progress.finish();
            let bag = Arc::try_unwrap(bag)
                .map_err(|_| PipelineError::Worker("the bag is still shared".into()))?;
            let manifest = seal_bag(ContentWriter::new(out), bag.finish()?, manifest)?;
            Ok(Written { made, manifest })
        }))
    }
}
