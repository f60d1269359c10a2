//! A rig file's `[ros2]` table: the topic names and frame ids its ROS 2 bag uses in place of
//! EuRoC's, for a SLAM node's launch file as it is:
//!
//! ```toml
//! [ros2]
//! body_frame = "base_link"
//! ground_truth_topic = "/vicon/pose"
//! cam0 = { topic = "/stereo/left/image_raw", frame_id = "left_optical" }
//! cam1 = { topic = "/stereo/right/image_raw", frame_id = "right_optical" }
//! imu0 = { topic = "/imu/data", frame_id = "imu_link" }
//! ```

use std::collections::HashSet;

use rslam_core::dataset::ros2::{check_frame_id, check_topic, BagNames, SensorNames};

/// The names `table` gives a rig of `cameras` cameras (and an IMU when `has_imu`); each name
/// checked as ROS 2 takes it, and no two topics or frames the same.
pub fn bag_names(table: &toml::Table, cameras: usize, has_imu: bool) -> Result<BagNames, String> {
    let mut names = BagNames::default();
    let sensors: Vec<String> = (0..cameras)
        .map(|i| format!("cam{i}"))
        .chain(has_imu.then(|| "imu0".to_string()))
        .collect();
    for (key, value) in table {
        match key.as_str() {
            "body_frame" => {
                let frame = string(key, value)?;
                check_frame_id(&frame).map_err(|e| format!("{key}: {e}"))?;
                names.body_frame = Some(frame);
            }
            "ground_truth_topic" => {
                let topic = string(key, value)?;
                check_topic(&topic).map_err(|e| format!("{key}: {e}"))?;
                names.ground_truth_topic = Some(topic);
            }
            sensor if sensors.iter().any(|s| s == sensor) => {
                names
                    .sensors
                    .insert(sensor.to_string(), sensor_names(sensor, value)?);
            }
            other => {
                return Err(format!(
                    "unknown key '{other}': expected body_frame, ground_truth_topic or a sensor of the rig ({})",
                    sensors.join(", ")
                ))
            }
        }
    }
    let cameras = sensors.iter().filter(|s| s.starts_with("cam"));
    let mut topics: Vec<String> = cameras
        .clone()
        .flat_map(|c| [names.image_topic(c), names.camera_info_topic(c)])
        .chain([names.ground_truth_topic()])
        .collect();
    let mut frames: Vec<String> = cameras.map(|c| names.frame_id(c)).collect();
    frames.push(names.body_frame());
    if has_imu {
        topics.push(names.imu_topic());
        frames.push(names.imu_frame());
    }
    unique("topic", &topics)?;
    unique("frame id", &frames)?;
    Ok(names)
}

fn sensor_names(sensor: &str, value: &toml::Value) -> Result<SensorNames, String> {
    let Some(table) = value.as_table() else {
        return Err(format!(
            "{sensor}: expected a table such as {{ topic = \"/left/image_raw\", frame_id = \"left\" }}"
        ));
    };
    let mut names = SensorNames::default();
    for (key, value) in table {
        let text = string(&format!("{sensor}.{key}"), value)?;
        match key.as_str() {
            "topic" => {
                check_topic(&text).map_err(|e| format!("{sensor}: {e}"))?;
                names.topic = Some(text);
            }
            "frame_id" => {
                check_frame_id(&text).map_err(|e| format!("{sensor}: {e}"))?;
                names.frame_id = Some(text);
            }
            other => {
                return Err(format!(
                    "{sensor}: unknown key '{other}': expected topic or frame_id"
                ))
            }
        }
    }
    Ok(names)
}

fn string(key: &str, value: &toml::Value) -> Result<String, String> {
    value
        .as_str()
        .map(str::to_string)
        .ok_or_else(|| format!("{key}: expected a string, got {}", value.type_str()))
}

fn unique(what: &str, names: &[String]) -> Result<(), String> {
    let mut seen = HashSet::new();
    match names.iter().find(|name| !seen.insert(name.as_str())) {
        Some(twice) => Err(format!(
            "the {what} '{twice}' is used twice: each sensor needs its own"
        )),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(text: &str, cameras: usize, has_imu: bool) -> Result<BagNames, String> {
        bag_names(&text.parse::<toml::Table>().unwrap(), cameras, has_imu)
    }

    #[test]
    fn a_table_replaces_the_names_it_gives_and_keeps_the_others() {
        let given = names(
            "body_frame = \"base_link\"\ncam1 = { topic = \"/right/image_raw\" }\nimu0 = { frame_id = \"imu_link\" }\n",
            2,
            true,
        )
        .unwrap();
        assert_eq!(given.body_frame(), "base_link");
        assert_eq!(given.image_topic("cam0"), "/cam0/image_raw");
        assert_eq!(given.image_topic("cam1"), "/right/image_raw");
        assert_eq!(given.camera_info_topic("cam1"), "/right/camera_info");
        assert_eq!(
            (given.imu_topic(), given.imu_frame()),
            ("/imu0".into(), "imu_link".into())
        );
    }

    #[test]
    fn bad_names_and_sensors_the_rig_lacks_are_refused_by_name() {
        let error = |text: &str| names(text, 2, false).unwrap_err();
        assert!(error("cam2 = { topic = \"/c\" }").contains("unknown key 'cam2'"));
        assert!(error("imu0 = { topic = \"/imu\" }").contains("(cam0, cam1)"));
        assert!(error("cam0 = { topic = \"left\" }").contains("cam0: topic 'left'"));
        assert!(error("cam0 = { frame = \"left\" }").contains("unknown key 'frame'"));
        assert!(error("body_frame = \"/base\"").contains("body_frame: frame id '/base'"));
        assert!(error("cam0 = \"/left\"").contains("cam0: expected a table"));
        assert!(error("cam0 = { topic = \"/cam1/image_raw\" }")
            .contains("'/cam1/image_raw' is used twice"));
        assert!(error("cam1 = { frame_id = \"body\" }").contains("frame id 'body' is used twice"));
    }
}
