//! Depth for the eye: metric z-depth turned into Turbo colours between a near and a far distance,
//! on the GPU for display (`shaders/display/depth_colormap.wgsl`) and on the CPU for the legend
//! and as the shader's test oracle.

use rslam_gpu::{wgpu, GpuContext};

use crate::PipelineError;

const SHADER: &str = "display/depth_colormap.wgsl";

/// Workgroup edge of the shader.
const WORKGROUP: u32 = 8;

/// Which distances the colours span: `near` gets the first colour, `far` and beyond the last.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthRange {
    pub near: f32,
    pub far: f32,
}

impl Default for DepthRange {
    /// Indoor RGB-D: the working range of a structured-light sensor.
    fn default() -> Self {
        Self {
            near: 0.0,
            far: 6.0,
        }
    }
}

/// Turbo polynomial coefficients (Ruofei Du, Google 2019, "Polynomial approximation of Turbo"):
/// per channel, the weights of 1, t, t², t³ and of t⁴, t⁵.
const RED: ([f32; 4], [f32; 2]) = (
    [0.135_721_38, 4.615_392_6, -42.660_324, 132.131_08],
    [-152.942_4, 59.286_38],
);
const GREEN: ([f32; 4], [f32; 2]) = (
    [0.091_402_61, 2.194_188_4, 4.842_966_6, -14.185_033],
    [4.277_298_6, 2.829_566],
);
const BLUE: ([f32; 4], [f32; 2]) = (
    [0.106_673_3, 12.641_946, -60.582_05, 110.362_77],
    [-89.903_11, 27.348_25],
);

/// Turbo at `t` in [0, 1] (clamped), sRGB-encoded channels in [0, 1]; mirrors the shader's `turbo`.
pub fn turbo(t: f32) -> [f32; 3] {
    let t = t.clamp(0.0, 1.0);
    let v4 = [1.0, t, t * t, t * t * t];
    let v2 = [v4[2] * v4[2], v4[3] * v4[2]];
    let channel = |(w4, w2): ([f32; 4], [f32; 2])| {
        let sum = v4[0] * w4[0] + v4[1] * w4[1] + v4[2] * w4[2] + v4[3] * w4[3];
        (sum + v2[0] * w2[0] + v2[1] * w2[1]).clamp(0.0, 1.0)
    };
    [channel(RED), channel(GREEN), channel(BLUE)]
}

/// The 8-bit colour depth `z` (metres) gets: what the shader writes; black where there is no
/// depth (0).
pub fn depth_color(z: f32, range: DepthRange) -> [u8; 3] {
    if z.is_nan() || z <= 0.0 {
        return [0, 0, 0];
    }
    let span = (range.far - range.near).max(1e-6);
    turbo((z - range.near) / span).map(|c| (c * 255.0).round() as u8)
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Params {
    range: [f32; 4],
}

/// The colour-mapping pass, built once; writes an `Rgba8Unorm` storage texture of the depth's size.
pub struct DepthColormap {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
}

impl DepthColormap {
    pub fn new(ctx: &GpuContext) -> Result<Self, PipelineError> {
        Ok(Self {
            pipeline: ctx.compute_pipeline(SHADER)?,
            params: ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("depth colormap params"),
                size: std::mem::size_of::<Params>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
        })
    }

    /// Records the colouring of each `(depth, colors)` pair at `range`. The range is written
    /// now and holds for the whole submission.
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        pairs: &[(&wgpu::Texture, &wgpu::Texture)],
        range: DepthRange,
    ) {
        let params = Params {
            range: [range.near, range.far, 0.0, 0.0],
        };
        ctx.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        for (depth, colors) in pairs {
            let view = |t: &wgpu::Texture| t.create_view(&Default::default());
            let (depth_view, colors_view) = (view(depth), view(colors));
            let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("depth colormap"),
                layout: &self.pipeline.get_bind_group_layout(0),
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(&depth_view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(&colors_view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: self.params.as_entire_binding(),
                    },
                ],
            });
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(
                depth.width().div_ceil(WORKGROUP),
                depth.height().div_ceil(WORKGROUP),
                1,
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turbo_runs_blue_green_red() {
        let [r, g, b] = turbo(0.1);
        assert!(b > 0.8 && b > g && g > r, "near is blue: {:?}", turbo(0.1));
        let [_, g_mid, b_mid] = turbo(0.5);
        assert!(
            g_mid > 0.8 && b_mid < 0.5,
            "middle is green: {:?}",
            turbo(0.5)
        );
        let [r, g, b] = turbo(0.9);
        assert!(r > 0.6 && r > g && g > b, "far is red: {:?}", turbo(0.9));
        assert_eq!(turbo(-1.0), turbo(0.0), "clamped below");
        assert_eq!(turbo(2.0), turbo(1.0), "clamped above");
    }

    #[test]
    fn no_depth_is_black_and_far_is_clamped() {
        let range = DepthRange {
            near: 0.5,
            far: 4.0,
        };
        assert_eq!(depth_color(0.0, range), [0, 0, 0]);
        assert_eq!(depth_color(f32::NAN, range), [0, 0, 0]);
        assert_eq!(depth_color(9.0, range), depth_color(4.0, range));
        assert_ne!(depth_color(1.0, range), depth_color(3.0, range));
    }
}
