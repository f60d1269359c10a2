//! What each kind of job offers a spec's items, in one place: the [`Setting`] a job's plan checks
//! its spec against ([`PerturbSpec::refusal`], which answers from what every item needs).

use std::path::Path;

use rslam_core::dataset::euroc::{EurocDataset, IMU_DIR};
use rslam_core::dataset::ros2::{RecordedBagCameras, IMU_TYPE};
use rslam_core::dataset::SourceDataset;
use rslam_perturb::{Lenses, Need, PerturbSpec, Setting};
use rslam_render::Scene;

use crate::rig::calibration::sensor_names;
use crate::{PipelineError, Rig};

/// Refuses the first item of `spec` that `setting` cannot take.
pub fn check(spec: &PerturbSpec, setting: &Setting) -> Result<(), PipelineError> {
    match spec.refusal(setting) {
        Some(refused) => Err(refused.into()),
        None => Ok(()),
    }
}

/// A scene loaded from a file (a mesh or a Gaussian-splat capture), which lacks what only the
/// built-in scenes keep (`need`: their light as layers, their free floor); the reason names it.
pub fn scene_file(scene: &Scene, need: Need) -> Setting {
    let what = match scene.splats {
        Some(_) => "a Gaussian-splat capture",
        None => "a mesh file",
    };
    Setting::any_one_camera().lacking(need, format!("'{}' is {what}", scene.name))
}

/// A scene rendered through one camera (`input` names it: "a one-camera render").
pub fn one_camera_render(input: &str) -> Setting {
    Setting::one_camera(input).lacking_all(&[Need::Imu])
}

/// A scene rendered through the `rgbd-imu` rig (one RGB-D camera and an IMU) in the TUM layout
/// with `imu0/` beside it, which states no lens yet.
pub fn rgbd_imu_render() -> Setting {
    Setting::new("the rgbd-imu rig", &["cam0", IMU_DIR]).with_lenses(Lenses::None)
}

/// A scene rendered through `rig` in the EuRoC layout: cameras without depth, radial-tangential
/// lenses in its calibration files.
pub fn euroc_rig_render(rig: &Rig) -> Setting {
    let input = format!("the '{}' rig", rig.name);
    let no_depth = format!("{input}'s cameras have no depth stream");
    let setting = Setting::new(input, &sensor_names(rig))
        .with_lenses(Lenses::Radtan)
        .lacking(Need::Depth, no_depth);
    match rig.imu {
        Some(_) => setting,
        None => setting.lacking_all(&[Need::Imu]),
    }
}

/// A recorded Replica or TUM dataset read from `root`; `imu`: it has `imu0/` beside it (an
/// `rgbd-imu` output), which cannot follow frames played faster or re-stamped.
pub fn recorded_dataset(dataset: &SourceDataset, root: &Path, imu: bool) -> Setting {
    let setting = Setting::one_camera("an RGB-D dataset").lacking_all(&[Need::Scene]);
    let setting = match imu {
        true => {
            let clause = format!(
                "{} has an IMU (imu0/) that cannot follow re-stamped frames",
                root.display()
            );
            setting
                .lacking(Need::SpeedUp, &clause)
                .lacking(Need::NewStamps, clause)
        }
        false => setting.lacking_all(&[Need::Imu]),
    };
    match dataset.frames.iter().find(|f| f.depth.is_none()) {
        Some(frame) => setting.lacking(Need::Depth, format!("{} has none", frame.rgb.display())),
        None => setting,
    }
}

