//! Where a dataset's cameras looked from: every ground-truth pose of every camera, with its
//! intrinsics and the farthest depth its depth files can hold. Mapping metrics cull to what
//! these views saw.

use std::path::Path;

use crate::dataset::euroc::{read_euroc, read_euroc_without_frames};
use crate::dataset::{
    read_dataset, read_frames_deleted, DatasetFormat, DatasetOverrides, Manifest, MANIFEST_FILE,
};
use crate::trajectory_io::{read_trajectory, TrajectoryFormat};
use crate::{nearest_time, CoreError, Intrinsics, Pose};

/// One camera of a dataset (of one of its agents, for several agents).
#[derive(Clone, Debug, PartialEq)]
pub struct ViewCamera {
    /// `rgb` for a one-camera layout, `cam0`, `cam1`, … for EuRoC; prefixed `<agent>/` for agents.
    pub name: String,
    pub intrinsics: Intrinsics,
    /// The largest depth the camera's depth files can encode, metres (65535 / units per metre);
    /// `None` for a camera without depth.
    pub max_depth_m: Option<f64>,
}

/// One ground-truth pose of one camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Index into [`DatasetViews::cameras`].
    pub camera: usize,
    pub world_from_camera: Pose,
}

#[derive(Clone, Debug, PartialEq)]
pub struct DatasetViews {
    pub cameras: Vec<ViewCamera>,
    pub views: Vec<View>,
}

/// The views of the dataset at `root`: a Replica or TUM dataset (its ground-truth trajectory), a
/// EuRoC one (each camera's frames at the ground-truth body pose nearest in time, within half a
/// frame period), or a folder of agents, one dataset per subfolder.
pub fn read_views(root: &Path) -> Result<DatasetViews, CoreError> {
    let mut views = DatasetViews {
        cameras: Vec::new(),
        views: Vec::new(),
    };
    if is_dataset(root) {
        add_views(root, "", &mut views)?;
        return Ok(views);
    }
    let mut agents: Vec<_> = std::fs::read_dir(root)
        .map_err(|e| CoreError::io(root, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir() && is_dataset(p))
        .collect();
    agents.sort();
    if agents.is_empty() {
        return Err(CoreError::bad_file(
            root,
            "not a dataset: expected the Replica, TUM or EuRoC layout with ground truth, or a folder of such datasets (one per agent)",
        ));
    }
    for agent in agents {
        let name = agent
            .file_name()
            .map_or(String::new(), |n| format!("{}/", n.to_string_lossy()));
        add_views(&agent, &name, &mut views)?;
    }
    Ok(views)
}

fn is_dataset(dir: &Path) -> bool {
    dir.join(MANIFEST_FILE).is_file()
        || dir.join("rgb.txt").is_file()
        || dir.join("results").is_dir()
        || dir.join("mav0").is_dir()
}

fn add_views(root: &Path, prefix: &str, out: &mut DatasetViews) -> Result<(), CoreError> {
    if root.join("mav0").is_dir() {
        return add_euroc_views(root, prefix, out);
    }
    if root.join("metadata.yaml").is_file() {
        return Err(CoreError::bad_file(
            root,
            "a rosbag2: its cameras are not read for culling; render the same job in the tum or replica layout",
        ));
    }
    let (intrinsics, format, poses) = match read_frames_deleted(root)? {
        Some(_) => kept_camera_and_poses(root)?,
        None => {
            let dataset = read_dataset(root, &DatasetOverrides::default())?;
            let ground_truth = dataset.ground_truth.ok_or_else(|| {
                CoreError::bad_file(
                    root,
                    "no ground-truth trajectory (traj.txt or groundtruth.txt): the cameras' poses are needed",
                )
            })?;
            (dataset.intrinsics, dataset.format, ground_truth.poses)
        }
    };
    let camera = out.cameras.len();
    out.cameras.push(ViewCamera {
        name: format!("{prefix}rgb"),
        intrinsics,
        max_depth_m: Some(u16::MAX as f64 / format.depth_scale()),
    });
    out.views
        .extend(poses.into_iter().map(|world_from_camera| View {
            camera,
            world_from_camera,
        }));
    Ok(())
}

/// The camera, layout and ground-truth poses of a dataset whose frames were deleted after use,
/// from what it keeps: the manifest and the ground-truth file.
fn kept_camera_and_poses(root: &Path) -> Result<(Intrinsics, DatasetFormat, Vec<Pose>), CoreError> {
    let manifest = Manifest::read(root)?;
    let missing = |what: &str| {
        CoreError::bad_file(
            root.join(MANIFEST_FILE),
            format!("no {what}: the cameras of a dataset whose frames were deleted come from its manifest"),
        )
    };
    let camera = manifest.camera.ok_or_else(|| missing("camera"))?;
    let format = manifest.format.ok_or_else(|| missing("format"))?;
    let (file, file_format) = match format {
        DatasetFormat::Replica => ("traj.txt", TrajectoryFormat::Replica),
        DatasetFormat::Tum => ("groundtruth.txt", TrajectoryFormat::Tum),
        DatasetFormat::Ros2 => return Err(missing("ground-truth file beside a bag")),
    };
    let poses = read_trajectory(&root.join(file), Some(file_format))?
        .trajectory
        .poses;
    Ok((camera, format, poses))
}

fn add_euroc_views(root: &Path, prefix: &str, out: &mut DatasetViews) -> Result<(), CoreError> {
    let dataset = match read_frames_deleted(root)? {
        Some(_) => read_euroc_without_frames(root)?,
        None => read_euroc(root)?,
    };
    let states = dataset.ground_truth.ok_or_else(|| {
        CoreError::bad_file(
            &dataset.mav_dir,
            "no state_groundtruth_estimate0/data.csv: the cameras' poses are needed",
        )
    })?;
    let state_times: Vec<f64> = states.iter().map(|s| s.t_ns as f64 * 1e-9).collect();
    let views_before = out.views.len();
    for camera_frames in &dataset.cameras {
        let camera = out.cameras.len();
        let sensor = &camera_frames.camera;
        out.cameras.push(ViewCamera {
            name: format!("{prefix}{}", sensor.name),
            intrinsics: sensor.intrinsics,
            max_depth_m: None,
        });
        let max_gap_s = 0.5 / sensor.rate_hz;
        for frame in &camera_frames.frames {
            let t = frame.t_ns as f64 * 1e-9;
            if let Some(i) = nearest_time(state_times.iter().copied(), t, max_gap_s) {
                out.views.push(View {
                    camera,
                    world_from_camera: states[i].world_from_body.compose(&sensor.body_from_camera),
                });
            }
        }
    }
    if out.views.len() == views_before {
        return Err(CoreError::bad_file(
            &dataset.mav_dir,
            "no camera frame has a ground-truth pose within half a frame period",
        ));
    }
    Ok(())
}
