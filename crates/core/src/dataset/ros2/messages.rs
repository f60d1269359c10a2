//! The ROS 2 messages a bag carries, as serde structs in the field order of their `.msg`
//! definitions ([`super::schemas`]), which is the order CDR writes them in; the ones rslam reads
//! from recorded bags deserialise too, their byte arrays borrowed from the message.

use std::fmt;

use byteorder::{BigEndian, LittleEndian};
use serde::de::{Deserialize, Deserializer, Visitor};
use serde::{Serialize, Serializer};

/// `builtin_interfaces/msg/Time`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, serde::Deserialize)]
pub struct Time {
    pub sec: i32,
    pub nanosec: u32,
}

impl Time {
    /// The stamp of a capture time in seconds, rounded to the nanosecond.
    pub fn from_seconds(seconds: f64) -> Self {
        Self::from_nanoseconds((seconds * 1e9).round() as i64)
    }

    pub fn from_nanoseconds(nanoseconds: i64) -> Self {
        Self {
            sec: nanoseconds.div_euclid(1_000_000_000) as i32,
            nanosec: nanoseconds.rem_euclid(1_000_000_000) as u32,
        }
    }

    /// Nanoseconds since the epoch, negative before it.
    pub fn signed_nanoseconds(self) -> i64 {
        self.sec as i64 * 1_000_000_000 + self.nanosec as i64
    }

    /// Nanoseconds since the epoch: an MCAP message's log and publish time.
    pub fn nanoseconds(self) -> u64 {
        self.signed_nanoseconds().max(0) as u64
    }

    pub fn seconds(self) -> f64 {
        self.sec as f64 + self.nanosec as f64 * 1e-9
    }
}

/// `std_msgs/msg/Header`.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Header {
    pub stamp: Time,
    pub frame_id: String,
}

/// A `uint8[]` field, written as one length and its bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bytes<'a>(pub &'a [u8]);

impl Serialize for Bytes<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_bytes(self.0)
    }
}

impl<'de: 'a, 'a> Deserialize<'de> for Bytes<'a> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Borrowed;
        impl<'de> Visitor<'de> for Borrowed {
            type Value = Bytes<'de>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a byte array")
            }
            fn visit_borrowed_bytes<E>(self, bytes: &'de [u8]) -> Result<Self::Value, E> {
                Ok(Bytes(bytes))
            }
        }
        deserializer.deserialize_bytes(Borrowed)
    }
}

/// `sensor_msgs/msg/Image`.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Image<'a> {
    pub header: Header,
    pub height: u32,
    pub width: u32,
    pub encoding: String,
    pub is_bigendian: u8,
    pub step: u32,
    #[serde(borrow)]
    pub data: Bytes<'a>,
}

/// `sensor_msgs/msg/CompressedImage`: `format` is image_transport's, e.g. `rgb8; jpeg compressed
/// bgr8`, or a bare `jpeg` or `png`.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct CompressedImage<'a> {
    pub header: Header,
    pub format: String,
    #[serde(borrow)]
    pub data: Bytes<'a>,
}

/// `sensor_msgs/msg/RegionOfInterest`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, serde::Deserialize)]
pub struct RegionOfInterest {
    pub x_offset: u32,
    pub y_offset: u32,
    pub height: u32,
    pub width: u32,
    pub do_rectify: bool,
}

/// `sensor_msgs/msg/CameraInfo`.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct CameraInfo {
    pub header: Header,
    pub height: u32,
    pub width: u32,
    pub distortion_model: String,
    pub d: Vec<f64>,
    pub k: [f64; 9],
    pub r: [f64; 9],
    pub p: [f64; 12],
    pub binning_x: u32,
    pub binning_y: u32,
    pub roi: RegionOfInterest,
}

/// `geometry_msgs/msg/Point` (and `Vector3`, which has the same fields).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Vector3 {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// `geometry_msgs/msg/Quaternion`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Quaternion {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub w: f64,
}

/// `geometry_msgs/msg/Pose`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Pose {
    pub position: Vector3,
    pub orientation: Quaternion,
}

/// `geometry_msgs/msg/PoseStamped`.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct PoseStamped {
    pub header: Header,
    pub pose: Pose,
}

/// `geometry_msgs/msg/Transform`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Transform {
    pub translation: Vector3,
    pub rotation: Quaternion,
}

/// `geometry_msgs/msg/TransformStamped`.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct TransformStamped {
    pub header: Header,
    pub child_frame_id: String,
    pub transform: Transform,
}

/// The start of `nav_msgs/msg/Odometry`: its header, child frame and pose (the first field of
/// its `PoseWithCovariance`); the covariance and twist after it are not read.
#[derive(Clone, Debug, PartialEq, serde::Deserialize)]
pub struct OdometryPose {
    pub header: Header,
    pub child_frame_id: String,
    pub pose: Pose,
}

/// The start of `geometry_msgs/msg/PoseWithCovarianceStamped`: its header and pose; the
/// covariance after it is not read.
#[derive(Clone, Debug, PartialEq, serde::Deserialize)]
pub struct PoseWithCovarianceStamped {
    pub header: Header,
    pub pose: Pose,
}

