//! A scene frame through a lens (`distortion`): the frame is drawn — one render or a shutter's
//! sum — by the wider pinhole of the lens view into a texture of that size, then resampled
//! through the lens into the frame on the GPU. Under `rolling_shutter` the rows read out are the
//! wide render's rows: a lens image row, curved in the pinhole image, is read out at the instants
//! of the pinhole rows it crosses (a few rows' read-out time apart at the corners).

use rslam_core::{Distortion, Intrinsics};
use rslam_gpu::{wgpu, FrameTextures, GpuContext};
use rslam_perturb::sensor::{distortion, LensPass, LensView};
use rslam_perturb::PerturbError;

use crate::PipelineError;

pub(crate) struct LensRender {
    lens: Distortion,
    wide_camera: Intrinsics,
    pass: LensPass,
    wide: FrameTextures,
}

impl LensRender {
    /// `camera` seen through `lens` (the wide render with an instance mask when `with_mask`); the
    /// error names the item and why the lens cannot be drawn.
    pub fn new(
        ctx: &GpuContext,
        camera: &Intrinsics,
        lens: Distortion,
        with_mask: bool,
    ) -> Result<Self, PipelineError> {
        let view = LensView::new(camera, &lens)
            .map_err(|message| PerturbError::spec(distortion::item(&lens), message))?;
        let wide_camera = view.wide;
        Ok(Self {
            lens,
            wide_camera,
            pass: LensPass::new(ctx, &view, (camera.width, camera.height))?,
            wide: FrameTextures::with_mask(ctx, wide_camera.width, wide_camera.height, with_mask),
        })
    }

    pub fn lens(&self) -> &Distortion {
        &self.lens
    }

    /// The pinhole the scene is drawn with.
    pub fn wide_camera(&self) -> Intrinsics {
        self.wide_camera
    }

    /// Where the scene is drawn before [`LensRender::record`].
    pub fn wide(&self) -> &FrameTextures {
        &self.wide
    }

    /// Records the resampling of the wide render through the lens into `frame`.
    pub fn record(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
    ) {
        self.pass.record(ctx, encoder, &self.wide, frame);
    }
}
