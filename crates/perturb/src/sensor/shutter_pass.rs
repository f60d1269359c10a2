//! The GPU side of a shutter (`shutter.wgsl`): sub-frames summed in linear light over their rows
//! into a per-pixel float buffer, then encoded to sRGB into the frame once. Its CPU twin is
//! [`twin`].

use std::ops::Range;

use bytemuck::{Pod, Zeroable};
use rslam_core::RgbImage;
use rslam_gpu::compute::bind_group_at;
use rslam_gpu::{FrameTextures, GpuContext};

use crate::image_f32::{linear_to_srgb, srgb_to_linear};
use crate::perturbation::{dispatch_grid, view};
use crate::uniform_layout::{rust_layout, RustLayout, UniformLayout};
use crate::PerturbError;

pub const SHADER: &str = "perturb/sensor/shutter.wgsl";

/// WGSL `struct Params` of `shutter.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct Params {
    /// First row, row count, 1 = start the sum, unused.
    rows: [u32; 4],
    /// Weight, unused ×3.
    weight: [f32; 4],
}

impl Params {
    const LAYOUT: RustLayout = rust_layout!(Params { rows, weight });
}

pub const UNIFORMS: UniformLayout = UniformLayout {
    rust: Params::LAYOUT,
    wgsl: "Params",
    shader: SHADER,
};

/// The running sum of one frame's sub-frames, built once for a frame size.
pub struct ShutterPass {
    width: u32,
    height: u32,
    sum: wgpu::Buffer,
    params: wgpu::Buffer,
    accumulate: wgpu::ComputePipeline,
    resolve: wgpu::ComputePipeline,
}

impl ShutterPass {
    pub fn new(ctx: &GpuContext, width: u32, height: u32) -> Result<Self, PerturbError> {
        let sum = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("shutter sum"),
            size: width as u64 * height as u64 * 16,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let params = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("shutter params"),
            size: std::mem::size_of::<Params>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Ok(Self {
            width,
            height,
            sum,
            params,
            accumulate: ctx.compute_pipeline_entry(SHADER, "accumulate")?,
            resolve: ctx.compute_pipeline_entry(SHADER, "resolve")?,
        })
    }

    /// Adds `weight` × the linear light of `subframe`'s rows `rows` to the sum (or starts it
    /// there). Its parameters are written now: one `add` per queue submission.
    pub fn add(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        subframe: &FrameTextures,
        rows: Range<u32>,
        weight: f32,
        starts_sum: bool,
    ) {
        let rows = rows.start.min(self.height)..rows.end.min(self.height);
        let params = Params {
            rows: [rows.start, rows.len() as u32, starts_sum as u32, 0],
            weight: [weight, 0.0, 0.0, 0.0],
        };
        ctx.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let bind_group = bind_group_at(
            ctx,
            &self.accumulate,
            SHADER,
            &[
                (0, wgpu::BindingResource::TextureView(subframe.color_view())),
                (1, self.sum.as_entire_binding()),
                (2, self.params.as_entire_binding()),
            ],
        );
        dispatch_grid(
            encoder,
            &self.accumulate,
            &bind_group,
            SHADER,
            [self.width, rows.len() as u32],
        );
    }

    /// Writes the sum, encoded to sRGB, into `frame.color`.
    pub fn resolve(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
    ) {
        let output = view(&frame.color);
        let bind_group = bind_group_at(
            ctx,
            &self.resolve,
            SHADER,
            &[
                (1, self.sum.as_entire_binding()),
                (3, wgpu::BindingResource::TextureView(&output)),
            ],
        );
        dispatch_grid(
            encoder,
            &self.resolve,
            &bind_group,
            SHADER,
            [self.width, self.height],
        );
    }
}

/// One weighted sub-frame for [`twin`].
pub struct WeightedRows<'a> {
    pub image: &'a RgbImage,
    pub rows: Range<u32>,
    pub weight: f32,
}

/// CPU twin of `shutter.wgsl`: the weighted linear-light sum of every part over its rows
/// (rows no part covers are black), encoded to sRGB and rounded to 8 bits as the store does.
pub fn twin(width: u32, height: u32, parts: &[WeightedRows]) -> RgbImage {
    let mut sum = vec![[0.0f32; 3]; (width * height) as usize];
    for part in parts {
        for y in part.rows.clone() {
            for x in 0..width {
                let i = (y * width + x) as usize;
                for (total, &v) in sum[i].iter_mut().zip(&part.image.data[i * 3..i * 3 + 3]) {
                    *total += srgb_to_linear(v as f32 / 255.0) * part.weight;
                }
            }
        }
    }
    RgbImage {
        width,
        height,
        data: sum
            .iter()
            .flat_map(|p| p.map(|c| (linear_to_srgb(c) * 255.0).round() as u8))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use rslam_gpu::FrameReadback;

    use super::*;
    use crate::testing;

    /// Three different images summed over two bands of rows with unequal weights, one add per
    /// submission as the scene source does, against the twin.
    #[test]
    fn gpu_sum_matches_the_twin() {
        let ctx = testing::context();
        let (w, h) = (40, 30);
        let images: Vec<RgbImage> = (0..3)
            .map(|i| {
                let mut image = testing::test_image(w, h);
                image.data.rotate_left(i * 97);
                image
            })
            .collect();
        let pass = ShutterPass::new(ctx, w, h).unwrap();
        let subframe = FrameTextures::new(ctx, w, h);
        let frame = FrameTextures::new(ctx, w, h);
        let weights = [0.5f32, 0.3, 0.2];
        let mut parts = Vec::new();
        for rows in [0..11, 11..h] {
            for (i, image) in images.iter().enumerate() {
                subframe.upload(ctx, image, None);
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                pass.add(
                    ctx,
                    &mut encoder,
                    &subframe,
                    rows.clone(),
                    weights[i],
                    i == 0,
                );
                ctx.queue.submit([encoder.finish()]);
                parts.push(WeightedRows {
                    image,
                    rows: rows.clone(),
                    weight: weights[i],
                });
            }
        }
        let readback = FrameReadback::new(ctx, w, h, false);
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        pass.resolve(ctx, &mut encoder, &frame);
        readback.encode_copy(&mut encoder, &frame);
        let (color, _) = readback
            .read(ctx, ctx.queue.submit([encoder.finish()]))
            .unwrap();
        testing::assert_close(&color, &twin(w, h, &parts), 1, "shutter-sum");
    }

    /// Averaging copies of one image gives that image back: the sRGB round trip is exact to
    /// the level.
    #[test]
    fn averaging_one_image_gives_it_back() {
        let image = testing::test_image(16, 12);
        let parts: Vec<WeightedRows> = (0..5)
            .map(|_| WeightedRows {
                image: &image,
                rows: 0..12,
                weight: 0.2,
            })
            .collect();
        testing::assert_close(&twin(16, 12, &parts), &image, 0, "shutter-identity");
    }
}
