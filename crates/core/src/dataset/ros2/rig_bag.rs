//! A rig of cameras and an IMU (the stereo rigs) as a ROS 2 bag, with the topics of EuRoC's
//! recordings: `/cam0/image_raw` (`mono8`, or `rgb8` for a colour camera) with
//! `/cam0/camera_info`, the same for each camera, `/imu0` (`sensor_msgs/Imu` in frame `imu0`),
//! the body's ground-truth pose on `/ground_truth/pose` (the rows of EuRoC's
//! `state_groundtruth_estimate0`), and every sensor's `T_BS` in frame `body` on `/tf_static`.
//!
//! The cameras are drawn one after another, so each camera's messages go to a spool file of its
//! own (`camN.spool`, MCAP); [`RigBag::finish`] merges the spools, the IMU and the ground truth
//! into the bag in stamp order and removes the spools.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use super::bag::{BagWriter, ClosedBag, Topic};
use super::camera::{camera_info, imu_message, pose_in_world, transform_stamped};
use super::messages::{Bytes, Header, Image, TfMessage, Time};
use super::recorded::{BagMessage, RecordedBag};
use super::schemas::MessageType;
use super::{GROUND_TRUTH_TOPIC, IMU_FRAME, IMU_TOPIC, TF_STATIC_TOPIC};
use crate::dataset::codec::luma8;
use crate::dataset::euroc::{CameraColour, EurocCamera, EurocImu, GroundTruthState, ImuSample};
use crate::{CoreError, Distortion, RgbImage};

/// The frame the rig's sensors are placed in.
pub const RIG_BODY_FRAME: &str = "body";
const SPOOL_EXTENSION: &str = "spool";

pub struct RigBag {
    folder: PathBuf,
    cameras: Vec<EurocCamera>,
    imu: Option<EurocImu>,
    /// Per camera, its messages so far.
    spools: Vec<Mutex<BagWriter>>,
}

impl RigBag {
    pub fn create(
        folder: &Path,
        cameras: Vec<EurocCamera>,
        imu: Option<EurocImu>,
    ) -> Result<Self, CoreError> {
        let spools = cameras
            .iter()
            .map(|camera| {
                let topics = camera_topics(camera);
                let file = format!("{}.{SPOOL_EXTENSION}", camera.name);
                BagWriter::create_file(folder, &file, &topics).map(Mutex::new)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            folder: folder.to_path_buf(),
            cameras,
            imu,
            spools,
        })
    }

    /// Camera `camera`'s frame stamped `t_ns`, its grey (luma) or colour pixels, and its camera
    /// info; each camera's frames in stamp order.
    pub fn write_frame(&self, camera: usize, t_ns: u64, image: &RgbImage) -> Result<(), CoreError> {
        let (Some(spec), Some(spool)) = (self.cameras.get(camera), self.spools.get(camera)) else {
            return Err(CoreError::bad_file(
                &self.folder,
                format!("camera {camera}: the rig has {}", self.cameras.len()),
            ));
        };
        let stamp = Time::from_nanoseconds(t_ns as i64);
        let header = Header {
            stamp,
            frame_id: spec.name.clone(),
        };
        let grey: Vec<u8>;
        let (encoding, step, data) = match spec.colour {
            CameraColour::Rgb => ("rgb8", 3 * image.width, &image.data[..]),
            CameraColour::Grey | CameraColour::Grey16 => {
                grey = luma8(image).collect();
                ("mono8", image.width, &grey[..])
            }
        };
        let message = Image {
            header: header.clone(),
            height: image.height,
            width: image.width,
            encoding: encoding.into(),
            is_bigendian: 0,
            step,
            data: Bytes(data),
        };
        let lens = spec.distortion.to_array();
        let distortion = lens
            .iter()
            .any(|&c| c != 0.0)
            .then(|| Distortion::from_coefficients(Distortion::RADTAN, lens))
            .flatten();
        let info = camera_info(header, &spec.intrinsics, distortion);
        let mut spool = spool.lock().unwrap_or_else(|p| p.into_inner());
        spool.write(0, stamp, &message)?;
        spool.write(1, stamp, &info)
    }

