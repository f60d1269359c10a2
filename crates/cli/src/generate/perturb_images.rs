//! `rslam perturb` on images: a folder of PNG/JPEG files or one file. Image i is frame i of a
//! sequence (its RNG key); it is perturbed on the GPU and written under its own name, in its own
//! format. Decoding runs ahead, frames overlap on the GPU, and encoding runs on worker threads.

use std::collections::hash_map::Entry;
use std::collections::HashMap;
use std::ops::Range;
use std::path::{Path, PathBuf};

use anyhow::Context;
use rslam_core::dataset::{read_image_size, read_rgb, write_rgb_like, ItemSeverities, Manifest};
use rslam_gpu::GpuContext;
use rslam_perturb::{PerturbSpec, Perturber};

use super::decode_ahead::DecodeAhead;
use super::drive::FrameRun;
use super::encoder_pool::EncoderPool;
use super::perturb_job::{is_image, PerturbJob};
use super::progress::Progress;

/// JPEG quality of perturbed JPEG images.
const JPEG_QUALITY: u8 = 95;

/// The PNG/JPEG files of `dir`, sorted by name.
pub fn image_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("--input {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file() && is_image(p))
        .collect();
    files.sort();
    anyhow::ensure!(
        !files.is_empty(),
        "--input {}: no .png/.jpg images in this folder",
        dir.display()
    );
    Ok(files)
}

/// Perturbs `files`; a folder input writes each under its own name in `--out` plus a manifest,
/// a single image is written to `--out` itself.
pub fn perturb_images(
    ctx: &GpuContext,
    job: &PerturbJob,
    files: &[PathBuf],
    folder: bool,
) -> anyhow::Result<usize> {
    let spec = &job.perturb;
    if !spec.depth.is_empty() {
        anyhow::bail!("--perturb '{spec}': depth corruptions need depth images, and an image input has none; use a dataset (Replica or TUM layout)");
    }
    if spec.fast.is_some() || spec.misalign.is_some() {
        anyhow::bail!("--perturb '{spec}': fast and misalign act on RGB-D streams; use a dataset (Replica or TUM layout) as --input");
    }
    let outputs: Vec<PathBuf> = if folder {
        std::fs::create_dir_all(&job.out)
            .with_context(|| format!("--out {}", job.out.display()))?;
        let _ = std::fs::remove_file(job.out.join(rslam_core::dataset::MANIFEST_FILE));
        files
            .iter()
            .map(|f| {
                Ok(job
                    .out
                    .join(f.file_name().context("image without a file name")?))
            })
            .collect::<anyhow::Result<_>>()?
    } else {
        vec![job.out.clone()]
    };
    let sizes = files
        .iter()
        .map(|f| read_image_size(f))
        .collect::<Result<Vec<_>, _>>()?;
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get());
    let pool = EncoderPool::new(threads, 2 * threads);
    let progress = Progress::new(files.len(), "perturbing");
    let mut perturbers: HashMap<(u32, u32), Perturber> = HashMap::new();
    let mut per_frame = vec![String::new(); spec.image.len()];
    for run in runs_of_equal_size(&sizes) {
        let (width, height) = sizes[run.start];
        let perturber = match perturbers.entry((width, height)) {
            Entry::Occupied(e) => e.into_mut(),
            Entry::Vacant(e) => e.insert(Perturber::new(ctx, spec, width, height, job.seed)?),
        };
        let decoder = DecodeAhead::start(files[run.clone()].to_vec(), |file| Ok(read_rgb(file)?));
        let sources: Vec<usize> = run.collect();
        FrameRun {
            ctx,
            width,
            height,
            sources: &sources,
            with_depth: false,
        }
        .run(
            &progress,
            |index, encoder, frame| {
                let color = decoder.next()?;
                anyhow::ensure!(
                    (color.width, color.height) == (width, height),
                    "{}: image is {}x{} but its header says {width}x{height}",
                    files[index].display(),
                    color.width,
                    color.height
                );
                frame.upload(ctx, &color, None);
                let got = perturber.encode(ctx, encoder, frame, index as u32)?;
                for (column, item) in per_frame.iter_mut().zip(&got.items) {
                    column.push(char::from(b'0' + item.severity));
                }
                Ok(())
            },
            |frame| {
                let out = outputs[frame.index].clone();
                pool.submit(move || Ok(write_rgb_like(&out, &frame.color, JPEG_QUALITY)?))
            },
        )?;
    }
    progress.finish();
    pool.finish()?;
    if folder {
        folder_manifest(job, files, per_frame)?.write(&job.out)?;
    }
    Ok(files.len())
}

/// Consecutive files of the same size share one perturber and one frame ring.
fn runs_of_equal_size(sizes: &[(u32, u32)]) -> Vec<Range<usize>> {
    let mut runs: Vec<Range<usize>> = Vec::new();
    for (i, size) in sizes.iter().enumerate() {
        match runs.last_mut() {
            Some(run) if sizes[run.start] == *size => run.end = i + 1,
            _ => runs.push(i..i + 1),
        }
    }
    runs
}

fn folder_manifest(
    job: &PerturbJob,
    files: &[PathBuf],
    per_frame: Vec<String>,
) -> anyhow::Result<Manifest> {
    let spec: &PerturbSpec = &job.perturb;
    let labels = spec.frame_items().map(|item| item.to_string());
    Ok(Manifest {
        tool: "rslam".into(),
        tool_version: env!("CARGO_PKG_VERSION").into(),
        command: job.command.clone(),
        source: files
            .first()
            .and_then(|f| f.parent())
            .map(|p| p.display().to_string())
            .unwrap_or_default(),
        source_hash: String::new(),
        format: None,
        camera: None,
        rate_hz: 0.0,
        frame_count: files.len(),
        seed: job.seed,
        perturbation: spec.to_string(),
        perturbation_parsed: serde_json::to_value(spec)?,
        severities: labels
            .zip(per_frame)
            .map(|(item, per_frame)| ItemSeverities { item, per_frame })
            .collect(),
        rgb_source: (0..files.len()).collect(),
        depth_source: Vec::new(),
        extra: serde_json::json!({ "files": files.iter().map(|f| f.display().to_string()).collect::<Vec<_>>() }),
    })
}

#[cfg(test)]
mod tests {
    use super::runs_of_equal_size;

    #[test]
    fn consecutive_equal_sizes_form_one_run() {
        let sizes = [(4, 3), (4, 3), (8, 6), (4, 3), (4, 3), (4, 3)];
        assert_eq!(runs_of_equal_size(&sizes), vec![0..2, 2..3, 3..6]);
        assert!(runs_of_equal_size(&[]).is_empty());
    }
}
