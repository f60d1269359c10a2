//! The contract every GPU perturbation implements, and the kit of shared GPU resources they use.

use bytemuck::Pod;
use rslam_core::Intrinsics;
use rslam_gpu::{compute, FrameTextures, GpuContext};
use serde::Serialize;

use crate::rng::RngKey;
use crate::severity::Severity;
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::UniformLayout;
use crate::{Need, PerturbError};

/// Which frame texture a perturbation transforms.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Group {
    Image,
    Depth,
}

/// An explicit parameter form, e.g. `depth_range:0.42-10`, besides the severity levels.
pub struct ExplicitForm {
    /// The syntax shown in errors and in `rslam list`, e.g. "MIN-MAX (metres)".
    pub syntax: &'static str,
    /// A text `parse` accepts, the one `syntax` shows; the twin test runs it.
    pub example: &'static str,
    /// Parses the text after the colon into the values the perturbation reads from
    /// [`FrameKey::explicit`]; the error says what was expected.
    pub parse: fn(&str) -> Result<Vec<f64>, String>,
    /// The canonical text of parsed values (`parse(format(v)) == v`).
    pub format: fn(&[f64]) -> String,
}

/// How an item takes a real severity (`fog:2.5`) between two whole ones.
#[derive(Clone, Copy, Debug)]
pub enum Between {
    /// Its parameters are interpolated between the table's rows (row 0: the clean frame's
    /// parameters); the text says in what, for `rslam list` and the book.
    Interpolated(&'static str),
    /// Whole severities only; the text says why.
    WholeOnly(&'static str),
}

/// One line of the catalogue: everything `rslam list`, the spec parser and the viewer need.
pub struct CatalogueEntry {
    /// The id used in spec strings and the WGSL file name.
    pub name: &'static str,
    pub group: Group,
    /// One line on what it does, for `rslam list`.
    pub description: &'static str,
    /// Human-readable parameters at severity 1..=5.
    pub parameters: fn(severity: u8) -> String,
    /// Builds pipelines, buffers and any private textures, once.
    pub build: fn(&Kit) -> Result<Box<dyn GpuPerturbation>, PerturbError>,
    /// An explicit parameter form, where the perturbation has one.
    pub explicit: Option<ExplicitForm>,
    /// How it takes a real severity between two whole ones.
    pub between: Between,
    /// The CPU twin: what `build`'s pass does, on the CPU.
    pub twin: Twin,
    /// How far the GPU pass may be from `twin`.
    pub twin_tolerance: Tolerance,
    /// Every parameter struct `build`'s passes write into a uniform block, with the WGSL struct
    /// it binds to.
    pub uniforms: &'static [UniformLayout],
}

impl CatalogueEntry {
    /// What it needs of a job: depth for a depth corruption, frames in capture order for one
    /// that carries a state; an image corruption takes any frames.
    pub fn needs(&self) -> Vec<Need> {
        let depth = (self.group == Group::Depth).then_some(Need::Depth);
        let order = self.carries_state().then_some(Need::CaptureOrder);
        depth.into_iter().chain(order).collect()
    }

    /// Whether its GPU pass carries a state from frame to frame (auto_exposure's controller), so
    /// a frame's output depends on every frame before it in the run.
    pub fn carries_state(&self) -> bool {
        self.state_fields().is_some()
    }

    /// The names of the four values of its state ([`GpuPerturbation::state`]), where it has one.
    pub fn state_fields(&self) -> Option<[&'static str; 4]> {
        match self.twin {
            Twin::ColorSequence { fields, .. } => Some(fields),
            _ => None,
        }
    }

    /// `parameters` for severities 1..=5.
    pub fn parameter_table(&self) -> [String; 5] {
        std::array::from_fn(|i| (self.parameters)(i as u8 + 1))
    }
}

/// What a perturbation needs to know about the frame it is applied to.
#[derive(Clone, Copy, Debug)]
pub struct FrameKey<'a> {
    pub seed: u64,
    pub frame: u32,
    /// In (0, 5]; frames whose severity is 0 are never handed to a perturbation. Real
    /// severities reach only items whose entry interpolates ([`Between::Interpolated`]). For an
    /// explicit parameter form it is 5 and [`FrameKey::explicit`] holds the values.
    pub severity: Severity,
    pub explicit: Option<&'a [f64]>,
    /// The camera the frame was taken with, where it is known (rendered scenes, datasets); image
    /// files have none. Perturbations computed from the geometry (`depth_sensor`) need it.
    pub camera: Option<Intrinsics>,
}

impl FrameKey<'_> {
    /// Index into a 5-entry severity table, for an item that takes whole severities only.
    pub fn level(&self) -> usize {
        (self.severity.ceil().clamp(1, 5) - 1) as usize
    }

