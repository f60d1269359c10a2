//! The ROS 2 bag layout (`--format ros2`): one rosbag2 folder holding an MCAP file (profile
//! `ros2`, `ros2msg` schemas, CDR messages) and the `metadata.yaml` that `ros2 bag` reads
//! (docs/src/formats.md, "ROS 2 bag layout"); and a recorded bag read, its camera's images
//! perturbed and every other message copied ([`RecordedBagCameras`], [`PerturbedBag`]).

mod bag;
mod camera;
mod image_codec;
mod merge;
mod messages;
mod metadata;
mod names;
mod options;
mod perturbed_bag;
mod pose_topic;
mod record_lengths;
mod recorded;
mod recorded_camera;
mod recorded_imu;
mod rig_bag;
mod schemas;

pub use bag::{BagWriter, ClosedBag, LogTimes, Topic};
pub use camera::{
    BagImu, CameraBag, DEPTH_UNITS_PER_METRE, GROUND_TRUTH_TOPIC, IMU_FRAME, IMU_TOPIC,
    TF_STATIC_TOPIC, TF_TOPIC,
};
pub use image_codec::{decode_colour, decode_depth, Codec, ImageEncoding};
pub use messages::{
    cdr_bytes, from_cdr, Bytes, CameraInfo, CompressedImage, Header, Image, Imu, Pose, PoseStamped,
    Quaternion, RegionOfInterest, TfMessage, Time, Transform, TransformStamped, Vector3,
};
pub use names::{check_frame_id, check_topic, BagNames, SensorNames, RIG_BODY_FRAME};
pub use options::{BagCompression, BagDepth, BagOptions};
pub use perturbed_bag::PerturbedBag;
pub use pose_topic::read_pose_topic;
pub use recorded::{BagMessage, BagMessages, RecordedBag};
pub use recorded_camera::{ImageMessage, ImageTopic, RecordedBagCamera, RecordedBagCameras};
pub use recorded_imu::{RecordedImu, IMU_TYPE};
pub use rig_bag::{variances, RigBag};
pub use schemas::MessageType;
