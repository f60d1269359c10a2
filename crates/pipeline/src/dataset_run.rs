//! Writing a dataset from a pipeline, resumably: the output folder decides what is left to do,
//! only source frames with a missing file are drawn, and the manifest comes last.

use std::path::Path;

use rslam_core::dataset::{DatasetFormat, DatasetWriter, Manifest};
use rslam_core::{Intrinsics, Trajectory};
use rslam_gpu::GpuContext;

use crate::output_folder::{make_output, FolderState, Made, Written};
use crate::pipeline::Pipeline;
use crate::plan::FramePlan;
use crate::progress::Progress;
use crate::sink::DatasetSink;
use crate::source::FrameSource;
use crate::PipelineError;

/// What a run did.
#[derive(Clone, Debug, PartialEq)]
pub struct RunReport {
    /// Output frames of the finished output.
    pub frames: usize,
    /// Source frames drawn (or perturbed) by this run; fewer than needed when it resumed.
    pub made: usize,
    /// What the output folder held when the run began.
    pub found: FolderState,
    /// The manifest as written (as found, when the folder was complete already).
    pub manifest: Manifest,
}

impl RunReport {
    pub(crate) fn of(frames: usize, made: Made) -> Self {
        Self {
            frames,
            made: made.made,
            found: made.found,
            manifest: made.manifest,
        }
    }
}

/// One dataset to write: where, in which layout, and what it holds besides the frames.
pub struct DatasetOutput<'a> {
    pub out: &'a Path,
    pub format: DatasetFormat,
    pub camera: Intrinsics,
    /// Replace whatever rslam output `out` holds.
    pub force: bool,
    pub plan: &'a FramePlan,
    pub ground_truth: &'a Trajectory,
    /// The job's manifest, without the content digest; its `depth_png` is how depth is encoded,
    /// its `distortion` the lens the camera files carry.
    pub manifest: Manifest,
    /// Files of other sensors beside the frames (relative path, text), written before the
    /// checksums: the `rgbd-imu` rig's IMU.
    pub sensor_files: Vec<(String, String)>,
}

pub fn write_dataset<S: FrameSource>(
    ctx: &GpuContext,
    pipeline: &mut Pipeline<S>,
    target: DatasetOutput,
    progress: &dyn Progress,
    what: &str,
) -> Result<RunReport, PipelineError> {
    let plan = target.plan;
    let job = target.manifest;
    let made = make_output(target.out, job, target.force, |_, job| {
        let writer = DatasetWriter::open(target.out, target.format, target.camera, job.depth_png)?
            .with_distortion(job.distortion);
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
        let manifest = sink.finish(target.ground_truth, &target.sensor_files, job)?;
        Ok(Written {
            made: sources.len(),
            manifest,
        })
    })?;
    Ok(RunReport::of(plan.len(), made))
}
