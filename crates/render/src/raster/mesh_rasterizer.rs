use std::sync::Arc;

use rslam_core::{Intrinsics, Pose};
use rslam_gpu::{FrameTextures, GpuContext};
use wgpu::util::DeviceExt;

use super::camera::CameraUniform;
use super::light_mix::LightMix;
use super::texture_array;
use crate::actors::{ActorMesh, Actors};
use crate::{RenderError, Scene, Vertex};

const SHADER: &str = "render/mesh.wgsl";
const DEPTH_BUFFER_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuVertex {
    position: [f32; 3],
    uv: [f32; 2],
    color: [u8; 4],
    layer: u32,
    /// Instance-mask id: 0 the scene, k walker k.
    object: u32,
}

const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 5] = wgpu::vertex_attr_array![
    0 => Float32x3, 1 => Float32x2, 2 => Unorm8x4, 3 => Uint32, 4 => Uint32
];

/// The scene uploaded once (vertices, indices, texture array) and the pipeline that draws it
/// into [`FrameTextures`] of one size. With actors, their posed vertices follow the scene's in
/// the same buffers (their light layers too) and are written before each render
/// ([`MeshRasterizer::pose_actors`]); one draw covers both, and writes each pixel's object id
/// into the frame's instance mask (or into a mask of its own for frames without one).
pub(crate) struct MeshRasterizer {
    intrinsics: Intrinsics,
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
    camera: wgpu::Buffer,
    light_mix: LightMix,
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    depth_buffer: wgpu::TextureView,
    actors: Option<SceneActors>,
}

/// The actors drawn with the scene and where their vertices start.
struct SceneActors {
    actors: Arc<Actors>,
    first_vertex: usize,
    vertex_count: usize,
    /// Where object ids go when the frame has no instance mask.
    unused_mask: wgpu::TextureView,
}

