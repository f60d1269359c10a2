//! The GPU side of `distortion` (`distortion.wgsl`): the wide pinhole render resampled through
//! the lens map into the frame, colour and depth. Its CPU twin is [`twin`].

use rslam_core::{DepthImage, MaskImage, RgbImage};
use rslam_gpu::compute::bind_group_at;
use rslam_gpu::{FrameTextures, GpuContext};
use wgpu::util::DeviceExt;

use super::LensView;
use crate::image_f32::{linear_to_srgb, srgb_to_linear};
use crate::perturbation::{dispatch_grid, view};
use crate::PerturbError;

pub const SHADER: &str = "perturb/sensor/distortion.wgsl";

/// `DEPTH_AGREE` of `distortion.wgsl`.
const DEPTH_AGREE: f32 = 0.02;

/// The lens map on the GPU and the pass that samples through it, built once per lens and size.
pub struct LensPass {
    width: u32,
    height: u32,
    lookup: wgpu::Buffer,
    pipeline: wgpu::ComputePipeline,
    /// Resamples instance masks (`mask_main`).
    mask_pipeline: wgpu::ComputePipeline,
}

impl LensPass {
    /// The pass for frames of `width`×`height` (the size `view.map` was made for).
    pub fn new(
        ctx: &GpuContext,
        view: &LensView,
        (width, height): (u32, u32),
    ) -> Result<Self, PerturbError> {
        let lookup = ctx
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("lens map"),
                contents: bytemuck::cast_slice(&view.map),
                usage: wgpu::BufferUsages::STORAGE,
            });
        Ok(Self {
            width,
            height,
            lookup,
            pipeline: ctx.compute_pipeline(SHADER)?,
            mask_pipeline: ctx.compute_pipeline_entry(SHADER, "mask_main")?,
        })
    }

    /// Writes the view of `wide` (the wide pinhole render) through the lens into `frame`; its
    /// instance mask too where both have one (nearest-neighbour: ids never blend).
    pub fn record(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        wide: &FrameTextures,
        frame: &FrameTextures,
    ) {
        let (color, depth) = (view(&frame.color), view(&frame.depth));
        let bind_group = bind_group_at(
            ctx,
            &self.pipeline,
            SHADER,
            &[
                (0, wgpu::BindingResource::TextureView(wide.color_view())),
                (1, wgpu::BindingResource::TextureView(wide.depth_view())),
                (2, self.lookup.as_entire_binding()),
                (3, wgpu::BindingResource::TextureView(&color)),
                (4, wgpu::BindingResource::TextureView(&depth)),
            ],
        );
        dispatch_grid(
            encoder,
            &self.pipeline,
            &bind_group,
            SHADER,
            [self.width, self.height],
        );
        if let (Some(wide_mask), Some(mask)) = (wide.mask_view(), &frame.mask) {
            let mask = view(mask);
            let bind_group = bind_group_at(
                ctx,
                &self.mask_pipeline,
                SHADER,
                &[
                    (2, self.lookup.as_entire_binding()),
                    (5, wgpu::BindingResource::TextureView(wide_mask)),
                    (6, wgpu::BindingResource::TextureView(&mask)),
                ],
            );
            dispatch_grid(
                encoder,
                &self.mask_pipeline,
                &bind_group,
                SHADER,
                [self.width, self.height],
            );
        }
    }
}

/// CPU twin of `distortion.wgsl`: `color` and `depth` (the wide render) sampled through
/// `view.map` into a `width`×`height` frame.
pub fn twin(
    view: &LensView,
    (width, height): (u32, u32),
    color: &RgbImage,
    depth: &DepthImage,
) -> (RgbImage, DepthImage) {
    let last = [color.width as i64 - 1, color.height as i64 - 1];
    let texel = |x: i64, y: i64| (y * color.width as i64 + x) as usize;
    let light = |i: usize| -> [f32; 3] {
        std::array::from_fn(|c| srgb_to_linear(color.data[i * 3 + c] as f32 / 255.0))
    };
    let mix = |a: f32, b: f32, t: f32| a * (1.0 - t) + b * t;
    let mut out_color = RgbImage::new(width, height);
    let mut out_depth = DepthImage::new(width, height);
    for (i, &[x, y]) in view.map.iter().enumerate() {
        let (bx, by) = (x.floor(), y.floor());
        let (tx, ty) = (x - bx, y - by);
        let (x0, y0) = ((bx as i64).clamp(0, last[0]), (by as i64).clamp(0, last[1]));
        let (x1, y1) = (
            (bx as i64 + 1).clamp(0, last[0]),
            (by as i64 + 1).clamp(0, last[1]),
        );
        let corners = [texel(x0, y0), texel(x1, y0), texel(x0, y1), texel(x1, y1)];
        let [c00, c10, c01, c11] = corners.map(light);
        for c in 0..3 {
            let v = mix(mix(c00[c], c10[c], tx), mix(c01[c], c11[c], tx), ty);
            out_color.data[i * 3 + c] = (linear_to_srgb(v) * 255.0).round() as u8;
        }
        let [d00, d10, d01, d11] = corners.map(|t| depth.data[t]);
        let low = d00.min(d10).min(d01.min(d11));
        let high = d00.max(d10).max(d01.max(d11));
        out_depth.data[i] = if low > 0.0 && high - low <= DEPTH_AGREE * low {
            mix(mix(d00, d10, tx), mix(d01, d11, tx), ty)
        } else {
            let top = if tx >= 0.5 { d10 } else { d00 };
            let bottom = if tx >= 0.5 { d11 } else { d01 };
            if ty >= 0.5 {
                bottom
            } else {
                top
            }
        };
    }
    (out_color, out_depth)
}

