//! A scene frame under a shutter (`exposure`, `rolling_shutter`): every render of the frame's
//! schedule is drawn from its own pose into one sub-frame texture and added on the GPU to the
//! frame's linear-light sum (its depth rows, and its instance-mask rows, copied where it is the
//! rows' read-out instant); the
//! sum is then encoded into the frame's colour, where the image corruptions pick it up. Nothing
//! leaves the GPU until the frame's one readback.

use rslam_core::Pose;
use rslam_gpu::{wgpu, FrameTextures, GpuContext};
use rslam_perturb::sensor::{CameraPath, Shutter, ShutterPass, SubRender};
use rslam_render::Rasterizer;

use crate::source::FrameLight;
use crate::PipelineError;

pub(crate) struct ShutterRender {
    shutter: Shutter,
    rate_hz: f64,
    pass: ShutterPass,
    subframe: FrameTextures,
}

impl ShutterRender {
    /// `None` when `shutter` has no item: frames are single renders. Sub-renders carry an
    /// instance mask when `with_mask`.
    pub fn new(
        ctx: &GpuContext,
        shutter: Shutter,
        rate_hz: f64,
        (width, height): (u32, u32),
        with_mask: bool,
    ) -> Result<Option<Self>, PipelineError> {
        if shutter.is_none() {
            return Ok(None);
        }
        Ok(Some(Self {
            shutter,
            rate_hz,
            pass: ShutterPass::new(ctx, width, height)?,
            subframe: FrameTextures::with_mask(ctx, width, height, with_mask),
        }))
    }

    /// The time a plain render of a frame exposes, in seconds from its timestamp.
    pub fn window(&self) -> (f64, f64) {
        self.shutter.window()
    }

    pub fn is(&self, shutter: &Shutter, rate_hz: f64) -> bool {
        self.shutter == *shutter && self.rate_hz == rate_hz
    }

    /// The renders frame `index` of `poses` takes (empty: one plain render at its pose).
    pub fn schedule(
        &self,
        rasterizer: &Rasterizer,
        poses: &[Pose],
        index: usize,
    ) -> Vec<SubRender> {
        let path = CameraPath {
            poses,
            rate_hz: self.rate_hz,
            camera: *rasterizer.intrinsics(),
        };
        self.shutter.schedule(&path, index)
    }

    /// Records `renders` into `frame`, the final encoding into `encoder`; `light` lights each
    /// render with the light of its window, and the actors stand where they are at its middle. The rasterizer's camera and light and the pass's
    /// parameters are uniforms written at record time, so each render is its own submission;
    /// the queue runs them in order before `encoder`'s.
    pub fn record(
        &self,
        ctx: &GpuContext,
        rasterizer: &mut Rasterizer,
        renders: &[SubRender],
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        light: &FrameLight,
    ) -> Result<(), PipelineError> {
        for render in renders {
            light.apply(ctx, rasterizer, render.light_window)?;
            rasterizer.pose_actors(ctx, light.instant(render.light_window));
            let mut sub = ctx.device.create_command_encoder(&Default::default());
            rasterizer.encode(ctx, &mut sub, &self.subframe, &render.world_from_camera)?;
            if render.weight > 0.0 {
                self.pass.add(
                    ctx,
                    &mut sub,
                    &self.subframe,
                    render.rows.clone(),
                    render.weight,
                    render.starts_sum,
                );
            }
            if render.depth {
                copy_rows(&mut sub, &self.subframe.depth, &frame.depth, render);
                if let (Some(from), Some(to)) = (&self.subframe.mask, &frame.mask) {
                    copy_rows(&mut sub, from, to, render);
                }
            }
            ctx.queue.submit([sub.finish()]);
        }
        self.pass.resolve(ctx, encoder, frame);
        Ok(())
    }
}

fn copy_rows(
    encoder: &mut wgpu::CommandEncoder,
    from: &wgpu::Texture,
    to: &wgpu::Texture,
    render: &SubRender,
) {
    let at = |texture| wgpu::TexelCopyTextureInfo {
        texture,
        mip_level: 0,
        origin: wgpu::Origin3d {
            x: 0,
            y: render.rows.start,
            z: 0,
        },
        aspect: wgpu::TextureAspect::All,
    };
    encoder.copy_texture_to_texture(
        at(from),
        at(to),
        wgpu::Extent3d {
            width: from.width(),
            height: render.rows.len() as u32,
            depth_or_array_layers: 1,
        },
    );
}
