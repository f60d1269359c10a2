//! How well a rendered depth image agrees with the ray-cast oracle, pixel by pixel.

use rslam_core::DepthImage;

/// Largest second difference of inverse depth, relative to the inverse depth, that a smooth
/// surface shows; inverse depth is linear in pixel coordinates across a plane, so this only
/// tolerates float noise and gentle curvature, and flags even millimetre steps (decals, rugs).
const MAX_SMOOTH_CURVATURE: f32 = 2e-4;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct DepthAgreement {
    /// Pixels where both hit a surface, away from silhouettes.
    pub compared: usize,
    /// Largest |rendered − oracle| / oracle over `compared`.
    pub max_relative_error: f32,
    /// Pixels away from silhouettes where one hit and the other missed.
    pub mask_mismatches: usize,
    /// Pixels on a silhouette in either image (excluded from the two numbers above).
    pub silhouette_pixels: usize,
}

/// A pixel is on a silhouette when a 3×3 neighbour of it misses while it hits
/// (or the reverse), or when inverse depth bends through it more than a smooth surface does.
pub(crate) fn on_silhouette(oracle: &DepthImage, x: u32, y: u32) -> bool {
    let (w, h) = (oracle.width as i32, oracle.height as i32);
    let at = |x: i32, y: i32| oracle.at(x.clamp(0, w - 1) as u32, y.clamp(0, h - 1) as u32);
    let (x, y) = (x as i32, y as i32);
    let z = at(x, y);
    for dy in -1..=1 {
        for dx in -1..=1 {
            if (at(x + dx, y + dy) > 0.0) != (z > 0.0) {
                return true;
            }
        }
    }
    if z <= 0.0 {
        return false;
    }
    let inv = 1.0 / z;
    let bend = |a: f32, b: f32| (1.0 / a - 2.0 * inv + 1.0 / b).abs() > MAX_SMOOTH_CURVATURE * inv;
    bend(at(x - 1, y), at(x + 1, y)) || bend(at(x, y - 1), at(x, y + 1))
}

pub fn depth_agreement(rendered: &DepthImage, oracle: &DepthImage) -> DepthAgreement {
    assert_eq!(
        (rendered.width, rendered.height),
        (oracle.width, oracle.height),
        "depth images of different sizes"
    );
    let mut a = DepthAgreement::default();
    for y in 0..oracle.height {
        for x in 0..oracle.width {
            if on_silhouette(oracle, x, y) || on_silhouette(rendered, x, y) {
                a.silhouette_pixels += 1;
                continue;
            }
            let (r, o) = (rendered.at(x, y), oracle.at(x, y));
            match (r > 0.0, o > 0.0) {
                (true, true) => {
                    a.compared += 1;
                    a.max_relative_error = a.max_relative_error.max((r - o).abs() / o);
                }
                (false, false) => {}
                _ => a.mask_mismatches += 1,
            }
        }
    }
    a
}