/// CPU twin of `distortion.wgsl`'s `mask_main`: `mask` (the wide render's) sampled through
/// `view.map` at the nearest texel into a `width`×`height` mask.
pub fn mask_twin(view: &LensView, (width, height): (u32, u32), mask: &MaskImage) -> MaskImage {
    let last = [mask.width as i64 - 1, mask.height as i64 - 1];
    let mut out = MaskImage::new(width, height);
    for (id, &[x, y]) in out.data.iter_mut().zip(&view.map) {
        let nearest = |v: f32, last: i64| {
            let base = v.floor();
            (base as i64 + i64::from(v - base >= 0.5)).clamp(0, last) as u32
        };
        *id = mask.at(nearest(x, last[0]), nearest(y, last[1]));
    }
    out
}

#[cfg(test)]
mod tests {
    use rslam_core::{Distortion, Intrinsics};
    use rslam_gpu::FrameReadback;

    use super::*;
    use crate::testing;

    /// The test image, a depth with steps and smooth parts and a mask of id blocks, seen through
    /// both lens models, on the GPU against the twin.
    #[test]
    fn gpu_remap_matches_the_twin() {
        let ctx = testing::context();
        let camera = Intrinsics {
            width: 48,
            height: 36,
            fx: 30.0,
            fy: 31.0,
            cx: 23.5,
            cy: 17.5,
        };
        for text in [
            "radtan(-0.3,0.08,0.002,-0.001)",
            "equidistant(0.06,-0.02,0.004,-0.001)",
        ] {
            let lens = Distortion::parse(text).unwrap();
            let view = LensView::new(&camera, &lens).unwrap();
            let (ww, wh) = (view.wide.width, view.wide.height);
            let color = testing::test_image(ww, wh);
            let depth = testing::test_depth(ww, wh);
            let wide = FrameTextures::with_mask(ctx, ww, wh, true);
            wide.upload(ctx, &color, Some(&depth));
            let ids: Vec<u32> = (0..ww * wh)
                .map(|i| (i % ww) / 5 + (i / ww) / 4 * 7)
                .collect();
            ctx.queue.write_texture(
                wide.mask.as_ref().unwrap().as_image_copy(),
                bytemuck::cast_slice(&ids),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(ww * 4),
                    rows_per_image: Some(wh),
                },
                wide.size(),
            );
            let frame = FrameTextures::with_mask(ctx, camera.width, camera.height, true);
            let pass = LensPass::new(ctx, &view, (camera.width, camera.height)).unwrap();
            let readback = FrameReadback::with_mask(ctx, camera.width, camera.height, true, true);
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            pass.record(ctx, &mut encoder, &wide, &frame);
            readback.encode_copy(&mut encoder, &frame);
            let (got_color, got_depth, got_mask) = readback
                .read_with_mask(ctx, ctx.queue.submit([encoder.finish()]))
                .unwrap();
            let wide_mask = MaskImage {
                width: ww,
                height: wh,
                data: ids.iter().map(|&id| id as u16).collect(),
            };
            let want_mask = mask_twin(&view, (camera.width, camera.height), &wide_mask);
            assert_eq!(got_mask.unwrap(), want_mask, "lens mask {}", lens.model());
            let (want_color, want_depth) =
                twin(&view, (camera.width, camera.height), &color, &depth);
            testing::assert_close(
                &got_color,
                &want_color,
                1,
                &format!("lens-{}", lens.model()),
            );
            testing::assert_depth_close(
                &got_depth.unwrap(),
                &want_depth,
                1e-5,
                &format!("lens-depth-{}", lens.model()),
            );
        }
    }

    /// Depth across an edge never mixes the two surfaces; inside one surface it interpolates.
    #[test]
    fn depth_takes_the_nearest_surface_across_an_edge() {
        let view = LensView {
            wide: Intrinsics {
                width: 2,
                height: 2,
                fx: 1.0,
                fy: 1.0,
                cx: 0.5,
                cy: 0.5,
            },
            map: vec![[0.4, 0.2], [0.6, 0.2], [0.5, 0.5]],
        };
        let color = RgbImage::new(2, 2);
        let edge = DepthImage {
            width: 2,
            height: 2,
            data: vec![1.0, 3.0, 1.0, 3.0],
        };
        let (_, depth) = twin(&view, (3, 1), &color, &edge);
        assert_eq!(depth.data, vec![1.0, 3.0, 3.0]);
        let slope = DepthImage {
            width: 2,
            height: 2,
            data: vec![2.0, 2.02, 2.0, 2.02],
        };
        let (_, depth) = twin(&view, (3, 1), &color, &slope);
        assert!((depth.data[0] - 2.008).abs() < 1e-6, "{:?}", depth.data);
    }
}
