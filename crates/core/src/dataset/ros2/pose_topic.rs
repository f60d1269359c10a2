//! A trajectory read from a pose topic of a bag, as `rslam eval` takes an estimate or a ground
//! truth: `geometry_msgs/PoseStamped`, `PoseWithCovarianceStamped` or `nav_msgs/Odometry`
//! messages, each a pose stamped by its header; or the transforms of a `tf2_msgs/TFMessage`
//! topic to one child frame (`/tf:base_link`), each its parent-to-child transform. Poses are
//! ordered by stamp; a topic is chosen by name, or is the bag's one pose topic.

use std::path::Path;

use glam::{DQuat, DVec3};

use super::messages::{
    from_cdr, OdometryPose, Pose as PoseMessage, PoseStamped, PoseWithCovarianceStamped, TfMessage,
};
use super::recorded::RecordedBag;
use crate::{printable, CoreError, Pose, Trajectory};

const POSE_STAMPED: &str = "geometry_msgs/msg/PoseStamped";
const POSE_WITH_COVARIANCE: &str = "geometry_msgs/msg/PoseWithCovarianceStamped";
const ODOMETRY: &str = "nav_msgs/msg/Odometry";
const TF: &str = "tf2_msgs/msg/TFMessage";
const POSE_TYPES: [&str; 3] = [POSE_STAMPED, POSE_WITH_COVARIANCE, ODOMETRY];

/// The trajectory on `topic` of the bag in `folder`: `TOPIC` for a pose topic, `TOPIC:CHILD` for
/// a TF topic's transforms to frame `CHILD`; `None` for the bag's one pose topic.
pub fn read_pose_topic(folder: &Path, topic: Option<&str>) -> Result<Trajectory, CoreError> {
    let bag = RecordedBag::open(folder)?;
    let (name, child) = match topic.map(|t| t.split_once(':')) {
        Some(Some((name, child))) => (Some(name), Some(child)),
        Some(None) => (topic, None),
        None => (None, None),
    };
    let bad = |message: String| CoreError::bad_file(folder, message);
    let mut poses: Vec<(f64, Pose)> = Vec::new();
    let mut pose_topics: Vec<(String, String)> = Vec::new();
    let mut chosen: Option<(String, String)> = None;
    for message in bag.messages()? {
        let message = message?;
        let (topic, type_name) = (message.topic(), message.type_name());
        let is_pose = POSE_TYPES.contains(&type_name) || type_name == TF;
        if is_pose && !pose_topics.iter().any(|(t, _)| t == topic) {
            pose_topics.push((topic.to_string(), type_name.to_string()));
        }
        let wanted = match name {
            Some(name) => topic == name,
            None => POSE_TYPES.contains(&type_name),
        };
        if !wanted {
            continue;
        }
        match &chosen {
            None => chosen = Some((topic.to_string(), type_name.to_string())),
            Some((first, _)) if first != topic => {
                return Err(bad(format!(
                    "several pose topics ({first}, {topic}, ...): name the one to read"
                )))
            }
            Some(_) => {}
        }
        let at = |what: String| {
            bad(format!(
                "topic {} ({type_name}), message {}: {what}",
                printable(topic),
                message.sequence
            ))
        };
        match (type_name, child) {
            (POSE_STAMPED, None) => {
                let m: PoseStamped = from_cdr(&message.data).map_err(at)?;
                poses.push((m.header.stamp.seconds(), pose_of(&m.pose).map_err(at)?));
            }
            (POSE_WITH_COVARIANCE, None) => {
                let m: PoseWithCovarianceStamped = from_cdr(&message.data).map_err(at)?;
                poses.push((m.header.stamp.seconds(), pose_of(&m.pose).map_err(at)?));
            }
            (ODOMETRY, None) => {
                let m: OdometryPose = from_cdr(&message.data).map_err(at)?;
                poses.push((m.header.stamp.seconds(), pose_of(&m.pose).map_err(at)?));
            }
            (TF, Some(child)) => {
                let m: TfMessage = from_cdr(&message.data).map_err(at)?;
                for t in m.transforms.iter().filter(|t| t.child_frame_id == child) {
                    let pose = PoseMessage {
                        position: t.transform.translation,
                        orientation: t.transform.rotation,
                    };
                    poses.push((t.header.stamp.seconds(), pose_of(&pose).map_err(at)?));
                }
            }
            (TF, None) => {
                return Err(bad(format!(
                    "{} is a TF topic: name the child frame whose transforms to read, as {}:CHILD",
                    printable(topic),
                    printable(topic)
                )))
            }
            (_, Some(_)) => {
                return Err(bad(format!(
                    "{} is a {type_name} topic; TOPIC:CHILD names a frame of a {TF} topic",
                    printable(topic)
                )))
            }
            _ => {
                return Err(bad(format!(
                    "topic {} holds {type_name}; expected {}, {} or {}",
                    printable(topic),
                    POSE_STAMPED,
                    POSE_WITH_COVARIANCE,
                    ODOMETRY
                )))
            }
        }
    }
    if poses.is_empty() {
        let found: Vec<String> = pose_topics
            .iter()
            .map(|(topic, kind)| format!("{topic} ({kind})"))
            .collect();
        let found = if found.is_empty() {
            "none".to_string()
        } else {
            found.join(", ")
        };
        let what = match (name, child) {
            (Some(name), Some(child)) => format!("no transform to frame {child} on {name}"),
            (Some(name), None) => format!("no message on topic {name}"),
            (None, _) => "no pose topic".to_string(),
        };
        return Err(bad(format!(
            "{what}; the bag's pose and TF topics: {found}"
        )));
    }
    poses.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (timestamps, poses) = poses.into_iter().unzip();
    Ok(Trajectory::new(timestamps, poses))
}

/// A pose message as a rigid pose: a finite position and a rotation from a non-zero quaternion.
fn pose_of(pose: &PoseMessage) -> Result<Pose, String> {
    let p = pose.position;
    let o = pose.orientation;
    let q = DQuat::from_xyzw(o.x, o.y, o.z, o.w);
    let norm = q.length();
    let translation = DVec3::new(p.x, p.y, p.z);
    if !(norm > 0.0 && norm.is_finite() && translation.is_finite()) {
        return Err(format!(
            "position ({} {} {}) and orientation ({} {} {} {}): expected finite numbers and a non-zero quaternion",
            p.x, p.y, p.z, o.x, o.y, o.z, o.w
        ));
    }
    Ok(Pose::new(q / norm, translation))
}