/// `sensor_msgs/msg/Imu`.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Imu {
    pub header: Header,
    pub orientation: Quaternion,
    pub orientation_covariance: [f64; 9],
    pub angular_velocity: Vector3,
    pub angular_velocity_covariance: [f64; 9],
    pub linear_acceleration: Vector3,
    pub linear_acceleration_covariance: [f64; 9],
}

/// `tf2_msgs/msg/TFMessage`.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct TfMessage {
    pub transforms: Vec<TransformStamped>,
}

/// CDR's encapsulation header: plain CDR, little-endian, no options.
const CDR_LE: [u8; 4] = [0, 1, 0, 0];

/// Little-endian CDR with its 4-byte encapsulation header, as rosbag2 stores messages.
pub fn cdr_bytes<M: Serialize>(message: &M) -> Result<Vec<u8>, String> {
    let mut bytes = CDR_LE.to_vec();
    cdr_encoding::to_writer::<_, LittleEndian, _>(&mut bytes, message)
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}

/// A message from its CDR bytes (either byte order, after the encapsulation header); its byte
/// arrays borrow from `bytes`.
pub fn from_cdr<'de, M: Deserialize<'de>>(bytes: &'de [u8]) -> Result<M, String> {
    let body = bytes.get(4..).ok_or("shorter than CDR's 4-byte header")?;
    let message = match bytes[..2] {
        [0, 1] => cdr_encoding::from_bytes::<M, LittleEndian>(body),
        [0, 0] => cdr_encoding::from_bytes::<M, BigEndian>(body),
        [a, b] => return Err(format!("encapsulation {a:#04x}{b:02x} is not plain CDR")),
        _ => unreachable!("two bytes"),
    };
    message
        .map(|(message, _)| message)
        .map_err(|e| format!("not a CDR message of its type: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_header_is_its_stamp_then_a_null_terminated_string_after_the_encapsulation() {
        let header = Header {
            stamp: Time::from_seconds(2.5),
            frame_id: "cam".into(),
        };
        let bytes = cdr_bytes(&header).unwrap();
        let expected: Vec<u8> = [
            &[0, 1, 0, 0][..],             // CDR_LE encapsulation, options 0
            &2i32.to_le_bytes(),           // sec
            &500_000_000u32.to_le_bytes(), // nanosec
            &4u32.to_le_bytes(),           // string length with its terminating null
            b"cam\0",
        ]
        .concat();
        assert_eq!(bytes, expected);
    }

    #[test]
    fn an_image_aligns_its_fields_and_writes_its_data_as_one_sequence() {
        let image = Image {
            header: Header {
                stamp: Time::from_seconds(0.0),
                frame_id: "a".into(),
            },
            height: 1,
            width: 2,
            encoding: "mono8".into(),
            is_bigendian: 0,
            step: 2,
            data: Bytes(&[7, 9]),
        };
        let bytes = cdr_bytes(&image).unwrap();
        let body = &bytes[4..];
        // stamp (8), "a" (4 + 2), pad to 4 (2), height, width (8), "mono8" (4 + 6), is_bigendian
        // (1), pad to 4 (1), step (4), data length (4) and bytes (2).
        assert_eq!(body.len(), 8 + 6 + 2 + 8 + 10 + 1 + 1 + 4 + 4 + 2);
        assert_eq!(&body[body.len() - 6..], &[2, 0, 0, 0, 7, 9]);
    }

    #[test]
    fn a_message_reads_back_as_written_its_bytes_borrowed() {
        let image = Image {
            header: Header {
                stamp: Time::from_seconds(3.25),
                frame_id: "camera_color_optical_frame".into(),
            },
            height: 1,
            width: 3,
            encoding: "rgb8".into(),
            is_bigendian: 0,
            step: 9,
            data: Bytes(&[1, 2, 3, 4, 5, 6, 7, 8, 9]),
        };
        let bytes = cdr_bytes(&image).unwrap();
        let read: Image = from_cdr(&bytes).unwrap();
        assert_eq!(read, image);
        assert!(bytes.as_ptr_range().contains(&read.data.0.as_ptr()));
    }

    #[test]
    fn a_claimed_length_beyond_the_message_is_an_error_not_an_allocation() {
        let mut bytes = cdr_bytes(&CompressedImage {
            header: Header {
                stamp: Time::from_seconds(0.0),
                frame_id: String::new(),
            },
            format: "png".into(),
            data: Bytes(&[1, 2]),
        })
        .unwrap();
        let length_at = bytes.len() - 6;
        bytes[length_at..length_at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
        let error = from_cdr::<CompressedImage>(&bytes).unwrap_err();
        assert!(error.contains("not a CDR message"), "{error}");
        assert!(from_cdr::<Header>(&[0, 1]).is_err());
    }

    #[test]
    fn stamps_round_to_the_nanosecond_and_order_like_times() {
        let t = Time::from_seconds(1.000_000_000_4);
        assert_eq!((t.sec, t.nanosec), (1, 0));
        assert_eq!(Time::from_seconds(0.05).nanoseconds(), 50_000_000);
        assert!(Time::from_seconds(0.9) < Time::from_seconds(1.1));
    }
}
