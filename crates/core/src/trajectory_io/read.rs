use std::path::Path;

use super::detect::detect;
use super::lines::check_line_count;
use super::{colmap, euroc, kitti, nerfstudio, replica, tum};
use super::{ReadOptions, TimeSource, TrajectoryFile, TrajectoryFormat};
use crate::dataset::ros2::read_pose_topic;
use crate::{read_text_file, CoreError, Trajectory};

/// Reads a trajectory file, detecting its format from the content unless `format` forces one.
/// Replica frames are stamped at 20 Hz; KITTI poses get their frame index as timestamp
/// ([`TimeSource::FrameIndex`]). See [`read_trajectory_with`] for the options.
pub fn read_trajectory(
    path: &Path,
    format: Option<TrajectoryFormat>,
) -> Result<TrajectoryFile, CoreError> {
    read_trajectory_with(
        path,
        &ReadOptions {
            format,
            ..ReadOptions::default()
        },
    )
}

/// Reads a trajectory file with explicit options (forced format, Replica rate, KITTI times file),
/// or a pose topic of a ROS 2 bag folder ([`ReadOptions::topic`]). Every pose is a
/// unit-quaternion rigid transform; a file without poses is an error.
pub fn read_trajectory_with(
    path: &Path,
    options: &ReadOptions,
) -> Result<TrajectoryFile, CoreError> {
    let rate = options.replica_rate_hz;
    if !(rate.is_finite() && rate > 0.0) {
        return Err(CoreError::BadRate { hz: rate });
    }
    let is_bag = path.join("metadata.yaml").is_file();
    if is_bag || options.format == Some(TrajectoryFormat::Ros2) {
        return Ok(TrajectoryFile {
            format: TrajectoryFormat::Ros2,
            time_source: TimeSource::File,
            trajectory: read_pose_topic(path, options.topic.as_deref())?,
        });
    }
    if options.topic.is_some() {
        return Err(CoreError::bad_file(
            path,
            "a topic was named, but this is no ROS 2 bag (a folder with metadata.yaml)",
        ));
    }
    let text = read_text_file(path, "a trajectory in text form")?;
    check_line_count(path, &text)?;
    let format = match options.format {
        Some(format) => format,
        None => detect(path, &text)?,
    };
    if options.dataparser_transforms.is_some() && format != TrajectoryFormat::Nerfstudio {
        return Err(CoreError::bad_file(
            path,
            format!("a {format} trajectory, but dataparser transforms move a nerfstudio transforms.json"),
        ));
    }
    let (trajectory, time_source) = match format {
        TrajectoryFormat::Tum => (tum::parse(path, &text)?, TimeSource::File),
        TrajectoryFormat::Euroc => (euroc::parse(path, &text)?, TimeSource::File),
        TrajectoryFormat::Replica => (
            replica::parse(path, &text, rate)?,
            TimeSource::Rate { hz: rate },
        ),
        TrajectoryFormat::Colmap => (
            colmap::parse(path, &text, rate)?,
            TimeSource::Rate { hz: rate },
        ),
        TrajectoryFormat::Nerfstudio => {
            let dataparser = options.dataparser_transforms.as_deref();
            let trajectory = nerfstudio::parse(path, &text, rate, dataparser)?;
            let hz = match trajectory.timestamps.get(1) {
                Some(t) => 1.0 / t,
                None => rate,
            };
            (trajectory, TimeSource::Rate { hz })
        }
        TrajectoryFormat::Kitti => read_kitti(path, &text, options.kitti_times.as_deref())?,
        TrajectoryFormat::Ros2 => {
            return Err(CoreError::bad_file(
                path,
                "a file, but a ros2 trajectory is a pose topic of a rosbag2 folder",
            ))
        }
    };
    if trajectory.is_empty() {
        return Err(CoreError::bad_file(
            path,
            "no poses (the file is empty or only comments)",
        ));
    }
    Ok(TrajectoryFile {
        format,
        time_source,
        trajectory,
    })
}

fn read_kitti(
    path: &Path,
    text: &str,
    times_path: Option<&Path>,
) -> Result<(Trajectory, TimeSource), CoreError> {
    let poses = kitti::parse(path, text)?;
    let Some(times_path) = times_path else {
        let indices = (0..poses.len()).map(|i| i as f64).collect();
        return Ok((Trajectory::new(indices, poses), TimeSource::FrameIndex));
    };
    let times_text = read_text_file(times_path, "a times file in text form")?;
    check_line_count(times_path, &times_text)?;
    let times = kitti::parse_times(times_path, &times_text)?;
    if times.len() != poses.len() {
        return Err(CoreError::bad_file(
            times_path,
            format!(
                "{} timestamps, but {} has {} poses; expected one timestamp per pose",
                times.len(),
                path.display(),
                poses.len()
            ),
        ));
    }
    Ok((Trajectory::new(times, poses), TimeSource::File))
}
