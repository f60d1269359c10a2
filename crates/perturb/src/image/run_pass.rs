//! Like [`super::color_pass::ColorPass`] (copy the frame's colour to scratch, one shader reads the
//! copy and writes the frame; bindings 0 source, 1 output, 2 parameters, then extras), for shaders
//! whose invocations each write a run of 8 pixels of a row (see `filter.wgsl`).

use bytemuck::Pod;
use rslam_gpu::FrameTextures;

use crate::perturbation::{view, Kit};
use crate::PerturbError;

/// Pixels per invocation.
const RUN: u32 = 8;

pub struct RunPass {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    label: &'static str,
}

impl RunPass {
    pub fn new<P: Pod>(kit: &Kit, shader: &'static str) -> Result<Self, PerturbError> {
        Ok(Self {
            pipeline: kit.pipeline(shader)?,
            params: kit.uniform_buffer::<P>(shader),
            label: shader,
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
        let runs = kit.width.div_ceil(RUN);
        kit.dispatch_grid(
            encoder,
            &self.pipeline,
            &bind_group,
            self.label,
            runs,
            kit.height,
        );
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