impl MeshRasterizer {
    pub fn new(
        ctx: &GpuContext,
        scene: &Scene,
        intrinsics: Intrinsics,
        actors: Option<Arc<Actors>>,
    ) -> Result<Self, RenderError> {
        let device = &ctx.device;
        let at_start = actors.as_ref().map(|a| a.mesh_at(0.0)).unwrap_or_default();
        let first_actor_vertex = scene.mesh.vertices.len();
        // The shader clamps an out-of-range array index to the last layer: a silent wrong texture.
        if let Some((vertex, v)) = (scene.mesh.vertices.iter().enumerate())
            .find(|(_, v)| v.layer as usize >= scene.textures.len())
        {
            return Err(RenderError::LayerOutOfRange {
                name: scene.name.clone(),
                vertex,
                layer: v.layer,
                count: scene.textures.len(),
            });
        }
        let gpu_vertices: Vec<GpuVertex> = (scene.mesh.vertices.iter().map(|v| gpu_vertex(v, 0)))
            .chain(actor_vertices(&at_start))
            .collect();
        let first = first_actor_vertex as u32;
        // Actors first: they stand in front of much of the room, and the depth test then skips
        // what they hide instead of shading it twice.
        let scene_indices = match &actors {
            Some(actors) => actors.scene_indices(scene),
            None => std::borrow::Cow::Borrowed(&scene.mesh.indices[..]),
        };
        let all_indices: Vec<u32> = (at_start.mesh.indices.iter().map(|i| first + i))
            .chain(scene_indices.iter().copied())
            .collect();
        let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("scene vertices"),
            contents: bytemuck::cast_slice(&gpu_vertices),
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        });
        let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("scene indices"),
            contents: bytemuck::cast_slice(&all_indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        let actor_textures = actors.as_ref().map(|a| a.textures()).unwrap_or_default();
        let all_textures: Vec<crate::Texture> = (scene.textures.iter().chain(actor_textures))
            .cloned()
            .collect();
        let textures = texture_array::upload(ctx, &scene.name, &all_textures)?;
        let camera = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("camera"),
            size: std::mem::size_of::<CameraUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("scene textures"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        let light_mix = LightMix::new(ctx, scene, at_start.mesh.vertices.len())?;
        light_mix.set_actor_light(ctx, first_actor_vertex, &at_start.light);
        let module = ctx.shader_module(SHADER)?;
        let with_masks = actors.is_some();
        let mut targets = vec![
            Some(FrameTextures::COLOR_SRGB_FORMAT.into()),
            Some(FrameTextures::DEPTH_FORMAT.into()),
        ];
        if with_masks {
            targets.push(Some(FrameTextures::MASK_FORMAT.into()));
        }
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("mesh"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<GpuVertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &VERTEX_ATTRIBUTES,
                })],
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(if with_masks { "fs_mask" } else { "fs_main" }),
                compilation_options: Default::default(),
                targets: &targets,
            }),
            primitive: wgpu::PrimitiveState {
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_BUFFER_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Greater),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("mesh"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: camera.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&textures.create_view(
                        &wgpu::TextureViewDescriptor {
                            dimension: Some(wgpu::TextureViewDimension::D2Array),
                            ..Default::default()
                        },
                    )),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Sampler(&sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: light_mix.uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: light_mix.layers.as_entire_binding(),
                },
            ],
        });
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(rslam_gpu::GpuError::Shader {
                path: SHADER.into(),
                message: e.to_string(),
            }
            .into());
        }
        let depth_buffer = z_buffer(ctx, &intrinsics);
        Ok(Self {
            intrinsics,
            pipeline,
            bind_group,
            camera,
            light_mix,
            vertices,
            indices,
            index_count: all_indices.len() as u32,
            depth_buffer,
            actors: actors.map(|actors| SceneActors {
                actors,
                first_vertex: first_actor_vertex,
                vertex_count: at_start.mesh.vertices.len(),
                unused_mask: unused_mask(ctx, &intrinsics),
            }),
        })
    }

    /// Poses the actors as they are `t` seconds from the start for the renders submitted from
    /// now on (a buffer write, like the camera's).
    pub fn pose_actors(&self, ctx: &GpuContext, t: f64) {
        let Some(scene_actors) = &self.actors else {
            return;
        };
        let posed = scene_actors.actors.mesh_at(t);
        assert_eq!(
            posed.mesh.vertices.len(),
            scene_actors.vertex_count,
            "a walker's mesh keeps its vertices in every pose"
        );
        let vertices: Vec<GpuVertex> = actor_vertices(&posed).collect();
        let offset = (scene_actors.first_vertex * std::mem::size_of::<GpuVertex>()) as u64;
        ctx.queue
            .write_buffer(&self.vertices, offset, bytemuck::cast_slice(&vertices));
        self.light_mix
            .set_actor_light(ctx, scene_actors.first_vertex, &posed.light);
    }

    pub fn intrinsics(&self) -> &Intrinsics {
        &self.intrinsics
    }

    /// Draws with `intrinsics` from now on (frames of its size); the scene stays uploaded.
    pub fn set_intrinsics(&mut self, ctx: &GpuContext, intrinsics: Intrinsics) {
        if (intrinsics.width, intrinsics.height) != (self.intrinsics.width, self.intrinsics.height)
        {
            self.depth_buffer = z_buffer(ctx, &intrinsics);
            if let Some(actors) = &mut self.actors {
                actors.unused_mask = unused_mask(ctx, &intrinsics);
            }
        }
        self.intrinsics = intrinsics;
    }

    /// Lights the renders submitted from now on with `weights`, one RGB weight per layer of the
    /// scene's [`crate::LightLayers`]; `None` (the start) keeps the baked colours.
    pub fn set_light(
        &self,
        ctx: &GpuContext,
        weights: Option<&[[f32; 3]]>,
    ) -> Result<(), RenderError> {
        self.light_mix.set(ctx, weights)
    }

    /// Records the render of the view from `world_from_camera` into `frame` (colour and z-depth;
    /// pixels that see nothing get black and depth 0; with actors, object ids into its mask). The camera uniform is written now and takes
    /// effect with the next queue submission, so submit each frame before encoding the next.
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        world_from_camera: &Pose,
    ) {
        let uniform = CameraUniform::new(world_from_camera, &self.intrinsics);
        ctx.queue
            .write_buffer(&self.camera, 0, bytemuck::bytes_of(&uniform));
        let color_view = frame.color_render_view();
        let depth_view = frame.depth_view();
        let clear = |color| wgpu::Operations {
            load: wgpu::LoadOp::Clear(color),
            store: wgpu::StoreOp::Store,
        };
        let attachment = |view, color| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: clear(color),
            })
        };
        let mut attachments = vec![
            attachment(color_view, wgpu::Color::BLACK),
            attachment(depth_view, wgpu::Color::TRANSPARENT),
        ];
        if let Some(actors) = &self.actors {
            let mask = frame.mask_view().unwrap_or(&actors.unused_mask);
            attachments.push(attachment(mask, wgpu::Color::TRANSPARENT));
        }
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("mesh"),
            color_attachments: &attachments,
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.depth_buffer,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..self.index_count, 0, 0..1);
    }
}

fn gpu_vertex(v: &Vertex, object: u32) -> GpuVertex {
    GpuVertex {
        position: v.position,
        uv: v.uv,
        color: v.color,
        layer: v.layer,
        object,
    }
}

/// The posed actors' vertices, each with its walker's instance-mask id.
fn actor_vertices(posed: &ActorMesh) -> impl Iterator<Item = GpuVertex> + '_ {
    (posed.mesh.vertices.iter())
        .zip(posed.vertex_ids())
        .map(|(v, id)| gpu_vertex(v, id))
}

/// The object-id target of frames without an instance mask.
fn unused_mask(ctx: &GpuContext, intrinsics: &Intrinsics) -> wgpu::TextureView {
    ctx.texture_2d(
        "unused instance mask",
        FrameTextures::MASK_FORMAT,
        (intrinsics.width, intrinsics.height),
        wgpu::TextureUsages::RENDER_ATTACHMENT,
        &[],
    )
    .create_view(&Default::default())
}

/// The z-buffer for frames of the camera's size.
fn z_buffer(ctx: &GpuContext, intrinsics: &Intrinsics) -> wgpu::TextureView {
    ctx.texture_2d(
        "z-buffer",
        DEPTH_BUFFER_FORMAT,
        (intrinsics.width, intrinsics.height),
        wgpu::TextureUsages::RENDER_ATTACHMENT,
        &[],
    )
    .create_view(&Default::default())
}
