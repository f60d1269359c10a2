//! A perturbed copy of `MH_01_easy/`: a recorded EuRoC (ASL) dataset copied with its camera
//! frames corrupted and its IMU perturbed.
//!
//! Each camera is its own source (its PNGs decoded ahead), pipeline and sink, seeded with
//! [`camera_seed`]`(seed, i)` as a rendered rig's cameras are; frames keep their nanosecond
//! timestamps (moved by `cam_imu_offset`, file names with them), size and PNG colour type. With
//! no image corruption for a camera its PNGs are copied byte for byte. Image corruptions apply to
//! every camera or the one named (`cam1:fog:3`). IMU items apply to imu0's readings (from the
//! job's seed) and, where they change the true biases, to the ground truth. Calibration items in
//! `@calibration` mode change what the written calibration says (the sensor.yaml of each sensor
//! they move is written anew from its values with the perturbed `T_BS`, and ORB-SLAM3's settings
//! follow); the frames stay as recorded. Every other sensor.yaml, and the IMU readings and ground
//! truth that no item changed, are copied byte for byte (through the writer, so they are in the
//! checksum list). A recorded dataset cannot be re-rendered, so depth, trajectory, stream,
//! shutter and rendered-mode calibration items are refused.
//!
//! TUM-VI's EuRoC-style export (`dataset-room1_512_16/`) goes the same way with its own
//! calibration files ([`TumViFiles`]): no sensor.yaml or ORB-SLAM3 settings are written, the
//! manifest's layout is `tum-vi`. Its frames are 16-bit grey: a corrupted one is made from the
//! frame's high byte (the GPU frames are 8-bit, as OpenCV reads such a PNG into 8 bits) and
//! written 16-bit as 257 × its 8-bit value; the manifest says so. Frames of a camera without
//! image corruptions are copied byte for byte.

use std::path::Path;
use std::sync::Arc;

use rslam_core::dataset::euroc::{
    read_euroc, CameraColour, EurocCameraFrames, EurocDataset, EurocWriter, GROUND_TRUTH_DIR,
    IMU_DIR, MAV_DIR,
};
use rslam_core::dataset::{DepthPng, Manifest};
use rslam_core::CoreError;
use rslam_gpu::GpuContext;
use rslam_perturb::imu::{ImuOrigin, PerturbedImu};
use rslam_perturb::PerturbSpec;

use super::calibration::PerturbedRig;
use super::euroc_render::CameraFrames;
use super::imu_items::{camera_stamps, perturb_imu_stream, with_imu_report};
use super::preset::Rig;
use super::seeds::camera_seed;
use super::tum_vi_files::TumViFiles;
use crate::job::{Planned, Streams, Writing};
use crate::manifest::ManifestParts;
use crate::output_folder::Written;
use crate::pipeline::Pipeline;
use crate::plan::{FramePlan, SourceTiming};
use crate::progress::Progress;
use crate::sink::{finish_writer, frames_kept, RigCameraSink};
use crate::source::RecordedSource;
use crate::{settings, PipelineError};

/// Whether `path` is a EuRoC dataset: a folder holding `mav0/`, or `mav0/` itself.
pub fn is_euroc_input(path: &Path) -> bool {
    path.join(MAV_DIR).is_dir() || (path.file_name().is_some_and(|n| n == MAV_DIR) && path.is_dir())
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

/// How a camera's frames were written, for the manifest.
fn written_frames(colour: CameraColour, spec: &PerturbSpec) -> &'static str {
    match (spec.image.is_empty(), colour) {
        (true, _) => "copied byte for byte",
        (false, CameraColour::Grey16) => {
            "corrupted from each 16-bit sample's high byte (the GPU frames are 8-bit) and written 16-bit as 257 x the 8-bit result: the low byte is not kept"
        }
        (false, CameraColour::Grey | CameraColour::Rgb) => "corrupted",
    }
}

fn read_bytes(path: &Path) -> Result<Vec<u8>, PipelineError> {
    Ok(std::fs::read(path).map_err(|e| CoreError::io(path, e))?)
}

/// Copies the sensor.yaml of every sensor whose written calibration is the recorded one (the
/// writer makes the others from `written`; TUM-VI has none); writes the IMU readings and the
/// ground truth that the IMU items changed, and copies the others as they are.
fn write_sensor_files(
    dataset: &EurocDataset,
    written: &Rig,
    imu: Option<&PerturbedImu>,
    writer: &EurocWriter,
) -> Result<(), PipelineError> {
    let mav = &dataset.mav_dir;
    let copy = |sensor: &str, file: &str| -> Result<(), PipelineError> {
        let bytes = read_bytes(&mav.join(sensor).join(file))?;
        Ok(writer.copy_sensor_file(sensor, file, &bytes)?)
    };
    let sensor_yaml = dataset.tum_vi.is_none();
    for (camera, written) in dataset.cameras.iter().zip(&written.cameras) {
        if sensor_yaml && camera.camera == *written {
            copy(&camera.camera.name, "sensor.yaml")?;
        }
    }
    if let Some(recorded) = &dataset.imu {
        if sensor_yaml && written.imu.as_ref() == Some(&recorded.imu) {
            copy(IMU_DIR, "sensor.yaml")?;
        }
        match imu.filter(|p| p.samples_changed) {
            Some(perturbed) => writer.write_imu(&perturbed.samples)?,
            None => copy(IMU_DIR, "data.csv")?,
        }
    }
    if dataset.ground_truth.is_some() {
        match imu.filter(|p| p.ground_truth_changed) {
            Some(perturbed) => writer.write_ground_truth(&perturbed.ground_truth)?,
            None => copy(GROUND_TRUTH_DIR, "data.csv")?,
        }
    }
    Ok(())
}

