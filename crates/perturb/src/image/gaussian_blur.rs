//! gaussian_blur: a separable Gaussian with edges replicated, as imagecorruptions' `gaussian_blur`
//! (scikit-image `gaussian`, i.e. SciPy `gaussian_filter`, mode 'nearest', truncate 4).
//! The two passes ([`GaussianPasses`]) also serve glass_blur.

use rslam_gpu::FrameTextures;

use super::kernels::{gaussian_half_kernel, store_truncated, symmetric_filter};
use super::kernels::{Axis, Edge, Kernel1dUniform};
use super::separable::{gaussian_runs, Channels, SeparableFilter};
use crate::image_f32::RgbF32;
use crate::perturbation::{view, Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::twin::{Tolerance, Twin};
use crate::PerturbError;

const NAME: &str = "gaussian_blur";

/// σ in pixels per severity (docs/src/perturbations.md §3, imagecorruptions `gaussian_blur`).
pub const SIGMA: [f64; 5] = [1.0, 2.0, 3.0, 4.0, 6.0];

/// SciPy's default truncation: radius = int(4σ + 0.5).
const TRUNCATE: f64 = 4.0;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "Gaussian blur (σ px, radius 4σ, edges replicated), separable",
    parameters: |s| format!("σ={}px", SIGMA[s as usize - 1]),
    build: |kit| Ok(Box::new(GaussianBlur::new(kit)?)),
    between: Between::Interpolated("σ linear from 0"),
    explicit: None,
    twin: Twin::Color(twin),
    // f32 weighted sums in another order (runs of 8 on the GPU).
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[
        Kernel1dUniform::layout(Channels::Rgb8.shaders()[0]),
        Kernel1dUniform::layout(Channels::Rgb8.shaders()[1]),
    ],
};

/// The two passes of a separable Gaussian: rows into an f32 texture, then columns into an
/// `Rgba8Unorm` target, truncated to 8 bits.
pub(crate) struct GaussianPasses {
    filter: SeparableFilter,
    intermediate: wgpu::Texture,
}

impl GaussianPasses {
    pub fn new(kit: &Kit) -> Result<Self, PerturbError> {
        Ok(Self {
            filter: SeparableFilter::new(kit, Channels::Rgb8)?,
            intermediate: Channels::Rgb8.frame_texture(kit, "gaussian blur rows"),
        })
    }

    /// Sets σ for every [`GaussianPasses::encode`] of this frame.
    pub fn set_sigma(&self, kit: &Kit, name: &str, sigma: f64) -> Result<(), PerturbError> {
        let kernel = gaussian_runs(name, sigma, TRUNCATE, Edge::Replicate)?;
        self.filter.set_kernels(kit, &kernel, &kernel);
        Ok(())
    }

    /// Blurs `source` into `target` (which must differ from `source`).
    pub fn encode(
        &self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        source: &wgpu::TextureView,
        target: &wgpu::TextureView,
    ) {
        let intermediate = view(&self.intermediate);
        self.filter
            .encode(kit, encoder, source, &intermediate, target);
    }
}

struct GaussianBlur {
    passes: GaussianPasses,
}

impl GaussianBlur {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        Ok(Self {
            passes: GaussianPasses::new(kit)?,
        })
    }
}

impl GpuPerturbation for GaussianBlur {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        self.passes
            .set_sigma(kit, NAME, key.interpolate(0.0, &SIGMA))?;
        kit.copy_color_to_scratch(encoder, frame);
        let source = view(&kit.scratch.color);
        self.passes
            .encode(kit, encoder, &source, frame.color_view());
        Ok(())
    }
}

/// CPU twin of [`GaussianPasses`]: rows then columns, edges replicated, truncated to 8 bits.
pub fn blur_twin(image: &RgbF32, sigma: f64) -> RgbF32 {
    let half = gaussian_half_kernel(sigma, TRUNCATE);
    let (w, h) = (image.width, image.height);
    let rows = symmetric_filter(&image.data, w, h, &half, Axis::Rows, Edge::Replicate);
    let columns = symmetric_filter(&rows, w, h, &half, Axis::Columns, Edge::Replicate);
    RgbF32 {
        width: w,
        height: h,
        data: columns
            .into_iter()
            .map(|p| p.map(store_truncated))
            .collect(),
    }
}

/// CPU twin of `gaussian_blur`.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    blur_twin(image, key.interpolate(0.0, &SIGMA))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn flat_regions_keep_their_level_and_edges_spread() {
        // A vertical step 40 → 200: far from it the levels stay exact (no truncation loss), at
        // the step the blur passes through the mean, symmetric about it.
        let mut image = RgbF32::new(64, 8);
        for (i, p) in image.data.iter_mut().enumerate() {
            *p = [if i % 64 < 32 { 40.0 } else { 200.0 } / 255.0; 3];
        }
        let out = twin(&image, &testing::key(0, 2)).to_rgb8();
        let at = |x: usize| out.data[3 * x];
        assert_eq!((at(0), at(20), at(44), at(63)), (40, 40, 200, 200));
        let mid = (at(31) as i32 + at(32) as i32) / 2;
        assert!((mid - 120).abs() <= 1, "{} {}", at(31), at(32));
        assert!(at(28) > 40 && at(35) < 200);
    }
}
