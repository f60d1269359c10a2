//! The wgpu rasterizer: camera projection, scene upload, the light mix, and the render pass for
//! meshes; [`Rasterizer`] draws a mesh with it or a capture with [`crate::splat`].

mod camera;
mod color_agreement;
mod depth_agreement;
mod light_mix;
mod mesh_rasterizer;
mod rasterizer;
mod texture_array;

pub use camera::{clip_from_camera, CameraUniform, NEAR};
pub use color_agreement::{color_agreement, edge_mask, ColorAgreement};
pub use depth_agreement::{depth_agreement, DepthAgreement};
pub use rasterizer::Rasterizer;
