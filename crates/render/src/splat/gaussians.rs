//! A capture as the GPU takes it, computed once at upload: per Gaussian its mean and activated
//! opacity, and its 3D covariance R S Sᵀ Rᵀ (from the file's log scales and quaternion) as two
//! rows of three; the spherical-harmonic coefficients as they are.

use glam::{Mat3, Quat, Vec3};
use rslam_core::splat_io::SplatCloud;

/// Three arrays of one `vec4<f32>` per Gaussian (shaders/render/splat/project.wgsl).
pub(super) struct PackedGaussians {
    pub mean_opacity: Vec<[f32; 4]>,
    /// xx, xy, xz
    pub cov_a: Vec<[f32; 4]>,
    /// yy, yz, zz
    pub cov_b: Vec<[f32; 4]>,
}

pub(super) fn pack(cloud: &SplatCloud) -> PackedGaussians {
    let mut packed = PackedGaussians {
        mean_opacity: Vec::with_capacity(cloud.len()),
        cov_a: Vec::with_capacity(cloud.len()),
        cov_b: Vec::with_capacity(cloud.len()),
    };
    for i in 0..cloud.len() {
        let [w, x, y, z] = cloud.rotations[i];
        let rotation = Mat3::from_quat(Quat::from_xyzw(x, y, z, w).normalize());
        let scale = Mat3::from_diagonal(Vec3::from(cloud.log_scales[i]).exp());
        let m = rotation * scale;
        let cov = m * m.transpose();
        let [mx, my, mz] = cloud.means[i];
        let opacity = 1.0 / (1.0 + (-cloud.opacity_logits[i]).exp());
        packed.mean_opacity.push([mx, my, mz, opacity]);
        packed
            .cov_a
            .push([cov.x_axis.x, cov.y_axis.x, cov.z_axis.x, 0.0]);
        packed
            .cov_b
            .push([cov.y_axis.y, cov.z_axis.y, cov.z_axis.z, 0.0]);
    }
    packed
}

/// The coefficients as one f32 array: per Gaussian its coefficients, each as r, g, b.
pub(super) fn sh_values(cloud: &SplatCloud) -> Vec<f32> {
    cloud.sh.iter().flatten().copied().collect()
}
