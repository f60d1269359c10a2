//! A rig render in the EuRoC layout: a scene seen by every camera of a rig, with the
//! rig's IMU, written in the EuRoC layout.
//!
//! The scene's path (or a trajectory file) is cam0's path, so cam0 sees what the path was made to show;
//! the body (= the IMU, as in EuRoC) follows it at `body_from_cam0⁻¹`. A cubic B-spline through
//! the body's poses gives its motion at any time; each camera samples it at its own rate over
//! the spline's valid range, the IMU at its rate. Each camera is its own source, pipeline and
//! sink on the GPU; frames are read back once and encoded on a worker thread.

use std::sync::Arc;

use rslam_core::dataset::euroc::{EurocWriter, RadialTangential};
use rslam_core::dataset::ros2::BagOptions;
use rslam_core::dataset::ros2::RigBag;
use rslam_core::dataset::{ContentWriter, DatasetFormat, DepthPng, Layout, Manifest};
use rslam_core::{Distortion, Pose, SplineSe3};
use rslam_gpu::GpuContext;
use rslam_perturb::imu::shift_stamp;
use rslam_perturb::PerturbSpec;

use super::calibration::{PerturbedRig, PER_FRAME_FILE};
use super::imu_items::{camera_stamps, with_imu_report};
use super::imu_stream::{imu_and_ground_truth, ImuStreams};
use super::motion::{body_path, camera_poses, motion_spline, nanoseconds, sample_times};
use super::preset::Rig;
use super::seeds::{camera_seed, imu_seed};
use crate::agents::record_agent;
use crate::job::{Planned, Streams, Writing};
use crate::manifest::ManifestParts;
use crate::output_folder::Written;
use crate::pipeline::Pipeline;
use crate::plan::{camera_frame_spec, speed_up, FramePlan};
use crate::progress::Progress;
use crate::scene_job::{ResolvedScene, SceneCache, SceneJob};
use crate::sink::{finish_writer, frames_kept, seal_bag, RigCameraSink, RigFrameWriter};
use crate::source::SceneSource;
use crate::{scene_actors, scene_light};
use crate::{JobPart, PipelineError};

/// Frames one camera has in the output.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CameraFrames {
    /// `cam0`, `cam1`, …
    pub name: String,
    pub frames: usize,
}

/// `rig` seen through the spec's lens: every camera's distortion is its coefficients (radtan,
/// as [`crate::settings::euroc_rig_render`] lets through), so that sensor.yaml and ORB-SLAM3's settings state it.
fn through_lens(rig: &Rig, spec: &PerturbSpec) -> Rig {
    let mut rig = rig.clone();
    if let Some(Distortion::Radtan { k1, k2, p1, p2 }) = spec.distortion {
        for camera in &mut rig.cameras {
            camera.distortion = RadialTangential { k1, k2, p1, p2 };
        }
    }
    rig
}

/// One camera's part of the run.
struct CameraRun {
    times_s: Vec<f64>,
    seed: u64,
    /// The job's spec as it applies to this camera's frames.
    spec: PerturbSpec,
}

/// The frames each camera of `rig` gets from a path of `poses` poses evenly spaced at
/// `path_rate_hz`, played `speed_up` times faster ([`crate::plan::speed_up`]), as
/// a rig render samples them, without the scene (for a plan).
pub fn rig_camera_frames(
    rig: &Rig,
    poses: usize,
    path_rate_hz: f64,
    speed_up: u32,
) -> Result<Vec<CameraFrames>, PipelineError> {
    let times: Vec<f64> = (0..poses).map(|i| i as f64 / path_rate_hz).collect();
    let path = vec![Pose::IDENTITY; poses];
    let spline = motion_spline(&body_path(&times, &path, speed_up, &Pose::IDENTITY))?;
    Ok(rig
        .cameras
        .iter()
        .map(|camera| CameraFrames {
            name: camera.name.clone(),
            frames: sample_times(&spline, camera.rate_hz).len(),
        })
        .collect())
}

