//! `rslam perturb --input MH_01_easy/`: a recorded EuRoC (ASL) dataset copied with its camera
//! frames corrupted.
//!
//! Each camera is its own source (its PNGs decoded ahead), pipeline and sink, seeded with
//! [`camera_seed`]`(seed, i)` as a rendered rig's cameras are; frames keep their nanosecond
//! timestamps, file names, size and PNG colour type. Every sensor.yaml, the IMU readings and the
//! ground truth are copied byte for byte (through the writer, so they are in the checksum list);
//! ORB-SLAM3's settings are made from the cameras' and IMU's values. Only image corruptions
//! apply for now: depth, trajectory, stream and shutter items are refused.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use rslam_core::dataset::euroc::{
    read_euroc, EurocCameraFrames, EurocDataset, EurocWriter, GROUND_TRUTH_DIR, IMU_DIR, MAV_DIR,
};
use rslam_core::dataset::{DepthPng, Manifest};
use rslam_core::CoreError;
use rslam_gpu::GpuContext;
use rslam_perturb::PerturbSpec;

use super::camera_sink::EurocCameraSink;
use super::euroc_render::{camera_seed, CameraFrames, RigReport};
use super::euroc_source::EurocCameraSource;
use super::output;
use crate::manifest::ManifestParts;
use crate::output_folder::{self, FolderState};
use crate::pipeline::Pipeline;
use crate::plan::{FramePlan, SourceTiming};
use crate::progress::Progress;
use crate::PipelineError;

/// One perturbed copy of a EuRoC dataset.
pub struct PerturbEurocJob {
    /// The folder holding `mav0/`, or `mav0/` itself.
    pub input: PathBuf,
    pub out: PathBuf,
    pub spec: PerturbSpec,
    pub seed: u64,
    /// Replace whatever rslam output `out` holds.
    pub force: bool,
    /// The command as typed, for the manifest.
    pub command: Vec<String>,
}

/// Whether `path` is a EuRoC dataset: a folder holding `mav0/`, or `mav0/` itself.
pub fn is_euroc_input(path: &Path) -> bool {
    path.join(MAV_DIR).is_dir() || (path.file_name().is_some_and(|n| n == MAV_DIR) && path.is_dir())
}

/// Refuses every item that is not an image corruption, naming the first one.
pub fn check_euroc_spec(spec: &PerturbSpec) -> Result<(), PipelineError> {
    let mut others = spec.scene_items();
    others.extend(spec.depth.iter().map(|item| item.to_string()));
    others.extend(spec.fast.map(|k| format!("fast:{k}")));
    others.extend(spec.misalign.map(|m| format!("misalign:{}", m.frames)));
    match others.first() {
        Some(item) => Err(PipelineError::option(
            "--perturb",
            format!("'{item}': EuRoC inputs take image corruptions only for now (no depth, trajectory, stream or shutter items); see `rslam list`"),
        )),
        None => Ok(()),
    }
}

/// Seconds from the camera's nanosecond stamps, for the frame plan (its times are not written:
/// the frames keep their stamps).
fn times_s(camera: &EurocCameraFrames) -> Vec<f64> {
    camera.frames.iter().map(|f| f.t_ns as f64 * 1e-9).collect()
}

/// Frames keep their file names, which the writer makes from the stamps: refuse a frame whose
/// name is not `<t_ns>.png`.
fn check_file_names(dataset: &EurocDataset) -> Result<(), PipelineError> {
    for camera in &dataset.cameras {
        for frame in &camera.frames {
            let expected = format!("{}.png", frame.t_ns);
            if frame.path.file_name().is_none_or(|n| *n != *expected) {
                return Err(PipelineError::input(
                    &frame.path,
                    format!("{}: expected the frame's file to be named {expected}, as its data.csv timestamp", camera.camera.name),
                ));
            }
        }
    }
    Ok(())
}

fn read_bytes(path: &Path) -> Result<Vec<u8>, PipelineError> {
    Ok(std::fs::read(path).map_err(|e| CoreError::io(path, e))?)
}

/// Copies every sensor.yaml, the IMU readings and the ground truth as they are.
fn copy_sensor_files(dataset: &EurocDataset, writer: &EurocWriter) -> Result<(), PipelineError> {
    let mav = &dataset.mav_dir;
    for camera in &dataset.cameras {
        let name = &camera.camera.name;
        let bytes = read_bytes(&mav.join(name).join("sensor.yaml"))?;
        writer.copy_sensor_file(name, "sensor.yaml", &bytes)?;
    }
    if dataset.imu.is_some() {
        for file in ["sensor.yaml", "data.csv"] {
            let bytes = read_bytes(&mav.join(IMU_DIR).join(file))?;
            writer.copy_sensor_file(IMU_DIR, file, &bytes)?;
        }
    }
    if dataset.ground_truth.is_some() {
        let bytes = read_bytes(&mav.join(GROUND_TRUTH_DIR).join("data.csv"))?;
        writer.copy_sensor_file(GROUND_TRUTH_DIR, "data.csv", &bytes)?;
    }
    Ok(())
}

