//! One output frame kept on the GPU for display: the source frames it comes from, clean and
//! perturbed, and their depth colour-mapped. Nothing is read back; a window samples the textures
//! directly (the viewer registers [`ShownViews`] with its renderer).

use rslam_gpu::{read_texels, wgpu, FrameTextures, GpuContext};

use crate::depth_colormap::{DepthColormap, DepthRange};
use crate::PipelineError;

/// Which source frames an output frame shows: its colour's and its depth's (they differ under
/// `misalign`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShownSources {
    pub rgb: usize,
    pub depth: usize,
}

/// What a [`ShownFrame`] holds: its source frames, drawn from a pose of the caller's instead of
/// the path's for a free camera, from sources as they were at `generation`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Held {
    pub sources: ShownSources,
    pub pose: Option<rslam_core::Pose>,
    pub generation: u64,
}

/// Views for sampling, made once: colour seen as sRGB, depth as its Turbo colours (sRGB).
pub struct ShownViews {
    pub clean_color: wgpu::TextureView,
    pub perturbed_color: wgpu::TextureView,
    pub clean_depth: wgpu::TextureView,
    pub perturbed_depth: wgpu::TextureView,
}

/// What one pixel holds, clean and perturbed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelReadout {
    pub clean_rgb: [u8; 3],
    pub perturbed_rgb: [u8; 3],
    /// Metres; 0 = no depth.
    pub clean_depth: f32,
    pub perturbed_depth: f32,
}

/// The GPU side of the shown frame, allocated once per frame size.
pub struct ShownFrame {
    /// The colour's source frame, as drawn or uploaded and after the corruptions.
    pub(crate) clean: FrameTextures,
    pub(crate) perturbed: FrameTextures,
    /// The depth's source frame when it is another one (`misalign`).
    pub(crate) lagged_clean: FrameTextures,
    pub(crate) lagged_perturbed: FrameTextures,
    clean_depth_colors: wgpu::Texture,
    perturbed_depth_colors: wgpu::Texture,
    colormap: DepthColormap,
    views: ShownViews,
    /// What `clean` (and `lagged_clean`) hold; `None` once they must be redrawn.
    pub(crate) held: Option<Held>,
    with_depth: bool,
}

impl ShownFrame {
    pub fn new(ctx: &GpuContext, width: u32, height: u32) -> Result<Self, PipelineError> {
        let clean = FrameTextures::new(ctx, width, height);
        let perturbed = FrameTextures::new(ctx, width, height);
        let depth_colors = |label| {
            ctx.texture_2d(
                label,
                FrameTextures::COLOR_FORMAT,
                (width, height),
                wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                &[FrameTextures::COLOR_SRGB_FORMAT],
            )
        };
        let clean_depth_colors = depth_colors("shown clean depth colours");
        let perturbed_depth_colors = depth_colors("shown perturbed depth colours");
        let srgb = |t: &wgpu::Texture| {
            t.create_view(&wgpu::TextureViewDescriptor {
                format: Some(FrameTextures::COLOR_SRGB_FORMAT),
                usage: Some(wgpu::TextureUsages::TEXTURE_BINDING),
                ..Default::default()
            })
        };
        let views = ShownViews {
            clean_color: srgb(&clean.color),
            perturbed_color: srgb(&perturbed.color),
            clean_depth: srgb(&clean_depth_colors),
            perturbed_depth: srgb(&perturbed_depth_colors),
        };
        Ok(Self {
            lagged_clean: FrameTextures::new(ctx, width, height),
            lagged_perturbed: FrameTextures::new(ctx, width, height),
            clean,
            perturbed,
            clean_depth_colors,
            perturbed_depth_colors,
            colormap: DepthColormap::new(ctx)?,
            views,
            held: None,
            with_depth: true,
        })
    }

    pub fn size(&self) -> (u32, u32) {
        (self.clean.width, self.clean.height)
    }

    pub fn views(&self) -> &ShownViews {
        &self.views
    }

    /// Whether the shown frame has depth (image-only inputs have none).
    pub fn has_depth(&self) -> bool {
        self.with_depth
    }

    pub(crate) fn set_has_depth(&mut self, with_depth: bool) {
        self.with_depth = with_depth;
    }

    /// The source frames last shown, if any.
    pub fn sources(&self) -> Option<ShownSources> {
        self.held.map(|h| h.sources)
    }

    /// The textures holding the shown depth: the colour's frame or the lagged one.
    fn depth_frames(&self, sources: ShownSources) -> (&FrameTextures, &FrameTextures) {
        if sources.rgb == sources.depth {
            (&self.clean, &self.perturbed)
        } else {
            (&self.lagged_clean, &self.lagged_perturbed)
        }
    }

