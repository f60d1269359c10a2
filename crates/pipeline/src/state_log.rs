//! The per-frame log of perturbations that carry a state (auto_exposure: the exposure and gain
//! each frame was taken with). Each frame's state is copied on the GPU into one buffer of the
//! run, in the frame's own command encoder, and the buffer is read back once when the run ends:
//! no frame waits for it.

use std::collections::BTreeMap;

use rslam_gpu::{read_buffer, wgpu, GpuContext};
use rslam_perturb::{FrameSeverities, Perturber};

use crate::PipelineError;

/// The values each source frame was made with, one column per value.
#[derive(Clone, Debug, PartialEq)]
pub struct StateTable {
    /// `item.field`, e.g. `auto_exposure.gain`.
    pub columns: Vec<String>,
    /// By source frame; `None` for an item's cells where it did not run on the frame (severity
    /// 0 under `@dynamic`).
    pub rows: BTreeMap<usize, Vec<Option<f32>>>,
}

/// Values an item writes per frame (a `vec4<f32>` state).
const VALUES_PER_ITEM: usize = 4;

pub(crate) struct StateLog {
    buffer: wgpu::Buffer,
    row_bytes: u64,
    columns: Vec<String>,
    sources: Vec<usize>,
}

impl StateLog {
    /// A zeroed log for the frames `sources`, or `None` when no item of `perturber` has a state.
    pub fn new(ctx: &GpuContext, perturber: &Perturber, sources: &[usize]) -> Option<Self> {
        let columns = perturber.state_columns();
        if columns.is_empty() || sources.is_empty() {
            return None;
        }
        let row_bytes = perturber.state_row_bytes();
        let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("state log"),
            size: row_bytes * sources.len() as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        Some(Self {
            buffer,
            row_bytes,
            columns,
            sources: sources.to_vec(),
        })
    }

    /// Records the copy of the `position`-th frame's state (after `perturber` encoded it).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        perturber: &Perturber,
        got: &FrameSeverities,
        position: usize,
    ) {
        perturber.encode_state_copy(encoder, got, &self.buffer, self.row_bytes * position as u64);
    }

    /// Reads the log back; a block of an item's four values all 0 is a frame it did not run on
    /// (the buffer starts zeroed).
    pub fn read(self, ctx: &GpuContext) -> Result<StateTable, PipelineError> {
        let bytes = read_buffer(ctx, &self.buffer)?;
        let values: Vec<f32> = bytes
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        let row_len = self.columns.len();
        let rows = self
            .sources
            .iter()
            .zip(values.chunks_exact(row_len))
            .map(|(&source, row)| {
                let cells = row
                    .chunks_exact(VALUES_PER_ITEM)
                    .flat_map(|item| {
                        let ran = item.iter().any(|&v| v != 0.0);
                        item.iter().map(move |&v| ran.then_some(v))
                    })
                    .collect();
                (source, cells)
            })
            .collect();
        Ok(StateTable {
            columns: self.columns,
            rows,
        })
    }
}
