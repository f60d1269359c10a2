//! A rig of cameras and an IMU (the stereo rigs) as a ROS 2 bag, by default with the topics of
//! EuRoC's recordings ([`BagNames`]): `/cam0/image_raw` (`mono8`, or `rgb8` for a colour camera)
//! with `/cam0/camera_info`, the same for each camera, `/imu0` (`sensor_msgs/Imu` in frame
//! `imu0`), the body's ground-truth pose on `/ground_truth/pose` (the rows of EuRoC's
//! `state_groundtruth_estimate0`; asked for, also `world → body` on `/tf`), and every sensor's
//! `T_BS` in frame `body` on `/tf_static`.
//!
//! The cameras are drawn one after another, so each camera's messages go to a spool file of its
//! own (`camN.spool`, MCAP); [`RigBag::finish`] spools the IMU and the ground truth too, merges
//! every spool into the bag in stamp order and removes them.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

use super::bag::{bag_name, BagWriter, ClosedBag, Topic};
use super::camera::{body_in_world, camera_info, imu_message, pose_in_world, transform_stamped};
use super::merge::{close_spool, merge_by_log_time, remove_spools};
use super::messages::{Bytes, Header, Image, TfMessage, Time};
use super::names::BagNames;
use super::options::BagOptions;
use super::recorded::RecordedBag;
use super::schemas::MessageType;
use super::{TF_STATIC_TOPIC, TF_TOPIC};
use crate::dataset::codec::luma8;
use crate::dataset::euroc::{CameraColour, EurocCamera, EurocImu, GroundTruthState, ImuSample};
use crate::{CoreError, Distortion, RgbImage};

const SPOOL_EXTENSION: &str = "spool";

pub struct RigBag {
    folder: PathBuf,
    cameras: Vec<EurocCamera>,
    imu: Option<EurocImu>,
    options: BagOptions,
    names: BagNames,
    /// Per camera, its messages so far.
    spools: Vec<Mutex<BagWriter>>,
    /// The earliest frame stamp written, in nanoseconds (`u64::MAX` before the first).
    first_frame_ns: AtomicU64,
}

impl RigBag {
    pub fn create(
        folder: &Path,
        cameras: Vec<EurocCamera>,
        imu: Option<EurocImu>,
        options: BagOptions,
        names: BagNames,
    ) -> Result<Self, CoreError> {
        let spools = cameras
            .iter()
            .map(|camera| {
                let topics = camera_topics(camera, &names);
                let file = format!("{}.{SPOOL_EXTENSION}", camera.name);
                BagWriter::create_file(folder, &file, &topics).map(Mutex::new)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            folder: folder.to_path_buf(),
            cameras,
            imu,
            options,
            names,
            spools,
            first_frame_ns: AtomicU64::new(u64::MAX),
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
            frame_id: self.names.frame_id(&spec.name),
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
        self.first_frame_ns.fetch_min(t_ns, Ordering::Relaxed);
        let mut spool = spool.lock().unwrap_or_else(|p| p.into_inner());
        spool.write(0, stamp, &message)?;
        spool.write(1, stamp, &info)
    }

    /// Merges the cameras' spools, `imu` and `ground_truth` (each written to a spool of its
    /// own first) into the bag in stamp order, with `/tf_static` first; removes the spools.
    pub fn finish(
        mut self,
        imu: &[ImuSample],
        ground_truth: &[GroundTruthState],
    ) -> Result<ClosedBag, CoreError> {
        let names = &self.names;
        let mut topics: Vec<Topic> = self
            .cameras
            .iter()
            .flat_map(|camera| camera_topics(camera, names))
            .collect();
        let imu_samples = if self.imu.is_some() { imu } else { &[] };
        let imu_topic = Topic::new(&names.imu_topic(), MessageType::Imu);
        let truth_topic = Topic::new(&names.ground_truth_topic(), MessageType::PoseStamped);
        let mut truth_topics = vec![truth_topic];
        if self.options.tf {
            truth_topics.push(Topic::new(TF_TOPIC, MessageType::TfMessage));
        }
        if self.imu.is_some() {
            topics.push(imu_topic.clone());
        }
        topics.extend(truth_topics.iter().cloned());
        topics.push(Topic::latched(TF_STATIC_TOPIC, MessageType::TfMessage));

        let mut imu_spool = BagWriter::create_file(&self.folder, "imu0.spool", &[imu_topic])?;
        let (gyro, accel) = self.imu.as_ref().map_or((0.0, 0.0), variances);
        let imu_frame = names.imu_frame();
        for sample in imu_samples {
            let stamp = Time::from_nanoseconds(sample.t_ns as i64);
            imu_spool.write(
                0,
                stamp,
                &imu_message(sample, stamp, &imu_frame, gyro, accel),
            )?;
        }
        let mut truth_spool =
            BagWriter::create_file(&self.folder, "ground_truth.spool", &truth_topics)?;
        let body_frame = names.body_frame();
        for state in ground_truth {
            let stamp = Time::from_nanoseconds(state.t_ns as i64);
            let body = &state.world_from_body;
            truth_spool.write(0, stamp, &pose_in_world(stamp, body))?;
            if self.options.tf {
                truth_spool.write(1, stamp, &body_in_world(stamp, &body_frame, body))?;
            }
        }
        // On a tie the IMU comes first, then the ground truth, then the cameras in order.
        let mut spools = vec![
            close_spool(&self.folder, imu_spool)?,
            close_spool(&self.folder, truth_spool)?,
        ];
        for spool in std::mem::take(&mut self.spools) {
            let spool = spool.into_inner().unwrap_or_else(|p| p.into_inner());
            spools.push(close_spool(&self.folder, spool)?);
        }

        let name = bag_name(&self.folder);
        let mut bag = BagWriter::create(&self.folder, &name, &topics, self.options.compression)?;
        let first_frame = self.first_frame_ns.load(Ordering::Relaxed);
        let first = [
            imu_samples.first().map(|s| s.t_ns),
            ground_truth.first().map(|s| s.t_ns),
        ]
        .into_iter()
        .flatten()
        .fold(first_frame, u64::min);
        if first != u64::MAX {
            let stamp = Time::from_nanoseconds(first as i64);
            bag.write(topics.len() - 1, stamp, &self.sensors_in_body(stamp))?;
        }
        let streams = spools
            .iter()
            .map(RecordedBag::messages)
            .collect::<Result<Vec<_>, _>>()?;
        merge_by_log_time(&mut bag, streams, |_, message| {
            topics.iter().position(|t| t.name == message.topic())
        })?;
        remove_spools(&spools)?;
        bag.finish()
    }

    /// `/tf_static`: every camera's and the IMU's `T_BS`.
    fn sensors_in_body(&self, stamp: Time) -> TfMessage {
        let (names, body) = (&self.names, self.names.body_frame());
        let cameras = self.cameras.iter().map(|camera| {
            let frame = names.frame_id(&camera.name);
            transform_stamped(stamp, &body, &frame, &camera.body_from_camera)
        });
        let imu = self
            .imu
            .iter()
            .map(|imu| transform_stamped(stamp, &body, &names.imu_frame(), &imu.body_from_imu));
        TfMessage {
            transforms: cameras.chain(imu).collect(),
        }
    }
}

/// A camera's image and camera-info topics.
fn camera_topics(camera: &EurocCamera, names: &BagNames) -> [Topic; 2] {
    [
        Topic::new(&names.image_topic(&camera.name), MessageType::Image),
        Topic::new(
            &names.camera_info_topic(&camera.name),
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
