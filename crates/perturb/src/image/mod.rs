//! RGB corruptions: one file per corruption (parameters, GPU pass, CPU twin, tests), plus the
//! shared per-pixel pass and HSV conversion.

pub mod auto_exposure;
pub mod brightness;
pub mod color_pass;
pub mod contrast;
pub mod defocus_blur;
pub mod elastic_transform;
pub mod fog;
pub mod frost;
pub mod gaussian_blur;
pub mod gaussian_noise;
pub mod glass_blur;
pub mod hsv;
pub mod impulse_noise;
pub mod jpeg_compression;
pub mod kernels;
pub mod motion_blur;
pub mod pixelate;
pub mod saturate;
pub mod separable;
pub mod shot_noise;
pub mod snow;
pub mod spatter;
pub mod speckle_noise;
pub mod textures;
pub mod vignetting;
pub mod zoom_blur;