/// A rig render, planned: the scene loaded, the body's motion, each camera's capture times,
/// the IMU's readings and the body's ground truth.
pub(crate) struct RigRender<'a> {
    scene: &'a SceneJob,
    /// The rig through the spec's lens.
    rig: Rig,
    perturbed: PerturbedRig,
    resolved: ResolvedScene,
    spline: SplineSe3,
    runs: Vec<CameraRun>,
    streams: ImuStreams,
    /// The EuRoC layout, or a ROS 2 bag (`Camera(Ros2)`).
    layout: Layout,
    manifest: Manifest,
}

pub(crate) fn plan<'a>(
    scene: &'a SceneJob,
    rig: &Rig,
    layout: Layout,
    bag: BagOptions,
    command: &[String],
    scenes: &SceneCache,
) -> Result<RigRender<'a>, PipelineError> {
    let rig = through_lens(rig, &scene.spec);
    let Some(cam0) = rig.cameras.first() else {
        return Err(PipelineError::option(JobPart::Rig, "the rig has no camera"));
    };
    let perturbed = PerturbedRig::new(&rig, &scene.spec, scene.seed)?;
    let resolved = scene.resolve_in(scenes)?;
    scene.require_metres(&resolved.scene, "a rig's extrinsics and IMU are")?;
    let spline = motion_spline(&body_path(
        &resolved.clean.timestamps,
        &resolved.poses,
        speed_up(&scene.spec),
        &cam0.body_from_camera,
    ))?;
    let runs: Vec<CameraRun> = rig
        .cameras
        .iter()
        .enumerate()
        .map(|(i, camera)| CameraRun {
            times_s: sample_times(&spline, camera.rate_hz),
            seed: camera_seed(scene.seed, i),
            spec: camera_frame_spec(&scene.spec, &camera.name),
        })
        .collect();
    let cam0_plan = FramePlan::rendered(
        runs[0].times_s.len(),
        cam0.rate_hz,
        &runs[0].spec,
        runs[0].seed,
    );
    let imu_seed = imu_seed(scene.seed);
    let streams = imu_and_ground_truth(
        scene,
        perturbed.actual.imu.as_ref(),
        &spline,
        &runs[0].times_s,
    )?;
    let mut extra = serde_json::json!({
        "layout": "euroc",
        "rig": rig.name,
        "path_rate_hz": scene.rate_hz,
        "cameras": rig.cameras.iter().zip(&runs).zip(&rig.time_offsets_ns).map(|((c, r), &offset_ns)| {
            let mut camera = serde_json::json!({
                "name": c.name,
                "frames": r.times_s.len(),
                "rate_hz": c.rate_hz,
                "seed": r.seed,
            });
            if offset_ns != 0 {
                camera["time_offset_ns"] = offset_ns.into();
            }
            camera
        }).collect::<Vec<_>>(),
        "imu": rig.imu.as_ref().map(|imu| serde_json::json!({
            "rate_hz": imu.rate_hz,
            "seed": imu_seed,
        })),
    });
    record_agent(&mut extra, scene);
    scene.record_capture(&mut extra, &resolved.scene);
    scene_light::record(
        &mut extra,
        &resolved.scene,
        &scene.spec,
        scene.seed,
        &cam0_plan,
    )?;
    scene_actors::record(&mut extra, resolved.actors.as_deref(), &cam0_plan);
    if layout == Layout::Camera(DatasetFormat::Ros2) && !rig.bag_names.is_default() {
        extra["ros2_names"] = serde_json::to_value(&rig.bag_names)
            .map_err(|e| PipelineError::Worker(format!("bag names for the manifest: {e}")))?;
    }
    if !scene.spec.calibration.is_empty() {
        extra["calibration"] = perturbed.record(&rig);
    }
    let manifest = ManifestParts {
        command,
        source: resolved.scene.name.clone(),
        source_hash: resolved.source_hash().to_string(),
        format: (layout == Layout::Camera(DatasetFormat::Ros2)).then_some(DatasetFormat::Ros2),
        camera: Some(cam0.intrinsics),
        distortion: scene.spec.distortion,
        depth_png: DepthPng::default(),
        bag,
        rate_hz: cam0.rate_hz,
        seed: scene.seed,
        spec: &scene.spec,
        plan: &cam0_plan,
        extra,
    }
    .build()?;
    let manifest = with_imu_report(manifest, streams.report.as_ref())?;
    Ok(RigRender {
        scene,
        rig,
        perturbed,
        resolved,
        spline,
        runs,
        streams,
        layout,
        manifest,
    })
}

