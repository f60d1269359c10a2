//! `rslam scene stats`: per-frame image statistics of a scene's default path or of a dataset.

use std::path::{Path, PathBuf};

use anyhow::Context;
use rslam_core::dataset::{read_dataset, DatasetOverrides};
use rslam_core::Intrinsics;
use rslam_eval::image_stats::{frame_stats, FrameStats, SequenceStats, Spread};
use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_perturb::PerturbSpec;
use rslam_pipeline::source::FrameSource;
use rslam_pipeline::{FramesInMemory, SceneJob};

#[derive(clap::Args)]
pub struct StatsArgs {
    /// Built-in scene or mesh file (frames along its default path), or a dataset folder.
    input: String,
    /// Measure every K-th frame.
    #[arg(long, default_value_t = 20)]
    every: usize,
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
    if args.every == 0 {
        anyhow::bail!("--every: 0: expected a whole number of frames, at least 1");
    }
    let ctx = GpuContext::new(&AdapterChoice {
        name_contains: args.adapter.clone(),
    })?;
    let camera = match &args.camera {
        Some(text) => Some(Intrinsics::parse(text).context("--camera")?),
        None => None,
    };
    let frames = if Path::new(&args.input).is_dir() {
        // Image statistics never use the frame rate; a Replica folder without rslam.json has none.
        let overrides = DatasetOverrides {
            camera,
            rate_hz: Some(rslam_core::REPLICA_RATE_HZ),
        };
        let dataset = read_dataset(Path::new(&args.input), &overrides)?;
        let mut source = FramesInMemory::dataset(&ctx, &dataset, &PerturbSpec::default(), 0)?;
        measure(&ctx, &mut source, args.every)?
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
        };
        let mut source = FramesInMemory::scene(&ctx, &job)?;
        measure(&ctx, &mut source, args.every)?
    };
    println!("frame  fast20  grad_p50  grad_p90  saturation  low_texture");
    for (i, s) in &frames {
        println!(
            "{i:5}  {:6}  {:8.2}  {:8.2}  {:10.3}  {:10.0}%",
            s.fast_corners,
            s.gradient_p50,
            s.gradient_p90,
            s.saturation,
            100.0 * s.low_texture_cells
        );
    }
    let all: Vec<FrameStats> = frames.iter().map(|(_, s)| s.clone()).collect();
    let summary = SequenceStats::of(&all);
    let line = |name: &str, s: Spread, scale: f32| {
        println!(
            "{name:<28} {:9.2} {:9.2} {:9.2}",
            s.p10 * scale,
            s.p50 * scale,
            s.p90 * scale
        )
    };
    println!(
        "\n{} frames of {}           p10       p50       p90",
        summary.frames, args.input
    );
    line("FAST corners (threshold 20)", summary.fast_corners, 1.0);
    line("gradient median (grey/px)", summary.gradient_p50, 1.0);
    line("gradient p90 (grey/px)", summary.gradient_p90, 1.0);
    line("saturation", summary.saturation, 1.0);
    line("low-texture cells (%)", summary.low_texture_cells, 100.0);
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