    /// Merges the cameras' spools, `imu` and `ground_truth` into the bag in stamp order, with
    /// `/tf_static` first; removes the spools.
    pub fn finish(
        mut self,
        name: &str,
        imu: &[ImuSample],
        ground_truth: &[GroundTruthState],
    ) -> Result<ClosedBag, CoreError> {
        let mut topics: Vec<Topic> = self.cameras.iter().flat_map(camera_topics).collect();
        let imu_topic = topics.len();
        if self.imu.is_some() {
            topics.push(Topic::new(IMU_TOPIC, MessageType::Imu));
        }
        let truth_topic = topics.len();
        topics.push(Topic::new(GROUND_TRUTH_TOPIC, MessageType::PoseStamped));
        let tf_topic = topics.len();
        topics.push(Topic::latched(TF_STATIC_TOPIC, MessageType::TfMessage));

        let mut spools = Vec::new();
        for spool in std::mem::take(&mut self.spools) {
            let closed = spool
                .into_inner()
                .unwrap_or_else(|p| p.into_inner())
                .finish()?;
            let storage = self.folder.join(&closed.file);
            spools.push(RecordedBag {
                folder: self.folder.clone(),
                storage,
            });
        }
        let mut bag = BagWriter::create(&self.folder, name, &topics)?;
        let mut streams = spools
            .iter()
            .map(|spool| spool.messages().map(Iterator::peekable))
            .collect::<Result<Vec<_>, _>>()?;
        let (mut next_imu, mut next_truth) = (0, 0);
        let imu_samples = if self.imu.is_some() { imu } else { &[] };
        let mut tf_written = false;
        loop {
            // The earliest of the next messages: a camera's (its log time), the IMU's, the truth's.
            let mut earliest: Option<(u64, usize)> = None;
            for (i, stream) in streams.iter_mut().enumerate() {
                if let Some(message) = stream.peek() {
                    let t = match message {
                        Ok(message) => message.log_time,
                        Err(_) => 0,
                    };
                    if earliest.is_none_or(|(e, _)| t < e) {
                        earliest = Some((t, i));
                    }
                }
            }
            let imu_t = imu_samples.get(next_imu).map(|s| s.t_ns);
            let truth_t = ground_truth.get(next_truth).map(|s| s.t_ns);
            let first = [earliest.map(|e| e.0), imu_t, truth_t]
                .into_iter()
                .flatten()
                .min();
            let Some(first) = first else { break };
            if !tf_written {
                tf_written = true;
                let stamp = Time::from_nanoseconds(first as i64);
                bag.write(tf_topic, stamp, &self.sensors_in_body(stamp))?;
            }
            if imu_t == Some(first) {
                let sample = &imu_samples[next_imu];
                let stamp = Time::from_nanoseconds(sample.t_ns as i64);
                let (gyro, accel) = self.imu.as_ref().map_or((0.0, 0.0), variances);
                bag.write(imu_topic, stamp, &imu_message(sample, stamp, gyro, accel))?;
                next_imu += 1;
            } else if truth_t == Some(first) {
                let state = &ground_truth[next_truth];
                let stamp = Time::from_nanoseconds(state.t_ns as i64);
                bag.write(
                    truth_topic,
                    stamp,
                    &pose_in_world(stamp, &state.world_from_body),
                )?;
                next_truth += 1;
            } else if let Some((_, camera)) = earliest {
                let message: BagMessage = match streams[camera].next() {
                    Some(message) => message?,
                    None => continue,
                };
                let topic = 2 * camera + usize::from(message.topic().ends_with("camera_info"));
                let times = super::bag::LogTimes {
                    log_time: message.log_time,
                    publish_time: message.publish_time,
                    sequence: message.sequence,
                };
                bag.write_bytes(topic, times, &message.data)?;
            }
        }
        drop(streams);
        for spool in &spools {
            std::fs::remove_file(&spool.storage).map_err(|e| CoreError::io(&spool.storage, e))?;
        }
        bag.finish()
    }

    /// `/tf_static`: every camera's and the IMU's `T_BS`.
    fn sensors_in_body(&self, stamp: Time) -> TfMessage {
        let cameras = self.cameras.iter().map(|camera| {
            transform_stamped(
                stamp,
                RIG_BODY_FRAME,
                &camera.name,
                &camera.body_from_camera,
            )
        });
        let imu = self
            .imu
            .iter()
            .map(|imu| transform_stamped(stamp, RIG_BODY_FRAME, IMU_FRAME, &imu.body_from_imu));
        TfMessage {
            transforms: cameras.chain(imu).collect(),
        }
    }
}

/// A camera's image and camera-info topics.
fn camera_topics(camera: &EurocCamera) -> [Topic; 2] {
    [
        Topic::new(&format!("/{}/image_raw", camera.name), MessageType::Image),
        Topic::new(
            &format!("/{}/camera_info", camera.name),
            MessageType::CameraInfo,
        ),
    ]
}

/// The variance of one gyroscope and accelerometer reading: a noise density `σ` in units/√Hz at
/// `f` Hz is a discrete standard deviation `σ √f` (Kalibr's convention).
pub fn variances(imu: &EurocImu) -> (f64, f64) {
    (
        imu.gyroscope_noise_density.powi(2) * imu.rate_hz,
        imu.accelerometer_noise_density.powi(2) * imu.rate_hz,
    )
}
