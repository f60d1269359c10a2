//! The splat passes' camera uniform (shaders/render/splat/types.wgsl).

use rslam_core::{Intrinsics, Pose};

use super::SplatSettings;

pub(super) const TILE: u32 = 16;

/// How far past the frustum the projection's Jacobian is still taken at the true mean, as a
/// share of the half-width (the reference implementation's 1.3× the field of view).
const JACOBIAN_MARGIN: f64 = 0.3;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub(super) struct SplatCamera {
    camera_from_world: [[f32; 4]; 4],
    position: [f32; 3],
    count: u32,
    focal: [f32; 2],
    principal: [f32; 2],
    size: [u32; 2],
    tiles: [u32; 2],
    slope_min: [f32; 2],
    slope_max: [f32; 2],
    sh_degree: u32,
    depth_mode: u32,
    min_opacity: f32,
    pad: u32,
}

pub(super) fn tiles(k: &Intrinsics) -> [u32; 2] {
    [k.width.div_ceil(TILE), k.height.div_ceil(TILE)]
}

impl SplatCamera {
    pub fn new(
        world_from_camera: &Pose,
        k: &Intrinsics,
        count: u32,
        sh_degree: u32,
        settings: &SplatSettings,
    ) -> Self {
        let camera_from_world = world_from_camera.inverse().to_mat4().as_mat4();
        let position = world_from_camera.to_mat4().w_axis.truncate().as_vec3();
        let (w, h) = (k.width as f64, k.height as f64);
        // The frustum's x/z range is [-cx, w-cx]/fx around its centre; widen each side by the
        // margin of half the width.
        let slope = |size: f64, c: f64, f: f64, low: bool| {
            let margin = JACOBIAN_MARGIN * 0.5 * size / f;
            if low {
                (-0.5 - c) / f - margin
            } else {
                (size - 0.5 - c) / f + margin
            }
        };
        Self {
            camera_from_world: camera_from_world.to_cols_array_2d(),
            position: position.to_array(),
            count,
            focal: [k.fx as f32, k.fy as f32],
            principal: [k.cx as f32, k.cy as f32],
            size: [k.width, k.height],
            tiles: tiles(k),
            slope_min: [
                slope(w, k.cx, k.fx, true) as f32,
                slope(h, k.cy, k.fy, true) as f32,
            ],
            slope_max: [
                slope(w, k.cx, k.fx, false) as f32,
                slope(h, k.cy, k.fy, false) as f32,
            ],
            sh_degree,
            depth_mode: match settings.depth {
                super::SplatDepth::Expected => 0,
                super::SplatDepth::Median => 1,
            },
            min_opacity: settings.min_opacity,
            pad: 0,
        }
    }
}
