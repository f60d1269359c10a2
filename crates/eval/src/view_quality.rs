//! How close a map's rendered view is to the clean frame at the same pose, as SplaTAM and the
//! Robust-SLAM paper report it: PSNR and SSIM of colour, L1 of depth. No learned metric (LPIPS
//! needs downloaded weights).
//!
//! - PSNR = 10·log10(255² / MSE) over every pixel and channel of 8-bit colour; infinite for
//!   identical images.
//! - SSIM (Wang et al. 2004): an 11×11 Gaussian window of σ = 1.5, C1 = (0.01·255)²,
//!   C2 = (0.03·255)², on each colour channel, averaged over the window positions that lie
//!   wholly inside the image and over the channels.
//! - Depth L1 = mean |rendered − reference| over the pixels where the reference has a
//!   measurement (depth > 0), rendered holes counting as 0 m, as SplaTAM's evaluation does.

use rslam_core::{DepthImage, RgbImage};

const WINDOW: usize = 11;
const SIGMA: f64 = 1.5;
const C1: f64 = (0.01 * 255.0) * (0.01 * 255.0);
const C2: f64 = (0.03 * 255.0) * (0.03 * 255.0);

/// PSNR of `a` against `b` (same size), dB.
pub fn psnr_db(a: &RgbImage, b: &RgbImage) -> f64 {
    let squared: f64 = a
        .data
        .iter()
        .zip(&b.data)
        .map(|(&x, &y)| (x as f64 - y as f64).powi(2))
        .sum();
    let mse = squared / a.data.len() as f64;
    10.0 * (255.0 * 255.0 / mse).log10()
}

/// SSIM of `a` against `b` (same size); `None` for an image smaller than the window.
pub fn ssim(a: &RgbImage, b: &RgbImage) -> Option<f64> {
    let (w, h) = (a.width as usize, a.height as usize);
    if w < WINDOW || h < WINDOW {
        return None;
    }
    let weights = gaussian_weights();
    let channel = |image: &RgbImage, c: usize| -> Vec<f64> {
        image
            .data
            .iter()
            .skip(c)
            .step_by(3)
            .map(|&v| v as f64)
            .collect()
    };
    let mut total = 0.0;
    for c in 0..3 {
        let (x, y) = (channel(a, c), channel(b, c));
        let product = |p: &[f64], q: &[f64]| -> Vec<f64> {
            p.iter().zip(q).map(|(u, v)| u * v).collect::<Vec<f64>>()
        };
        let blur = |plane: &[f64]| blur_valid(plane, w, h, &weights);
        let (mx, my) = (blur(&x), blur(&y));
        let (xx, yy, xy) = (
            blur(&product(&x, &x)),
            blur(&product(&y, &y)),
            blur(&product(&x, &y)),
        );
        let sum: f64 = (0..mx.len())
            .map(|i| {
                let (vx, vy) = (xx[i] - mx[i] * mx[i], yy[i] - my[i] * my[i]);
                let cov = xy[i] - mx[i] * my[i];
                ((2.0 * mx[i] * my[i] + C1) * (2.0 * cov + C2))
                    / ((mx[i] * mx[i] + my[i] * my[i] + C1) * (vx + vy + C2))
            })
            .sum();
        total += sum / mx.len() as f64;
    }
    Some(total / 3.0)
}

/// Mean |rendered − reference| over the reference's measured pixels, metres; `None` when the
/// reference has none.
pub fn depth_l1_m(rendered: &DepthImage, reference: &DepthImage) -> Option<f64> {
    let (sum, count) = rendered
        .data
        .iter()
        .zip(&reference.data)
        .filter(|(_, &r)| r > 0.0)
        .fold((0.0, 0usize), |(sum, n), (&d, &r)| {
            (sum + (d as f64 - r as f64).abs(), n + 1)
        });
    (count > 0).then(|| sum / count as f64)
}

fn gaussian_weights() -> [f64; WINDOW] {
    let centre = (WINDOW / 2) as f64;
    let mut weights = [0.0; WINDOW];
    for (i, w) in weights.iter_mut().enumerate() {
        *w = (-((i as f64 - centre).powi(2)) / (2.0 * SIGMA * SIGMA)).exp();
    }
    let sum: f64 = weights.iter().sum();
    weights.map(|w| w / sum)
}