impl Planned for RigRender<'_> {
    fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    fn streams(&self) -> Streams {
        Streams::Rig {
            cameras: self
                .rig
                .cameras
                .iter()
                .zip(&self.runs)
                .map(|(c, r)| CameraFrames {
                    name: c.name.clone(),
                    frames: r.times_s.len(),
                })
                .collect(),
            imu_samples: self.streams.imu.len(),
        }
    }

    fn open<'a>(&'a self, ctx: &'a GpuContext) -> Result<Writing<'a>, PipelineError> {
        if self.layout == Layout::Camera(DatasetFormat::Ros2) {
            return Ok(self.bag_writing(ctx));
        }
        Ok(Box::new(move |out, found, manifest, progress| {
            let (rig, perturbed, spec) = (&self.rig, &self.perturbed, &self.scene.spec);
            let mut writer = EurocWriter::open(
                out,
                perturbed.written.cameras.clone(),
                perturbed.written.imu.clone(),
            )?;
            if self.resolved.actors.is_some() {
                writer = writer.with_masks()?;
            }
            let writer = Arc::new(writer);
            let stamps = self.stamps()?;
            // A resumed run keeps each camera's frames up to the first one missing.
            let keep = found.keeps_written_frames(spec.stateful_item().is_some());
            let (kept, made) = frames_kept(&writer, &stamps, keep)?;
            progress.start(made, "rendering");
            if let Some(csv) = perturbed.per_frame_csv(&stamps[0]) {
                writer.write_record(PER_FRAME_FILE, csv.as_bytes())?;
            }
            self.draw_cameras(ctx, writer.clone(), stamps, &kept, progress)?;
            progress.finish();

            if rig.imu.is_some() {
                writer.write_imu(&self.streams.imu)?;
            }
            writer.write_ground_truth(&self.streams.ground_truth)?;
            Ok(Written {
                made,
                manifest: finish_writer(writer, manifest)?,
            })
        }))
    }
}

