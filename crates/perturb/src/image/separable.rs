//! The generic separable filter in runs (`filter_rows.wgsl`, `filter_columns.wgsl`): one, two or
//! three f32 channels, replicated or reflected edges, a kernel per direction. Used for the
//! smoothing of spatter's noise and mud mask (one channel), of elastic_transform's displacement
//! fields (two) and for the Gaussians of gaussian_blur and glass_blur (three, from and to the
//! frame's 8-bit colour).

use super::kernels::{gaussian_half_kernel, symmetric_runs, Edge, Kernel1dUniform};
use super::textures::storage_texture;
use crate::perturbation::Kit;
use crate::PerturbError;

/// Pixels per invocation of the passes.
const RUN: u32 = 8;

/// The channels a [`SeparableFilter`] filters, each in its own pair of shaders: filtering only
/// the channels used spares the arithmetic of the unused ones.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Channels {
    One,
    Two,
    /// Colour: rows into an f32 texture, columns into an `Rgba8Unorm` frame, truncated.
    Rgb8,
}

impl Channels {
    /// The (rows, columns) shaders.
    pub const fn shaders(self) -> [&'static str; 2] {
        match self {
            Channels::One => [
                "perturb/image/filter_rows_r.wgsl",
                "perturb/image/filter_columns_r.wgsl",
            ],
            Channels::Two => [
                "perturb/image/filter_rows_rg.wgsl",
                "perturb/image/filter_columns_rg.wgsl",
            ],
            Channels::Rgb8 => [
                "perturb/image/gaussian_blur_rows.wgsl",
                "perturb/image/gaussian_blur.wgsl",
            ],
        }
    }

    /// The format of the textures the filter writes (for `Rgb8`, of its intermediate only).
    pub const fn format(self) -> wgpu::TextureFormat {
        match self {
            Channels::One => wgpu::TextureFormat::R32Float,
            Channels::Two => wgpu::TextureFormat::Rg32Float,
            Channels::Rgb8 => wgpu::TextureFormat::Rgba32Float,
        }
    }

    /// A frame-sized texture of [`Channels::format`].
    pub fn frame_texture(self, kit: &Kit, label: &str) -> wgpu::Texture {
        storage_texture(kit, label, self.format(), kit.width, kit.height)
    }
}

pub(crate) struct SeparableFilter {
    rows: wgpu::ComputePipeline,
    columns: wgpu::ComputePipeline,
    row_kernel: wgpu::Buffer,
    column_kernel: wgpu::Buffer,
}

/// A Gaussian kernel (SciPy radius int(truncate·σ + 0.5)) in the runs layout.
pub(crate) fn gaussian_runs(
    name: &str,
    sigma: f64,
    truncate: f64,
    edge: Edge,
) -> Result<Kernel1dUniform, PerturbError> {
    symmetric_runs(&gaussian_half_kernel(sigma, truncate), edge).ok_or_else(|| {
        PerturbError::Unsupported {
            name: name.into(),
            message: format!("σ={sigma:.2} px needs a longer kernel than the filter shaders take"),
        }
    })
}

impl SeparableFilter {
    pub fn new(kit: &Kit, channels: Channels) -> Result<Self, PerturbError> {
        let [rows, columns] = channels.shaders();
        Ok(Self {
            rows: kit.pipeline(rows)?,
            columns: kit.pipeline(columns)?,
            row_kernel: kit.uniform_buffer::<Kernel1dUniform>("separable row kernel"),
            column_kernel: kit.uniform_buffer::<Kernel1dUniform>("separable column kernel"),
        })
    }

    /// Sets the kernels for every [`SeparableFilter::encode`] of this frame.
    pub fn set_kernels(&self, kit: &Kit, rows: &Kernel1dUniform, columns: &Kernel1dUniform) {
        kit.write_uniform(&self.row_kernel, rows);
        kit.write_uniform(&self.column_kernel, columns);
    }

    /// `source` → rows → `intermediate` → columns → `target` (for `Rgb8` an 8-bit frame, else
    /// like `intermediate` a texture of [`Channels::format`]).
    pub fn encode(
        &self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        source: &wgpu::TextureView,
        intermediate: &wgpu::TextureView,
        target: &wgpu::TextureView,
    ) {
        use wgpu::BindingResource::TextureView as T;
        let (w, h) = (kit.width, kit.height);
        let rows = [
            T(source),
            T(intermediate),
            self.row_kernel.as_entire_binding(),
        ];
        let rows = kit.bind_group(&self.rows, "filter rows", &rows);
        kit.dispatch_grid(
            encoder,
            &self.rows,
            &rows,
            "filter rows",
            w.div_ceil(RUN),
            h,
        );
        let columns = [
            T(intermediate),
            T(target),
            self.column_kernel.as_entire_binding(),
        ];
        let columns = kit.bind_group(&self.columns, "filter columns", &columns);
        let label = "filter columns";
        kit.dispatch_grid(encoder, &self.columns, &columns, label, w, h.div_ceil(RUN));
    }
}
