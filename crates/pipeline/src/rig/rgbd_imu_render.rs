//! The `rgbd-imu` rig in the TUM layout: one RGB-D camera (the job's camera, at the path's
//! rate) on a RealSense D435i-like body with its IMU, written in the TUM layout as a one-camera
//! render writes it, plus the IMU and the body's ground truth as the EuRoC layout has them
//! (`imu0/data.csv`, `imu0/sensor.yaml`, `state_groundtruth_estimate0/data.csv`) and ORB-SLAM3's
//! RGB-D-inertial settings (`orbslam3_rgbd_inertial.yaml`); or in a ROS 2 bag, the IMU's
//! readings on `/imu0` between the frames and its pose on `/tf_static`.
//!
//! The motion is the EuRoC rig render's: the path (the scene's or a trajectory file) is the camera's, the
//! body follows it at `body_from_camera⁻¹` along a cubic B-spline, the camera samples it at its
//! rate and the IMU at 200 Hz over the spline's valid range, both from its start (a camera frame
//! every 1/rate s, an IMU sample every 5 ms; no frame after the IMU's last sample). `groundtruth.txt` is the camera's
//! pose at each frame's capture time; under `cam_imu_offset` the frames' stamps move and it does
//! not (its clock is the IMU's, as the body's ground truth).

use rslam_core::dataset::euroc::{inertial_files, EurocCamera, EurocImu, ImuSample};
use rslam_core::dataset::ros2::{variances, BagImu, BagOptions};
use rslam_core::dataset::{rgbd_inertial_settings, DatasetFormat, DepthPng, Manifest};
use rslam_core::{Pose, SplineSe3, Trajectory};
use rslam_gpu::GpuContext;
use rslam_perturb::PerturbSpec;

use super::calibration::{PerturbedRig, PER_FRAME_FILE};
use super::imu_items::{camera_stamps, with_imu_report};
use super::imu_stream::imu_and_ground_truth;
use super::motion::{body_path, camera_poses, motion_spline, nanoseconds, sample_times};
use super::preset::Rig;
use super::seeds::imu_seed;
use crate::agents::record_agent;
use crate::dataset_run::{dataset_writing, DatasetOutput};
use crate::job::{Planned, Streams, Writing};
use crate::manifest::ManifestParts;
use crate::pipeline::Pipeline;
use crate::plan::{self, camera_frame_spec, FramePlan, SourceTiming};
use crate::scene_job::{ResolvedScene, SceneCache, SceneJob};
use crate::source::SceneSource;
use crate::PipelineError;
use crate::{scene_actors, scene_light};

/// ORB-SLAM3 v1.0 RGB-D-inertial settings of the `rgbd-imu` rig, in the dataset root.
pub const ORBSLAM3_RGBD_INERTIAL_FILE: &str = "orbslam3_rgbd_inertial.yaml";

/// The camera's capture times along `spline`: its rate's grid from the spline's start, without
/// frames after the IMU's last sample, which would have no readings since the previous frame
/// (at 30 Hz the camera's grid may run up to 5 ms past the IMU's).
fn frame_times(spline: &SplineSe3, rig: &Rig) -> Vec<f64> {
    let imu_end = rig
        .imu
        .as_ref()
        .and_then(|imu| sample_times(spline, imu.rate_hz).last().copied())
        .unwrap_or(f64::INFINITY);
    let mut times_s = sample_times(spline, rig.cameras[0].rate_hz);
    times_s.retain(|&t| t <= imu_end + 1e-9);
    times_s
}

/// The frames an `rgbd-imu` render of `poses` path poses at `rate_hz` (the camera's rate),
/// played `speed_up` times faster ([`crate::plan::speed_up`]), writes, without the scene (for a
/// plan).
pub fn rgbd_imu_frame_count(
    poses: usize,
    rate_hz: f64,
    speed_up: u32,
) -> Result<usize, PipelineError> {
    let rig = Rig::rgbd_imu(rslam_core::Intrinsics::TUM, rate_hz);
    let times: Vec<f64> = (0..poses).map(|i| i as f64 / rate_hz).collect();
    let path = vec![rslam_core::Pose::IDENTITY; poses];
    let spline = motion_spline(&body_path(
        &times,
        &path,
        speed_up,
        &rslam_core::Pose::IDENTITY,
    ))?;
    Ok(frame_times(&spline, &rig).len())
}

