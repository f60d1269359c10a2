//! Real severities on the GPU: every entry that interpolates moves its frames further from the
//! clean frame at every step of 0.5 from 0 to 5 (the PSNR falls strictly), and a real severity
//! gives frames made with its own parameters, not a mix of its neighbours' frames.

use rslam_core::{DepthImage, RgbImage};

use crate::perturbation::{Between, CatalogueEntry, FrameKey, Group};
use crate::severity::Severity;
use crate::testing::{self, EntryOnGpu, Frame};
use crate::CATALOGUE;

const WIDTH: u32 = 160;
const HEIGHT: u32 = 120;
/// Random entries are averaged over these seeds.
const SEEDS: [u64; 8] = [1, 2, 3, 4, 5, 6, 7, 8];
/// The depth ramp's far end, the peak of the depth PSNR.
const FAR: f32 = 8.0;

/// Depth from 0.05 m to 8 m across the frame, so that every depth range clips some of it, with
/// a box 1.2 m away and steps along the bottom (edges for the edge items).
fn ramp_depth() -> DepthImage {
    let mut depth = DepthImage::new(WIDTH, HEIGHT);
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let t = 0.7 * x as f32 / (WIDTH - 1) as f32 + 0.3 * y as f32 / (HEIGHT - 1) as f32;
            let in_box = (30..70).contains(&x) && (16..48).contains(&y);
            let on_steps = y >= 3 * HEIGHT / 4;
            depth.data[(y * WIDTH + x) as usize] = if in_box {
                1.2
            } else if on_steps {
                2.0 + 0.5 * ((x / 12) % 3) as f32
            } else {
                0.05 + (FAR - 0.05) * t
            };
        }
    }
    depth
}

/// A photo-like image: value noise summed over octaves with amplitudes falling as 1/f, as
/// natural images' spectra do, so that no pattern lines up with a block or kernel size.
fn natural_image() -> RgbImage {
    let lattice = |cell: u32, x: u32, y: u32, channel: u32| {
        let key = crate::rng::RngKey::new(11, "natural", cell, channel);
        let corner = |i: u32, j: u32| key.uniform_f64([x / cell + i, y / cell + j, 0, 0]);
        let (fx, fy) = (
            (x % cell) as f64 / cell as f64,
            (y % cell) as f64 / cell as f64,
        );
        let top = corner(0, 0) * (1.0 - fx) + corner(1, 0) * fx;
        let bottom = corner(0, 1) * (1.0 - fx) + corner(1, 1) * fx;
        top * (1.0 - fy) + bottom * fy
    };
    let mut image = RgbImage::new(WIDTH, HEIGHT);
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            for channel in 0..3 {
                let cells = [32, 16, 8, 4, 2];
                let value: f64 = cells
                    .iter()
                    .map(|&cell| lattice(cell, x, y, channel) * cell as f64 / 62.0)
                    .sum();
                image.data[((y * WIDTH + x) * 3 + channel) as usize] = (value * 255.0) as u8;
            }
        }
    }
    image
}

/// How far a frame is from the clean one: the fraction of valid depth pixels it voided, and the
/// mean squared error (colour in [0, 1], depth over [0, FAR]) of the pixels valid in both.
#[derive(Clone, Copy, Debug, Default)]
struct Distance {
    voided: f64,
    squared_error: f64,
}

impl Distance {
    fn between(group: Group, out: &Frame, clean: &Frame) -> Self {
        match group {
            Group::Image => {
                let squares = (out.color.data.iter().zip(&clean.color.data))
                    .map(|(&a, &b)| ((a as f64 - b as f64) / 255.0).powi(2));
                Distance {
                    voided: 0.0,
                    squared_error: squares.sum::<f64>() / out.color.data.len() as f64,
                }
            }
            Group::Depth => {
                let valid: Vec<(f32, f32)> = (out.depth.data.iter().zip(&clean.depth.data))
                    .filter(|(_, &b)| b > 0.0)
                    .map(|(&a, &b)| (a, b))
                    .collect();
                let kept: Vec<f64> = (valid.iter().filter(|(a, _)| *a > 0.0))
                    .map(|(a, b)| ((a - b) / FAR) as f64)
                    .collect();
                Distance {
                    voided: 1.0 - kept.len() as f64 / valid.len() as f64,
                    squared_error: kept.iter().map(|e| e * e).sum::<f64>()
                        / kept.len().max(1) as f64,
                }
            }
        }
    }

    fn psnr(&self) -> f64 {
        -10.0 * self.squared_error.log10()
    }

    /// Further from the clean frame than `nearer`: a lower PSNR of the pixels both kept, or the
    /// same (items that only void pixels) and more pixels voided. The void fraction of an item
    /// that changes values is not compared: noise moves pixels across a sensor's range limits
    /// both ways.
    fn further_than(&self, nearer: &Distance) -> bool {
        self.squared_error > nearer.squared_error
            || (self.squared_error == nearer.squared_error && self.voided > nearer.voided)
    }
}

impl std::fmt::Display for Distance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:.3} dB", self.psnr())?;
        if self.voided > 0.0 {
            write!(f, " {:.2}% voided", 100.0 * self.voided)?;
        }
        Ok(())
    }
}

