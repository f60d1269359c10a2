//! Scenes and the wgpu rasterizer.
//!
//! Data flow: [`scene`] loads a built-in or user mesh, or a Gaussian-splat capture, into one
//! [`Scene`]; the [`Rasterizer`] uploads it once and renders sRGB colour and metric z-depth into
//! the frame textures of `rslam-gpu` (a mesh through the render pipeline, a capture through the
//! [`splat`] passes), where perturbations pick them up.

pub mod actors;
mod error;
pub mod raster;
pub mod raycast;
pub mod scene;
pub mod splat;

pub use error::RenderError;
pub use raster::Rasterizer;
pub use scene::{
    agent_trajectory, builtin_path_length, load_scene, load_scene_scaled, Door, FreeFloor,
    LightKind, LightLayers, Mesh, Scene, Texture, Vertex, BUILTIN_SCENES, MAX_LIGHT_LAYERS,
};