    /// A parameter at this frame's severity: `clean` at 0, `table` at 1..=5, linear between
    /// (see [`Severity::interpolate`]).
    pub fn interpolate<T: Copy + Into<f64>>(&self, clean: f64, table: &[T; 5]) -> f64 {
        self.severity.interpolate(clean, &table.map(Into::into))
    }

    /// A parameter interpolated linearly in `measure(parameter)`, see
    /// [`Severity::interpolate_in`].
    pub fn interpolate_in<T: Copy + Into<f64>>(
        &self,
        clean_measure: f64,
        table: &[T; 5],
        measure: fn(f64) -> f64,
        inverse: fn(f64) -> f64,
    ) -> f64 {
        self.severity
            .interpolate_in(clean_measure, &table.map(Into::into), measure, inverse)
    }

    /// The key of this frame's random stream for `purpose` of perturbation `name`.
    pub fn rng(&self, name: &str, purpose: u32) -> RngKey {
        RngKey::new(self.seed, name, self.frame, purpose)
    }
}

/// A GPU perturbation, built once for a frame size and applied frame after frame.
pub trait GpuPerturbation: Send {
    /// Records passes that transform `frame.color` (image group) or `frame.depth` (depth group)
    /// in place. Per-frame parameters go through uniform buffers written with
    /// `queue.write_buffer` here: each frame is its own submission, so the writes land in order.
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError>;

    /// For a pass that carries a state from frame to frame: a buffer (`COPY_SRC`) holding the
    /// state the last encoded frame was made with, four f32 named by the entry's
    /// [`CatalogueEntry::state_fields`], for a per-frame log copied on the GPU.
    fn state(&self) -> Option<&wgpu::Buffer> {
        None
    }
}

/// Textures shared by all perturbations of one [`crate::Perturber`], allocated once. Passes run
/// one after the other, so any perturbation may overwrite any scratch texture.
pub struct Scratch {
    /// `Rgba8Unorm`: the copy of `frame.color` a pass reads while writing `frame.color`.
    pub color: wgpu::Texture,
    /// Two `Rgba16Float` textures (filterable) for multi-pass work, e.g. separable blurs.
    pub float4: [wgpu::Texture; 2],
    /// Two `R32Float` textures for single-channel layers (noise, masks, edge maps).
    pub float1: [wgpu::Texture; 2],
    /// Bilinear, clamp-to-edge.
    pub linear_clamp: wgpu::Sampler,
}

impl Scratch {
    pub fn new(ctx: &GpuContext, width: u32, height: u32) -> Self {
        let texture = |label, format| ctx.storage_texture(label, format, (width, height));
        use wgpu::TextureFormat as F;
        Self {
            color: texture("scratch colour", F::Rgba8Unorm),
            float4: [
                texture("scratch float4 a", F::Rgba16Float),
                texture("scratch float4 b", F::Rgba16Float),
            ],
            float1: [
                texture("scratch float1 a", F::R32Float),
                texture("scratch float1 b", F::R32Float),
            ],
            linear_clamp: ctx.device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("linear clamp"),
                address_mode_u: wgpu::AddressMode::ClampToEdge,
                address_mode_v: wgpu::AddressMode::ClampToEdge,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                ..Default::default()
            }),
        }
    }
}

/// Side of the square workgroups every perturbation shader declares: `@workgroup_size(8, 8)`.
pub const WORKGROUP: u32 = 8;

/// The context, the frame size and the shared scratch, with the helpers passes need.
pub struct Kit<'a> {
    pub ctx: &'a GpuContext,
    pub width: u32,
    pub height: u32,
    pub scratch: &'a Scratch,
    /// The camera of the frames, where it is known; `build` of a perturbation that needs it
    /// fails without it.
    pub camera: Option<Intrinsics>,
}

