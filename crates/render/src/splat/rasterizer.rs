use rslam_core::splat_io::SplatCloud;
use rslam_core::{Intrinsics, Pose};
use rslam_gpu::compute::{
    bind_group, bind_group_at, dispatch_linear, storage_buffer, uniform_buffer,
};
use rslam_gpu::{BufferReadback, FrameTextures, GpuContext, RadixSort, Scan};
use wgpu::util::DeviceExt;

use super::camera::{tiles, SplatCamera};
use super::gaussians::{pack, sh_values};
use super::SplatSettings;
use crate::RenderError;

const PROJECT: &str = "render/splat/project.wgsl";
const TILES: &str = "render/splat/tiles.wgsl";
const BLEND: &str = "render/splat/blend.wgsl";
const GROUP: u32 = 256;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct InstanceCount {
    n: u32,
    pad: [u32; 3],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ChunkUniform {
    first: u32,
    count: u32,
    pad: [u32; 2],
}

/// The projected Gaussians, one array per part (shaders/render/splat/types.wgsl).
struct Splats {
    position: wgpu::Buffer,
    conic: wgpu::Buffer,
    color: wgpu::Buffer,
    tiles: wgpu::Buffer,
}

impl Splats {
    fn new(ctx: &GpuContext, count: u32) -> Self {
        let array = |label, bytes: u64| storage_buffer(ctx, label, count as u64 * bytes);
        Self {
            position: array("splat positions", 16),
            conic: array("splat conics", 16),
            color: array("splat colours", 16),
            tiles: array("splat tiles", 8),
        }
    }
}

/// One projection dispatch: the Gaussians whose harmonics fit one binding.
struct ProjectChunk {
    count: u32,
    bind_group: wgpu::BindGroup,
    _uniform: wgpu::Buffer,
}

/// A splat capture uploaded once, and the passes that draw it into [`FrameTextures`] of one size.
pub struct SplatRasterizer {
    intrinsics: Intrinsics,
    settings: SplatSettings,
    count: u32,
    sh_degree: u32,
    camera: wgpu::Buffer,
    pipelines: Pipelines,
    /// Per Gaussian: projected splats, and the depth sort's keys and Gaussian indices.
    splats: Splats,
    depth_sort: RadixSort,
    project: Vec<ProjectChunk>,
    depth_keys: wgpu::BindGroup,
    /// Per depth-sorted Gaussian its first instance slot, and the total at `[count]`.
    offsets: wgpu::Buffer,
    offsets_scan: Scan,
    count_tiles: wgpu::BindGroup,
    /// Reads the total back.
    total: BufferReadback,
    /// Everything sized by the frame and by the number of instances.
    instances: Instances,
}

struct Pipelines {
    project: wgpu::ComputePipeline,
    depth_keys: wgpu::ComputePipeline,
    count_tiles: wgpu::ComputePipeline,
    duplicate: wgpu::ComputePipeline,
    tile_ranges: wgpu::ComputePipeline,
    blend: wgpu::ComputePipeline,
}

/// The tile sort and per-tile ranges, rebuilt when the instances outgrow them or the frame size
/// changes.
struct Instances {
    sort: RadixSort,
    count: wgpu::Buffer,
    ranges: wgpu::Buffer,
    duplicate: wgpu::BindGroup,
    tile_ranges: wgpu::BindGroup,
}

impl SplatRasterizer {
    pub fn new(
        ctx: &GpuContext,
        cloud: &SplatCloud,
        intrinsics: Intrinsics,
        settings: SplatSettings,
    ) -> Result<Self, RenderError> {
        let max_binding = ctx.device.limits().max_storage_buffer_binding_size;
        Self::with_binding_limit(ctx, cloud, intrinsics, settings, max_binding)
    }

    /// Like [`SplatRasterizer::new`], the harmonics bound at most `max_binding` bytes at a time.
    fn with_binding_limit(
        ctx: &GpuContext,
        cloud: &SplatCloud,
        intrinsics: Intrinsics,
        settings: SplatSettings,
        max_binding: u64,
    ) -> Result<Self, RenderError> {
        if cloud.is_empty() {
            return Err(RenderError::EmptyCapture);
        }
        let device = &ctx.device;
        let count = cloud.len() as u32;
        let pipelines = Pipelines {
            project: ctx.compute_pipeline(PROJECT)?,
            depth_keys: ctx.compute_pipeline_entry(TILES, "depth_keys")?,
            count_tiles: ctx.compute_pipeline_entry(TILES, "count_tiles")?,
            duplicate: ctx.compute_pipeline_entry(TILES, "duplicate")?,
            tile_ranges: ctx.compute_pipeline_entry(TILES, "tile_ranges")?,
            blend: ctx.compute_pipeline(BLEND)?,
        };
        let init = |label, contents: &[u8]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        let packed = pack(cloud);
        let mean_opacity = init("splat means", bytemuck::cast_slice(&packed.mean_opacity));
        let cov_a = init("splat covariances", bytemuck::cast_slice(&packed.cov_a));
        let cov_b = init("splat covariances", bytemuck::cast_slice(&packed.cov_b));
        let sh = init("splat harmonics", bytemuck::cast_slice(&sh_values(cloud)));
        let camera = uniform_buffer::<SplatCamera>(ctx, "splat camera");
        let splats = Splats::new(ctx, count);
        let depth_sort = RadixSort::new(ctx, count, 32)?;
        // The harmonics of a capture of millions outgrow one binding (128 MiB on some adapters):
        // each chunk binds its own range, a multiple of 256 Gaussians (the offset alignment).
        let sh_bytes = cloud.coefficients() as u64 * 12;
        let per_chunk = ((max_binding / sh_bytes) / 256 * 256).max(256) as u32;
        let project = (0..count)
            .step_by(per_chunk as usize)
            .map(|first| {
                let chunk_count = per_chunk.min(count - first);
                let uniform = uniform_buffer::<ChunkUniform>(ctx, "splat chunk");
                let chunk = ChunkUniform {
                    first,
                    count: chunk_count,
                    pad: [0; 2],
                };
                ctx.queue
                    .write_buffer(&uniform, 0, bytemuck::bytes_of(&chunk));
                let harmonics = wgpu::BufferBinding {
                    buffer: &sh,
                    offset: first as u64 * sh_bytes,
                    size: std::num::NonZeroU64::new(chunk_count as u64 * sh_bytes),
                };
                let bind_group = bind_group(
                    ctx,
                    &pipelines.project,
                    "splat project",
                    &[
                        camera.as_entire_binding(),
                        mean_opacity.as_entire_binding(),
                        cov_a.as_entire_binding(),
                        cov_b.as_entire_binding(),
                        wgpu::BindingResource::Buffer(harmonics),
                        splats.position.as_entire_binding(),
                        splats.conic.as_entire_binding(),
                        splats.color.as_entire_binding(),
                        splats.tiles.as_entire_binding(),
                        uniform.as_entire_binding(),
                    ],
                );
                ProjectChunk {
                    count: chunk_count,
                    bind_group,
                    _uniform: uniform,
                }
            })
            .collect();
        let depth_keys = bind_group_at(
            ctx,
            &pipelines.depth_keys,
            "splat depth keys",
            &[
                (0, camera.as_entire_binding()),
                (1, splats.tiles.as_entire_binding()),
                (8, splats.position.as_entire_binding()),
                (9, depth_sort.keys().as_entire_binding()),
                (10, depth_sort.values().as_entire_binding()),
            ],
        );
        let offsets = storage_buffer(ctx, "splat instance offsets", (count as u64 + 1) * 4);
        let offsets_scan = Scan::new(ctx, &offsets, count + 1)?;
        let count_tiles = bind_group(
            ctx,
            &pipelines.count_tiles,
            "splat count tiles",
            &[
                camera.as_entire_binding(),
                splats.tiles.as_entire_binding(),
                depth_sort.values().as_entire_binding(),
                offsets.as_entire_binding(),
            ],
        );
        let total = BufferReadback::new(ctx, 4);
        let instances = Instances::new(
            ctx,
            &pipelines,
            &intrinsics,
            count.max(1024),
            [&camera, &splats.tiles, depth_sort.values(), &offsets],
        )?;
        Ok(Self {
            intrinsics,
            settings,
            count,
            sh_degree: cloud.sh_degree,
            camera,
            pipelines,
            splats,
            depth_sort,
            project,
            depth_keys,
            offsets,
            offsets_scan,
            count_tiles,
            total,
            instances,
        })
    }

    pub fn intrinsics(&self) -> &Intrinsics {
        &self.intrinsics
    }

    pub fn settings(&self) -> &SplatSettings {
        &self.settings
    }

    /// Draws with `intrinsics` from now on (frames of its size); the capture stays uploaded.
    pub fn set_intrinsics(
        &mut self,
        ctx: &GpuContext,
        intrinsics: Intrinsics,
    ) -> Result<(), RenderError> {
        let resized = tiles(&intrinsics) != tiles(&self.intrinsics);
        self.intrinsics = intrinsics;
        if resized {
            self.instances = self.instances_for(ctx, self.instances.sort.capacity())?;
        }
        Ok(())
    }

    fn instances_for(&self, ctx: &GpuContext, capacity: u32) -> Result<Instances, RenderError> {
        Instances::new(
            ctx,
            &self.pipelines,
            &self.intrinsics,
            capacity,
            [
                &self.camera,
                &self.splats.tiles,
                self.depth_sort.values(),
                &self.offsets,
            ],
        )
    }

    /// Records the render of the view from `world_from_camera` into `frame` (colour as the
    /// capture's display values, z-depth; pixels that see nothing get black and depth 0).
    /// Projection and depth sort are submitted now and the instance count read back; the tile
    /// sort and blending go into `encoder`. Submit it before encoding the next frame.
    pub fn encode(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        world_from_camera: &Pose,
    ) -> Result<(), RenderError> {
        let uniform = SplatCamera::new(
            world_from_camera,
            &self.intrinsics,
            self.count,
            self.sh_degree,
            &self.settings,
        );
        ctx.queue
            .write_buffer(&self.camera, 0, bytemuck::bytes_of(&uniform));
        let instances = self.count_instances(ctx)?;
        if instances > self.instances.sort.capacity() {
            self.instances = self.instances_for(ctx, instances.next_power_of_two())?;
        }
        let i = &self.instances;
        ctx.queue.write_buffer(
            &i.count,
            0,
            bytemuck::bytes_of(&InstanceCount {
                n: instances,
                pad: [0; 3],
            }),
        );
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            let groups = self.count.div_ceil(GROUP);
            dispatch_linear(&mut pass, &self.pipelines.duplicate, &i.duplicate, groups);
        }
        i.sort.encode(ctx, encoder, instances);
        encoder.clear_buffer(&i.ranges, 0, None);
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            let groups = instances.div_ceil(GROUP);
            dispatch_linear(
                &mut pass,
                &self.pipelines.tile_ranges,
                &i.tile_ranges,
                groups,
            );
            let blend = bind_group(
                ctx,
                &self.pipelines.blend,
                "splat blend",
                &[
                    self.camera.as_entire_binding(),
                    self.splats.position.as_entire_binding(),
                    self.splats.conic.as_entire_binding(),
                    self.splats.color.as_entire_binding(),
                    i.sort.values().as_entire_binding(),
                    i.ranges.as_entire_binding(),
                    wgpu::BindingResource::TextureView(frame.color_view()),
                    wgpu::BindingResource::TextureView(frame.depth_view()),
                ],
            );
            let [tiles_x, tiles_y] = tiles(&self.intrinsics);
            pass.set_pipeline(&self.pipelines.blend);
            pass.set_bind_group(0, &blend, &[]);
            pass.dispatch_workgroups(tiles_x, tiles_y, 1);
        }
        Ok(())
    }

    /// Projects, sorts by depth and counts the tile instances: submitted, and the count read
    /// back (it sizes the tile sort).
    fn count_instances(&self, ctx: &GpuContext) -> Result<u32, RenderError> {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            for chunk in &self.project {
                let groups = chunk.count.div_ceil(GROUP);
                dispatch_linear(
                    &mut pass,
                    &self.pipelines.project,
                    &chunk.bind_group,
                    groups,
                );
            }
            let groups = self.count.div_ceil(GROUP);
            dispatch_linear(
                &mut pass,
                &self.pipelines.depth_keys,
                &self.depth_keys,
                groups,
            );
        }
        self.depth_sort.encode(ctx, &mut encoder, self.count);
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            let groups = (self.count + 1).div_ceil(GROUP);
            dispatch_linear(
                &mut pass,
                &self.pipelines.count_tiles,
                &self.count_tiles,
                groups,
            );
        }
        self.offsets_scan.encode(ctx, &mut encoder, self.count + 1);
        self.total
            .encode_copy(&mut encoder, &self.offsets, self.count as u64 * 4);
        let submission = ctx.queue.submit([encoder.finish()]);
        let bytes = self.total.read(ctx, submission)?;
        Ok(u32::from_le_bytes(bytes[..4].try_into().expect("4 bytes")))
    }
}

