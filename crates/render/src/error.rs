use std::path::PathBuf;

/// Errors of rslam-render: each names the scene, file or value that was wrong.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(
        "unknown scene '{name}': expected a built-in scene ({choices}) or a mesh file (.ply, .gltf, .glb, .obj)"
    )]
    UnknownScene { name: String, choices: String },
    #[error("{path}: unsupported mesh format '{extension}': expected .ply, .gltf, .glb or .obj")]
    UnsupportedFormat { path: PathBuf, extension: String },
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: {message}")]
    BadMesh { path: PathBuf, message: String },
    #[error("a Gaussian-splat capture has no light layers: light items need a built-in scene")]
    CaptureLight,
    #[error("scene '{name}': {message}")]
    Actors { name: String, message: String },
    #[error("a Gaussian-splat capture of no Gaussians: nothing to render")]
    EmptyCapture,
    #[error("'{name}' is a Gaussian-splat capture: it has no triangle mesh to export")]
    CaptureMesh { name: String },
    #[error("scene '{name}': capture scale {message}")]
    CaptureScale { name: String, message: String },
    #[error("{path}: texture '{texture}': {message}")]
    BadTexture {
        path: PathBuf,
        texture: String,
        message: String,
    },
    #[error("{name}: texture layer {layer}: {message}")]
    BadTextureData {
        name: String,
        layer: usize,
        message: String,
    },
    #[error(
        "{name}: vertex {vertex} samples texture layer {layer}, but the scene has {count} textures"
    )]
    LayerOutOfRange {
        name: String,
        vertex: usize,
        layer: u32,
        count: usize,
    },
    #[error(transparent)]
    Gpu(#[from] rslam_gpu::GpuError),
    #[error(transparent)]
    Core(#[from] rslam_core::CoreError),
    #[error("{name}: {count} textures exceed the GPU's limit of {limit} texture layers")]
    TooManyTextures {
        name: String,
        count: usize,
        limit: u32,
    },
    #[error("{name}: {count} light layers exceed the renderer's {max}")]
    TooManyLights {
        name: String,
        count: usize,
        max: usize,
    },
    #[error("{given} light weights given for a scene of {layers} light layers")]
    LightWeights { given: usize, layers: usize },
}

impl RenderError {
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        RenderError::Io {
            path: path.into(),
            source,
        }
    }

    pub fn bad_mesh(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        RenderError::BadMesh {
            path: path.into(),
            message: message.into(),
        }
    }
}
