//! The common shape of a colour corruption's last pass: copy the frame's colour to scratch, run one
//! shader that reads the copy and writes the frame, with a uniform block of parameters. The shader
//! writes one pixel per invocation, or a run of 8 pixels of a row (see `filter.wgsl`).

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use crate::perturbation::{view, FrameKey, GpuPerturbation, Kit};
use crate::PerturbError;

/// One pass `source (scratch colour) → frame colour` with parameters `P` at binding 2;
/// bindings: 0 source `texture_2d<f32>`, 1 output `texture_storage_2d<rgba8unorm, write>`,
/// 2 `var<uniform>` of `P`, then any `extra` resources at 3, 4, ….
pub struct ColorPass {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    label: &'static str,
    /// Pixels of a row each invocation writes.
    run: u32,
}

/// Pixels per invocation of the shaders that write runs.
const RUN: u32 = 8;

impl ColorPass {
    /// A shader writing one pixel per invocation.
    pub fn new<P: Pod>(kit: &Kit, shader: &'static str) -> Result<Self, PerturbError> {
        Self::with_run::<P>(kit, shader, 1)
    }

    /// A shader writing a run of 8 pixels of a row per invocation.
    pub fn runs<P: Pod>(kit: &Kit, shader: &'static str) -> Result<Self, PerturbError> {
        Self::with_run::<P>(kit, shader, RUN)
    }

    fn with_run<P: Pod>(kit: &Kit, shader: &'static str, run: u32) -> Result<Self, PerturbError> {
        Ok(Self {
            pipeline: kit.pipeline(shader)?,
            params: kit.uniform_buffer::<P>(shader),
            label: shader,
            run,
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
        kit.dispatch_grid(
            encoder,
            &self.pipeline,
            &bind_group,
            self.label,
            kit.width.div_ceil(self.run),
            kit.height,
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

#[cfg(test)]
mod tests {
    use crate::image::{
        defocus_blur, elastic_transform, fog, frost, gaussian_blur, glass_blur, jpeg_compression,
        motion_blur, snow, spatter, zoom_blur,
    };
    use crate::image_f32::RgbF32;
    use crate::testing;

    /// Frames whose sides are not multiples of 8 (runs) or 16 (JPEG MCUs) still match the twins
    /// everywhere, including the last partial run of each row and column.
    #[test]
    fn odd_frame_sizes_match_the_twins() {
        let clean = testing::test_image(77, 53);
        let image = RgbF32::from_rgb8(&clean);
        let (seed, s) = (5, 3);
        let cases: [(&crate::CatalogueEntry, RgbF32); 11] = [
            (&gaussian_blur::ENTRY, gaussian_blur::twin(&image, s)),
            (&glass_blur::ENTRY, glass_blur::twin(&image, s, seed, 0)),
            (&defocus_blur::ENTRY, defocus_blur::twin(&image, s)),
            (&motion_blur::ENTRY, motion_blur::twin(&image, s, seed, 0)),
            (&zoom_blur::ENTRY, zoom_blur::twin(&image, s)),
            (&snow::ENTRY, snow::twin(&image, s, seed, 0)),
            (&frost::ENTRY, frost::twin(&image, s, seed, 0)),
            (&fog::ENTRY, fog::twin(&image, s, seed, 0)),
            (&spatter::ENTRY, spatter::twin(&image, s, seed, 0)),
            (&jpeg_compression::ENTRY, jpeg_compression::twin(&image, s)),
            (
                &elastic_transform::ENTRY,
                elastic_transform::twin(&image, s, seed, 0),
            ),
        ];
        for (entry, expected) in cases {
            let gpu = testing::run_color(entry, s, seed, &clean);
            let name = format!("{}-77x53", entry.name);
            testing::assert_close(&gpu, &expected.to_rgb8(), 1, &name);
        }
    }
}