/// The separable Gaussian filter at every window position inside the image:
/// (w − 10) × (h − 10) values, row-major.
fn blur_valid(plane: &[f64], w: usize, h: usize, weights: &[f64; WINDOW]) -> Vec<f64> {
    let out_w = w - WINDOW + 1;
    let mut rows = vec![0.0; out_w * h];
    for y in 0..h {
        for x in 0..out_w {
            rows[y * out_w + x] = (0..WINDOW).map(|k| weights[k] * plane[y * w + x + k]).sum();
        }
    }
    let out_h = h - WINDOW + 1;
    let mut out = vec![0.0; out_w * out_h];
    for y in 0..out_h {
        for x in 0..out_w {
            out[y * out_w + x] = (0..WINDOW)
                .map(|k| weights[k] * rows[(y + k) * out_w + x])
                .sum();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::image;

    #[test]
    fn psnr_of_a_known_error_and_of_identical_images() {
        let a = image(4, 4, |_, _| [100, 100, 100]);
        // One channel of one pixel off by 48: MSE = 48² / 48 samples = 48.
        let mut b = a.clone();
        b.data[0] = 148;
        let expected = 10.0 * (255.0f64 * 255.0 / 48.0).log10();
        assert!(
            (psnr_db(&a, &b) - expected).abs() < 1e-12,
            "{}",
            psnr_db(&a, &b)
        );
        assert!((expected - 31.3184).abs() < 1e-4);
        assert_eq!(psnr_db(&a, &a), f64::INFINITY);
    }

    #[test]
    fn ssim_is_one_for_identical_images_and_falls_with_noise_and_contrast() {
        let texture = |x: u32, y: u32| {
            let v = ((x * 37 + y * 91) % 256) as u8;
            [v, v / 2, 255 - v]
        };
        let a = image(32, 24, texture);
        assert!((ssim(&a, &a).unwrap() - 1.0).abs() < 1e-12);
        let halved = image(32, 24, |x, y| texture(x, y).map(|v| 64 + v / 2));
        let noisy = image(32, 24, |x, y| {
            let n = (x * 7 + y * 13) % 5;
            texture(x, y).map(|v| v.saturating_add(n as u8 * 10))
        });
        let (s_halved, s_noisy) = (ssim(&a, &halved).unwrap(), ssim(&a, &noisy).unwrap());
        assert!(
            s_halved < 0.95 && s_noisy < 1.0 && s_noisy > s_halved,
            "{s_halved} {s_noisy}"
        );
        // Symmetric, and a flat image against itself is 1 (the constants keep 0/0 away).
        assert!((ssim(&halved, &a).unwrap() - s_halved).abs() < 1e-12);
        let flat = image(11, 11, |_, _| [7, 7, 7]);
        assert_eq!(ssim(&flat, &flat), Some(1.0));
        assert_eq!(ssim(&image(10, 11, texture), &image(10, 11, texture)), None);
    }

    #[test]
    fn ssim_of_a_uniform_shift_is_the_luminance_term_alone() {
        // Same structure, means 100 and 120: SSIM = (2·100·120 + C1) / (100² + 120² + C1).
        let a = image(16, 16, |_, _| [100, 100, 100]);
        let b = image(16, 16, |_, _| [120, 120, 120]);
        let expected = (2.0 * 100.0 * 120.0 + C1) / (100.0f64.powi(2) + 120.0f64.powi(2) + C1);
        assert!((ssim(&a, &b).unwrap() - expected).abs() < 1e-9);
    }

    #[test]
    fn depth_l1_is_over_the_reference_measurements_with_holes_as_zero() {
        let reference = DepthImage {
            width: 2,
            height: 2,
            data: vec![1.0, 2.0, 0.0, 4.0],
        };
        let rendered = DepthImage {
            width: 2,
            height: 2,
            data: vec![1.5, 0.0, 9.0, 4.0],
        };
        // |1.5 − 1| + |0 − 2| + |4 − 4| over 3 measured pixels; the reference's hole is left out.
        assert_eq!(depth_l1_m(&rendered, &reference), Some(2.5 / 3.0));
        let empty = DepthImage {
            width: 2,
            height: 2,
            data: vec![0.0; 4],
        };
        assert_eq!(depth_l1_m(&rendered, &empty), None);
    }
}