/// The IMU items applied to imu0 (`None` without IMU items); refused without imu0.
fn perturb_recorded_imu(
    dataset: &EurocDataset,
    spec: &PerturbSpec,
    seed: u64,
) -> Result<Option<PerturbedImu>, PipelineError> {
    let Some(imu) = &dataset.imu else {
        return Ok(None);
    };
    if spec.imu.is_empty() {
        return Ok(None);
    }
    let ground_truth = dataset.ground_truth.as_deref().unwrap_or_default();
    let perturbed = perturb_imu_stream(
        spec,
        &imu.samples,
        ground_truth,
        imu.imu.rate_hz,
        ImuOrigin::Recorded(imu.imu.noise()),
        seed,
    )?;
    Ok(Some(perturbed))
}

/// Camera `index`'s frames after the first `kept` (an interrupted run's, already there),
/// written at `times_ns`: copied as they are when its spec has no image corruption, else
/// through the GPU pipeline.
fn write_camera(
    ctx: &GpuContext,
    spec: &PerturbSpec,
    camera: &EurocCameraFrames,
    (index, seed, kept): (usize, u64, usize),
    times_ns: Vec<u64>,
    writer: &Arc<EurocWriter>,
    progress: &dyn Progress,
) -> Result<Option<RigCameraSink>, PipelineError> {
    if spec.image.is_empty() {
        for (frame, &t_ns) in camera.frames.iter().zip(&times_ns).skip(kept) {
            writer.copy_frame_ns(index, t_ns, &read_bytes(&frame.path)?)?;
            progress.advance()?;
        }
        return Ok(None);
    }
    let source = RecordedSource::euroc_camera(camera);
    let mut pipeline = Pipeline::new(ctx, source, spec, seed)?;
    let mut sink = RigCameraSink::new(writer.clone(), index, times_ns);
    let sources: Vec<usize> = (kept..camera.frames.len()).collect();
    pipeline.run(ctx, &sources, progress, &mut sink)?;
    Ok(Some(sink))
}

/// A EuRoC perturb, planned: the dataset read, its IMU perturbed, the calibration as written.
pub(crate) struct EurocPerturb<'a> {
    spec: &'a PerturbSpec,
    dataset: EurocDataset,
    perturbed: PerturbedRig,
    seeds: Vec<u64>,
    specs: Vec<PerturbSpec>,
    imu: Option<PerturbedImu>,
    stamps: Vec<Vec<u64>>,
    imu_samples: usize,
    tum_vi: Option<TumViFiles>,
    manifest: Manifest,
}

