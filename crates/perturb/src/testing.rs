//! Shared test helpers: one GPU context, deterministic test frames, running one catalogue entry
//! on frames and reading them back, and comparisons that write images to look at on failure.

use std::path::PathBuf;
use std::sync::OnceLock;

use rslam_core::{DepthImage, Intrinsics, RgbImage};
use rslam_gpu::{AdapterChoice, FrameReadback, FrameTextures, GpuContext};

use crate::perturbation::{CatalogueEntry, FrameKey, GpuPerturbation, Kit, Scratch};
use crate::severity::Severity;
use crate::twin::Tolerance;

/// The process-wide context. No adapter is a failure, never a skip.
pub fn context() -> &'static GpuContext {
    static CONTEXT: OnceLock<GpuContext> = OnceLock::new();
    CONTEXT.get_or_init(|| {
        GpuContext::new(&AdapterChoice::default())
            .unwrap_or_else(|e| panic!("GPU tests need an adapter (lavapipe is fine): {e}"))
    })
}

/// A colour and depth frame on the CPU.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    pub color: RgbImage,
    pub depth: DepthImage,
}

/// One catalogue entry built once for a frame size and applied to frame after frame, each in
/// its own submission, as the [`crate::Perturber`] does.
pub struct EntryOnGpu {
    scratch: Scratch,
    perturbation: Box<dyn GpuPerturbation>,
    frame: FrameTextures,
    readback: FrameReadback,
    width: u32,
    height: u32,
}

impl EntryOnGpu {
    pub fn new(entry: &CatalogueEntry, width: u32, height: u32) -> Result<Self, String> {
        let ctx = context();
        let scratch = Scratch::new(ctx, width, height);
        let kit = Kit {
            ctx,
            width,
            height,
            scratch: &scratch,
            camera: Some(camera(width, height)),
        };
        let perturbation = (entry.build)(&kit).map_err(|e| format!("building: {e}"))?;
        Ok(Self {
            perturbation,
            frame: FrameTextures::new(ctx, width, height),
            readback: FrameReadback::new(ctx, width, height, true),
            scratch,
            width,
            height,
        })
    }

    /// Uploads `color` and `depth`, applies the entry with `key` and reads the frame back.
    pub fn apply(
        &mut self,
        key: &FrameKey,
        color: &RgbImage,
        depth: Option<&DepthImage>,
    ) -> Result<Frame, String> {
        let ctx = context();
        let kit = Kit {
            ctx,
            width: self.width,
            height: self.height,
            scratch: &self.scratch,
            camera: Some(camera(self.width, self.height)),
        };
        self.frame.upload(ctx, color, depth);
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.perturbation
            .encode(&kit, &mut encoder, &self.frame, key)
            .map_err(|e| format!("encoding: {e}"))?;
        self.readback.encode_copy(&mut encoder, &self.frame);
        let submission = ctx.queue.submit([encoder.finish()]);
        let (color, depth) = self
            .readback
            .read(ctx, submission)
            .map_err(|e| format!("running: {e}"))?;
        Ok(Frame {
            color,
            depth: depth.expect("depth was asked for"),
        })
    }
}

/// Builds `entry` for the frame size, applies it once with `key` and reads the frame back.
pub fn run_frame(
    entry: &CatalogueEntry,
    key: &FrameKey,
    color: &RgbImage,
    depth: Option<&DepthImage>,
) -> Frame {
    EntryOnGpu::new(entry, color.width, color.height)
        .and_then(|mut gpu| gpu.apply(key, color, depth))
        .unwrap_or_else(|e| panic!("{}: {e}", entry.name))
}

/// A key for frame 0 at the whole `severity`.
pub fn key(seed: u64, severity: u8) -> FrameKey<'static> {
    key_at(seed, Severity::whole(severity).expect("a severity 0..=5"))
}

/// A key for frame 0 at `severity`, whole or real.
pub fn key_at(seed: u64, severity: Severity) -> FrameKey<'static> {
    FrameKey {
        seed,
        frame: 0,
        severity,
        explicit: None,
        camera: None,
    }
}

/// The camera GPU tests build entries with: f = width pixels (a 53° horizontal field of view),
/// principal point at the centre.
pub fn camera(width: u32, height: u32) -> Intrinsics {
    Intrinsics {
        width,
        height,
        fx: width as f64,
        fy: width as f64,
        cx: (width as f64 - 1.0) / 2.0,
        cy: (height as f64 - 1.0) / 2.0,
    }
}

/// Runs an image corruption on `color` (frame 0) and returns the corrupted colour.
pub fn run_color(entry: &CatalogueEntry, severity: u8, seed: u64, color: &RgbImage) -> RgbImage {
    run_frame(entry, &key(seed, severity), color, None).color
}

/// Runs a depth corruption on `depth` (frame 0, black colour) and returns the corrupted depth.
pub fn run_depth(entry: &CatalogueEntry, key: &FrameKey, depth: &DepthImage) -> DepthImage {
    let color = RgbImage::new(depth.width, depth.height);
    run_frame(entry, key, &color, Some(depth)).depth
}