pub fn perturb_euroc(
    ctx: &GpuContext,
    job: &PerturbEurocJob,
    progress: &dyn Progress,
) -> Result<RigReport, PipelineError> {
    output_folder::check_not_input(&job.out, &job.input)?;
    check_euroc_spec(&job.spec)?;
    let dataset = read_euroc(&job.input)?;
    let Some(cam0) = dataset.cameras.first() else {
        return Err(PipelineError::input(
            &dataset.mav_dir,
            "no camera folder (cam0/ …): nothing to perturb",
        ));
    };
    check_file_names(&dataset)?;
    let seeds: Vec<u64> = (0..dataset.cameras.len())
        .map(|i| camera_seed(job.seed, i))
        .collect();
    let cam0_times = times_s(cam0);
    let cam0_plan = FramePlan::recorded(
        &SourceTiming {
            rgb_times: &cam0_times,
            depth_offsets: &vec![0.0; cam0_times.len()],
            rate_hz: cam0.camera.rate_hz,
        },
        &job.spec,
        seeds[0],
    );
    let imu_samples = dataset.imu.as_ref().map_or(0, |imu| imu.samples.len());
    let manifest = ManifestParts {
        command: &job.command,
        source: job.input.display().to_string(),
        source_hash: String::new(),
        format: None,
        camera: Some(cam0.camera.intrinsics),
        distortion: None,
        depth_png: DepthPng::default(),
        rate_hz: cam0.camera.rate_hz,
        seed: job.seed,
        spec: &job.spec,
        plan: &cam0_plan,
        extra: serde_json::json!({
            "adapter": ctx.describe(),
            "layout": "euroc",
            "input": "recorded",
            "cameras": dataset.cameras.iter().zip(&seeds).map(|(c, seed)| serde_json::json!({
                "name": c.camera.name,
                "frames": c.frames.len(),
                "rate_hz": c.camera.rate_hz,
                "seed": seed,
            })).collect::<Vec<_>>(),
            "imu": dataset.imu.as_ref().map(|_| serde_json::json!({
                "samples": imu_samples,
                "copied": true,
            })),
            "ground_truth_copied": dataset.ground_truth.is_some(),
        }),
    }
    .build()?;
    let cameras: Vec<CameraFrames> = dataset
        .cameras
        .iter()
        .map(|c| CameraFrames {
            name: c.camera.name.clone(),
            frames: c.frames.len(),
        })
        .collect();

    let found = output::prepare(&job.out, &manifest, job.force)?;
    if found == FolderState::Complete {
        return Ok(RigReport {
            cameras,
            imu_samples,
            found,
            manifest: Manifest::read(&job.out)?,
        });
    }
    let writer = Arc::new(EurocWriter::open(
        &job.out,
        dataset.cameras.iter().map(|c| c.camera.clone()).collect(),
        dataset.imu.as_ref().map(|imu| imu.imu.clone()),
    )?);

    progress.start(cameras.iter().map(|c| c.frames).sum(), "perturbing");
    let mut sinks = Vec::new();
    for (i, (camera, &seed)) in dataset.cameras.iter().zip(&seeds).enumerate() {
        let source = EurocCameraSource::new(camera.frames.clone(), camera.camera.intrinsics);
        let mut pipeline = Pipeline::new(ctx, source, &job.spec, seed)?;
        let times_ns = camera.frames.iter().map(|f| f.t_ns).collect();
        let mut sink = EurocCameraSink::new(writer.clone(), i, times_ns);
        let sources: Vec<usize> = (0..camera.frames.len()).collect();
        pipeline.run(ctx, &sources, progress, &mut sink)?;
        sinks.push(sink);
    }
    for sink in sinks {
        sink.finish()?;
    }
    progress.finish();

    copy_sensor_files(&dataset, &writer)?;
    let writer = Arc::try_unwrap(writer)
        .map_err(|_| PipelineError::Worker("EuRoC writer still shared".into()))?;
    let manifest = writer.finish(manifest)?;
    output_folder::finish(&job.out)?;
    Ok(RigReport {
        cameras,
        imu_samples,
        found,
        manifest,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_image_corruptions_pass_and_the_first_other_item_is_named() {
        check_euroc_spec(&PerturbSpec::parse("gaussian_noise:3,fog:2@dynamic").unwrap()).unwrap();
        for (text, item) in [
            ("fog:2,depth_noise:3", "depth_noise:3"),
            ("fast:2", "fast:2"),
            ("misalign:4", "misalign:4"),
            ("rot:1", "rot:1"),
            ("exposure:20", "exposure:20"),
        ] {
            let spec = PerturbSpec::parse(text).unwrap();
            let err = check_euroc_spec(&spec).unwrap_err().to_string();
            assert!(
                err.starts_with(&format!(
                    "--perturb: '{item}': EuRoC inputs take image corruptions only for now"
                )),
                "{err}"
            );
            assert!(!err.contains('\n'), "{err}");
        }
    }
}