    /// Records the colour-mapping of the shown depth at `range`.
    pub(crate) fn encode_depth_colors(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        sources: ShownSources,
        range: DepthRange,
    ) {
        let (clean, perturbed) = self.depth_frames(sources);
        self.colormap.encode(
            ctx,
            encoder,
            &[
                (&clean.depth, &self.clean_depth_colors),
                (&perturbed.depth, &self.perturbed_depth_colors),
            ],
            range,
        );
    }

    /// Colour and depth at pixel (`x`, `y`) of the frame last shown (a one-pixel readback, for
    /// the readout under the cursor; not part of displaying).
    pub fn read_pixel(
        &self,
        ctx: &GpuContext,
        x: u32,
        y: u32,
    ) -> Result<Option<PixelReadout>, PipelineError> {
        let (width, height) = self.size();
        let Some(Held { sources, .. }) = self.held else {
            return Ok(None);
        };
        if x >= width || y >= height {
            return Ok(None);
        }
        let (clean_depth, perturbed_depth) = self.depth_frames(sources);
        let texels = read_texels(
            ctx,
            &[
                (&self.clean.color, x, y),
                (&self.perturbed.color, x, y),
                (&clean_depth.depth, x, y),
                (&perturbed_depth.depth, x, y),
            ],
        )?;
        let rgb = |t: [u8; 4]| [t[0], t[1], t[2]];
        let depth = |t: [u8; 4]| {
            if self.with_depth {
                f32::from_ne_bytes(t)
            } else {
                0.0
            }
        };
        Ok(Some(PixelReadout {
            clean_rgb: rgb(texels[0]),
            perturbed_rgb: rgb(texels[1]),
            clean_depth: depth(texels[2]),
            perturbed_depth: depth(texels[3]),
        }))
    }
}

/// Records a copy of `from`'s colour and depth into `to` (same size).
pub(crate) fn copy_frame(
    encoder: &mut wgpu::CommandEncoder,
    from: &FrameTextures,
    to: &FrameTextures,
) {
    for (a, b) in [(&from.color, &to.color), (&from.depth, &to.depth)] {
        encoder.copy_texture_to_texture(a.as_image_copy(), b.as_image_copy(), from.size());
    }
}

#[cfg(test)]
mod tests {
    //! The shown frame against the frames a run reads back: the same pixels, with no readback on the
    //! way; a new spec re-perturbs the held source frames like a new run would; the depth colours
    //! are the CPU twin's.

    use std::sync::OnceLock;

    use rslam_core::{DepthImage, Intrinsics, RgbImage};
    use rslam_gpu::{read_texels, AdapterChoice, FrameReadback, FrameTextures, GpuContext};
    use rslam_perturb::PerturbSpec;

    use super::*;
    use crate::depth_colormap::depth_color;
    use crate::{FramesInMemory, SceneJob};

    const CAMERA: Intrinsics = Intrinsics {
        width: 48,
        height: 32,
        fx: 26.0,
        fy: 26.0,
        cx: 23.5,
        cy: 15.5,
    };

    /// A channel may differ by one step where the depth colours are rounded (f32 on both sides, but
    /// not bit-identical polynomial evaluation).
    const COLOR_TOLERANCE: i32 = 1;