/// A recorded ROS 2 bag's cameras and IMU topics: its other topics (odometry, `/tf`, each
/// camera's `CameraInfo`) are copied as recorded, so the frames keep their times and each
/// `CameraInfo` its lens.
pub fn recorded_bag(recorded: &RecordedBagCameras) -> Setting {
    let folder = recorded.bag.folder.display();
    let input = format!("the bag {folder}");
    let copied = format!("{input}'s other topics are copied with their times");
    let info_copied = format!(
        "{input}'s CameraInfo messages are copied with their stamps, which the images must keep"
    );
    let mut setting = Setting::one_camera(input)
        .lacking_all(&[Need::Scene])
        .lacking(Need::SpeedUp, copied)
        .lacking(Need::NewStamps, info_copied)
        .with_lenses(Lenses::None);
    if recorded.imus.is_empty() {
        setting = setting.lacking(Need::Imu, format!("{folder} has no {IMU_TYPE} topic"));
    }
    match recorded.cameras.iter().any(|c| c.depth.is_some()) {
        true => setting,
        false => setting.lacking(Need::Depth, format!("{folder} has no depth topic")),
    }
}

/// A recorded EuRoC (or TUM-VI) dataset: its cameras without depth and its IMU as recorded,
/// each frame keeping its stamp, which names its file.
pub fn recorded_euroc(dataset: &EurocDataset) -> Setting {
    let cameras = dataset.cameras.iter().map(|c| c.camera.name.as_str());
    let sensors: Vec<&str> = cameras
        .chain(dataset.imu.as_ref().map(|_| IMU_DIR))
        .collect();
    let setting = Setting::new("a recorded EuRoC dataset", &sensors)
        .lacking_all(&[Need::Scene])
        .lacking(Need::Depth, "a EuRoC dataset's cameras have no depth stream")
        .lacking(
            Need::SpeedUp,
            "a recorded EuRoC dataset keeps each frame's stamp (it names the file): not supported there yet",
        );
    match dataset.imu {
        Some(_) => setting,
        None => setting.lacking(
            Need::Imu,
            format!(
                "the dataset {} (no imu0/) has none",
                dataset.mav_dir.display()
            ),
        ),
    }
}

/// Image files, each perturbed on its own.
pub fn image_files() -> Setting {
    Setting::one_camera("an image input").lacking_all(&[
        Need::Scene,
        Need::Sequence,
        Need::Depth,
        Need::Imu,
    ])
}

