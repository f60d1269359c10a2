//! What the viewer shows frames of: a scene along its path or a dataset on disk, both as the
//! pipeline's [`FramesInMemory`]; one enum so that the rest of the viewer need not care which.

use std::ops::Range;

use rslam_core::dataset::SourceDataset;
use rslam_core::{Pose, Trajectory};
use rslam_gpu::GpuContext;
use rslam_perturb::PerturbSpec;
use rslam_pipeline::source::{RecordedSource, SceneSource};
use rslam_pipeline::{
    DepthRange, FramePlan, FramesInMemory, PipelineError, RgbdFrame, SceneJob, ShownFrame,
};

pub enum Sequence {
    Scene {
        frames: Box<FramesInMemory<SceneSource>>,
        name: String,
        rate_hz: f64,
    },
    Dataset {
        frames: Box<FramesInMemory<RecordedSource>>,
        name: String,
        rate_hz: f64,
    },
}

/// Calls `$body` with `$f` bound to the `FramesInMemory` of either kind.
macro_rules! with_frames {
    ($seq:expr, $f:ident => $body:expr) => {
        match $seq {
            Sequence::Scene { frames: $f, .. } => $body,
            Sequence::Dataset { frames: $f, .. } => $body,
        }
    };
}

impl Sequence {
    pub fn scene(ctx: &GpuContext, job: &SceneJob) -> Result<Self, PipelineError> {
        Ok(Self::Scene {
            frames: Box::new(FramesInMemory::scene(ctx, job)?),
            name: job.scene.clone(),
            rate_hz: job.rate_hz,
        })
    }

    pub fn dataset(
        ctx: &GpuContext,
        dataset: &SourceDataset,
        spec: &PerturbSpec,
        seed: u64,
    ) -> Result<Self, PipelineError> {
        Ok(Self::Dataset {
            frames: Box::new(FramesInMemory::dataset(ctx, dataset, spec, seed)?),
            name: dataset.root.display().to_string(),
            rate_hz: dataset.rate_hz,
        })
    }

    pub fn name(&self) -> &str {
        match self {
            Sequence::Scene { name, .. } | Sequence::Dataset { name, .. } => name,
        }
    }

    /// The sensor rate: playback runs at it.
    pub fn rate_hz(&self) -> f64 {
        match self {
            Sequence::Scene { rate_hz, .. } | Sequence::Dataset { rate_hz, .. } => *rate_hz,
        }
    }

    pub fn is_scene(&self) -> bool {
        matches!(self, Sequence::Scene { .. })
    }

    pub fn plan(&self) -> &FramePlan {
        with_frames!(self, f => f.plan())
    }

    /// Output frames.
    pub fn len(&self) -> usize {
        self.plan().len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn size(&self) -> (u32, u32) {
        with_frames!(self, f => f.size())
    }

    pub fn ground_truth(&self) -> Trajectory {
        with_frames!(self, f => f.ground_truth())
    }

    pub fn set_spec(
        &mut self,
        ctx: &GpuContext,
        spec: &PerturbSpec,
        seed: u64,
    ) -> Result<(), PipelineError> {
        with_frames!(self, f => f.set_spec(ctx, spec, seed))
    }

    /// Output frame `index` on the GPU in `shown`, or the free camera's view when `pose` is given
    /// (scenes only).
    pub fn show(
        &mut self,
        ctx: &GpuContext,
        index: usize,
        pose: Option<&Pose>,
        shown: &mut ShownFrame,
        range: DepthRange,
    ) -> Result<(), PipelineError> {
        match (self, pose) {
            (Sequence::Scene { frames, .. }, Some(pose)) => {
                frames.show_from(ctx, pose, index, shown, range)
            }
            (seq, _) => with_frames!(seq, f => f.show(ctx, index, shown, range)),
        }
    }

    /// Output frames `range`, read back, to `deliver` (for export).
    pub fn frames(
        &mut self,
        ctx: &GpuContext,
        range: Range<usize>,
        deliver: impl FnMut(RgbdFrame) -> Result<(), PipelineError>,
    ) -> Result<(), PipelineError> {
        with_frames!(self, f => f.frames(ctx, range, deliver))
    }
}