/// A deterministic photo-like test image: smooth shading, hard edges, saturated and grey
/// regions, fine texture, pure black and white.
pub fn test_image(width: u32, height: u32) -> RgbImage {
    let mut image = RgbImage::new(width, height);
    let (w, h) = (width as f32, height as f32);
    for y in 0..height {
        for x in 0..width {
            let (u, v) = (x as f32 / w, y as f32 / h);
            let mut c = [
                0.15 + 0.7 * u,
                0.25 + 0.5 * v,
                0.5 + 0.4 * (6.0 * u + 3.0 * v).sin(),
            ];
            let (dx, dy) = (u - 0.35, v - 0.45);
            if dx * dx + dy * dy < 0.04 {
                c = [0.9, 0.15, 0.1];
            }
            if u > 0.6 && u < 0.85 && v > 0.2 && v < 0.7 {
                let check = ((x / 3) + (y / 3)) % 2 == 0;
                c = if check {
                    [0.8, 0.8, 0.75]
                } else {
                    [0.1, 0.1, 0.2]
                };
            }
            if v > 0.85 {
                c = if u < 0.5 { [0.0; 3] } else { [1.0; 3] };
            }
            let i = (y as usize * width as usize + x as usize) * 3;
            for (k, value) in c.iter().enumerate() {
                image.data[i + k] = (value.clamp(0.0, 1.0) * 255.0).round() as u8;
            }
        }
    }
    image
}

/// A deterministic depth frame: a slanted floor, a box in front of a wall (depth steps), and a
/// band of invalid (0) pixels.
pub fn test_depth(width: u32, height: u32) -> DepthImage {
    let mut depth = DepthImage::new(width, height);
    for y in 0..height {
        for x in 0..width {
            let (u, v) = (x as f32 / width as f32, y as f32 / height as f32);
            let mut z = if v > 0.6 {
                1.0 + 3.0 * (1.0 - v)
            } else {
                4.0 + 0.5 * u
            };
            if (0.3..0.55).contains(&u) && (0.25..0.7).contains(&v) {
                z = 1.8;
            }
            if (0.05..0.15).contains(&u) && v < 0.3 {
                z = 0.0;
            }
            depth.data[y as usize * width as usize + x as usize] = z;
        }
    }
    depth
}

fn failure_dir() -> PathBuf {
    let dir = std::env::temp_dir().join("rslam-perturb-tests");
    let _ = std::fs::create_dir_all(&dir);
    dir
}

fn save_rgb(image: &RgbImage, path: &PathBuf) {
    let buffer = image::RgbImage::from_raw(image.width, image.height, image.data.clone());
    if let Some(buffer) = buffer {
        let _ = buffer.save(path);
    }
}

/// Checks every colour value of `actual` against `expected` within `tolerance` (levels, and
/// the fraction of values allowed beyond them); on failure writes `<name>-actual.png`,
/// `<name>-expected.png` and `<name>-diff.png` (diff ×32) and says where.
pub fn compare_color(
    actual: &RgbImage,
    expected: &RgbImage,
    tolerance: &Tolerance,
    name: &str,
) -> Result<(), String> {
    assert_eq!(
        (actual.width, actual.height),
        (expected.width, expected.height)
    );
    let diffs: Vec<u8> = actual
        .data
        .iter()
        .zip(&expected.data)
        .map(|(a, b)| a.abs_diff(*b))
        .collect();
    let bad = diffs.iter().filter(|&&d| d > tolerance.levels).count();
    if bad as f64 <= tolerance.outliers * diffs.len() as f64 {
        return Ok(());
    }
    let worst = diffs.iter().copied().max().unwrap_or(0);
    let first = diffs
        .iter()
        .position(|&d| d > tolerance.levels)
        .unwrap_or(0);
    let (pixel, channel) = (first / 3, first % 3);
    let (x, y) = (pixel as u32 % actual.width, pixel as u32 / actual.width);
    let dir = failure_dir();
    save_rgb(actual, &dir.join(format!("{name}-actual.png")));
    save_rgb(expected, &dir.join(format!("{name}-expected.png")));
    let diff_image = RgbImage {
        width: actual.width,
        height: actual.height,
        data: diffs.iter().map(|d| d.saturating_mul(32)).collect(),
    };
    save_rgb(&diff_image, &dir.join(format!("{name}-diff.png")));
    Err(format!(
        "{name}: {bad} colour values differ by more than {} (worst {worst}); first at \
         ({x}, {y}) channel {channel}: actual {} expected {}; images in {}",
        tolerance.levels,
        actual.data[first],
        expected.data[first],
        dir.display()
    ))
}

/// Asserts every channel of `actual` is within `levels` of `expected` (see [`compare_color`]).
pub fn assert_close(actual: &RgbImage, expected: &RgbImage, levels: u8, name: &str) {
    let tolerance = Tolerance {
        levels,
        ..Tolerance::EXACT
    };
    if let Err(message) = compare_color(actual, expected, &tolerance, name) {
        panic!("{message}");
    }
}

