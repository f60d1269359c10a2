//! Every perturbation that runs on frames: one line each. Feeds `rslam list`, the spec parser and
//! the viewer's menus.

use crate::perturbation::CatalogueEntry;
use crate::{depth, image};

pub static CATALOGUE: &[CatalogueEntry] = &[
    image::gaussian_noise::ENTRY,
    image::shot_noise::ENTRY,
    image::impulse_noise::ENTRY,
    image::speckle_noise::ENTRY,
    image::brightness::ENTRY,
    image::contrast::ENTRY,
    image::pixelate::ENTRY,
    image::saturate::ENTRY,
    image::gaussian_blur::ENTRY,
    image::motion_blur::ENTRY,
    image::zoom_blur::ENTRY,
    image::defocus_blur::ENTRY,
    image::glass_blur::ENTRY,
    image::elastic_transform::ENTRY,
    image::jpeg_compression::ENTRY,
    image::fog::ENTRY,
    image::frost::ENTRY,
    image::snow::ENTRY,
    image::spatter::ENTRY,
    image::vignetting::ENTRY,
    image::auto_exposure::ENTRY,
    depth::depth_noise::ENTRY,
    depth::depth_edge_erosion::ENTRY,
    depth::depth_missing::ENTRY,
    depth::depth_range::ENTRY,
    depth::depth_noise_kinect::ENTRY,
    depth::depth_sensor::ENTRY,
];

/// The entry named `name`, if any.
pub fn find(name: &str) -> Option<&'static CatalogueEntry> {
    CATALOGUE.iter().find(|e| e.name == name)
}

/// Every name, comma-separated, for error messages.
pub fn names() -> String {
    CATALOGUE
        .iter()
        .map(|e| e.name)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_have_a_shader() {
        let shaders: Vec<&str> = rslam_gpu::shader::paths().collect();
        for (i, entry) in CATALOGUE.iter().enumerate() {
            assert!(
                CATALOGUE[..i].iter().all(|e| e.name != entry.name),
                "{} listed twice",
                entry.name
            );
            let dir = match entry.group {
                crate::Group::Image => "perturb/image/",
                crate::Group::Depth => "perturb/depth/",
            };
            let prefix = format!("{dir}{}", entry.name);
            assert!(
                shaders.iter().any(|s| s.starts_with(&prefix)),
                "{}: no shader {prefix}*.wgsl",
                entry.name
            );
            assert!(!entry.description.is_empty());
            for s in 1..=5 {
                assert!(!(entry.parameters)(s).is_empty());
            }
        }
    }
}
