//! `rslam perturb`: corruptions applied to what is already on disk: a dataset (Replica or TUM
//! layout), a folder of images, or one image.

use std::path::{Path, PathBuf};

use rslam_core::dataset::{
    decode_depth_png, read_dataset, read_rgb, DatasetFrame, DatasetWriter, SourceDataset,
};
use rslam_core::{DepthImage, Pose, RgbImage, Trajectory};
use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_perturb::{PerturbSpec, Perturber};

use super::decode_ahead::DecodeAhead;
use super::drive::drive;
use super::manifest::ManifestBuilder;
use super::perturb_images::{image_files, perturb_images};
use super::sink::{FrameSink, OutputPlan};

/// Largest |Δt| at which a ground-truth pose stands for a frame when re-stamping (TUM's 100 Hz
/// motion capture has one within 5 ms of every frame).
const GT_MATCH_MAX_DIFF_S: f64 = 0.02;

pub enum PerturbInput {
    Dataset(PathBuf),
    ImageFolder(PathBuf),
    Image(PathBuf),
}

pub(super) fn is_image(path: &Path) -> bool {
    path.extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .is_some_and(|e| matches!(e.as_str(), "png" | "jpg" | "jpeg"))
}

impl PerturbInput {
    /// A dataset (Replica `results/` or TUM `rgb.txt`), a folder of PNG/JPEG images, or one image.
    pub fn detect(path: &Path) -> anyhow::Result<Self> {
        if path.is_file() {
            anyhow::ensure!(
                is_image(path),
                "--input {}: expected a dataset folder, an image folder or a .png/.jpg file",
                path.display()
            );
            return Ok(Self::Image(path.to_path_buf()));
        }
        anyhow::ensure!(
            path.is_dir(),
            "--input {}: no such file or folder",
            path.display()
        );
        if path.join("rgb.txt").is_file() || path.join("results").is_dir() {
            return Ok(Self::Dataset(path.to_path_buf()));
        }
        Ok(Self::ImageFolder(path.to_path_buf()))
    }
}

pub struct PerturbJob {
    pub input: PerturbInput,
    pub out: PathBuf,
    pub perturb: PerturbSpec,
    pub seed: u64,
    pub adapter: AdapterChoice,
    pub command: Vec<String>,
}

pub fn run_perturb(job: PerturbJob) -> anyhow::Result<usize> {
    if job.perturb.needs_scene() {
        anyhow::bail!(
            "--perturb '{}': trajectory deviations (rot, trans) re-render the frames along new poses and need a scene (mesh); use `rslam render --scene NAME|MESH --perturb ...`",
            job.perturb
        );
    }
    let ctx = GpuContext::new(&job.adapter)?;
    eprintln!("adapter: {}", ctx.describe());
    match &job.input {
        PerturbInput::Dataset(root) => perturb_dataset(&ctx, &job, root),
        PerturbInput::ImageFolder(dir) => perturb_images(&ctx, &job, &image_files(dir)?, true),
        PerturbInput::Image(file) => perturb_images(&ctx, &job, std::slice::from_ref(file), false),
    }
}

