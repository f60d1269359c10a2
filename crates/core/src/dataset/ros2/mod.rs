//! The ROS 2 bag layout (`--format ros2`): one rosbag2 folder holding an MCAP file (profile
//! `ros2`, `ros2msg` schemas, CDR messages) and the `metadata.yaml` that `ros2 bag` reads
//! (docs/src/formats.md, "ROS 2 bag layout").

mod bag;
mod camera;
mod messages;
mod metadata;
mod schemas;

pub use bag::{BagWriter, ClosedBag, Topic};
pub use camera::{CameraBag, DEPTH_UNITS_PER_METRE};
pub use messages::{
    cdr_bytes, Bytes, CameraInfo, Header, Image, Pose, PoseStamped, Quaternion, RegionOfInterest,
    TfMessage, Time, Transform, TransformStamped, Vector3,
};
pub use schemas::MessageType;