/// An `rgbd-imu` render, planned: the scene loaded, the motion sampled by the camera and the
/// IMU, the frame plan made and the inertial files written in memory.
pub(crate) struct RgbdImuRender<'a> {
    scene: &'a SceneJob,
    resolved: ResolvedScene,
    camera: EurocCamera,
    frame_spec: PerturbSpec,
    plan: FramePlan,
    poses: Vec<Pose>,
    /// The camera's capture times, one per pose.
    times_s: Vec<f64>,
    ground_truth: Trajectory,
    format: DatasetFormat,
    sensor_files: Vec<(String, String)>,
    bag_imu: Option<BagImu>,
    manifest: Manifest,
}

/// Plans `scene` seen by [`Rig::rgbd_imu`] of its camera and rate, in the TUM layout or a ROS 2
/// bag (`format`). Items
/// are those [`crate::settings::rgbd_imu_render`] takes (checked by the job): IMU items,
/// `cam_imu_offset` and the calibration items of `cam0` and `imu0` apply. An unfinished output of the same job is resumed frame by
/// frame, as a one-camera render is.
pub(crate) fn plan<'a>(
    scene: &'a SceneJob,
    format: DatasetFormat,
    depth_png: DepthPng,
    bag: BagOptions,
    command: &[String],
    scenes: &SceneCache,
) -> Result<RgbdImuRender<'a>, PipelineError> {
    let spec = &scene.spec;
    let rig = Rig::rgbd_imu(scene.camera, scene.rate_hz);
    let camera = rig.cameras[0].clone();
    let frame_spec = camera_frame_spec(spec, &camera.name);
    let perturbed = PerturbedRig::new(&rig, spec, scene.seed)?;
    let resolved = scene.resolve_in(scenes)?;
    scene.require_metres(&resolved.scene, "a rig's extrinsics and IMU are")?;
    let spline = motion_spline(&body_path(
        &resolved.clean.timestamps,
        &resolved.poses,
        plan::speed_up(spec),
        &camera.body_from_camera,
    ))?;
    let times_s = frame_times(&spline, &rig);
    let streams = imu_and_ground_truth(scene, perturbed.actual.imu.as_ref(), &spline, &times_s)?;
    let times_ns = times_s
        .iter()
        .map(|&t| nanoseconds(t))
        .collect::<Result<Vec<_>, _>>()?;
    let stamps_ns = camera_stamps(spec, &camera.name, &times_ns)?;
    let stamps_s: Vec<f64> = stamps_ns.iter().map(|&t| t as f64 * 1e-9).collect();
    let frame_plan = FramePlan::recorded(
        &SourceTiming {
            rgb_times: &stamps_s,
            depth_offsets: &vec![0.0; stamps_s.len()],
            rate_hz: camera.rate_hz,
        },
        &frame_spec,
        scene.seed,
    );
    let poses = camera_poses(&spline, |k| perturbed.body_from_camera(0, k), &times_s)?;
    let ground_truth = Trajectory::new(
        times_ns.iter().map(|&t| t as f64 * 1e-9).collect(),
        poses.clone(),
    );

    let mut extra = serde_json::json!({
        "rig": rig.name,
        "path_rate_hz": scene.rate_hz,
        "imu": rig.imu.as_ref().map(|imu| serde_json::json!({
            "rate_hz": imu.rate_hz,
            "seed": imu_seed(scene.seed),
        })),
    });
    record_agent(&mut extra, scene);
    scene.record_capture(&mut extra, &resolved.scene);
    scene_light::record(
        &mut extra,
        &resolved.scene,
        &frame_spec,
        scene.seed,
        &frame_plan,
    )?;
    scene_actors::record(&mut extra, resolved.actors.as_deref(), &frame_plan);
    if !spec.calibration.is_empty() {
        extra["calibration"] = perturbed.record(&rig);
    }
    let manifest = ManifestParts {
        command,
        source: resolved.scene.name.clone(),
        source_hash: resolved.source_hash().to_string(),
        format: Some(format),
        camera: Some(camera.intrinsics),
        distortion: None,
        depth_png,
        bag,
        rate_hz: camera.rate_hz,
        seed: scene.seed,
        spec,
        plan: &frame_plan,
        extra,
    }
    .build()?;
    let manifest = with_imu_report(manifest, streams.report.as_ref())?;

    let written_camera = &perturbed.written.cameras[0];
    let written_imu = perturbed.written.imu.as_ref();
    let (sensor_files, bag_imu) = match format {
        DatasetFormat::Ros2 => (
            Vec::new(),
            written_imu.map(|imu| bag_imu(imu, written_camera, streams.imu)),
        ),
        _ => {
            let mut files = inertial_files(written_imu, &streams.imu, &streams.ground_truth);
            if let Some(csv) = perturbed.per_frame_csv(&stamps_ns) {
                files.push((PER_FRAME_FILE.into(), csv));
            }
            if let Some(imu) = written_imu {
                files.push((
                    ORBSLAM3_RGBD_INERTIAL_FILE.into(),
                    rgbd_inertial_settings(
                        &written_camera.intrinsics,
                        camera.rate_hz,
                        &written_camera.body_from_camera,
                        imu,
                    ),
                ));
            }
            (files, None)
        }
    };
    Ok(RgbdImuRender {
        scene,
        resolved,
        camera,
        frame_spec,
        plan: frame_plan,
        poses,
        times_s,
        ground_truth,
        format,
        sensor_files,
        bag_imu,
        manifest,
    })
}

