//! The light mix on the GPU: the scene's [`LightLayers`] uploaded once, and the per-render
//! uniform of one RGB weight per layer that `mesh.wgsl` mixes them with. With no weights set the
//! shader keeps the baked vertex colours.

use bytemuck::Zeroable;
use rslam_gpu::GpuContext;
use wgpu::util::DeviceExt;

use crate::{LightLayers, RenderError, Scene, MAX_LIGHT_LAYERS};

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct LightMixUniform {
    /// 0: the baked colours; else the number of layers mixed.
    count: u32,
    _pad: [u32; 3],
    weights: [[f32; 4]; MAX_LIGHT_LAYERS],
}

pub(super) struct LightMix {
    layer_count: usize,
    pub uniform: wgpu::Buffer,
    /// Vertex-major layer colours (vec4 each); 16 unused bytes for a scene without layers.
    pub layers: wgpu::Buffer,
}

impl LightMix {
    /// The scene's layers, with room for the layers of `actor_vertices` more vertices after
    /// its own ([`LightMix::set_actor_light`]).
    pub fn new(
        ctx: &GpuContext,
        scene: &Scene,
        actor_vertices: usize,
    ) -> Result<Self, RenderError> {
        let device = &ctx.device;
        let empty = LightLayers {
            kinds: Vec::new(),
            colours: Vec::new(),
        };
        let lights = scene.lights.as_ref().unwrap_or(&empty);
        if lights.kinds.len() > MAX_LIGHT_LAYERS {
            return Err(RenderError::TooManyLights {
                name: scene.name.clone(),
                count: lights.kinds.len(),
                max: MAX_LIGHT_LAYERS,
            });
        }
        let mut colours: Vec<[f32; 4]> = lights
            .colours
            .iter()
            .map(|c| [c[0], c[1], c[2], 0.0])
            .collect();
        colours.resize(
            colours.len() + actor_vertices * lights.kinds.len(),
            [0.0; 4],
        );
        if colours.is_empty() {
            colours.push([0.0; 4]);
        }
        let layers = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("light layers"),
            contents: bytemuck::cast_slice(&colours),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        });
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("light mix"),
            contents: bytemuck::bytes_of(&LightMixUniform::zeroed()),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        Ok(Self {
            layer_count: lights.kinds.len(),
            uniform,
            layers,
        })
    }

    /// Sets the layers of the vertices from `first_vertex` on (the actors') to `light`, linear
    /// RGB per vertex and layer, vertex-major.
    pub fn set_actor_light(&self, ctx: &GpuContext, first_vertex: usize, light: &[[f32; 3]]) {
        let padded: Vec<[f32; 4]> = light.iter().map(|c| [c[0], c[1], c[2], 0.0]).collect();
        let offset = (first_vertex * self.layer_count * std::mem::size_of::<[f32; 4]>()) as u64;
        ctx.queue
            .write_buffer(&self.layers, offset, bytemuck::cast_slice(&padded));
    }

    /// Mixes the layers with `weights` (one per layer) in the renders submitted from now on;
    /// `None` keeps the baked colours.
    pub fn set(&self, ctx: &GpuContext, weights: Option<&[[f32; 3]]>) -> Result<(), RenderError> {
        let mut uniform = LightMixUniform::zeroed();
        if let Some(weights) = weights {
            if weights.len() != self.layer_count {
                return Err(RenderError::LightWeights {
                    given: weights.len(),
                    layers: self.layer_count,
                });
            }
            uniform.count = weights.len() as u32;
            for (slot, w) in uniform.weights.iter_mut().zip(weights) {
                *slot = [w[0], w[1], w[2], 0.0];
            }
        }
        ctx.queue
            .write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        Ok(())
    }
}
