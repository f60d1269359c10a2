//! One RGB-D camera as a ROS 2 bag, with the topics and frame ids of the RealSense ROS 2 driver:
//! colour (`rgb8`) and depth registered to it (`16UC1`, millimetres, 0 = no measurement; or
//! `32FC1` metres, NaN = no measurement; REP 118) each with its `CameraInfo`, the optical frame's
//! pose in `camera_link` on `/tf_static` (REP 103 axes: z forward, x right, y down), and the
//! ground-truth pose of the optical frame in `world`, the pose a TUM `groundtruth.txt` of the
//! same job holds (and, asked for, `camera_link` in `world` on `/tf`). With an IMU (the `rgbd-imu`
//! rig), its readings on `/imu0` in its own frame `imu0`, whose pose in `camera_link` joins
//! `/tf_static`, each logged before the frames stamped after it. With actors, each colour
//! frame's instance mask (`mono16`: 0 static, k actor k) on `/camera/mask/image_raw`.

use std::path::Path;

use super::bag::{bag_name, BagWriter, ClosedBag, Topic};
use super::image_codec::{depth_bytes, depth_image};
use super::messages::{
    Bytes, CameraInfo, Header, Image, Imu as ImuMessage, Pose, PoseStamped, Quaternion,
    RegionOfInterest, TfMessage, Time, Transform, TransformStamped, Vector3,
};
use super::options::BagOptions;
use super::schemas::MessageType;
use crate::dataset::euroc::ImuSample;
use crate::{CoreError, DepthImage, Distortion, Intrinsics, MaskImage, RgbImage};

pub const COLOR_TOPIC: &str = "/camera/color/image_raw";
pub const COLOR_INFO_TOPIC: &str = "/camera/color/camera_info";
pub const DEPTH_TOPIC: &str = "/camera/depth/image_raw";
pub const DEPTH_INFO_TOPIC: &str = "/camera/depth/camera_info";
pub const GROUND_TRUTH_TOPIC: &str = "/ground_truth/pose";
pub const TF_STATIC_TOPIC: &str = "/tf_static";
pub const TF_TOPIC: &str = "/tf";
pub const OPTICAL_FRAME: &str = "camera_color_optical_frame";
pub const BODY_FRAME: &str = "camera_link";
pub const WORLD_FRAME: &str = "world";
pub const IMU_TOPIC: &str = "/imu0";
pub const MASK_TOPIC: &str = "/camera/mask/image_raw";
pub const IMU_FRAME: &str = "imu0";
/// 16UC1 depth units per metre.
pub const DEPTH_UNITS_PER_METRE: f64 = 1000.0;

// Topic indices, in the order `CameraBag::create` lists them.
const COLOR: usize = 0;
const COLOR_INFO: usize = 1;
const DEPTH: usize = 2;
const DEPTH_INFO: usize = 3;
const GROUND_TRUTH: usize = 4;
const TF_STATIC: usize = 5;

/// The IMU beside the camera: its readings (in its own frame), where it sits, and the variance
/// of one reading's noise per axis, for the messages' covariances.
#[derive(Clone, Debug, PartialEq)]
pub struct BagImu {
    pub samples: Vec<ImuSample>,
    /// The IMU frame in the camera's optical frame.
    pub camera_from_imu: crate::Pose,
    /// (rad/s)²
    pub gyro_variance: f64,
    /// (m/s²)²
    pub accel_variance: f64,
}

pub struct CameraBag {
    bag: BagWriter,
    intrinsics: Intrinsics,
    distortion: Option<Distortion>,
    options: BagOptions,
    imu: Option<BagImu>,
    /// The indices of the optional topics.
    imu_topic: Option<usize>,
    tf_topic: Option<usize>,
    mask_topic: Option<usize>,
    /// The IMU samples written so far.
    imu_written: usize,
    tf_written: bool,
}