impl Instances {
    fn new(
        ctx: &GpuContext,
        pipelines: &Pipelines,
        intrinsics: &Intrinsics,
        capacity: u32,
        [camera, splat_tiles, depth_order, offsets]: [&wgpu::Buffer; 4],
    ) -> Result<Self, RenderError> {
        let [tiles_x, tiles_y] = tiles(intrinsics);
        let tile_count = tiles_x * tiles_y;
        let key_bits = u32::BITS - tile_count.saturating_sub(1).leading_zeros();
        let sort = RadixSort::new(ctx, capacity, key_bits)?;
        let count = uniform_buffer::<InstanceCount>(ctx, "splat instance count");
        let ranges = storage_buffer(ctx, "splat tile ranges", tile_count as u64 * 8);
        let duplicate = bind_group(
            ctx,
            &pipelines.duplicate,
            "splat duplicate",
            &[
                camera.as_entire_binding(),
                splat_tiles.as_entire_binding(),
                depth_order.as_entire_binding(),
                offsets.as_entire_binding(),
                sort.keys().as_entire_binding(),
                sort.values().as_entire_binding(),
            ],
        );
        let tile_ranges = bind_group_at(
            ctx,
            &pipelines.tile_ranges,
            "splat tile ranges",
            &[
                (4, sort.keys().as_entire_binding()),
                (6, ranges.as_entire_binding()),
                (7, count.as_entire_binding()),
            ],
        );
        Ok(Self {
            sort,
            count,
            ranges,
            duplicate,
            tile_ranges,
        })
    }
}

#[cfg(test)]
mod tests;
