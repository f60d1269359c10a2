//! Where read-back source frames go: into a dataset on disk (a Replica or TUM dataset, one
//! camera of a EuRoC one, a ROS 2 bag, or a recorded bag's camera perturbed), or assembled into output frames handed to a callback
//! in memory.

mod bag;
mod dataset;
mod memory;
mod perturbed_bag;
mod rig_camera;

pub use bag::{seal_bag, CameraBagSink};
pub use dataset::DatasetSink;
pub use memory::{MemorySink, RgbdFrame};
pub use perturbed_bag::PerturbedBagSink;
pub use rig_camera::{finish_writer, frames_kept, RigCameraSink, RigFrameWriter};

use rslam_gpu::MappedFrame;

use crate::state_log::StateTable;
use crate::PipelineError;

pub trait FrameSink {
    /// Whether it uses depth: a sink that drops it spares the frame loop its readback.
    fn wants_depth(&self) -> bool {
        true
    }
    /// Whether it writes instance masks: only then are they read back.
    fn wants_mask(&self) -> bool {
        false
    }
    /// Source frame `source`, read back into staging buffers that stay mapped until its images
    /// are unpacked: a sink with worker threads unpacks them there, sparing the frame loop's
    /// thread. Its depth is `None` for inputs without depth, its mask unless the source has one
    /// and the sink wants it.
    fn accept(&mut self, source: usize, frame: MappedFrame) -> Result<(), PipelineError>;
    /// The state stateful perturbations made each source frame with, once after the last
    /// frame; a sink that writes no dataset drops it.
    fn accept_state(&mut self, _table: StateTable) -> Result<(), PipelineError> {
        Ok(())
    }
}