impl CameraBag {
    /// With `masks`, the bag has the instance-mask topic ([`CameraBag::write_mask`]).
    pub fn create(
        folder: &Path,
        intrinsics: Intrinsics,
        distortion: Option<Distortion>,
        (imu, masks): (Option<BagImu>, bool),
        options: BagOptions,
    ) -> Result<Self, CoreError> {
        let name = bag_name(folder);
        let mut topics = vec![
            Topic::new(COLOR_TOPIC, MessageType::Image),
            Topic::new(COLOR_INFO_TOPIC, MessageType::CameraInfo),
            Topic::new(DEPTH_TOPIC, MessageType::Image),
            Topic::new(DEPTH_INFO_TOPIC, MessageType::CameraInfo),
            Topic::new(GROUND_TRUTH_TOPIC, MessageType::PoseStamped),
            Topic::latched(TF_STATIC_TOPIC, MessageType::TfMessage),
        ];
        let mut optional = |wanted: bool, topic: Topic| {
            wanted.then(|| {
                topics.push(topic);
                topics.len() - 1
            })
        };
        let imu_topic = optional(imu.is_some(), Topic::new(IMU_TOPIC, MessageType::Imu));
        let tf_topic = optional(options.tf, Topic::new(TF_TOPIC, MessageType::TfMessage));
        let mask_topic = optional(masks, Topic::new(MASK_TOPIC, MessageType::Image));
        Ok(Self {
            bag: BagWriter::create(folder, &name, &topics, options.compression)?,
            intrinsics,
            distortion,
            options,
            imu,
            imu_topic,
            tf_topic,
            mask_topic,
            imu_written: 0,
            tf_written: false,
        })
    }

    /// Colour captured at `time` and its camera info.
    pub fn write_rgb(&mut self, time: f64, image: &RgbImage) -> Result<(), CoreError> {
        let stamp = self.stamp_at(time)?;
        let message = Image {
            header: header(stamp),
            height: image.height,
            width: image.width,
            encoding: "rgb8".into(),
            is_bigendian: 0,
            step: 3 * image.width,
            data: Bytes(&image.data),
        };
        self.bag.write(COLOR, stamp, &message)?;
        let info = camera_info(header(stamp), &self.intrinsics, self.distortion);
        self.bag.write(COLOR_INFO, stamp, &info)
    }

    pub fn has_masks(&self) -> bool {
        self.mask_topic.is_some()
    }

    /// The instance mask of the colour captured at `time`, as `mono16`.
    pub fn write_mask(&mut self, time: f64, mask: &MaskImage) -> Result<(), CoreError> {
        let Some(topic) = self.mask_topic else {
            return Err(CoreError::Encode {
                message: format!("{MASK_TOPIC}: an instance mask for a bag made without masks"),
            });
        };
        let stamp = self.stamp_at(time)?;
        let data: &[u8] = bytemuck::cast_slice(&mask.data);
        let message = Image {
            header: header(stamp),
            height: mask.height,
            width: mask.width,
            encoding: "mono16".into(),
            is_bigendian: u8::from(cfg!(target_endian = "big")),
            step: 2 * mask.width,
            data: Bytes(data),
        };
        self.bag.write(topic, stamp, &message)
    }

    /// Depth captured at `time` and its camera info, in the options' encoding.
    pub fn write_depth(&mut self, time: f64, depth: &DepthImage) -> Result<(), CoreError> {
        let stamp = self.stamp_at(time)?;
        let data = depth_bytes(depth, self.options.depth);
        let message = depth_image(header(stamp), depth, self.options.depth, &data);
        self.bag.write(DEPTH, stamp, &message)?;
        let info = camera_info(header(stamp), &self.intrinsics, self.distortion);
        self.bag.write(DEPTH_INFO, stamp, &info)
    }

    /// The optical frame's ground-truth pose in the world at `time` (and `camera_link`'s on
    /// `/tf`, when asked for).
    pub fn write_ground_truth(&mut self, time: f64, pose: &crate::Pose) -> Result<(), CoreError> {
        let stamp = self.stamp_at(time)?;
        self.bag
            .write(GROUND_TRUTH, stamp, &pose_in_world(stamp, pose))?;
        if let Some(tf) = self.tf_topic {
            let body = pose.compose(&optical_in_body().inverse());
            self.bag
                .write(tf, stamp, &body_in_world(stamp, BODY_FRAME, &body))?;
        }
        Ok(())
    }

