//! `rslam perturb` on images: a folder of PNG/JPEG files or one file. Image i is frame i of a
//! sequence (its RNG key); it is perturbed on the GPU and written under its own name, in its own
//! format. Decoding runs ahead, frames overlap on the GPU, encoding runs on worker threads. A
//! folder output is resumable and gets checksums and a manifest like a dataset.

use std::collections::hash_map::Entry;
use std::collections::HashMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use rslam_core::dataset::{
    encode_rgb_like, read_image_size, read_rgb, ContentWriter, DepthPng, Manifest,
};
use rslam_core::{CoreError, ImagePool, RgbImage};
use rslam_gpu::GpuContext;
use rslam_perturb::{PerturbSpec, Perturber};

use crate::encoder_pool::EncoderPool;
use crate::frame_loop::FrameRun;
use crate::job::{Planned, Streams, Writing};
use crate::manifest::ManifestParts;
use crate::output_folder::Written;
use crate::plan::FramePlan;
use crate::progress::Progress;
use crate::upload_ahead::UploadAhead;
use crate::{settings, PipelineError};

/// JPEG quality of perturbed JPEG images.
const JPEG_QUALITY: u8 = 95;

/// Whether `path` names a PNG or JPEG file by its extension.
pub fn is_image(path: &Path) -> bool {
    path.extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .is_some_and(|e| matches!(e.as_str(), "png" | "jpg" | "jpeg"))
}

/// The PNG/JPEG files of `dir`, sorted by name.
pub fn image_files(dir: &Path) -> Result<Vec<PathBuf>, PipelineError> {
    let entries = std::fs::read_dir(dir).map_err(|e| CoreError::io(dir, e))?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file() && is_image(p))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(PipelineError::input(
            dir,
            "no .png/.jpg images in this folder",
        ));
    }
    Ok(files)
}

/// Where perturbed image i goes.
#[derive(Clone)]
enum Destination {
    Folder {
        content: Arc<ContentWriter>,
        names: Arc<Vec<String>>,
    },
    File(PathBuf),
}

impl Destination {
    fn write(&self, index: usize, image: &RgbImage) -> Result<(), PipelineError> {
        match self {
            Self::Folder { content, names } => {
                let name = &names[index];
                let bytes = encode_rgb_like(&content.root().join(name), image, JPEG_QUALITY)?;
                Ok(content.write(name, &bytes)?)
            }
            Self::File(path) => {
                let bytes = encode_rgb_like(path, image, JPEG_QUALITY)?;
                std::fs::write(path, bytes).map_err(|e| CoreError::io(path, e))?;
                Ok(())
            }
        }
    }
}

/// Perturbs `file` into the file `out` (in its own format, no manifest); its spec was checked
/// by the job's plan ([`crate::settings::image_files`]).
pub(crate) fn perturb_one(
    ctx: &GpuContext,
    file: &Path,
    out: &Path,
    spec: &PerturbSpec,
    seed: u64,
    progress: &dyn Progress,
) -> Result<(), PipelineError> {
    let destination = Destination::File(out.to_path_buf());
    run_images(
        ctx,
        &[file.to_path_buf()],
        spec,
        seed,
        &[0],
        &destination,
        progress,
    )
}

/// A folder of images perturbed, planned: their names and the frame plan.
pub(crate) struct ImagesPerturb<'a> {
    files: &'a [PathBuf],
    spec: &'a PerturbSpec,
    seed: u64,
    names: Vec<String>,
    frames: usize,
    manifest: Manifest,
}

pub(crate) fn plan<'a>(
    files: &'a [PathBuf],
    spec: &'a PerturbSpec,
    seed: u64,
    command: &[String],
) -> Result<ImagesPerturb<'a>, PipelineError> {
    settings::check(spec, &settings::image_files())?;
    let names: Vec<String> = files
        .iter()
        .map(|f| {
            f.file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .ok_or_else(|| PipelineError::input(f, "an image path without a file name"))
        })
        .collect::<Result<_, _>>()?;
    let plan = FramePlan::images(files.len(), false, spec, seed);
    let manifest = ManifestParts {
        command,
        source: files
            .first()
            .and_then(|f| f.parent())
            .map(|p| p.display().to_string())
            .unwrap_or_default(),
        source_hash: String::new(),
        format: None,
        camera: None,
        distortion: None,
        depth_png: DepthPng::default(),
        bag: Default::default(),
        rate_hz: 0.0,
        seed,
        spec,
        plan: &plan,
        extra: serde_json::json!({ "files": names }),
    }
    .build()?;
    Ok(ImagesPerturb {
        files,
        spec,
        seed,
        names,
        frames: plan.len(),
        manifest,
    })
}

