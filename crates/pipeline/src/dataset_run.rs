//! Writing a dataset of one camera (Replica or TUM layout) from a pipeline, resumably: only
//! source frames with a missing file are drawn, and the manifest comes last.

use rslam_core::dataset::{DatasetFormat, DatasetWriter};
use rslam_core::{Intrinsics, Trajectory};
use rslam_gpu::GpuContext;

use crate::job::Writing;
use crate::output_folder::Written;
use crate::pipeline::Pipeline;
use crate::plan::FramePlan;
use crate::sink::DatasetSink;
use crate::source::FrameSource;

/// One camera's dataset to write: in which layout, and what it holds besides the frames.
pub struct DatasetOutput<'a> {
    pub format: DatasetFormat,
    pub camera: Intrinsics,
    pub plan: &'a FramePlan,
    pub ground_truth: &'a Trajectory,
    /// Files of other sensors beside the frames (relative path, text), written before the
    /// checksums: the `rgbd-imu` rig's IMU.
    pub sensor_files: &'a [(String, String)],
}

/// The writer of a one-camera dataset: the frames `pipeline` makes, into the prepared folder
/// (the frames a resumed run finds whole stay), then the index files, checksums and the
/// manifest (its `depth_png` is how depth is encoded, its `distortion` the lens the camera files
/// carry). `what` names the work on the progress bar.
pub fn dataset_writing<'a, S: FrameSource + 'a>(
    ctx: &'a GpuContext,
    mut pipeline: Pipeline<S>,
    target: DatasetOutput<'a>,
    what: &'a str,
) -> Writing<'a> {
    Box::new(move |out, found, manifest, progress| {
        let plan = target.plan;
        let writer = DatasetWriter::open(out, target.format, target.camera, manifest.depth_png)?
            .with_distortion(manifest.distortion);
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