    fn context() -> &'static GpuContext {
        static CONTEXT: OnceLock<GpuContext> = OnceLock::new();
        CONTEXT.get_or_init(|| {
            GpuContext::new(&AdapterChoice::default())
                .unwrap_or_else(|e| panic!("these tests need an adapter (lavapipe is fine): {e}"))
        })
    }

    fn job(spec: &str) -> SceneJob {
        SceneJob {
            scene: "room0".into(),
            trajectory: None,
            frames: Some(6),
            camera: CAMERA,
            rate_hz: 20.0,
            spec: match spec {
                "" => PerturbSpec::default(),
                text => PerturbSpec::parse(text).unwrap(),
            },
            seed: 5,
            agent: None,
            capture: Default::default(),
            actor_files: Vec::new(),
        }
    }

    fn read(ctx: &GpuContext, frame: &FrameTextures) -> (RgbImage, DepthImage) {
        let readback = FrameReadback::new(ctx, frame.width, frame.height, true);
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        readback.encode_copy(&mut encoder, frame);
        let (color, depth) = readback
            .read(ctx, ctx.queue.submit([encoder.finish()]))
            .unwrap();
        (color, depth.unwrap())
    }

    /// The perturbed colour and depth `shown` holds, read back for the test.
    fn shown_pixels(ctx: &GpuContext, shown: &ShownFrame) -> (RgbImage, DepthImage) {
        let sources = shown.sources().unwrap();
        let (color, _) = read(ctx, &shown.perturbed);
        let (_, depth) = read(ctx, shown.depth_frames(sources).1);
        (color, depth)
    }

    #[test]
    fn a_shown_frame_holds_what_the_frame_loop_reads_back() {
        let ctx = context();
        let spec = "gaussian_noise:2@dynamic,depth_noise:3,misalign:1";
        let mut frames = FramesInMemory::scene(ctx, &job(spec)).unwrap();
        let mut shown = ShownFrame::new(ctx, CAMERA.width, CAMERA.height).unwrap();
        let len = frames.plan().len();
        for index in [0, len - 1, 2] {
            frames
                .show(ctx, index, &mut shown, DepthRange::default())
                .unwrap();
            let expected = frames.frame(ctx, index).unwrap();
            let (color, depth) = shown_pixels(ctx, &shown);
            assert_eq!(color, expected.color, "colour of output frame {index}");
            assert_eq!(Some(depth), expected.depth, "depth of output frame {index}");
        }
        let sources = shown.sources().unwrap();
        assert_ne!(
            sources.rgb, sources.depth,
            "misalign:1 shows another depth frame"
        );
    }

    #[test]
    fn a_new_spec_re_perturbs_the_held_frame_like_a_new_run() {
        let ctx = context();
        let mut frames = FramesInMemory::scene(ctx, &job("fog:1,depth_missing:2")).unwrap();
        let mut shown = ShownFrame::new(ctx, CAMERA.width, CAMERA.height).unwrap();
        frames
            .show(ctx, 3, &mut shown, DepthRange::default())
            .unwrap();
        let before = shown_pixels(ctx, &shown);
        for (spec, seed) in [("fog:4,depth_missing:2", 5), ("fog:4,depth_missing:5", 9)] {
            let spec = PerturbSpec::parse(spec).unwrap();
            frames.set_spec(ctx, &spec, seed).unwrap();
            frames
                .show(ctx, 3, &mut shown, DepthRange::default())
                .unwrap();
            let fresh_job = SceneJob {
                spec: spec.clone(),
                seed,
                agent: None,
                capture: Default::default(),
                ..job("")
            };
            let expected = FramesInMemory::scene(ctx, &fresh_job)
                .unwrap()
                .frame(ctx, 3)
                .unwrap();
            let (color, depth) = shown_pixels(ctx, &shown);
            assert_eq!(color, expected.color, "{spec}");
            assert_eq!(Some(depth), expected.depth, "{spec}");
            assert_ne!(color, before.0, "{spec} changed the colour");
        }
    }

    #[test]
    fn depth_colours_are_the_cpu_twins() {
        let ctx = context();
        let mut frames = FramesInMemory::scene(ctx, &job("depth_missing:5")).unwrap();
        let mut shown = ShownFrame::new(ctx, CAMERA.width, CAMERA.height).unwrap();
        let range = DepthRange {
            near: 0.5,
            far: 4.0,
        };
        frames.show(ctx, 1, &mut shown, range).unwrap();
        let (_, depth) = shown_pixels(ctx, &shown);
        let pixels: Vec<(u32, u32)> = (0..CAMERA.height)
            .step_by(3)
            .flat_map(|y| (0..CAMERA.width).step_by(5).map(move |x| (x, y)))
            .collect();
        let texels: Vec<_> = pixels
            .iter()
            .map(|&(x, y)| (&shown.perturbed_depth_colors, x, y))
            .collect();
        let got = read_texels(ctx, &texels).unwrap();
        let mut holes = 0;
        for (&(x, y), texel) in pixels.iter().zip(&got) {
            let z = depth.data[(y * CAMERA.width + x) as usize];
            holes += (z == 0.0) as usize;
            let want = depth_color(z, range);
            for c in 0..3 {
                let diff = (texel[c] as i32 - want[c] as i32).abs();
                assert!(
                    diff <= COLOR_TOLERANCE,
                    "pixel ({x}, {y}) z = {z}: GPU {texel:?}, twin {want:?}"
                );
            }
        }
        assert!(holes > 0, "depth_missing:5 leaves holes, which show black");
        let readout = shown.read_pixel(ctx, 7, 9).unwrap().unwrap();
        assert_eq!(
            readout.perturbed_depth,
            depth.data[(9 * CAMERA.width + 7) as usize]
        );
    }
}