    /// Writes the IMU readings left, then closes the bag: its storage file's name and
    /// checksum, and the `metadata.yaml` text.
    pub fn finish(mut self) -> Result<ClosedBag, CoreError> {
        self.advance_to(None)?;
        self.bag.finish()
    }

    /// The stamp of `time`, after what comes before it: `/tf_static` first, then the IMU
    /// readings up to it.
    fn stamp_at(&mut self, time: f64) -> Result<Time, CoreError> {
        let stamp = Time::from_seconds(time);
        self.advance_to(Some(stamp))?;
        Ok(stamp)
    }

    /// Writes what comes before `stamp` (`None`: before the end).
    fn advance_to(&mut self, stamp: Option<Time>) -> Result<(), CoreError> {
        let samples = self.imu.as_ref().map_or(&[][..], |imu| &imu.samples[..]);
        let imu_stamp = |sample: &ImuSample| Time::from_nanoseconds(sample.t_ns as i64);
        let first_imu = samples.first().map(imu_stamp);
        if !self.tf_written {
            if let Some(first) = first_imu.into_iter().chain(stamp).min() {
                self.tf_written = true;
                let tf = self.frames_in_body(first);
                self.bag.write(TF_STATIC, first, &tf)?;
            }
        }
        let (Some(imu), Some(topic)) = (&self.imu, self.imu_topic) else {
            return Ok(());
        };
        while let Some(sample) = imu.samples.get(self.imu_written) {
            let at = imu_stamp(sample);
            if stamp.is_some_and(|stamp| at > stamp) {
                break;
            }
            let (gyro, accel) = (imu.gyro_variance, imu.accel_variance);
            let message = imu_message(sample, at, IMU_FRAME, gyro, accel);
            self.bag.write(topic, at, &message)?;
            self.imu_written += 1;
        }
        Ok(())
    }

    /// `/tf_static`: the optical frame, and the IMU's, in `camera_link`.
    fn frames_in_body(&self, stamp: Time) -> TfMessage {
        let optical = optical_in_body();
        let mut transforms = vec![transform_stamped(
            stamp,
            BODY_FRAME,
            OPTICAL_FRAME,
            &optical,
        )];
        if let Some(imu) = &self.imu {
            let imu_in_body = optical.compose(&imu.camera_from_imu);
            transforms.push(transform_stamped(
                stamp,
                BODY_FRAME,
                IMU_FRAME,
                &imu_in_body,
            ));
        }
        TfMessage { transforms }
    }
}

/// The `CameraInfo` of a pinhole camera with `distortion` (`plumb_bob` k1 k2 p1 p2 0, or
/// `equidistant`), not rectified.
pub(super) fn camera_info(
    header: Header,
    k: &Intrinsics,
    distortion: Option<Distortion>,
) -> CameraInfo {
    let (model, d) = match distortion {
        Some(Distortion::Radtan { k1, k2, p1, p2 }) => ("plumb_bob", vec![k1, k2, p1, p2, 0.0]),
        Some(Distortion::Equidistant { k1, k2, k3, k4 }) => ("equidistant", vec![k1, k2, k3, k4]),
        None => ("plumb_bob", vec![0.0; 5]),
    };
    CameraInfo {
        header,
        height: k.height,
        width: k.width,
        distortion_model: model.into(),
        d,
        k: [k.fx, 0.0, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0],
        r: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        p: [
            k.fx, 0.0, k.cx, 0.0, 0.0, k.fy, k.cy, 0.0, 0.0, 0.0, 1.0, 0.0,
        ],
        binning_x: 0,
        binning_y: 0,
        roi: RegionOfInterest::default(),
    }
}

fn header(stamp: Time) -> Header {
    Header {
        stamp,
        frame_id: OPTICAL_FRAME.into(),
    }
}

/// Depth in metres as 16UC1 millimetres: 0 for no measurement and beyond 65.535 m.
pub(super) fn millimetres(z: f32) -> u16 {
    let mm = (z as f64 * DEPTH_UNITS_PER_METRE).round();
    if mm.is_finite() && mm >= 1.0 && mm <= u16::MAX as f64 {
        mm as u16
    } else {
        0
    }
}

