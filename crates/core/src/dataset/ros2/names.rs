//! The topic names and frame ids of a rig's bag: by default those of EuRoC's recordings played in
//! ROS 2 (`/cam0/image_raw` in frame `cam0`, `/imu0` in `imu0`, the sensors in `body`), each
//! replaceable (a rig file's `[ros2]` table). A camera's `CameraInfo` goes on `camera_info` in its
//! image topic's namespace, as image_transport pairs them.

use std::collections::BTreeMap;

use serde::Serialize;

use super::{GROUND_TRUTH_TOPIC, IMU_FRAME, IMU_TOPIC};

/// A sensor's names where they are not the default.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct SensorNames {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub topic: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub frame_id: Option<String>,
}

/// The names a rig's bag uses where they are not the default (serialised as given, for the
/// manifest).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct BagNames {
    /// By sensor (`cam0`, `cam1`, …, `imu0`).
    pub sensors: BTreeMap<String, SensorNames>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub body_frame: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ground_truth_topic: Option<String>,
}

/// The frame the rig's sensors are placed in, by default.
pub const RIG_BODY_FRAME: &str = "body";

impl BagNames {
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// Camera `camera`'s image topic.
    pub fn image_topic(&self, camera: &str) -> String {
        self.topic(camera)
            .unwrap_or_else(|| format!("/{camera}/image_raw"))
    }

    /// Camera `camera`'s `CameraInfo` topic: `camera_info` beside its image topic.
    pub fn camera_info_topic(&self, camera: &str) -> String {
        let image = self.image_topic(camera);
        let namespace = image.rsplit_once('/').map_or("", |(ns, _)| ns);
        format!("{namespace}/camera_info")
    }

    /// Sensor `sensor`'s frame id (a camera's, or `imu0`).
    pub fn frame_id(&self, sensor: &str) -> String {
        self.sensors
            .get(sensor)
            .and_then(|names| names.frame_id.clone())
            .unwrap_or_else(|| sensor.to_string())
    }

    pub fn imu_topic(&self) -> String {
        self.topic(IMU_FRAME).unwrap_or_else(|| IMU_TOPIC.into())
    }

    pub fn imu_frame(&self) -> String {
        self.frame_id(IMU_FRAME)
    }

    pub fn body_frame(&self) -> String {
        self.body_frame
            .clone()
            .unwrap_or_else(|| RIG_BODY_FRAME.into())
    }

    pub fn ground_truth_topic(&self) -> String {
        self.ground_truth_topic
            .clone()
            .unwrap_or_else(|| GROUND_TRUTH_TOPIC.into())
    }

    fn topic(&self, sensor: &str) -> Option<String> {
        self.sensors
            .get(sensor)
            .and_then(|names| names.topic.clone())
    }
}

/// Checks a topic name as ROS 2 takes it fully qualified: `/`, then tokens of letters, digits
/// and `_` separated by single `/`, none starting with a digit, no `/` at the end.
pub fn check_topic(name: &str) -> Result<(), String> {
    let why = || {
        format!(
            "topic '{}': expected a fully qualified ROS 2 name such as /left/image_raw (letters, digits and _ between single slashes, no token starting with a digit)",
            crate::printable(name)
        )
    };
    let tokens = name.strip_prefix('/').ok_or_else(why)?;
    let token_ok = |token: &str| {
        token.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && token.chars().next().is_some_and(|c| !c.is_ascii_digit())
    };
    match tokens.split('/').all(token_ok) {
        true => Ok(()),
        false => Err(why()),
    }
}

/// Checks a frame id as tf2 takes it: letters, digits, `_`, `-`, `.` and `/`, not starting with
/// `/` (tf2 refuses a leading slash).
pub fn check_frame_id(name: &str) -> Result<(), String> {
    let ok = !name.is_empty()
        && !name.starts_with('/')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_-./".contains(c));
    match ok {
        true => Ok(()),
        false => Err(format!(
            "frame id '{}': expected letters, digits, _ - . or /, not starting with / (tf2's frame ids)",
            crate::printable(name)
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_euroc_played_in_ros2_and_camera_info_follows_the_image_topic() {
        let mut names = BagNames::default();
        assert_eq!(names.image_topic("cam1"), "/cam1/image_raw");
        assert_eq!(names.camera_info_topic("cam1"), "/cam1/camera_info");
        assert_eq!(
            (names.imu_topic(), names.imu_frame()),
            ("/imu0".into(), "imu0".into())
        );
        assert_eq!(names.body_frame(), "body");
        names.sensors.insert(
            "cam1".into(),
            SensorNames {
                topic: Some("/stereo/right/image_rect".into()),
                frame_id: None,
            },
        );
        assert_eq!(names.camera_info_topic("cam1"), "/stereo/right/camera_info");
        assert_eq!(names.frame_id("cam1"), "cam1");
    }

    #[test]
    fn names_ros_2_refuses_are_refused() {
        for good in ["/imu", "/left/image_raw", "/a_1/b"] {
            assert_eq!(check_topic(good), Ok(()), "{good}");
        }
        for bad in ["imu", "/", "/left//raw", "/left/", "/1cam/image", "/cam 0"] {
            assert!(check_topic(bad).is_err(), "{bad}");
        }
        for good in ["base_link", "camera-left.optical", "robot1/imu"] {
            assert_eq!(check_frame_id(good), Ok(()), "{good}");
        }
        for bad in ["", "/base_link", "left cam"] {
            assert!(check_frame_id(bad).is_err(), "{bad}");
        }
    }
}