/// The IMU as a bag carries it: its readings, its pose in `camera`'s optical frame, and the
/// variance of one reading at its rate.
fn bag_imu(imu: &EurocImu, camera: &EurocCamera, samples: Vec<ImuSample>) -> BagImu {
    let (gyro_variance, accel_variance) = variances(imu);
    let camera_from_body = camera.body_from_camera.inverse();
    BagImu {
        samples,
        camera_from_imu: camera_from_body.compose(&imu.body_from_imu),
        gyro_variance,
        accel_variance,
    }
}

impl Planned for RgbdImuRender<'_> {
    fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    fn streams(&self) -> Streams {
        Streams::Frames(self.plan.len())
    }

    fn open<'a>(&'a self, ctx: &'a GpuContext) -> Result<Writing<'a>, PipelineError> {
        let camera = &self.camera;
        let mut source = SceneSource::new(
            ctx,
            &self.resolved.scene,
            camera.intrinsics,
            self.poses.clone(),
            self.scene.capture.settings,
            self.resolved.actors.clone(),
        )?;
        source.set_times(self.times_s.clone());
        source.set_sensor(ctx, &self.frame_spec, camera.rate_hz, self.scene.seed)?;
        let pipeline = Pipeline::new(ctx, source, &self.frame_spec, self.scene.seed)?;
        let output = DatasetOutput {
            format: self.format,
            camera: camera.intrinsics,
            plan: &self.plan,
            ground_truth: &self.ground_truth,
            sensor_files: &self.sensor_files,
            bag_imu: self.bag_imu.as_ref(),
        };
        Ok(dataset_writing(ctx, pipeline, output, "rendering"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plan_counts_the_frames_a_render_writes() {
        // 7 poses at 30 Hz: the spline is valid for 4/30 s, which the IMU covers to 0.130 s,
        // so the frame at 0.133 s is left out (the frames `rig_rgbd.rs` reads back).
        assert_eq!(rgbd_imu_frame_count(7, 30.0, 1).unwrap(), 4);
        // 400 poses at 30 Hz: 397/30 s = 13.233 s, frames every 1/30 s up to the IMU's last
        // sample at 13.230 s.
        assert_eq!(rgbd_imu_frame_count(400, 30.0, 1).unwrap(), 397);
        assert_eq!(rgbd_imu_frame_count(400, 30.0, 2).unwrap(), 199);
    }
}
