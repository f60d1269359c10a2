use glam::{DMat4, Mat4};
use rslam_core::{Intrinsics, Pose};

/// Near clip plane in metres; there is no far plane (reversed, infinite z).
pub const NEAR: f64 = 0.01;

/// The camera uniform: `camera_from_world` and the pinhole projection.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CameraUniform {
    camera_from_world: [[f32; 4]; 4],
    clip_from_camera: [[f32; 4]; 4],
}

impl CameraUniform {
    pub fn new(world_from_camera: &Pose, k: &Intrinsics) -> Self {
        let camera_from_world = world_from_camera.inverse().to_mat4();
        Self {
            camera_from_world: camera_from_world.as_mat4().to_cols_array_2d(),
            clip_from_camera: clip_from_camera(k).to_cols_array_2d(),
        }
    }
}

/// OpenCV pinhole → wgpu clip space. OpenCV pixel centres sit at integer coordinates, the
/// framebuffer's at +0.5, hence `cx + 0.5`; y flips because clip-space y points up. Depth is
/// reversed and infinite (z_ndc = NEAR / z), which keeps float precision uniform with distance.
pub fn clip_from_camera(k: &Intrinsics) -> Mat4 {
    let (w, h) = (k.width as f64, k.height as f64);
    let rows = [
        [2.0 * k.fx / w, 0.0, 2.0 * (k.cx + 0.5) / w - 1.0, 0.0],
        [0.0, -2.0 * k.fy / h, 1.0 - 2.0 * (k.cy + 0.5) / h, 0.0],
        [0.0, 0.0, 0.0, NEAR],
        [0.0, 0.0, 1.0, 0.0],
    ];
    let m = DMat4::from_cols_array_2d(&std::array::from_fn(|c| {
        std::array::from_fn(|r| rows[r][c])
    }));
    m.as_mat4()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    /// A camera-space point must land on the framebuffer pixel that OpenCV's projection gives,
    /// shifted by the half-pixel framebuffer convention.
    #[test]
    fn projection_matches_opencv_pixel_convention() {
        let k = Intrinsics::REPLICA;
        let p = Vec4::new(0.3, -0.2, 2.0, 1.0);
        let clip = clip_from_camera(&k) * p;
        let ndc = clip.truncate() / clip.w;
        let fb_x = (ndc.x + 1.0) * 0.5 * k.width as f32;
        let fb_y = (1.0 - ndc.y) * 0.5 * k.height as f32;
        let u = k.fx as f32 * 0.3 / 2.0 + k.cx as f32;
        let v = k.fy as f32 * -0.2 / 2.0 + k.cy as f32;
        assert!((fb_x - (u + 0.5)).abs() < 1e-3, "{fb_x} vs {u}");
        assert!((fb_y - (v + 0.5)).abs() < 1e-3, "{fb_y} vs {v}");
        assert!((0.0..=1.0).contains(&ndc.z));
    }
}
