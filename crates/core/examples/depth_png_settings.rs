//! Re-encodes a dataset's 16-bit depth PNGs with each PNG compression × filter setting and
//! prints size and single-thread encoding time per frame: the measurement behind `--depth-png`.
//!
//! cargo run --release -p rslam-core --example depth_png_settings -- DATASET [STRIDE] [SETTINGS]
//!   DATASET: a Replica (results/depth*.png) or TUM (depth/*.png) folder; every STRIDE-th depth
//!   image is used (default 1). SETTINGS: `grid` (default: every compression × filter) or
//!   `levels` (deflate levels 1–9, every filter but NoFilter).
//! Prints one line per setting: compression, filter, KB/frame, then ms/frame as the encoding
//! thread's CPU time (mean; from /proc/thread-self/schedstat, so other processes on a busy
//! machine do not count) and as wall time (median). Every encoding is decoded back and compared
//! with the source samples: all settings are lossless.

use std::path::{Path, PathBuf};
use std::time::Instant;

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageBuffer, ImageEncoder, Luma};

type Depth16 = ImageBuffer<Luma<u16>, Vec<u16>>;

const FILTERS: [FilterType; 6] = [
    FilterType::NoFilter,
    FilterType::Sub,
    FilterType::Up,
    FilterType::Avg,
    FilterType::Paeth,
    FilterType::Adaptive,
];

fn depth_files(root: &Path) -> Result<Vec<PathBuf>, Box<dyn std::error::Error>> {
    let (dir, prefix) = if root.join("results").is_dir() {
        (root.join("results"), "depth")
    } else {
        (root.join("depth"), "")
    };
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let name = p.file_name().unwrap_or_default().to_string_lossy();
            name.starts_with(prefix) && name.ends_with(".png")
        })
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(format!("no depth PNGs under {}", dir.display()).into());
    }
    Ok(files)
}

fn settings(which: &str) -> Result<Vec<(CompressionType, FilterType)>, String> {
    let compressions: Vec<CompressionType> = match which {
        "grid" => vec![
            CompressionType::Fast,
            CompressionType::Default,
            CompressionType::Best,
        ],
        "levels" => (1..=9).map(CompressionType::Level).collect(),
        other => {
            return Err(format!(
                "unknown settings '{other}': expected grid or levels"
            ))
        }
    };
    let filters: &[FilterType] = match which {
        "grid" => &FILTERS,
        _ => &FILTERS[1..],
    };
    Ok(compressions
        .iter()
        .flat_map(|&c| filters.iter().map(move |&f| (c, f)))
        .collect())
}

fn encode(depth: &Depth16, compression: CompressionType, filter: FilterType) -> Vec<u8> {
    let mut out = Vec::new();
    PngEncoder::new_with_quality(&mut out, compression, filter)
        .write_image(
            bytemuck::cast_slice(depth.as_raw()),
            depth.width(),
            depth.height(),
            ExtendedColorType::L16,
        )
        .expect("encode");
    out
}

/// Nanoseconds this thread has run on a CPU (Linux); `None` elsewhere.
fn thread_cpu_ns() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(root) = args.first() else {
        return Err("usage: DATASET [STRIDE] [grid|levels]".into());
    };
    let stride: usize = args.get(1).map(|s| s.parse()).transpose()?.unwrap_or(1);
    let settings = settings(args.get(2).map_or("grid", String::as_str))?;
    let frames: Vec<Depth16> = depth_files(Path::new(root))?
        .iter()
        .step_by(stride.max(1))
        .map(|path| image::open(path).map(|d| d.into_luma16()))
        .collect::<Result<_, _>>()?;
    let (width, height) = frames[0].dimensions();
    println!("{root}: {} frames of {width}x{height}", frames.len());
    for (compression, filter) in settings {
        let mut bytes = 0usize;
        let (mut cpu_ns, mut wall_ms) = (0u64, Vec::new());
        for depth in &frames {
            let (start, start_cpu) = (Instant::now(), thread_cpu_ns());
            let png = encode(depth, compression, filter);
            wall_ms.push(start.elapsed().as_secs_f64() * 1e3);
            if let (Some(end), Some(start)) = (thread_cpu_ns(), start_cpu) {
                cpu_ns += end - start;
            }
            bytes += png.len();
            let back = image::load_from_memory(&png)?.into_luma16();
            assert!(back == *depth, "{compression:?} {filter:?} is not lossless");
        }
        let n = frames.len() as f64;
        println!(
            "{:<10} {:<9} {:>7.1} KB {:>7.1} ms cpu {:>7.1} ms wall",
            format!("{compression:?}"),
            format!("{filter:?}"),
            bytes as f64 / n / 1024.0,
            cpu_ns as f64 / n / 1e6,
            median(wall_ms)
        );
    }
    Ok(())
}
