//! Applies image corruptions from the catalogue to a PNG and times them: the tool behind the
//! fidelity table (PSNR against imagecorruptions) and the per-frame timings.
//!
//! cargo run -p rslam-perturb --example perturb_png -- IN.png OUT_DIR NAMES SEVERITIES [FRAMES] [SEED]
//!   NAMES: comma-separated catalogue names; SEVERITIES: e.g. 1,3,5; FRAMES: timed frames (5).
//! Writes OUT_DIR/<stem>_<name>_<severity>.png (frame 0) and prints one line per run:
//! name severity median-ms-gpu median-ms-with-readback (fastest gpu ms).

use std::path::{Path, PathBuf};
use std::time::Instant;

use rslam_core::RgbImage;
use rslam_gpu::{AdapterChoice, FrameReadback, FrameTextures, GpuContext};
use rslam_perturb::{find, FrameKey, Kit, Scratch, Severity};

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 4 {
        return Err("usage: IN.png OUT_DIR NAMES SEVERITIES [FRAMES] [SEED]".into());
    }
    let input = Path::new(&args[0]);
    let out_dir = PathBuf::from(&args[1]);
    let frames: u32 = args.get(4).map(|s| s.parse()).transpose()?.unwrap_or(5);
    let seed: u64 = args.get(5).map(|s| s.parse()).transpose()?.unwrap_or(0);
    let decoded = image::open(input)?.to_rgb8();
    let (width, height) = decoded.dimensions();
    let clean = RgbImage {
        width,
        height,
        data: decoded.into_raw(),
    };
    let stem = input
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("image");
    std::fs::create_dir_all(&out_dir)?;

    let ctx = GpuContext::new(&AdapterChoice::default())?;
    eprintln!("adapter: {}", ctx.describe());
    let scratch = Scratch::new(&ctx, width, height);
    let kit = Kit {
        ctx: &ctx,
        width,
        height,
        scratch: &scratch,
        // Image files carry no camera.
        camera: None,
    };
    let frame = FrameTextures::new(&ctx, width, height);
    let readback = FrameReadback::new(&ctx, width, height, false);
    for name in args[2].split(',') {
        let entry = find(name).ok_or_else(|| format!("unknown perturbation '{name}'"))?;
        let mut perturbation = (entry.build)(&kit)?;
        for severity in args[3].split(',') {
            let severity = Severity::parse(severity).ok_or_else(|| {
                format!("severity '{severity}': expected 0-5, at most two decimals")
            })?;
            let (mut gpu_ms, mut total_ms) = (Vec::new(), Vec::new());
            for index in 0..frames.max(1) {
                frame.upload(&ctx, &clean, None);
                ctx.wait_idle()?;
                let key = FrameKey {
                    seed,
                    frame: index,
                    severity,
                    explicit: None,
                    camera: None,
                };
                let start = Instant::now();
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                perturbation.encode(&kit, &mut encoder, &frame, &key)?;
                ctx.queue.submit([encoder.finish()]);
                ctx.wait_idle()?;
                gpu_ms.push(start.elapsed().as_secs_f64() * 1e3);
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                readback.encode_copy(&mut encoder, &frame);
                let (color, _) = readback.read(&ctx, ctx.queue.submit([encoder.finish()]))?;
                total_ms.push(start.elapsed().as_secs_f64() * 1e3);
                if index == 0 {
                    let path = out_dir.join(format!("{stem}_{name}_{severity}.png"));
                    image::RgbImage::from_raw(width, height, color.data)
                        .ok_or("image size")?
                        .save(&path)?;
                }
            }
            let fastest = gpu_ms.iter().copied().fold(f64::INFINITY, f64::min);
            println!(
                "{name} {severity} {:.2} {:.2} (fastest {fastest:.2})",
                median(gpu_ms),
                median(total_ms)
            );
        }
    }
    Ok(())
}
