use std::sync::Arc;

use rslam_core::{Intrinsics, Pose};
use rslam_gpu::{FrameTextures, GpuContext};

use super::mesh_rasterizer::MeshRasterizer;
use crate::actors::Actors;
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
        Self::with_actors(ctx, scene, intrinsics, settings, None)
    }

    /// Like [`Rasterizer::with_splat_settings`], with `actors` drawn into every render where
    /// [`Rasterizer::pose_actors`] last put them. A capture takes no actors.
    pub fn with_actors(
        ctx: &GpuContext,
        scene: &Scene,
        intrinsics: Intrinsics,
        settings: SplatSettings,
        actors: Option<Arc<Actors>>,
    ) -> Result<Self, RenderError> {
        let drawer = match (&scene.splats, actors) {
            (Some(_), Some(_)) => {
                return Err(RenderError::Actors {
                    name: scene.name.clone(),
                    message: "a Gaussian-splat capture cannot draw people into it".into(),
                })
            }
            (Some(cloud), None) => Drawer::Splats(Box::new(SplatRasterizer::new(
                ctx, cloud, intrinsics, settings,
            )?)),
            (None, actors) => Drawer::Mesh(Box::new(MeshRasterizer::new(
                ctx, scene, intrinsics, actors,
            )?)),
        };
        Ok(Self { drawer })
    }

    /// Poses the actors as they are `t` seconds from the sequence's start for the renders
    /// submitted from now on; nothing without actors.
    pub fn pose_actors(&self, ctx: &GpuContext, t: f64) {
        if let Drawer::Mesh(mesh) = &self.drawer {
            mesh.pose_actors(ctx, t);
        }
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
