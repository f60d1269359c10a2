//! Gaussian-splat captures (3DGS) rendered on the GPU as the reference implementation renders
//! them, every step in WGSL on the shared context: [`gaussians`] packs the capture once (3D
//! covariance, activated opacity); each frame [`SplatRasterizer`] projects the Gaussians
//! (EWA, spherical-harmonic colour), sorts them by depth, duplicates them per touched 16×16
//! tile, sorts the duplicates stably by tile ([`rslam_gpu::RadixSort`]), and blends each tile
//! front to back into the frame's colour and depth. The one value that leaves the GPU mid-frame
//! is the duplicates' count, which sizes the tile sort.

mod camera;
mod from_mesh;
mod gaussians;
mod rasterizer;

pub use from_mesh::capture_of_mesh;
pub use rasterizer::SplatRasterizer;

/// Which depth a splat render writes per pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SplatDepth {
    /// Σ wᵢ zᵢ / Σ wᵢ over the blended Gaussians (weights wᵢ = αᵢ Tᵢ).
    #[default]
    Expected,
    /// The depth of the Gaussian at which the transmittance falls below 0.5.
    Median,
}

impl SplatDepth {
    pub const ALL: [SplatDepth; 2] = [SplatDepth::Expected, SplatDepth::Median];

    pub fn name(self) -> &'static str {
        match self {
            SplatDepth::Expected => "expected",
            SplatDepth::Median => "median",
        }
    }
}

impl std::str::FromStr for SplatDepth {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        (Self::ALL.into_iter())
            .find(|depth| depth.name() == text)
            .ok_or_else(|| format!("'{text}': expected 'expected' or 'median'"))
    }
}

/// How a splat capture is rendered to depth.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SplatSettings {
    pub depth: SplatDepth,
    /// Pixels whose accumulated opacity stays below this get depth 0 (no measurement).
    pub min_opacity: f32,
}

impl Default for SplatSettings {
    fn default() -> Self {
        Self {
            depth: SplatDepth::Expected,
            min_opacity: 0.5,
        }
    }
}

/// How a capture enters a job: its metric scale, how its depth is rendered, and the transform
/// its path file needs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CaptureOptions {
    /// Metres per unit of the capture's coordinates; `None`: not stated (COLMAP and phone
    /// captures have no scale of their own), and items in metres are refused.
    pub metres_per_unit: Option<f64>,
    pub settings: SplatSettings,
    /// nerfstudio's `dataparser_transforms.json`, which moves a `transforms.json` path into the
    /// frame the capture was trained (and exported) in.
    pub dataparser_transforms: Option<std::path::PathBuf>,
}