/// The entry's distance at `severity` from the clean frame, averaged over seeds; a stateful entry
/// is built afresh for each frame so that each starts from its first frame.
fn distance(
    entry: &CatalogueEntry,
    gpu: &mut EntryOnGpu,
    severity: Severity,
    clean: &Frame,
) -> Distance {
    let mut total = Distance::default();
    for &seed in &SEEDS {
        let key = FrameKey {
            seed,
            frame: 0,
            severity,
            explicit: None,
            camera: Some(testing::camera(WIDTH, HEIGHT)),
        };
        if entry.carries_state() {
            *gpu = EntryOnGpu::new(entry, WIDTH, HEIGHT).expect("built once before");
        }
        let out = gpu
            .apply(&key, &clean.color, Some(&clean.depth))
            .unwrap_or_else(|e| panic!("{}:{severity}: {e}", entry.name));
        let one = Distance::between(entry.group, &out, clean);
        total.voided += one.voided / SEEDS.len() as f64;
        total.squared_error += one.squared_error / SEEDS.len() as f64;
    }
    total
}

/// Entries whose own whole rows do not move further from the clean frame at every step, and
/// why; between those rows a real severity must still lie between its neighbours.
const ROWS_NOT_ORDERED: [(&str, &str); 1] = [(
    "frost",
    "imagecorruptions' rows 3-5 lower the image weight (0.7, 0.65, 0.6) under frost weights \
     0.7-0.75: less of the frame clips, and it comes nearer the clean one",
)];

#[test]
fn every_half_step_moves_further_from_the_clean_frame() {
    let clean = Frame {
        color: natural_image(),
        depth: ramp_depth(),
    };
    let mut failures = Vec::new();
    let interpolating = CATALOGUE
        .iter()
        .filter(|e| matches!(e.between, Between::Interpolated(_)));
    for entry in interpolating {
        let mut gpu = EntryOnGpu::new(entry, WIDTH, HEIGHT).unwrap();
        let curve: Vec<(Severity, Distance)> = (1..=10)
            .map(|half| {
                let severity = Severity::from_hundredths(half * 50).unwrap();
                (severity, distance(entry, &mut gpu, severity, &clean))
            })
            .collect();
        let rows_ordered = !ROWS_NOT_ORDERED.iter().any(|(name, _)| *name == entry.name);
        let moved = curve[0].1.further_than(&Distance::default());
        let ordered = moved
            && curve.windows(2).all(|pair| {
                let ((low, nearer), (_, further)) = (pair[0], pair[1]);
                match (rows_ordered, low.as_whole()) {
                    (true, _) => further.further_than(&nearer),
                    // From a whole row to the half step after it: the next row decides the way.
                    (false, Some(_)) => true,
                    (false, None) => {
                        let before = curve
                            .iter()
                            .find(|(s, _)| s.hundredths() + 50 == low.hundredths());
                        let row_before = before.map_or(f64::INFINITY, |(_, d)| d.psnr());
                        let (a, b) = (row_before, further.psnr());
                        let mid = nearer.psnr();
                        (a.min(b) < mid && mid < a.max(b)) || (a == f64::INFINITY && mid > b)
                    }
                }
            });
        if !ordered {
            let shown: Vec<String> = (curve.iter()).map(|(s, d)| format!("{s}: {d}")).collect();
            failures.push(format!("{}: {}", entry.name, shown.join(", ")));
        }
    }
    assert!(
        failures.is_empty(),
        "not further from the clean frame at every half step:\n{}",
        failures.join("\n")
    );
}

/// gaussian_noise:2.5 on mid grey: the measured σ is the interpolated one, 0.15, between the
/// table's 0.12 at 2 and 0.18 at 3.
#[test]
fn gaussian_noise_between_rows_has_the_interpolated_sigma() {
    let grey = testing::uniform_image(WIDTH, HEIGHT, 128);
    let entry = crate::find("gaussian_noise").unwrap();
    let mut gpu = EntryOnGpu::new(entry, WIDTH, HEIGHT).unwrap();
    let key = testing::key_at(7, Severity::parse("2.5").unwrap());
    let out = gpu.apply(&key, &grey, None).unwrap().color;
    let n = out.data.len() as f64;
    let values: Vec<f64> = out.data.iter().map(|&v| v as f64 / 255.0).collect();
    let mean = values.iter().sum::<f64>() / n;
    let sigma = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
    // 57 600 draws: the estimate's own spread is about σ/√(2n) ≈ 0.0005.
    assert!((sigma - 0.15).abs() < 0.004, "σ = {sigma}");
}

/// Runs of equal pixels along one row.
fn runs(image: &RgbImage, y: u32) -> usize {
    let pixels: Vec<[u8; 3]> = (0..image.width).map(|x| image.pixel(x, y)).collect();
    1 + pixels.windows(2).filter(|p| p[0] != p[1]).count()
}

/// pixelate:2.5 shrinks by the interpolated scale 0.45: a row of the gradient shows ⌊0.45·W⌋
/// blocks. A mix of pixelate:2 (0.5) and pixelate:3 (0.4) would show the blocks of both.
#[test]
fn pixelate_between_rows_uses_the_interpolated_scale() {
    let image = testing::test_image(WIDTH, HEIGHT);
    let entry = crate::find("pixelate").unwrap();
    let mut gpu = EntryOnGpu::new(entry, WIDTH, HEIGHT).unwrap();
    let mut blocks = |severity: &str| {
        let key = testing::key_at(0, Severity::parse(severity).unwrap());
        runs(&gpu.apply(&key, &image, None).unwrap().color, 2)
    };
    let width = WIDTH as f64;
    assert_eq!(blocks("2"), (0.5 * width) as usize);
    assert_eq!(blocks("3"), (0.4 * width) as usize);
    assert_eq!(blocks("2.5"), (0.45 * width) as usize);
}
