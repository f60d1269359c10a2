//! The `.msg` definitions of the messages rslam writes, as ROS 2 Humble and later define them
//! (comments and constants left out), and each message's MCAP schema: its own definition followed
//! by every definition it uses, each under a line of 80 `=` and `MSG: package/Name` — the
//! `ros2msg` encoding of MCAP's ros2 profile. The Python tests check them field by field against
//! the definitions the `rosbags` library ships.

/// `package/Name` and the definition of one message type.
struct Definition {
    name: &'static str,
    text: &'static str,
    uses: &'static [&'static Definition],
}

const TIME: Definition = Definition {
    name: "builtin_interfaces/Time",
    text: "int32 sec\nuint32 nanosec\n",
    uses: &[],
};
const HEADER: Definition = Definition {
    name: "std_msgs/Header",
    text: "builtin_interfaces/Time stamp\nstring frame_id\n",
    uses: &[&TIME],
};
const IMAGE: Definition = Definition {
    name: "sensor_msgs/Image",
    text: "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\n\
           uint8 is_bigendian\nuint32 step\nuint8[] data\n",
    uses: &[&HEADER],
};
const REGION_OF_INTEREST: Definition = Definition {
    name: "sensor_msgs/RegionOfInterest",
    text: "uint32 x_offset\nuint32 y_offset\nuint32 height\nuint32 width\nbool do_rectify\n",
    uses: &[],
};
const CAMERA_INFO: Definition = Definition {
    name: "sensor_msgs/CameraInfo",
    text: "std_msgs/Header header\nuint32 height\nuint32 width\nstring distortion_model\n\
           float64[] d\nfloat64[9] k\nfloat64[9] r\nfloat64[12] p\nuint32 binning_x\n\
           uint32 binning_y\nsensor_msgs/RegionOfInterest roi\n",
    uses: &[&HEADER, &REGION_OF_INTEREST],
};
const POINT: Definition = Definition {
    name: "geometry_msgs/Point",
    text: "float64 x\nfloat64 y\nfloat64 z\n",
    uses: &[],
};
const VECTOR3: Definition = Definition {
    name: "geometry_msgs/Vector3",
    text: "float64 x\nfloat64 y\nfloat64 z\n",
    uses: &[],
};
const QUATERNION: Definition = Definition {
    name: "geometry_msgs/Quaternion",
    text: "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n",
    uses: &[],
};
const POSE: Definition = Definition {
    name: "geometry_msgs/Pose",
    text: "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n",
    uses: &[&POINT, &QUATERNION],
};
const POSE_STAMPED: Definition = Definition {
    name: "geometry_msgs/PoseStamped",
    text: "std_msgs/Header header\ngeometry_msgs/Pose pose\n",
    uses: &[&HEADER, &POSE],
};
const TRANSFORM: Definition = Definition {
    name: "geometry_msgs/Transform",
    text: "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n",
    uses: &[&VECTOR3, &QUATERNION],
};
const TRANSFORM_STAMPED: Definition = Definition {
    name: "geometry_msgs/TransformStamped",
    text: "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n",
    uses: &[&HEADER, &TRANSFORM],
};
const IMU: Definition = Definition {
    name: "sensor_msgs/Imu",
    text: "std_msgs/Header header\ngeometry_msgs/Quaternion orientation\n\
           float64[9] orientation_covariance\ngeometry_msgs/Vector3 angular_velocity\n\
           float64[9] angular_velocity_covariance\ngeometry_msgs/Vector3 linear_acceleration\n\
           float64[9] linear_acceleration_covariance\n",
    uses: &[&HEADER, &QUATERNION, &VECTOR3],
};
const TF_MESSAGE: Definition = Definition {
    name: "tf2_msgs/TFMessage",
    text: "geometry_msgs/TransformStamped[] transforms\n",
    uses: &[&TRANSFORM_STAMPED],
};

/// The message types a bag of rslam's holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MessageType {
    Image,
    CameraInfo,
    PoseStamped,
    TfMessage,
    Imu,
}

impl MessageType {
    fn definition(self) -> &'static Definition {
        match self {
            Self::Image => &IMAGE,
            Self::CameraInfo => &CAMERA_INFO,
            Self::PoseStamped => &POSE_STAMPED,
            Self::TfMessage => &TF_MESSAGE,
            Self::Imu => &IMU,
        }
    }

    /// The type's name as rosbag2 records it: `package/msg/Name`.
    pub fn name(self) -> String {
        let (package, name) = self
            .definition()
            .name
            .split_once('/')
            .unwrap_or(("", self.definition().name));
        format!("{package}/msg/{name}")
    }

    /// The MCAP schema: the definition, then each one it uses, depth first, each once.
    pub fn schema(self) -> String {
        let mut order: Vec<&Definition> = Vec::new();
        fn visit(definition: &'static Definition, order: &mut Vec<&'static Definition>) {
            for used in definition.uses {
                if !order.iter().any(|d| d.name == used.name) {
                    order.push(used);
                    visit(used, order);
                }
            }
        }
        visit(self.definition(), &mut order);
        let mut text = self.definition().text.to_string();
        for used in order {
            text.push_str(&"=".repeat(80));
            text.push_str(&format!("\nMSG: {}\n{}", used.name, used.text));
        }
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_schema_lists_every_definition_it_uses_once() {
        let schema = MessageType::TfMessage.schema();
        for name in [
            "geometry_msgs/TransformStamped",
            "std_msgs/Header",
            "builtin_interfaces/Time",
            "geometry_msgs/Transform",
            "geometry_msgs/Vector3",
            "geometry_msgs/Quaternion",
        ] {
            assert_eq!(
                schema.matches(&format!("MSG: {name}\n")).count(),
                1,
                "{name}"
            );
        }
        assert!(schema.starts_with("geometry_msgs/TransformStamped[] transforms\n"));
        assert_eq!(MessageType::TfMessage.name(), "tf2_msgs/msg/TFMessage");
    }
}
