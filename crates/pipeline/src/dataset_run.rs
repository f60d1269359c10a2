//! Writing a dataset of one camera from a pipeline: a Replica or TUM layout resumably (only
//! source frames with a missing file are drawn), a ROS 2 bag from its start; the manifest comes
//! last.

use rslam_core::dataset::ros2::{BagImu, CameraBag};
use rslam_core::dataset::{ContentWriter, DatasetFormat, DatasetWriter};
use rslam_core::{Intrinsics, Trajectory};
use rslam_gpu::GpuContext;

use crate::job::Writing;
use crate::output_folder::Written;
use crate::pipeline::Pipeline;
use crate::plan::FramePlan;
use crate::sink::{CameraBagSink, DatasetSink};
use crate::source::FrameSource;

/// One camera's dataset to write: in which layout, and what it holds besides the frames.
pub struct DatasetOutput<'a> {
    pub format: DatasetFormat,
    pub camera: Intrinsics,
    pub plan: &'a FramePlan,
    pub ground_truth: &'a Trajectory,
    /// Files of other sensors beside the frames (relative path, text), written before the
    /// checksums: the `rgbd-imu` rig's IMU in the TUM layout.
    pub sensor_files: &'a [(String, String)],
    /// The `rgbd-imu` rig's IMU in a ROS 2 bag.
    pub bag_imu: Option<&'a BagImu>,
}

/// The writer of a one-camera dataset: the frames `pipeline` makes (with their instance masks
/// when its source draws actors), into the prepared folder (the frames a resumed run finds whole
/// stay), then the index files, checksums and the manifest (its `depth_png` is how depth is encoded, its `distortion` the lens the camera files
/// carry). `what` names the work on the progress bar.
pub fn dataset_writing<'a, S: FrameSource + 'a>(
    ctx: &'a GpuContext,
    mut pipeline: Pipeline<S>,
    target: DatasetOutput<'a>,
    what: &'a str,
) -> Writing<'a> {
    if target.format == DatasetFormat::Ros2 {
        return bag_writing(ctx, pipeline, target, what);
    }
    Box::new(move |out, found, manifest, progress| {
        let plan = target.plan;
        let mut writer =
            DatasetWriter::open(out, target.format, target.camera, manifest.depth_png)?
                .with_distortion(manifest.distortion);
        if pipeline.source().has_mask() {
            writer = writer.with_masks()?;
        }
        let mut sink = DatasetSink::new(writer, plan);
        let keep = found.keeps_written_frames(pipeline.perturber().carries_state());
        let sources: Vec<usize> = plan
            .needed_sources()
            .into_iter()
            .filter(|&s| !keep || !sink.is_written(s))
            .collect();
        progress.start(sources.len(), what);
        pipeline.run(ctx, &sources, progress, &mut sink)?;
        progress.finish();
        let manifest = sink.finish(target.ground_truth, target.sensor_files, manifest)?;
        Ok(Written {
            made: sources.len(),
            manifest,
        })
    })
}

/// A ROS 2 bag is one file: a resumed run writes it again from the first frame.
fn bag_writing<'a, S: FrameSource + 'a>(
    ctx: &'a GpuContext,
    mut pipeline: Pipeline<S>,
    target: DatasetOutput<'a>,
    what: &'a str,
) -> Writing<'a> {
    Box::new(move |out, _found, manifest, progress| {
        let plan = target.plan;
        let imu = target.bag_imu.cloned();
        let masks = pipeline.source().has_mask();
        let (camera, lens) = (target.camera, manifest.distortion);
        let bag = CameraBag::create(out, camera, lens, (imu, masks), manifest.bag)?;
        let mut sink = CameraBagSink::new(bag, ContentWriter::new(out), plan, target.ground_truth);
        let sources = plan.needed_sources();
        progress.start(sources.len(), what);
        pipeline.run(ctx, &sources, progress, &mut sink)?;
        progress.finish();
        let manifest = sink.finish(manifest)?;
        Ok(Written {
            made: sources.len(),
            manifest,
        })
    })
}
