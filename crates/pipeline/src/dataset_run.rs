//! Writing a dataset of one camera (Replica or TUM layout) from a pipeline, resumably: only
//! source frames with a missing file are drawn, and the manifest comes last.

use std::path::Path;

use rslam_core::dataset::{DatasetFormat, DatasetWriter, Manifest};
use rslam_core::{Intrinsics, Trajectory};
use rslam_gpu::GpuContext;

use crate::output_folder::Written;
use crate::pipeline::Pipeline;
use crate::plan::FramePlan;
use crate::progress::Progress;
use crate::sink::DatasetSink;
use crate::source::FrameSource;
use crate::PipelineError;

/// One dataset to write: where, in which layout, and what it holds besides the frames.
pub struct DatasetOutput<'a> {
    pub out: &'a Path,
    pub format: DatasetFormat,
    pub camera: Intrinsics,
    pub plan: &'a FramePlan,
    pub ground_truth: &'a Trajectory,
    /// Files of other sensors beside the frames (relative path, text), written before the
    /// checksums: the `rgbd-imu` rig's IMU.
    pub sensor_files: Vec<(String, String)>,
}

/// Writes the frames `pipeline` makes into the prepared folder (the frames a resumed run finds
/// whole stay), then the index files, checksums and `manifest` (its `depth_png` is how depth is
/// encoded, its `distortion` the lens the camera files carry).
pub fn write_dataset<S: FrameSource>(
    ctx: &GpuContext,
    pipeline: &mut Pipeline<S>,
    target: DatasetOutput,
    manifest: Manifest,
    progress: &dyn Progress,
    what: &str,
) -> Result<Written, PipelineError> {
    let plan = target.plan;
    let writer = DatasetWriter::open(target.out, target.format, target.camera, manifest.depth_png)?
        .with_distortion(manifest.distortion);
    let mut sink = DatasetSink::new(writer, plan);
    // A stateful item (auto_exposure) gives each frame what the frames before it left, so a
    // resumed run redoes them all rather than start its state over at the first missing one.
    let redo_all = pipeline.perturber().carries_state();
    let sources: Vec<usize> = plan
        .needed_sources()
        .into_iter()
        .filter(|&s| redo_all || !sink.is_written(s))
        .collect();
    progress.start(sources.len(), what);
    pipeline.run(ctx, &sources, progress, &mut sink)?;
    progress.finish();
    let manifest = sink.finish(target.ground_truth, &target.sensor_files, manifest)?;
    Ok(Written {
        made: sources.len(),
        manifest,
    })
}
