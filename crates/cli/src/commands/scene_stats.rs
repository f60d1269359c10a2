//! `rslam scene stats`: per-frame image statistics of a scene's default path, a dataset or a
//! folder of photographs, beside what real indoor photographs give; with people in the frames
//! (a scene under `--perturb actors:S`, a dataset rendered with them), each frame's dynamic
//! fraction.

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
    /// Items applied to a scene's frames as `rslam render --perturb` applies them (`actors:4`:
    /// each frame's dynamic fraction, the share of pixels people cover).
    #[arg(long, value_name = "SPEC")]
    perturb: Option<String>,
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
    let spec = match &args.perturb {
        Some(text) => PerturbSpec::parse(text).context("--perturb")?,
        None => PerturbSpec::default(),
    };
    let folder = Path::new(&args.input);
    if folder.is_dir() && args.perturb.is_some() {
        anyhow::bail!(
            "--perturb: {}: items apply to a scene's frames, not to a folder",
            args.input
        );
    }
    let frames = if folder.is_dir() && holds_images(folder) {
        photographs(folder, args.every.unwrap_or(1))?
    } else {
        sequence(&args, camera, spec)?
    };
    let with_people = frames.iter().any(|f| f.dynamic.is_some());
    let people_column = if with_people { "  dynamic" } else { "" };
    println!("frame  fast20  weak/10k px  strength_p50  strong  contrast_p10  contrast_p50  contrast_p90  low_texture{people_column}");
    for Measured {
        frame,
        stats: s,
        dynamic,
    } in &frames
    {
        let people = dynamic.map_or(String::new(), |d| format!("  {:6.1}%", 100.0 * d));
        println!(
            "{frame:5}  {:6}  {:11.2}  {:12.0}  {:5.0}%  {:12.2}  {:12.2}  {:12.2}  {:10.0}%{people}",
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
    let all: Vec<FrameStats> = frames.iter().map(|f| f.stats.clone()).collect();
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
    let dynamic: Vec<f32> = frames.iter().filter_map(|f| f.dynamic).collect();
    let people = with_people.then(|| {
        let spread = Spread::of(dynamic.iter().map(|d| 100.0 * d));
        let in_view = dynamic.iter().filter(|&&d| d > 0.0).count();
        let share = 100.0 * in_view as f32 / dynamic.len() as f32;
        println!(
            "{:<38} {:9.2} {:9.2} {:9.2}  people in {share:.0}% of the frames",
            "dynamic pixels (%)", spread.p10, spread.p50, spread.p90
        );
        serde_json::json!({"dynamic_percent": spread, "frames_with_people": in_view})
    });
    if let Some(path) = &args.json {
        let per_frame: Vec<serde_json::Value> = (frames.iter())
            .map(|f| serde_json::json!({"frame": f.frame, "stats": f.stats, "dynamic_fraction": f.dynamic}))
            .collect();
        let doc = serde_json::json!({"input": args.input, "summary": summary, "people": people, "frames": per_frame});
        std::fs::write(path, serde_json::to_string_pretty(&doc)?)
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(())
}

/// One frame's statistics, and the share of its pixels people cover where it has them.
struct Measured {
    frame: usize,
    stats: FrameStats,
    dynamic: Option<f32>,
}

/// The frames of a dataset folder (their dynamic fractions from its manifest, when it was
/// rendered with people), or of a scene along its default path under `spec`.
fn sequence(
    args: &StatsArgs,
    camera: Option<Intrinsics>,
    spec: PerturbSpec,
) -> anyhow::Result<Vec<Measured>> {
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
        let folder = Path::new(&args.input);
        let dataset = read_dataset(folder, &overrides)?;
        let mut source = FramesInMemory::dataset(&ctx, &dataset, &PerturbSpec::default(), 0)?;
        let mut frames = measure(&ctx, &mut source, every)?;
        if let Ok(fractions) = rslam_eval::read_dynamic_fractions(folder) {
            for frame in &mut frames {
                frame.dynamic = fractions.get(frame.frame).map(|&f| f as f32);
            }
        }
        Ok(frames)
    } else {
        let job = SceneJob {
            scene: args.input.clone(),
            trajectory: None,
            frames: None,
            camera: camera.unwrap_or(Intrinsics::REPLICA),
            rate_hz: Intrinsics::preset_rate_hz(args.camera.as_deref().unwrap_or("replica")),
            spec,
            seed: 0,
            agent: None,
            capture: Default::default(),
            actor_files: Vec::new(),
        };
        let mut source = FramesInMemory::scene(&ctx, &job)?;
        measure(&ctx, &mut source, every)
    }
}

fn measure<S: FrameSource>(
    ctx: &GpuContext,
    source: &mut FramesInMemory<S>,
    every: usize,
) -> anyhow::Result<Vec<Measured>> {
    let count = source.plan().len();
    (0..count)
        .step_by(every)
        .map(|i| {
            let frame = source.frame(ctx, i)?;
            Ok(Measured {
                frame: i,
                stats: frame_stats(&frame.color),
                dynamic: frame.mask.map(|m| m.dynamic_fraction() as f32),
            })
        })
        .collect()
}

/// Whether `folder` holds PNG/JPEG files itself (a dataset keeps its images in sub-folders).
fn holds_images(folder: &Path) -> bool {
    rslam_pipeline::image_files(folder).is_ok()
}

fn photographs(folder: &Path, every: usize) -> anyhow::Result<Vec<Measured>> {
    let files = rslam_pipeline::image_files(folder)?;
    files
        .iter()
        .enumerate()
        .step_by(every)
        .map(|(i, file)| {
            Ok(Measured {
                frame: i,
                stats: frame_stats(&read_rgb(file)?),
                dynamic: None,
            })
        })
        .collect()
}
