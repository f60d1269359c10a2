use rslam_core::{Intrinsics, Pose};
use rslam_gpu::{FrameTextures, GpuContext};

use super::mesh_rasterizer::MeshRasterizer;
use crate::splat::{SplatRasterizer, SplatSettings};
use crate::{RenderError, Scene};

/// A scene uploaded once and drawn into [`FrameTextures`] of one size: a mesh by the render
/// pipeline, a splat capture by the splat passes.
pub struct Rasterizer {
    drawer: Drawer,
}

/// Boxed: both hold many GPU handles, and a rasterizer is moved into every source.
enum Drawer {
    Mesh(Box<MeshRasterizer>),
    Splats(Box<SplatRasterizer>),
}

impl Rasterizer {
    /// `scene` drawn with `intrinsics`; a capture with the default [`SplatSettings`].
    pub fn new(
        ctx: &GpuContext,
        scene: &Scene,
        intrinsics: Intrinsics,
    ) -> Result<Self, RenderError> {
        Self::with_splat_settings(ctx, scene, intrinsics, SplatSettings::default())
    }

    /// Like [`Rasterizer::new`], a capture's depth rendered as `settings` say (meshes ignore
    /// them).
    pub fn with_splat_settings(
        ctx: &GpuContext,
        scene: &Scene,
        intrinsics: Intrinsics,
        settings: SplatSettings,
    ) -> Result<Self, RenderError> {
        let drawer = match &scene.splats {
            Some(cloud) => Drawer::Splats(Box::new(SplatRasterizer::new(
                ctx, cloud, intrinsics, settings,
            )?)),
            None => Drawer::Mesh(Box::new(MeshRasterizer::new(ctx, scene, intrinsics)?)),
        };
        Ok(Self { drawer })
    }

    pub fn intrinsics(&self) -> &Intrinsics {
        match &self.drawer {
            Drawer::Mesh(mesh) => mesh.intrinsics(),
            Drawer::Splats(splats) => splats.intrinsics(),
        }
    }

    /// Draws with `intrinsics` from now on (frames of its size); the scene stays uploaded.
    pub fn set_intrinsics(
        &mut self,
        ctx: &GpuContext,
        intrinsics: Intrinsics,
    ) -> Result<(), RenderError> {
        match &mut self.drawer {
            Drawer::Mesh(mesh) => {
                mesh.set_intrinsics(ctx, intrinsics);
                Ok(())
            }
            Drawer::Splats(splats) => splats.set_intrinsics(ctx, intrinsics),
        }
    }

    /// Lights the renders submitted from now on with `weights`, one RGB weight per layer of the
    /// scene's [`crate::LightLayers`]; `None` (the start) keeps the baked colours. A capture has
    /// no light layers: it takes `None` only.
    pub fn set_light(
        &self,
        ctx: &GpuContext,
        weights: Option<&[[f32; 3]]>,
    ) -> Result<(), RenderError> {
        match (&self.drawer, weights) {
            (Drawer::Mesh(mesh), _) => mesh.set_light(ctx, weights),
            (Drawer::Splats(_), None) => Ok(()),
            (Drawer::Splats(_), Some(_)) => Err(RenderError::CaptureLight),
        }
    }

    /// Records the render of the view from `world_from_camera` into `frame` (colour and z-depth;
    /// pixels that see nothing get black and depth 0). The camera is a uniform written now that
    /// takes effect with the next queue submission, so submit each frame before encoding the
    /// next.
    pub fn encode(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        world_from_camera: &Pose,
    ) -> Result<(), RenderError> {
        match &mut self.drawer {
            Drawer::Mesh(mesh) => {
                mesh.encode(ctx, encoder, frame, world_from_camera);
                Ok(())
            }
            Drawer::Splats(splats) => splats.encode(ctx, encoder, frame, world_from_camera),
        }
    }
}