pub(crate) fn plan<'a>(
    input: &Path,
    spec: &'a PerturbSpec,
    seed: u64,
    command: &[String],
) -> Result<EurocPerturb<'a>, PipelineError> {
    let dataset = read_euroc(input)?;
    settings::check(spec, &settings::recorded_euroc(&dataset))?;
    let Some(cam0) = dataset.cameras.first() else {
        return Err(PipelineError::input(
            &dataset.mav_dir,
            "no camera folder (cam0/ …): nothing to perturb",
        ));
    };
    check_file_names(&dataset)?;
    let recorded = Rig {
        name: "recorded".into(),
        cameras: dataset.cameras.iter().map(|c| c.camera.clone()).collect(),
        time_offsets_ns: vec![0; dataset.cameras.len()],
        imu: dataset.imu.as_ref().map(|imu| imu.imu.clone()),
        bag_names: Default::default(),
    };
    let perturbed = PerturbedRig::new(&recorded, spec, seed)?;
    let seeds: Vec<u64> = (0..dataset.cameras.len())
        .map(|i| camera_seed(seed, i))
        .collect();
    let specs: Vec<PerturbSpec> = dataset
        .cameras
        .iter()
        .map(|c| spec.for_camera(&c.camera.name))
        .collect();
    let cam0_times = times_s(cam0);
    let cam0_plan = FramePlan::recorded(
        &SourceTiming {
            rgb_times: &cam0_times,
            depth_offsets: &vec![0.0; cam0_times.len()],
            rate_hz: cam0.camera.rate_hz,
        },
        &specs[0],
        seeds[0],
    );
    let imu = perturb_recorded_imu(&dataset, spec, seed)?;
    let stamps = dataset
        .cameras
        .iter()
        .map(|c| {
            let times: Vec<u64> = c.frames.iter().map(|f| f.t_ns).collect();
            camera_stamps(spec, &c.camera.name, &times)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let imu_samples = match (&imu, &dataset.imu) {
        (Some(perturbed), _) => perturbed.samples.len(),
        (None, recorded) => recorded.as_ref().map_or(0, |r| r.samples.len()),
    };
    let imu_changed = imu.as_ref().is_some_and(|p| p.samples_changed);
    let tum_vi = match &dataset.tum_vi {
        Some(calibration) => Some(TumViFiles::plan(
            &dataset,
            calibration,
            &perturbed.written,
            imu_changed,
        )?),
        None => None,
    };
    let mut extra = serde_json::json!({
        "layout": if tum_vi.is_some() { "tum-vi" } else { "euroc" },
        "input": "recorded",
        "cameras": dataset.cameras.iter().zip(&seeds).zip(&specs).map(|((c, seed), spec)| serde_json::json!({
            "name": c.camera.name,
            "frames": c.frames.len(),
            "rate_hz": c.camera.rate_hz,
            "seed": seed,
            "written_frames": written_frames(c.camera.colour, spec),
        })).collect::<Vec<_>>(),
        "imu": dataset.imu.as_ref().map(|_| serde_json::json!({
            "samples": imu_samples,
            "copied": !imu_changed,
        })),
        "ground_truth_copied": dataset.ground_truth.is_some()
            && !imu.as_ref().is_some_and(|p| p.ground_truth_changed),
    });
    if !spec.calibration.is_empty() {
        extra["calibration"] = perturbed.record(&recorded);
    }
    if let Some(files) = &tum_vi {
        extra["tum_vi"] = files.record();
    }
    if dataset.ground_truth.is_none() && imu.as_ref().is_some_and(|p| p.ground_truth_changed) {
        extra["imu_biases_in_ground_truth"] = serde_json::json!(
            "not written: the input has no ground truth with biases (state_groundtruth_estimate0/), so the biases the IMU items added are recorded here only"
        );
    }
    let manifest = ManifestParts {
        command,
        source: input.display().to_string(),
        source_hash: String::new(),
        format: None,
        camera: Some(cam0.camera.intrinsics),
        distortion: None,
        depth_png: DepthPng::default(),
        bag: Default::default(),
        rate_hz: cam0.camera.rate_hz,
        seed,
        spec,
        plan: &cam0_plan,
        extra,
    }
    .build()?;
    let manifest = with_imu_report(manifest, imu.as_ref().map(|p| &p.report))?;
    Ok(EurocPerturb {
        spec,
        dataset,
        perturbed,
        seeds,
        specs,
        imu,
        stamps,
        imu_samples,
        tum_vi,
        manifest,
    })
}

impl Planned for EurocPerturb<'_> {
    fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    fn streams(&self) -> Streams {
        Streams::Rig {
            cameras: self
                .dataset
                .cameras
                .iter()
                .map(|c| CameraFrames {
                    name: c.camera.name.clone(),
                    frames: c.frames.len(),
                })
                .collect(),
            imu_samples: self.imu_samples,
        }
    }

    fn open<'a>(&'a self, ctx: &'a GpuContext) -> Result<Writing<'a>, PipelineError> {
        Ok(Box::new(move |out, found, manifest, progress| {
            let (dataset, perturbed) = (&self.dataset, &self.perturbed);
            let (cameras_written, imu_written) = (
                perturbed.written.cameras.clone(),
                perturbed.written.imu.clone(),
            );
            let writer = Arc::new(match self.tum_vi {
                Some(_) => {
                    EurocWriter::open_calibration_elsewhere(out, cameras_written, imu_written)?
                }
                None => EurocWriter::open(out, cameras_written, imu_written)?,
            });
            // A resumed run keeps each camera's frames up to the first one missing.
            let keep = found.keeps_written_frames(self.spec.stateful_item().is_some());
            let (kept, made) = frames_kept(&writer, &self.stamps, keep)?;
            progress.start(made, "perturbing");
            let mut sinks = Vec::new();
            for (i, (((camera, &seed), times_ns), spec)) in dataset
                .cameras
                .iter()
                .zip(&self.seeds)
                .zip(self.stamps.iter().cloned())
                .zip(&self.specs)
                .enumerate()
            {
                let at = (i, seed, kept[i]);
                sinks.extend(write_camera(
                    ctx, spec, camera, at, times_ns, &writer, progress,
                )?);
            }
            for sink in sinks {
                sink.finish()?;
            }
            progress.finish();

            write_sensor_files(dataset, &perturbed.written, self.imu.as_ref(), &writer)?;
            if let Some(files) = &self.tum_vi {
                files.write(&writer)?;
            }
            Ok(Written {
                made,
                manifest: finish_writer(writer, manifest)?,
            })
        }))
    }
}
