//! A capture as the GPU takes it: per Gaussian its mean, activated opacity and 3D covariance
//! (R S Sᵀ Rᵀ from the file's log scales and quaternion), computed once at upload; the
//! spherical-harmonic coefficients as they are.

use glam::{Mat3, Quat, Vec3};
use rslam_core::splat_io::SplatCloud;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub(super) struct GpuGaussian {
    mean: [f32; 3],
    opacity: f32,
    /// xx, xy, xz
    cov_a: [f32; 3],
    pad0: f32,
    /// yy, yz, zz
    cov_b: [f32; 3],
    pad1: f32,
}

pub(super) fn pack(cloud: &SplatCloud) -> Vec<GpuGaussian> {
    (0..cloud.len())
        .map(|i| {
            let [w, x, y, z] = cloud.rotations[i];
            let rotation = Mat3::from_quat(Quat::from_xyzw(x, y, z, w).normalize());
            let scale = Mat3::from_diagonal(Vec3::from(cloud.log_scales[i]).exp());
            let m = rotation * scale;
            let cov = m * m.transpose();
            GpuGaussian {
                mean: cloud.means[i],
                opacity: 1.0 / (1.0 + (-cloud.opacity_logits[i]).exp()),
                cov_a: [cov.x_axis.x, cov.y_axis.x, cov.z_axis.x],
                cov_b: [cov.y_axis.y, cov.z_axis.y, cov.z_axis.z],
                pad0: 0.0,
                pad1: 0.0,
            }
        })
        .collect()
}

/// The coefficients as one f32 array: per Gaussian its coefficients, each as r, g, b.
pub(super) fn sh_values(cloud: &SplatCloud) -> Vec<f32> {
    cloud.sh.iter().flatten().copied().collect()
}
