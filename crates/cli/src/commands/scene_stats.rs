//! `rslam scene stats`: per-frame image statistics of a scene's default path, a dataset or a
//! folder of photographs, beside what real indoor photographs give.

use std::path::{Path, PathBuf};

use anyhow::Context;
use rslam_core::dataset::{read_dataset, read_rgb, DatasetOverrides};
use rslam_core::Intrinsics;
use rslam_eval::image_stats::{
    frame_stats, Band, FrameStats, SequenceStats, Spread, REAL_PHOTOGRAPHS,
};
use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_perturb::PerturbSpec;
use rslam_pipeline::source::FrameSource;
use rslam_pipeline::{FramesInMemory, SceneJob};

#[derive(clap::Args)]
pub struct StatsArgs {
    /// Built-in scene or mesh file (frames along its default path), a dataset folder, or a folder
    /// of PNG/JPEG photographs.
    input: String,
    /// Measure every K-th frame [default: 20; every photograph of a folder].
    #[arg(long)]
    every: Option<usize>,
    /// `replica` (a scene's default), `tum` or W,H,FX,FY,CX,CY; a TUM sequence without a camera
    /// file needs it, as for `rslam perturb`.
    #[arg(long)]
    camera: Option<String>,
    /// Also write every frame's statistics and the summary as JSON.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Use the GPU whose name contains this text.
    #[arg(long)]
    adapter: Option<String>,
}

pub fn run(args: StatsArgs) -> anyhow::Result<()> {
    if args.every == Some(0) {
        anyhow::bail!("--every: 0: expected a whole number of frames, at least 1");
    }
    let camera = match &args.camera {
        Some(text) => Some(Intrinsics::parse(text).context("--camera")?),
        None => None,
    };
    let folder = Path::new(&args.input);
    let frames = if folder.is_dir() && holds_images(folder) {
        photographs(folder, args.every.unwrap_or(1))?
    } else {
        sequence(&args, camera)?
    };
    println!("frame  fast20  weak/10k px  strength_p50  strong  contrast_p10  contrast_p50  contrast_p90  low_texture");
    for (i, s) in &frames {
        println!(
            "{i:5}  {:6}  {:11.2}  {:12.0}  {:5.0}%  {:12.2}  {:12.2}  {:12.2}  {:10.0}%",
            s.fast_corners,
            s.weak_corner_density,
            s.corner_strength_p50,
            100.0 * s.strong_corners,
            s.contrast_p10,
            s.contrast_p50,
            s.contrast_p90,
            100.0 * s.low_texture_cells
        );
    }
    let all: Vec<FrameStats> = frames.iter().map(|(_, s)| s.clone()).collect();
    let summary = SequenceStats::of(&all);
    let real = REAL_PHOTOGRAPHS;
    let rows: [(&str, Spread, f32, Option<Band>); 11] = [
        (
            "FAST corners (threshold 20)",
            summary.fast_corners,
            1.0,
            None,
        ),
        (
            "FAST corners at 7 per 10,000 pixels",
            summary.weak_corner_density,
            1.0,
            Some(real.weak_corner_density),
        ),
        (
            "their median strength (grey levels)",
            summary.corner_strength_p50,
            1.0,
            Some(real.corner_strength_p50),
        ),
        (
            "strong corners, at least 35 (%)",
            summary.strong_corners,
            100.0,
            Some(real.strong_corners),
        ),
        (
            "local contrast p10 (grey levels)",
            summary.contrast_p10,
            1.0,
            Some(real.contrast_p10),
        ),
        (
            "local contrast p50 (grey levels)",
            summary.contrast_p50,
            1.0,
            Some(real.contrast_p50),
        ),
        (
            "local contrast p90 (grey levels)",
            summary.contrast_p90,
            1.0,
            Some(real.contrast_p90),
        ),
        ("gradient median (grey/px)", summary.gradient_p50, 1.0, None),
        ("gradient p90 (grey/px)", summary.gradient_p90, 1.0, None),
        ("saturation", summary.saturation, 1.0, None),
        (
            "low-texture cells (%)",
            summary.low_texture_cells,
            100.0,
            None,
        ),
    ];
    println!(
        "\n{} frames of {:<20}              p10       p50       p90  real photographs (docs/src/scenes.md)",
        summary.frames, args.input
    );
    for (name, s, scale, target) in rows {
        let target = target.map_or(String::new(), |b| {
            let verdict = if b.holds(s.p50) { "" } else { "  (outside)" };
            format!("{:9.2}–{:.2}{verdict}", b.low * scale, b.high * scale)
        });
        println!(
            "{name:<38} {:9.2} {:9.2} {:9.2}  {target}",
            s.p10 * scale,
            s.p50 * scale,
            s.p90 * scale
        );
    }
    if let Some(path) = &args.json {
        let per_frame: Vec<serde_json::Value> = frames
            .iter()
            .map(|(i, s)| serde_json::json!({"frame": i, "stats": s}))
            .collect();
        let doc = serde_json::json!({"input": args.input, "summary": summary, "frames": per_frame});
        std::fs::write(path, serde_json::to_string_pretty(&doc)?)
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(())
}

/// The frames of a dataset folder, or of a scene along its default path.
fn sequence(
    args: &StatsArgs,
    camera: Option<Intrinsics>,
) -> anyhow::Result<Vec<(usize, FrameStats)>> {
    let ctx = GpuContext::new(&AdapterChoice {
        name_contains: args.adapter.clone(),
    })?;
    let every = args.every.unwrap_or(20);
    if Path::new(&args.input).is_dir() {
        // Image statistics never use the frame rate; a Replica folder without rslam.json has none.
        let overrides = DatasetOverrides {
            camera,
            rate_hz: Some(rslam_core::REPLICA_RATE_HZ),
        };
        let dataset = read_dataset(Path::new(&args.input), &overrides)?;
        let mut source = FramesInMemory::dataset(&ctx, &dataset, &PerturbSpec::default(), 0)?;
        measure(&ctx, &mut source, every)
    } else {
        let job = SceneJob {
            scene: args.input.clone(),
            trajectory: None,
            frames: None,
            camera: camera.unwrap_or(Intrinsics::REPLICA),
            rate_hz: Intrinsics::preset_rate_hz(args.camera.as_deref().unwrap_or("replica")),
            spec: PerturbSpec::default(),
            seed: 0,
            agent: None,
            capture: Default::default(),
        };
        let mut source = FramesInMemory::scene(&ctx, &job)?;
        measure(&ctx, &mut source, every)
    }
}

fn measure<S: FrameSource>(
    ctx: &GpuContext,
    source: &mut FramesInMemory<S>,
    every: usize,
) -> anyhow::Result<Vec<(usize, FrameStats)>> {
    let count = source.plan().len();
    (0..count)
        .step_by(every)
        .map(|i| Ok((i, frame_stats(&source.frame(ctx, i)?.color))))
        .collect()
}

/// Whether `folder` holds PNG/JPEG files itself (a dataset keeps its images in sub-folders).
fn holds_images(folder: &Path) -> bool {
    rslam_pipeline::image_files(folder).is_ok()
}

fn photographs(folder: &Path, every: usize) -> anyhow::Result<Vec<(usize, FrameStats)>> {
    let files = rslam_pipeline::image_files(folder)?;
    files
        .iter()
        .enumerate()
        .step_by(every)
        .map(|(i, file)| Ok((i, frame_stats(&read_rgb(file)?))))
        .collect()
}
