//! Frame-wide sums on the GPU (`shaders/common/reduce.wgsl`): one invocation per column adds the
//! column, one invocation adds the columns (no workgroup barriers: those are slow on lavapipe).
//! The result stays on the GPU, copied into a uniform buffer that the next pass of the same frame
//! reads (contrast: channel means; depth_noise: depth std): on lavapipe a per-pixel read of a
//! storage buffer doubled the cost of the contrast pass, a uniform read costs nothing.

use crate::perturbation::Kit;
use crate::PerturbError;

/// Invocations per workgroup of the `partial_sums` entry point (`@workgroup_size(64)`).
const COLUMNS_PER_GROUP: u32 = 64;

/// The two pipelines and buffers of one reduction, built once.
pub struct Reduction {
    partial: wgpu::ComputePipeline,
    finish: wgpu::ComputePipeline,
    partials: wgpu::Buffer,
    sums_storage: wgpu::Buffer,
    sums: wgpu::Buffer,
    groups: u32,
    label: &'static str,
}

impl Reduction {
    /// `shader` includes `common/reduce.wgsl` and defines its input at binding 0 and the
    /// per-column entry point `partial_sums`.
    pub fn new(kit: &Kit, shader: &'static str) -> Result<Self, PerturbError> {
        let vec4_bytes = 16;
        Ok(Self {
            partial: kit.pipeline_entry(shader, "partial_sums")?,
            finish: kit.pipeline_entry(shader, "finish_sums")?,
            partials: kit.storage_buffer(shader, kit.width as u64 * vec4_bytes),
            sums_storage: kit.storage_buffer(shader, vec4_bytes),
            sums: kit.uniform_buffer::<[f32; 4]>(shader),
            groups: kit.width.div_ceil(COLUMNS_PER_GROUP),
            label: shader,
        })
    }

    /// Records both passes over `input` (bound at binding 0).
    pub fn encode(&self, kit: &Kit, encoder: &mut wgpu::CommandEncoder, input: &wgpu::TextureView) {
        let partial = kit.bind_group_at(
            &self.partial,
            self.label,
            &[
                (0, wgpu::BindingResource::TextureView(input)),
                (1, self.partials.as_entire_binding()),
            ],
        );
        kit.dispatch_workgroups(
            encoder,
            &self.partial,
            &partial,
            self.label,
            [self.groups, 1, 1],
        );
        let finish = kit.bind_group_at(
            &self.finish,
            self.label,
            &[
                (1, self.partials.as_entire_binding()),
                (2, self.sums_storage.as_entire_binding()),
            ],
        );
        kit.dispatch_workgroups(encoder, &self.finish, &finish, self.label, [1, 1, 1]);
        encoder.copy_buffer_to_buffer(&self.sums_storage, 0, &self.sums, 0, None);
    }

    /// The vec4 of sums, as a uniform buffer for the next pass.
    pub fn sums(&self) -> &wgpu::Buffer {
        &self.sums
    }
}
