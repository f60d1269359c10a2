//! How well a rendered colour image agrees with the ray-cast oracle's, pixel by pixel, away from
//! edges: silhouettes and depth steps of either depth image (as in [`super::depth_agreement`])
//! and the surface edges the oracle reports (another layer, another plane).

use rslam_core::{DepthImage, RgbImage};

use super::depth_agreement::on_silhouette;
use crate::raycast::RayCastFrame;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct ColorAgreement {
    /// Pixels away from edges where either image sees a surface.
    pub compared: usize,
    /// Pixels left out as edges.
    pub edge_pixels: usize,
    /// Mean |rendered − oracle| per channel over `compared`, in 8-bit levels.
    pub mean_abs_error: [f64; 3],
    /// Pixels of `compared` where some channel is more than `level_tolerance` levels off.
    pub off_pixels: usize,
    pub level_tolerance: u8,
    /// Largest |rendered − oracle| over `compared` and channels.
    pub max_abs_error: u8,
}

impl ColorAgreement {
    /// `off_pixels / compared` (0 when nothing was compared).
    pub fn off_fraction(&self) -> f64 {
        self.off_pixels as f64 / self.compared.max(1) as f64
    }

    pub fn worst_mean_abs_error(&self) -> f64 {
        self.mean_abs_error.into_iter().fold(0.0, f64::max)
    }
}

/// Per-pixel edge mask: on a silhouette of either depth image, or flagged in `surface_edges`
/// (from [`crate::raycast::RayCaster::surface_edges`]).
pub fn edge_mask(
    rendered_depth: &DepthImage,
    oracle: &RayCastFrame,
    surface_edges: &[bool],
) -> Vec<bool> {
    let (w, h) = (oracle.depth.width, oracle.depth.height);
    assert_eq!(
        (
            rendered_depth.width,
            rendered_depth.height,
            surface_edges.len()
        ),
        (w, h, (w * h) as usize),
        "images of different sizes"
    );
    (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            surface_edges[i as usize]
                || on_silhouette(&oracle.depth, x, y)
                || on_silhouette(rendered_depth, x, y)
        })
        .collect()
}

/// Compares `rendered` with `oracle.rgb` where `edges` is false and either depth image has a hit.
pub fn color_agreement(
    rendered: &RgbImage,
    rendered_depth: &DepthImage,
    oracle: &RayCastFrame,
    edges: &[bool],
    level_tolerance: u8,
) -> ColorAgreement {
    assert_eq!(
        (rendered.width, rendered.height, edges.len()),
        (
            oracle.rgb.width,
            oracle.rgb.height,
            oracle.rgb.data.len() / 3
        ),
        "images of different sizes"
    );
    let mut a = ColorAgreement {
        level_tolerance,
        ..Default::default()
    };
    let mut sums = [0u64; 3];
    for (i, &edge) in edges.iter().enumerate() {
        if edge {
            a.edge_pixels += 1;
            continue;
        }
        if rendered_depth.data[i] <= 0.0 && oracle.depth.data[i] <= 0.0 {
            continue;
        }
        a.compared += 1;
        let mut worst = 0;
        for (c, sum) in sums.iter_mut().enumerate() {
            let d = rendered.data[3 * i + c].abs_diff(oracle.rgb.data[3 * i + c]);
            *sum += d as u64;
            worst = worst.max(d);
        }
        a.max_abs_error = a.max_abs_error.max(worst);
        if worst > level_tolerance {
            a.off_pixels += 1;
        }
    }
    a.mean_abs_error = sums.map(|s| s as f64 / a.compared.max(1) as f64);
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(rgb: Vec<u8>, depth: Vec<f32>, width: u32) -> RayCastFrame {
        let height = depth.len() as u32 / width;
        RayCastFrame {
            rgb: RgbImage {
                width,
                height,
                data: rgb,
            },
            triangles: depth.iter().map(|&z| (z > 0.0).then_some(0)).collect(),
            depth: DepthImage {
                width,
                height,
                data: depth,
            },
        }
    }

    /// Four hit pixels, one with no surface: the mean is over the hits, the tolerance is strict.
    #[test]
    fn counts_means_and_pixels_beyond_the_tolerance() {
        let oracle = frame(
            vec![10, 20, 30, 10, 20, 30, 10, 20, 30, 10, 20, 30, 0, 0, 0],
            vec![1.0, 1.0, 1.0, 1.0, 0.0],
            5,
        );
        let rendered = RgbImage {
            width: 5,
            height: 1,
            data: vec![10, 20, 30, 12, 20, 30, 10, 17, 30, 10, 20, 38, 0, 0, 0],
        };
        let a = color_agreement(&rendered, &oracle.depth, &oracle, &[false; 5], 2);
        assert_eq!(a.compared, 4);
        assert_eq!(a.mean_abs_error, [0.5, 0.75, 2.0]);
        assert_eq!(a.off_pixels, 2, "3 and 8 levels are beyond 2, 2 is not");
        assert_eq!(a.max_abs_error, 8);
        assert_eq!(a.off_fraction(), 0.5);
        let skip_last_hit = [false, false, false, true, false];
        let a = color_agreement(&rendered, &oracle.depth, &oracle, &skip_last_hit, 2);
        assert_eq!((a.compared, a.edge_pixels, a.off_pixels), (3, 1, 1));
    }

    /// A hit/miss boundary and a depth step are edges; the middle of a flat run is not.
    #[test]
    fn edge_mask_marks_silhouettes_and_steps_of_either_depth() {
        let oracle = frame(vec![0; 24], vec![2.0, 2.0, 2.0, 2.0, 2.0, 2.0, 0.0, 0.0], 8);
        let no_surface_edges = [false; 8];
        let same = edge_mask(&oracle.depth, &oracle, &no_surface_edges);
        assert_eq!(same, [false, false, false, false, false, true, true, false]);
        let mut stepped = oracle.depth.clone();
        stepped.data[2] = 1.0;
        let mask = edge_mask(&stepped, &oracle, &no_surface_edges);
        assert!(mask[1] && mask[2] && mask[3], "{mask:?}");
        assert!(!mask[0], "{mask:?}");
    }
}