/// Frames handed over in memory, in any order; `depth`: with depth images.
pub fn frames_in_memory(depth: bool) -> Setting {
    let setting = Setting::one_camera("a set of frames").lacking_all(&[
        Need::Scene,
        Need::Sequence,
        Need::Imu,
        Need::CaptureOrder,
    ]);
    match depth {
        true => setting,
        false => setting.lacking(Need::Depth, "the frames have none"),
    }
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use rslam_core::dataset::euroc::{EurocCameraFrames, EurocImuSamples};
    use rslam_core::dataset::{DatasetFormat, DatasetFrame};
    use rslam_core::Intrinsics;

    use super::*;

    /// The refusal of `text` where `setting` holds, as the CLI's library error prints it.
    fn refused(setting: &Setting, text: &str) -> Option<String> {
        let spec = PerturbSpec::parse(text).unwrap();
        let err = check(&spec, setting).err()?.to_string();
        assert!(!err.contains('\n'), "{err}");
        Some(err)
    }

    fn takes(setting: &Setting, texts: &[&str]) {
        for text in texts {
            assert_eq!(refused(setting, text), None, "{text}");
        }
    }

    /// Each of `(spec, first refused item, words of the reason)`.
    fn refuses(setting: &Setting, cases: &[(&str, &str, &str)]) {
        for (text, item, reason) in cases {
            let err = refused(setting, text).unwrap_or_else(|| panic!("{text} was taken"));
            let head = format!("spec item '{item}': ");
            assert!(
                err.starts_with(&head) && err.contains(reason),
                "{text}: {err}"
            );
        }
    }

    fn euroc(imu: bool) -> EurocDataset {
        let rig = Rig::stereo_imu();
        EurocDataset {
            mav_dir: PathBuf::from("seq/mav0"),
            cameras: rig
                .cameras
                .iter()
                .map(|c| EurocCameraFrames {
                    camera: c.clone(),
                    frames: Vec::new(),
                })
                .collect(),
            imu: rig.imu.filter(|_| imu).map(|imu| EurocImuSamples {
                imu,
                samples: Vec::new(),
            }),
            ground_truth: None,
            tum_vi: None,
        }
    }

    fn tum(depth_everywhere: bool) -> SourceDataset {
        let frame = |i: usize, depth: bool| DatasetFrame {
            rgb: PathBuf::from(format!("rgb/{i}.png")),
            rgb_time: i as f64,
            depth: depth.then(|| PathBuf::from(format!("depth/{i}.png"))),
            depth_time: i as f64,
        };
        SourceDataset {
            root: PathBuf::from("seq"),
            format: DatasetFormat::Tum,
            intrinsics: Intrinsics::REPLICA,
            distortion: None,
            rate_hz: 30.0,
            frames: vec![frame(0, true), frame(1, depth_everywhere)],
            ground_truth: None,
            manifest: None,
        }
    }

    #[test]
    fn a_one_camera_render_takes_everything_but_other_sensors_rigs_and_imu_items() {
        let setting = one_camera_render("a one-camera render");
        takes(&setting, &["cam0:fog:3,rot:1,trans:0.01@smooth,exposure:20,distortion:equidistant(0.1,0,0,0),depth_noise:2,fast:2,misalign:3,auto_exposure:2"]);
        refuses(
            &setting,
            &[
                (
                    "gaussian_noise:1,cam1:fog:3",
                    "cam1:fog:3",
                    "this input has one camera, cam0",
                ),
                (
                    "baseline:0.01@calibration",
                    "baseline:0.01@calibration",
                    "a calibration item needs a rig",
                ),
                (
                    "fog:1,imu_noise:2",
                    "imu_noise:2",
                    "IMU items need an IMU, and a one-camera render has none",
                ),
            ],
        );
    }

    #[test]
    fn a_euroc_rig_has_no_depth_and_states_radtan_lenses_only() {
        let stereo = euroc_rig_render(&Rig::stereo());
        takes(&stereo, &["cam1:fog:2,rot:1,fast:2,exposure:10,baseline:0.01,distortion:radtan(-0.28,0.07,0.0002,0.00002)"]);
        refuses(
            &stereo,
            &[
                ("fog:2,misalign:3", "misalign:3", "misalign delays depth against colour, and the 'stereo' rig's cameras have no depth stream"),
                ("depth_noise:2", "depth_noise:2", "the 'stereo' rig's cameras have no depth stream"),
                ("distortion:equidistant(0.1,0,0,0)", "distortion:equidistant(0.1,0,0,0)", "describe radial-tangential lenses"),
                ("cam_imu_offset:3", "cam_imu_offset:3", "IMU items need an IMU, and the 'stereo' rig has none"),
                ("imu0:extrinsic_rot:1", "imu0:extrinsic_rot:1", "no sensor 'imu0' here; the sensors are cam0, cam1"),
            ],
        );
        takes(
            &euroc_rig_render(&Rig::stereo_imu()),
            &["imu_noise:2,imu0:extrinsic_rot:1"],
        );
        refuses(
            &rgbd_imu_render(),
            &[(
                "distortion:radtan(0.1,0,0,0)",
                "distortion:radtan(0.1,0,0,0)",
                "the rgbd-imu rig does not support a lens yet",
            )],
        );
        takes(
            &rgbd_imu_render(),
            &["depth_noise:2,misalign:2,imu_noise:2,cam_imu_offset:3,fast:2"],
        );
    }

    #[test]
    fn a_recorded_euroc_dataset_takes_image_imu_and_written_calibration_items_only() {
        let setting = recorded_euroc(&euroc(true));
        takes(
            &setting,
            &[
                "gaussian_noise:3,fog:2@dynamic",
                "imu_noise:2,cam_imu_offset:3",
                "cam1:fog:2,baseline:0.01@calibration,imu0:extrinsic_rot:1@calibration",
            ],
        );
        refuses(
            &setting,
            &[
                (
                    "fog:2,depth_noise:3",
                    "depth_noise:3",
                    "a EuRoC dataset's cameras have no depth stream",
                ),
                ("fast:2", "fast:2", "keeps each frame's stamp"),
                (
                    "misalign:4",
                    "misalign:4",
                    "misalign delays depth against colour",
                ),
                ("rot:1", "rot:1", "needs a scene to render"),
                ("exposure:20", "exposure:20", "needs a scene to render"),
            ],
        );
        for (text, fix) in [
            ("baseline:0.01", "baseline:0.01@calibration"),
            ("baseline:0.01@dynamic", "baseline:0.01@calibration"),
            (
                "cam1:extrinsic_rot:0.5@dynamic",
                "cam1:extrinsic_rot:0.5@calibration",
            ),
            (
                "cam1:extrinsic_trans:0.02",
                "cam1:extrinsic_trans:0.02@calibration",
            ),
        ] {
            let err = refused(&setting, text).unwrap();
            assert!(
                err.contains("a recorded dataset cannot be re-rendered") && err.ends_with(fix),
                "{err}"
            );
        }
        refuses(
            &recorded_euroc(&euroc(false)),
            &[(
                "imu_drop:0.1",
                "imu_drop:0.1",
                "the dataset seq/mav0 (no imu0/) has none",
            )],
        );
    }

    #[test]
    fn a_recorded_rgbd_dataset_keeps_its_frames_and_an_imu_beside_it_keeps_their_stamps() {
        let plain = recorded_dataset(&tum(true), Path::new("seq"), false);
        takes(
            &plain,
            &["fog:2,depth_missing:3,fast:2,misalign:3@dynamic,auto_exposure:1"],
        );
        refuses(
            &plain,
            &[
                (
                    "rot:1",
                    "rot:1",
                    "rot forms the frames from the camera's poses and needs a scene to render",
                ),
                (
                    "distortion:radtan(0.1,0,0,0)",
                    "distortion:radtan(0.1,0,0,0)",
                    "needs a scene",
                ),
                (
                    "imu_drop:0.1",
                    "imu_drop:0.1",
                    "IMU items need an IMU, and an RGB-D dataset has none",
                ),
            ],
        );
        let with_imu = recorded_dataset(&tum(true), Path::new("seq"), true);
        takes(&with_imu, &["fog:2,misalign:2,imu_noise:2,imu_drop:0.1"]);
        refuses(
            &with_imu,
            &[
                (
                    "fast:2",
                    "fast:2",
                    "seq has an IMU (imu0/) that cannot follow re-stamped frames",
                ),
                (
                    "cam_imu_offset:2",
                    "cam_imu_offset:2",
                    "gives the frames new timestamps, and seq has an IMU",
                ),
            ],
        );
        let missing = recorded_dataset(&tum(false), Path::new("seq"), false);
        takes(&missing, &["fog:2"]);
        refuses(
            &missing,
            &[(
                "depth_noise:1",
                "depth_noise:1",
                "depth corruptions need depth, and rgb/1.png has none",
            )],
        );
    }

    #[test]
    fn separate_frames_take_frame_corruptions_only() {
        takes(&image_files(), &["fog:2,auto_exposure:3"]);
        refuses(
            &image_files(),
            &[
                (
                    "depth_missing:1",
                    "depth_missing:1",
                    "depth corruptions need depth, and an image input has none",
                ),
                (
                    "fog:1,misalign:5",
                    "misalign:5",
                    "misalign acts on a sequence of frames in time",
                ),
                (
                    "fast:2",
                    "fast:2",
                    "fast acts on a sequence of frames in time",
                ),
                ("trans:0.01", "trans:0.01", "needs a scene to render"),
                (
                    "imu_jitter:1",
                    "imu_jitter:1",
                    "IMU items need an IMU, and an image input has none",
                ),
            ],
        );
        takes(&frames_in_memory(true), &["fog:2,depth_missing:1"]);
        refuses(
            &frames_in_memory(true),
            &[(
                "auto_exposure:2",
                "auto_exposure:2",
                "auto_exposure carries its state from frame to frame",
            )],
        );
        refuses(
            &frames_in_memory(false),
            &[(
                "depth_missing:1",
                "depth_missing:1",
                "depth corruptions need depth, and the frames have none",
            )],
        );
    }
}
