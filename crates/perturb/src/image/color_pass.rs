//! The common shape of a colour corruption's last pass: copy the frame's colour to scratch, run one
//! shader that reads the copy and writes the frame, with a uniform block of parameters. The shader
//! writes a run of 8 pixels of a row per invocation (see `filter.wgsl`, `pointwise_runs.wgsl`;
//! on lavapipe one pixel per invocation paid the invocation overhead), or such a run and its
//! mirror image in the mirrored row (pixels (x, y) and (W − 1 − x, H − 1 − y)).

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use crate::perturbation::{view, FrameKey, GpuPerturbation, Kit};
use crate::uniform_layout::{rust_layout, RustLayout, UniformLayout};
use crate::PerturbError;

/// One pass `source (scratch colour) → frame colour` with parameters `P` at binding 2;
/// bindings: 0 source `texture_2d<f32>`, 1 output `texture_storage_2d<rgba8unorm, write>`,
/// 2 `var<uniform>` of `P`, then any `extra` resources at 3, 4, ….
pub struct ColorPass {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    label: &'static str,
    /// Whether each invocation also writes the mirror image of its run.
    mirrored: bool,
}

/// Pixels per invocation of the shaders that write runs.
const RUN: u32 = 8;

impl ColorPass {
    /// A shader writing a run of 8 pixels of a row per invocation.
    pub fn runs<P: Pod>(kit: &Kit, shader: &'static str) -> Result<Self, PerturbError> {
        Self::with_runs::<P>(kit, shader, false)
    }

    /// A shader writing a run of 8 pixels of row y < H / 2 and the mirrored run of row H − 1 − y
    /// per invocation (the middle row of an odd height: its own run only).
    pub fn mirrored_runs<P: Pod>(kit: &Kit, shader: &'static str) -> Result<Self, PerturbError> {
        Self::with_runs::<P>(kit, shader, true)
    }

    fn with_runs<P: Pod>(
        kit: &Kit,
        shader: &'static str,
        mirrored: bool,
    ) -> Result<Self, PerturbError> {
        Ok(Self {
            pipeline: kit.pipeline(shader)?,
            params: kit.uniform_buffer::<P>(shader),
            label: shader,
            mirrored,
        })
    }

    pub fn encode<P: Pod>(
        &self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        params: &P,
        extra: &[wgpu::BindingResource],
    ) {
        kit.write_uniform(&self.params, params);
        kit.copy_color_to_scratch(encoder, frame);
        let source = view(&kit.scratch.color);
        let output = frame.color_view();
        let mut resources = vec![
            wgpu::BindingResource::TextureView(&source),
            wgpu::BindingResource::TextureView(output),
            self.params.as_entire_binding(),
        ];
        resources.extend_from_slice(extra);
        let bind_group = kit.bind_group(&self.pipeline, self.label, &resources);
        let rows = if self.mirrored {
            kit.height.div_ceil(2)
        } else {
            kit.height
        };
        kit.dispatch_grid(
            encoder,
            &self.pipeline,
            &bind_group,
            self.label,
            kit.width.div_ceil(RUN),
            rows,
        );
    }
}

/// The uniform block of the per-pixel corruptions, WGSL
/// `struct Params { key: vec4<u32>, values: vec4<f32> }`: an RNG key and up to four parameters.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct KeyedParams {
    pub key: [u32; 4],
    pub values: [f32; 4],
}

impl KeyedParams {
    const LAYOUT: RustLayout = rust_layout!(KeyedParams { key, values });

    /// Its layout as `struct Params` of `shader`.
    pub const fn layout(shader: &'static str) -> UniformLayout {
        UniformLayout {
            rust: Self::LAYOUT,
            wgsl: "Params",
            shader,
        }
    }
}

/// A per-pixel corruption whose parameters are a function of the frame key only; its shader
/// defines `corrupt` and includes `pointwise_runs.wgsl` (runs of 8 pixels per invocation).
pub struct PointwisePass {
    pass: ColorPass,
    params: fn(&FrameKey) -> KeyedParams,
}

impl PointwisePass {
    pub fn boxed(
        kit: &Kit,
        shader: &'static str,
        params: fn(&FrameKey) -> KeyedParams,
    ) -> Result<Box<dyn GpuPerturbation>, PerturbError> {
        Ok(Box::new(Self {
            pass: ColorPass::runs::<KeyedParams>(kit, shader)?,
            params,
        }))
    }
}

impl GpuPerturbation for PointwisePass {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        self.pass
            .encode(kit, encoder, frame, &(self.params)(key), &[]);
        Ok(())
    }
}