fn perturb_dataset(ctx: &GpuContext, job: &PerturbJob, root: &Path) -> anyhow::Result<usize> {
    let src = read_dataset(root)?;
    if !job.perturb.depth.is_empty() {
        if let Some(frame) = src.frames.iter().find(|f| f.depth.is_none()) {
            anyhow::bail!(
                "--perturb '{}': depth corruptions need depth, but {} has none",
                job.perturb,
                frame.rgb.display()
            );
        }
    }
    let first = read_rgb(&src.frames[0].rgb)?;
    let k = src.intrinsics;
    if (k.width, k.height) != (first.width, first.height) {
        anyhow::bail!(
            "{}: image is {}x{} but the dataset's camera says {}x{}",
            src.frames[0].rgb.display(),
            first.width,
            first.height,
            k.width,
            k.height
        );
    }
    let stream = rslam_perturb::stream::plan(src.frames.len(), &job.perturb, job.seed);
    let restamp = job.perturb.fast.is_some();
    let t0 = src.frames[0].rgb_time;
    let rate = src.rate_hz;
    let rgb_times: Vec<f64> = stream
        .rgb_source
        .iter()
        .enumerate()
        .map(|(j, &s)| {
            if restamp {
                t0 + j as f64 / rate
            } else {
                src.frames[s].rgb_time
            }
        })
        .collect();
    let plan = OutputPlan::new(
        stream.rgb_source,
        stream.depth_source,
        |j| rgb_times[j],
        |s| src.frames[s].depth_time - src.frames[s].rgb_time,
    );
    let ground_truth = output_ground_truth(&src, &plan, restamp);
    let mut perturber = Perturber::new(ctx, &job.perturb, k.width, k.height, job.seed)?;
    let writer = DatasetWriter::create(&job.out, src.format, k)?;
    let sink = FrameSink::new(writer, plan);
    let with_depth = src.frames.iter().all(|f| f.depth.is_some());
    let scale = src.format.depth_scale();
    let needed: Vec<DatasetFrame> = sink
        .plan()
        .needed_sources()
        .into_iter()
        .map(|s| src.frames[s].clone())
        .collect();
    let decoder = DecodeAhead::start(needed, move |frame| decode_frame(frame, scale));
    let fps = drive(
        ctx,
        &sink,
        with_depth,
        "perturbing",
        |source, encoder, frame| {
            let (color, depth) = decoder.next()?;
            anyhow::ensure!(
                (color.width, color.height) == (k.width, k.height),
                "{}: image is {}x{}, expected {}x{} like the first frame",
                src.frames[source].rgb.display(),
                color.width,
                color.height,
                k.width,
                k.height
            );
            frame.upload(ctx, &color, depth.as_ref());
            perturber.encode(ctx, encoder, frame, source as u32)?;
            Ok(())
        },
    )?;
    drop(decoder);
    let manifest = ManifestBuilder {
        command: &job.command,
        source: &root.display().to_string(),
        source_hash: String::new(),
        format: src.format,
        camera: k,
        rate_hz: rate,
        seed: job.seed,
        spec: &job.perturb,
        perturber: &perturber,
        plan: sink.plan(),
        extra: serde_json::json!({ "adapter": ctx.describe(), "frames_per_second": fps }),
    }
    .build()?;
    let count = manifest.frame_count;
    sink.finish(&ground_truth, &manifest)?;
    Ok(count)
}

fn decode_frame(
    frame: &DatasetFrame,
    scale: f64,
) -> anyhow::Result<(RgbImage, Option<DepthImage>)> {
    let color = read_rgb(&frame.rgb)?;
    let depth = match &frame.depth {
        Some(path) => Some(decode_depth_png(path, scale)?),
        None => None,
    };
    Ok((color, depth))
}

/// The source's ground truth for the output frames. Without re-stamping it is kept whole (at its
/// own rate); with `fast` each kept frame takes the pose nearest its original capture time.
fn output_ground_truth(src: &SourceDataset, plan: &OutputPlan, restamp: bool) -> Trajectory {
    let Some(gt) = &src.ground_truth else {
        return Trajectory::default();
    };
    if !restamp {
        return gt.clone();
    }
    let mut timestamps = Vec::new();
    let mut poses: Vec<Pose> = Vec::new();
    for (j, &s) in plan.rgb_source.iter().enumerate() {
        let t = src.frames[s].rgb_time;
        let nearest = gt
            .timestamps
            .iter()
            .enumerate()
            .min_by(|a, b| (a.1 - t).abs().total_cmp(&(b.1 - t).abs()));
        if let Some((i, &tg)) = nearest {
            if (tg - t).abs() <= GT_MATCH_MAX_DIFF_S {
                timestamps.push(plan.frames[j].rgb_time);
                poses.push(gt.poses[i]);
            }
        }
    }
    Trajectory::new(timestamps, poses)
}