impl Planned for ImagesPerturb<'_> {
    fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    fn streams(&self) -> Streams {
        Streams::Frames(self.frames)
    }

    fn open<'a>(&'a self, ctx: &'a GpuContext) -> Result<Writing<'a>, PipelineError> {
        Ok(Box::new(move |out, found, manifest, progress| {
            let names = &self.names;
            let keep = found.keeps_written_frames(self.spec.stateful_item().is_some());
            let missing: Vec<usize> = (0..names.len())
                .filter(|&i| !keep || !out.join(&names[i]).is_file())
                .collect();
            let content = Arc::new(ContentWriter::new(out));
            let destination = Destination::Folder {
                content: content.clone(),
                names: Arc::new(names.clone()),
            };
            run_images(
                ctx,
                self.files,
                self.spec,
                self.seed,
                &missing,
                &destination,
                progress,
            )?;
            drop(destination);
            let content = Arc::try_unwrap(content)
                .map_err(|_| PipelineError::Worker("image writer still shared".into()))?;
            Ok(Written {
                made: missing.len(),
                manifest: content.finish(manifest)?,
            })
        }))
    }
}

/// Perturbs images `indices` of `files` (image i is frame i) into `destination`.
fn run_images(
    ctx: &GpuContext,
    files: &[PathBuf],
    spec: &PerturbSpec,
    seed: u64,
    indices: &[usize],
    destination: &Destination,
    progress: &dyn Progress,
) -> Result<(), PipelineError> {
    let sizes = indices
        .iter()
        .map(|&i| read_image_size(&files[i]))
        .collect::<Result<Vec<_>, _>>()?;
    let pool = EncoderPool::per_core();
    let images = Arc::new(ImagePool::default());
    progress.start(indices.len(), "perturbing");
    // Made once per image size, for every run of that size.
    let mut per_size: HashMap<(u32, u32), (Perturber, UploadAhead)> = HashMap::new();
    for run in runs_of_equal_size(&sizes) {
        let (width, height) = sizes[run.start];
        let (perturber, frames_ahead) = match per_size.entry((width, height)) {
            Entry::Occupied(e) => e.into_mut(),
            Entry::Vacant(e) => e.insert((
                // Image files carry no camera.
                Perturber::new(ctx, spec, width, height, seed, None)?,
                UploadAhead::new(width, height, false),
            )),
        };
        let sources: Vec<usize> = indices[run].to_vec();
        let paths: Vec<(usize, PathBuf)> = sources.iter().map(|&i| (i, files[i].clone())).collect();
        frames_ahead.start(ctx, paths, move |file, filler| {
            let color = read_rgb(file)?;
            if (color.width, color.height) != (width, height) {
                return Err(PipelineError::input(
                    file,
                    format!(
                        "image is {}x{} but its header says {width}x{height}",
                        color.width, color.height
                    ),
                ));
            }
            Ok(filler.fill(&color, None)?)
        });
        FrameRun {
            ctx,
            width,
            height,
            sources: &sources,
            with_depth: false,
            with_mask: false,
        }
        .run(
            progress,
            |index, encoder, frame| {
                frames_ahead.record(encoder, frame, index)?;
                perturber.encode(ctx, encoder, frame, index as u32)?;
                Ok(())
            },
            |frame| {
                let (destination, images) = (destination.clone(), images.clone());
                pool.submit(move || {
                    let color = frame.images.color.unpack(&images)?;
                    destination.write(frame.index, &color)?;
                    images.give_rgb(color);
                    Ok(())
                })
            },
        )?;
    }
    progress.finish();
    pool.finish()
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
