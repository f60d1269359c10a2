//! The common shape of a per-pixel depth corruption: one shader that reads and writes
//! `frame.depth` in place (`texture_storage_2d<r32float, read_write>` at binding 0) with a
//! uniform block of parameters at binding 1 and any extra resources at 2, 3, ….

use bytemuck::Pod;
use rslam_gpu::FrameTextures;

use crate::perturbation::{FrameKey, GpuPerturbation, Kit};
use crate::PerturbError;

pub struct DepthPass {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    label: &'static str,
}

impl DepthPass {
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
        let bind_group = self.bind(kit, frame, params, extra);
        kit.dispatch(encoder, &self.pipeline, &bind_group, self.label);
    }

    fn bind<P: Pod>(
        &self,
        kit: &Kit,
        frame: &FrameTextures,
        params: &P,
        extra: &[wgpu::BindingResource],
    ) -> wgpu::BindGroup {
        kit.write_uniform(&self.params, params);
        let depth = frame.depth_view();
        let mut resources = vec![
            wgpu::BindingResource::TextureView(depth),
            self.params.as_entire_binding(),
        ];
        resources.extend_from_slice(extra);
        kit.bind_group(&self.pipeline, self.label, &resources)
    }
}

/// A per-pixel depth corruption whose parameters are a function of the kit and frame key.
pub struct DepthPointwise<P: Pod> {
    pass: DepthPass,
    params: fn(&Kit, &FrameKey) -> P,
}

impl<P: Pod + Send> DepthPointwise<P> {
    pub fn boxed(
        kit: &Kit,
        shader: &'static str,
        params: fn(&Kit, &FrameKey) -> P,
    ) -> Result<Box<dyn GpuPerturbation>, PerturbError> {
        Ok(Box::new(Self {
            pass: DepthPass::new::<P>(kit, shader)?,
            params,
        }))
    }
}

impl<P: Pod + Send> GpuPerturbation for DepthPointwise<P> {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let params = (self.params)(kit, key);
        self.pass.encode(kit, encoder, frame, &params, &[]);
        Ok(())
    }
}