/// `camera_link` (x forward, y left, z up) to the optical frame (z forward, x right, y down):
/// the rotation the RealSense driver publishes, roll −90°, yaw −90°.
fn optical_in_body() -> crate::Pose {
    crate::Pose::new(
        glam::DQuat::from_xyzw(-0.5, 0.5, -0.5, 0.5),
        glam::DVec3::ZERO,
    )
}

/// A pose in `world` stamped `stamp`.
pub(super) fn pose_in_world(stamp: Time, pose: &crate::Pose) -> PoseStamped {
    let (t, q) = (pose.translation, pose.rotation);
    PoseStamped {
        header: Header {
            stamp,
            frame_id: WORLD_FRAME.into(),
        },
        pose: Pose {
            position: Vector3 {
                x: t.x,
                y: t.y,
                z: t.z,
            },
            orientation: Quaternion {
                x: q.x,
                y: q.y,
                z: q.z,
                w: q.w,
            },
        },
    }
}

/// `child`'s pose in `parent` as a transform stamped `stamp`.
pub(super) fn transform_stamped(
    stamp: Time,
    parent: &str,
    child: &str,
    pose: &crate::Pose,
) -> TransformStamped {
    let (t, q) = (pose.translation, pose.rotation);
    TransformStamped {
        header: Header {
            stamp,
            frame_id: parent.into(),
        },
        child_frame_id: child.into(),
        transform: Transform {
            translation: Vector3 {
                x: t.x,
                y: t.y,
                z: t.z,
            },
            rotation: Quaternion {
                x: q.x,
                y: q.y,
                z: q.z,
                w: q.w,
            },
        },
    }
}

/// `/tf`'s ground truth: `body_frame`'s pose `pose` in the world, stamped `stamp`.
pub(super) fn body_in_world(stamp: Time, body_frame: &str, pose: &crate::Pose) -> TfMessage {
    TfMessage {
        transforms: vec![transform_stamped(stamp, WORLD_FRAME, body_frame, pose)],
    }
}

/// One IMU reading in frame `frame_id`: no orientation (REP 145: its covariance's first element
/// −1), the rates and specific force with the reading's noise variance on the diagonal.
pub(super) fn imu_message(
    sample: &ImuSample,
    stamp: Time,
    frame_id: &str,
    gyro_variance: f64,
    accel_variance: f64,
) -> ImuMessage {
    let diagonal = |v: f64| [v, 0.0, 0.0, 0.0, v, 0.0, 0.0, 0.0, v];
    let vector = |v: glam::DVec3| Vector3 {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    let mut no_orientation = [0.0; 9];
    no_orientation[0] = -1.0;
    ImuMessage {
        header: Header {
            stamp,
            frame_id: frame_id.into(),
        },
        orientation: Quaternion {
            x: 0.0,
            y: 0.0,
            z: 0.0,
            w: 0.0,
        },
        orientation_covariance: no_orientation,
        angular_velocity: vector(sample.gyro),
        angular_velocity_covariance: diagonal(gyro_variance),
        linear_acceleration: vector(sample.accel),
        linear_acceleration_covariance: diagonal(accel_variance),
    }
}

#[cfg(test)]
mod tests {
    use glam::{DQuat, DVec3};

    use super::*;

    #[test]
    fn depth_becomes_whole_millimetres_and_no_measurement_zero() {
        assert_eq!(millimetres(1.2344), 1234);
        assert_eq!(millimetres(0.0), 0);
        assert_eq!(millimetres(f32::NAN), 0);
        assert_eq!(millimetres(70.0), 0);
    }

    #[test]
    fn the_optical_frame_looks_along_the_bodys_x_with_its_y_down() {
        let r: DQuat = optical_in_body().rotation;
        assert!((r * DVec3::Z - DVec3::X).length() < 1e-12);
        assert!((r * DVec3::Y - DVec3::NEG_Z).length() < 1e-12);
        assert!((r * DVec3::X - DVec3::NEG_Y).length() < 1e-12);
    }
}