impl Kit<'_> {
    /// A compute pipeline from `shaders/<path>`, entry point `main`.
    pub fn pipeline(&self, path: &str) -> Result<wgpu::ComputePipeline, PerturbError> {
        Ok(self.ctx.compute_pipeline(path)?)
    }

    /// A compute pipeline from `shaders/<path>` with a named entry point.
    pub fn pipeline_entry(
        &self,
        path: &str,
        entry: &str,
    ) -> Result<wgpu::ComputePipeline, PerturbError> {
        Ok(self.ctx.compute_pipeline_entry(path, entry)?)
    }

    /// A uniform buffer sized for `T`, written per frame with [`Kit::write_uniform`].
    /// A uniform block of `T`. Small results of a reduction pass (a storage buffer) that a later
    /// pass reads at every pixel are copied into one of these first: on lavapipe per-pixel
    /// storage-buffer reads cost as much as the rest of such a pass, uniform reads nothing.
    pub fn uniform_buffer<T: Pod>(&self, label: &str) -> wgpu::Buffer {
        compute::uniform_buffer::<T>(self.ctx, label)
    }

    pub fn write_uniform<T: Pod>(&self, buffer: &wgpu::Buffer, value: &T) {
        self.ctx
            .queue
            .write_buffer(buffer, 0, bytemuck::bytes_of(value));
    }

    /// A storage buffer of `size` bytes that stays on the GPU (reductions, counters).
    pub fn storage_buffer(&self, label: &str, size: u64) -> wgpu::Buffer {
        compute::storage_buffer(self.ctx, label, size)
    }

    /// A bind group for group 0 of `pipeline`, binding `resources[i]` at binding `i`.
    pub fn bind_group(
        &self,
        pipeline: &wgpu::ComputePipeline,
        label: &str,
        resources: &[wgpu::BindingResource],
    ) -> wgpu::BindGroup {
        compute::bind_group(self.ctx, pipeline, label, resources)
    }

    /// A bind group for group 0 of `pipeline` with explicit binding numbers, for entry points
    /// that use only some of their shader's bindings.
    pub fn bind_group_at(
        &self,
        pipeline: &wgpu::ComputePipeline,
        label: &str,
        resources: &[(u32, wgpu::BindingResource)],
    ) -> wgpu::BindGroup {
        compute::bind_group_at(self.ctx, pipeline, label, resources)
    }

    /// Copies `frame.color` into `scratch.color`, for a pass that reads it while writing the frame.
    pub fn copy_color_to_scratch(&self, encoder: &mut wgpu::CommandEncoder, frame: &FrameTextures) {
        encoder.copy_texture_to_texture(
            frame.color.as_image_copy(),
            self.scratch.color.as_image_copy(),
            frame.size(),
        );
    }

    /// One compute pass covering the frame with 8×8 workgroups.
    pub fn dispatch(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        pipeline: &wgpu::ComputePipeline,
        bind_group: &wgpu::BindGroup,
        label: &str,
    ) {
        self.dispatch_grid(
            encoder,
            pipeline,
            bind_group,
            label,
            self.width,
            self.height,
        );
    }

    /// One compute pass covering a `width`×`height` grid with 8×8 workgroups.
    pub fn dispatch_grid(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        pipeline: &wgpu::ComputePipeline,
        bind_group: &wgpu::BindGroup,
        label: &str,
        width: u32,
        height: u32,
    ) {
        dispatch_grid(encoder, pipeline, bind_group, label, [width, height]);
    }

    /// One compute pass with an explicit workgroup count.
    pub fn dispatch_workgroups(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        pipeline: &wgpu::ComputePipeline,
        bind_group: &wgpu::BindGroup,
        label: &str,
        workgroups: [u32; 3],
    ) {
        dispatch_workgroups(encoder, pipeline, bind_group, label, workgroups);
    }
}

/// One compute pass covering a `width`×`height` grid with 8×8 workgroups.
pub(crate) fn dispatch_grid(
    encoder: &mut wgpu::CommandEncoder,
    pipeline: &wgpu::ComputePipeline,
    bind_group: &wgpu::BindGroup,
    label: &str,
    [width, height]: [u32; 2],
) {
    let workgroups = [width.div_ceil(WORKGROUP), height.div_ceil(WORKGROUP), 1];
    dispatch_workgroups(encoder, pipeline, bind_group, label, workgroups);
}

/// One compute pass with an explicit workgroup count.
pub(crate) fn dispatch_workgroups(
    encoder: &mut wgpu::CommandEncoder,
    pipeline: &wgpu::ComputePipeline,
    bind_group: &wgpu::BindGroup,
    label: &str,
    workgroups: [u32; 3],
) {
    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some(label),
        timestamp_writes: None,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind_group, &[]);
    pass.dispatch_workgroups(workgroups[0], workgroups[1], workgroups[2]);
}

/// A view of a whole texture, for bind groups.
pub fn view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&Default::default())
}
