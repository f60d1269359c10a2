//! Where read-back source frames go: into a dataset on disk, or assembled into output frames
//! handed to a callback in memory.

mod dataset;
mod memory;

pub use dataset::DatasetSink;
pub use memory::{MemorySink, RgbdFrame};

use std::sync::Arc;

use rslam_core::{DepthImage, ImagePool, RgbImage};

use crate::state_log::StateTable;
use crate::PipelineError;

pub trait FrameSink {
    /// Whether it uses depth: a sink that drops it spares the frame loop its readback.
    fn wants_depth(&self) -> bool {
        true
    }
    /// Where the frame loop takes the buffers it reads frames back into: a sink that hands the
    /// images it was given back to this pool once written spares the loop fresh memory.
    fn image_pool(&self) -> Arc<ImagePool> {
        Arc::default()
    }
    /// Source frame `source`, read back; `depth` is `None` for inputs without depth.
    fn accept(
        &mut self,
        source: usize,
        color: RgbImage,
        depth: Option<DepthImage>,
    ) -> Result<(), PipelineError>;
    /// The state stateful perturbations made each source frame with, once after the last
    /// frame; a sink that writes no dataset drops it.
    fn accept_state(&mut self, _table: StateTable) -> Result<(), PipelineError> {
        Ok(())
    }
}