impl RigRender<'_> {
    /// Each camera's frame stamps: its capture times on its clock, moved by the spec's
    /// `cam_imu_offset`.
    fn stamps(&self) -> Result<Vec<Vec<u64>>, PipelineError> {
        let rig = &self.rig;
        rig.cameras
            .iter()
            .zip(&self.runs)
            .enumerate()
            .map(|(i, (camera, run))| {
                let clock = clock_stamps(rig, i, &run.times_s)?;
                camera_stamps(&self.scene.spec, &camera.name, &clock)
            })
            .collect()
    }

    /// Draws camera `i`'s frames from `kept[i]` on into `writer`, stamped `stamps[i]`, one
    /// camera after another.
    fn draw_cameras(
        &self,
        ctx: &GpuContext,
        writer: Arc<dyn RigFrameWriter>,
        stamps: Vec<Vec<u64>>,
        kept: &[usize],
        progress: &dyn Progress,
    ) -> Result<(), PipelineError> {
        let (rig, perturbed) = (&self.rig, &self.perturbed);
        let mut sinks = Vec::new();
        for (i, ((camera, run), times_ns)) in
            rig.cameras.iter().zip(&self.runs).zip(stamps).enumerate()
        {
            let poses = camera_poses(
                &self.spline,
                |k| perturbed.body_from_camera(i, k),
                &run.times_s,
            )?;
            let mut source = SceneSource::new(
                ctx,
                &self.resolved.scene,
                camera.intrinsics,
                poses,
                self.scene.capture.settings,
                self.resolved.actors.clone(),
            )?;
            source.set_times(run.times_s.clone());
            source.set_sensor(ctx, &run.spec, camera.rate_hz, self.scene.seed)?;
            let mut pipeline = Pipeline::new(ctx, source, &run.spec, run.seed)?;
            let mut sink = RigCameraSink::new(writer.clone(), i, times_ns);
            let sources: Vec<usize> = (kept[i]..run.times_s.len()).collect();
            pipeline.run(ctx, &sources, progress, &mut sink)?;
            sinks.push(sink);
        }
        for sink in sinks {
            sink.finish()?;
        }
        Ok(())
    }

    /// A ROS 2 bag of the rig ([`RigBag`]), written from its first frame on every run; a
    /// `@dynamic` calibration's per-frame record is not in it.
    fn bag_writing<'a>(&'a self, ctx: &'a GpuContext) -> Writing<'a> {
        Box::new(move |out, _found, manifest, progress| {
            let written = &self.perturbed.written;
            let bag = Arc::new(RigBag::create(
                out,
                written.cameras.clone(),
                written.imu.clone(),
                manifest.bag,
                self.rig.bag_names.clone(),
            )?);
            let stamps = self.stamps()?;
            let made = stamps.iter().map(Vec::len).sum();
            progress.start(made, "rendering");
            let kept = vec![0; stamps.len()];
            self.draw_cameras(ctx, bag.clone(), stamps, &kept, progress)?;
            progress.finish();
            let bag = Arc::try_unwrap(bag)
                .map_err(|_| PipelineError::Worker("the rig bag is still shared".into()))?;
            let closed = bag.finish(&self.streams.imu, &self.streams.ground_truth)?;
            Ok(Written {
                made,
                manifest: seal_bag(ContentWriter::new(out), closed, manifest)?,
            })
        })
    }
}

/// Camera `index`'s stamps of frames captured at `times_s`: on its own clock, which runs ahead of
/// the body's by the rig's time offset for it.
fn clock_stamps(rig: &Rig, index: usize, times_s: &[f64]) -> Result<Vec<u64>, PipelineError> {
    let offset_ns = rig.time_offsets_ns.get(index).copied().unwrap_or(0);
    times_s
        .iter()
        .map(|&t| {
            let t_ns = nanoseconds(t)?;
            shift_stamp(t_ns, offset_ns).ok_or_else(|| {
                PipelineError::option(
                    JobPart::Rig,
                    format!(
                        "{}: time_offset_ms {} puts its frame at {t_ns} ns before 0 ns",
                        rig.cameras[index].name,
                        offset_ns as f64 / 1e6
                    ),
                )
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plan_counts_the_frames_a_render_samples() {
        // 400 poses at 20 Hz: the spline is valid over 397 / 20 s, sampled at 20 Hz both ends
        // included (the 398 frames per camera of a stereo-imu render of 400 poses).
        let frames = rig_camera_frames(&Rig::stereo_imu(), 400, 20.0, 1).unwrap();
        let counted: Vec<(&str, usize)> =
            frames.iter().map(|c| (c.name.as_str(), c.frames)).collect();
        assert_eq!(counted, [("cam0", 398), ("cam1", 398)]);
        // the path's rate matters, not only its length: 400 poses at 40 Hz last half as long
        assert_eq!(
            rig_camera_frames(&Rig::stereo(), 400, 40.0, 1).unwrap()[0].frames,
            199
        );
        let err = rig_camera_frames(&Rig::stereo(), 3, 20.0, 1)
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("frames: 3 poses"), "{err}");
    }

    #[test]
    fn fast_plays_the_path_faster_so_each_camera_gets_fewer_frames() {
        // 400 poses at 20 Hz played twice as fast: a spline valid over 397 / 40 s, sampled at
        // 20 Hz both ends included.
        let frames = rig_camera_frames(&Rig::stereo(), 400, 20.0, 2).unwrap();
        assert_eq!(frames[0].frames, 199);
        assert_eq!(frames[1].frames, 199);
    }
}