/// Checks two depth frames agree within `metres` and have the same invalid pixels.
pub fn compare_depth(
    actual: &DepthImage,
    expected: &DepthImage,
    metres: f32,
    name: &str,
) -> Result<(), String> {
    assert_eq!(
        (actual.width, actual.height),
        (expected.width, expected.height)
    );
    let bad: Vec<(usize, f32, f32)> = actual
        .data
        .iter()
        .zip(&expected.data)
        .enumerate()
        .filter(|(_, (a, e))| (**a == 0.0) != (**e == 0.0) || (*a - *e).abs() > metres)
        .map(|(i, (a, e))| (i, *a, *e))
        .collect();
    match bad.first() {
        None => Ok(()),
        Some(&(i, a, e)) => {
            let (x, y) = (i as u32 % actual.width, i as u32 / actual.width);
            Err(format!(
                "{name}: {} depth values differ (tolerance {metres} m); first at ({x}, {y}): \
                 actual {a} expected {e}",
                bad.len()
            ))
        }
    }
}

/// Asserts two depth frames agree within `metres` (see [`compare_depth`]).
pub fn assert_depth_close(actual: &DepthImage, expected: &DepthImage, metres: f32, name: &str) {
    if let Err(message) = compare_depth(actual, expected, metres, name) {
        panic!("{message}");
    }
}

/// Every pixel the same grey level.
pub fn uniform_image(width: u32, height: u32, level: u8) -> RgbImage {
    RgbImage {
        width,
        height,
        data: vec![level; width as usize * height as usize * 3],
    }
}

/// Mean and standard deviation of all channel values, in [0, 1] units.
#[derive(Clone, Copy, Debug)]
pub struct Stats {
    pub mean: f64,
    pub std: f64,
    pub count: usize,
}

pub fn stats(image: &RgbImage) -> Stats {
    let count = image.data.len();
    let mean = image.data.iter().map(|&v| v as f64 / 255.0).sum::<f64>() / count as f64;
    let var = image
        .data
        .iter()
        .map(|&v| (v as f64 / 255.0 - mean).powi(2))
        .sum::<f64>()
        / count as f64;
    Stats {
        mean,
        std: var.sqrt(),
        count,
    }
}

/// Mean and std of an 8-bit output level given its probabilities (index = level).
pub fn level_stats(probabilities: &[f64; 256]) -> (f64, f64) {
    let mean: f64 = (0..256).map(|k| probabilities[k] * k as f64 / 255.0).sum();
    let var: f64 = (0..256)
        .map(|k| probabilities[k] * (k as f64 / 255.0 - mean).powi(2))
        .sum();
    (mean, var.sqrt())
}

/// Asserts sample statistics agree with the expected law within 5 standard errors
/// (mean: σ/√n; std: σ/√(2n), which holds for laws not far from normal; plus 1e-4 slack).
pub fn assert_stats(got: Stats, expected_mean: f64, expected_std: f64, what: &str) {
    let n = got.count as f64;
    let mean_tol = 5.0 * expected_std / n.sqrt() + 1e-4;
    let std_tol = 5.0 * expected_std / (2.0 * n).sqrt() + 1e-4;
    assert!(
        (got.mean - expected_mean).abs() < mean_tol,
        "{what}: mean {:.5}, expected {expected_mean:.5} ± {mean_tol:.5}",
        got.mean
    );
    assert!(
        (got.std - expected_std).abs() < std_tol,
        "{what}: std {:.5}, expected {expected_std:.5} ± {std_tol:.5}",
        got.std
    );
}

/// Same seed → byte-identical output; another seed or another frame → different output.
pub fn assert_seeded(entry: &CatalogueEntry, severity: u8) {
    let clean = test_image(64, 48);
    let run = |seed, frame| {
        let key = FrameKey {
            seed,
            frame,
            severity: Severity::whole(severity).expect("a severity 0..=5"),
            explicit: None,
            camera: Some(camera(64, 48)),
        };
        run_frame(entry, &key, &clean, Some(&test_depth(64, 48)))
    };
    let a = run(11, 0);
    assert!(
        a == run(11, 0),
        "{}: same seed, different output",
        entry.name
    );
    assert!(a != run(12, 0), "{}: another seed, same output", entry.name);
    assert!(
        a != run(11, 1),
        "{}: another frame, same output",
        entry.name
    );
}

/// Probabilities of each 8-bit level of trunc8(clip(x + N(0, σ), 0, 1)).
pub fn clipped_normal_levels(x: f64, sigma: f64) -> [f64; 256] {
    use statrs::distribution::{ContinuousCDF, Normal};
    let normal = Normal::new(x, sigma).expect("σ > 0");
    let mut p = [0.0; 256];
    for (k, pk) in p.iter_mut().enumerate() {
        let low = if k == 0 {
            f64::NEG_INFINITY
        } else {
            k as f64 / 255.0
        };
        let high = if k == 255 {
            f64::INFINITY
        } else {
            (k + 1) as f64 / 255.0
        };
        *pk = normal.cdf(high) - normal.cdf(low);
    }
    p
}
