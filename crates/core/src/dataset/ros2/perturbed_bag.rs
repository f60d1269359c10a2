//! A recorded bag written again with its cameras' images (and IMU topics) perturbed. The cameras
//! are perturbed one after another, each into a spool file of its own (`cameraN.spool`, MCAP),
//! and each IMU topic given anew into one (`imuN.spool`); at the end every other message of the
//! input is copied byte for byte with its times and sequence number, merged by log time with the
//! spools' messages, and the spools are removed. An image keeps its header (its stamp moved where
//! the plan re-stamps it, its log and publish times moved by as much) and its encoding.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use super::bag::{bag_name, BagWriter, ClosedBag, LogTimes};
use super::image_codec::{encode_colour, encode_depth};
use super::merge::{close_spool, merge_by_log_time, remove_spools};
use super::messages::{cdr_bytes, Header, Imu, Time};
use super::options::BagCompression;
use super::recorded::RecordedBag;
use super::recorded_camera::{ImageTopic, RecordedBagCamera, RecordedBagCameras};
use crate::{CoreError, DepthImage, RgbImage};

const SPOOL_EXTENSION: &str = "spool";

pub struct PerturbedBag {
    recorded: Arc<RecordedBagCameras>,
    folder: PathBuf,
    compression: BagCompression,
    /// Per camera, its images so far.
    spools: Vec<Mutex<BagWriter>>,
    /// The IMU topics written anew, and their spools, closed.
    imu_topics: HashSet<usize>,
    imu_spools: Vec<RecordedBag>,
}

impl PerturbedBag {
    /// Starts the bag in `folder` of `recorded`'s topics, a spool per camera; `imus` are IMU
    /// topics (by index among the recorded topics) whose messages are replaced by those given.
    /// The bag's chunks are compressed by `compression`.
    pub fn create(
        folder: &Path,
        recorded: Arc<RecordedBagCameras>,
        imus: &[(usize, Vec<(Imu, LogTimes)>)],
        compression: BagCompression,
    ) -> Result<Self, CoreError> {
        let mut imu_spools = Vec::new();
        for (i, (topic, messages)) in imus.iter().enumerate() {
            let file = format!("imu{i}.{SPOOL_EXTENSION}");
            let mut spool =
                BagWriter::create_file(folder, &file, &[recorded.topics[*topic].clone()])?;
            for (message, times) in messages {
                let data = cdr_bytes(message).map_err(|e| CoreError::bad_file(folder, e))?;
                spool.write_bytes(0, *times, &data)?;
            }
            imu_spools.push(close_spool(folder, spool)?);
        }
        let spools = recorded
            .cameras
            .iter()
            .enumerate()
            .map(|(i, camera)| {
                let topics: Vec<_> = [&camera.colour, &camera.depth]
                    .into_iter()
                    .flatten()
                    .map(|t| recorded.topics[t.index].clone())
                    .collect();
                let file = format!("camera{i}.{SPOOL_EXTENSION}");
                BagWriter::create_file(folder, &file, &topics).map(Mutex::new)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            recorded,
            folder: folder.to_path_buf(),
            compression,
            spools,
            imu_topics: imus.iter().map(|(topic, _)| *topic).collect(),
            imu_spools,
        })
    }

    /// Whether camera `camera` has a colour topic (not a depth camera of its own).
    pub fn has_colour(&self, camera: usize) -> bool {
        self.recorded
            .cameras
            .get(camera)
            .is_some_and(|c| c.colour.is_some())
    }

    /// Colour message `index` of camera `camera`, its stamp moved by `shift_s` seconds.
    pub fn write_colour(
        &self,
        camera: usize,
        index: usize,
        shift_s: f64,
        colour: &RgbImage,
    ) -> Result<(), CoreError> {
        let (spec, spool) = self.camera(camera)?;
        let Some(topic) = &spec.colour else {
            return Err(self.error(
                spec.frames(),
                "colour written to a camera without colour".into(),
            ));
        };
        let (header, times) = moved(topic, index, shift_s);
        let data =
            encode_colour(header, colour, &topic.encoding).map_err(|e| self.error(topic, e))?;
        let mut spool = spool.lock().unwrap_or_else(|p| p.into_inner());
        spool.write_bytes(0, times, &data)
    }

    /// Depth message `index` of camera `camera`, its stamp moved by `shift_s` seconds.
    pub fn write_depth(
        &self,
        camera: usize,
        index: usize,
        shift_s: f64,
        depth: &DepthImage,
    ) -> Result<(), CoreError> {
        let (spec, spool) = self.camera(camera)?;
        let Some(topic) = &spec.depth else {
            return Err(self.error(
                spec.frames(),
                "depth written to a camera without depth".into(),
            ));
        };
        let (header, times) = moved(topic, index, shift_s);
        let data =
            encode_depth(header, depth, &topic.encoding).map_err(|e| self.error(topic, e))?;
        let mut spool = spool.lock().unwrap_or_else(|p| p.into_inner());
        // The spool's topics are the camera's colour (when it has one), then its depth.
        spool.write_bytes(usize::from(spec.colour.is_some()), times, &data)
    }

    /// Merges the input's other messages with the cameras' spools into the bag and removes the
    /// spools.
    pub fn finish(self) -> Result<ClosedBag, CoreError> {
        let spools = self
            .spools
            .into_iter()
            .map(|spool| {
                let spool = spool.into_inner().unwrap_or_else(|p| p.into_inner());
                close_spool(&self.folder, spool)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let spools: Vec<RecordedBag> = spools.into_iter().chain(self.imu_spools).collect();
        let recorded = &self.recorded;
        let name = bag_name(&self.folder);
        let mut bag = BagWriter::create(&self.folder, &name, &recorded.topics, self.compression)?;
        let streams = std::iter::once(&recorded.bag)
            .chain(&spools)
            .map(RecordedBag::messages)
            .collect::<Result<Vec<_>, _>>()?;
        let topic_by_name: HashMap<&str, usize> = recorded
            .topics
            .iter()
            .enumerate()
            .map(|(i, topic)| (topic.name.as_str(), i))
            .collect();
        let imu_topics = &self.imu_topics;
        merge_by_log_time(&mut bag, streams, |stream, message| match stream {
            0 => {
                let topic = recorded
                    .topic_of_channel
                    .get(&message.channel.id)
                    .copied()?;
                let written_anew = recorded.is_perturbed(topic) || imu_topics.contains(&topic);
                (!written_anew).then_some(topic)
            }
            _ => topic_by_name.get(message.topic()).copied(),
        })?;
        remove_spools(&spools)?;
        bag.finish()
    }

    fn camera(&self, camera: usize) -> Result<(&RecordedBagCamera, &Mutex<BagWriter>), CoreError> {
        match (self.recorded.cameras.get(camera), self.spools.get(camera)) {
            (Some(spec), Some(spool)) => Ok((spec, spool)),
            _ => Err(CoreError::bad_file(
                &self.folder,
                format!(
                    "camera {camera}: the bag has {}",
                    self.recorded.cameras.len()
                ),
            )),
        }
    }

    fn error(&self, topic: &ImageTopic, message: String) -> CoreError {
        CoreError::bad_file(
            &self.recorded.bag.folder,
            format!("topic {}: {message}", topic.name),
        )
    }
}

/// Message `index` of `topic`, its header's stamp and its log and publish times moved by
/// `shift_s` (0 keeps them to the nanosecond).
fn moved(topic: &ImageTopic, index: usize, shift_s: f64) -> (Header, LogTimes) {
    let message = &topic.messages[index];
    let shift_ns = (shift_s * 1e9).round() as i64;
    let by = |ns: u64| ns.saturating_add_signed(shift_ns);
    let stamp = Time::from_nanoseconds(message.stamp.signed_nanoseconds() + shift_ns);
    let header = Header {
        stamp,
        frame_id: message.frame_id.clone(),
    };
    let times = LogTimes {
        log_time: by(message.times.log_time),
        publish_time: by(message.times.publish_time),
        sequence: message.times.sequence,
    };
    (header, times)
}

#[cfg(test)]
mod tests {
    use super::super::bag::Topic;
    use super::super::camera::{CameraBag, COLOR_TOPIC, DEPTH_TOPIC};
    use super::super::image_codec::{decode_colour, decode_depth};
    use super::super::recorded::BagMessage;
    use super::super::schemas::MessageType;
    use super::*;
    use crate::{Intrinsics, Pose};

    const FRAMES: usize = 3;

    fn colour(i: usize) -> RgbImage {
        RgbImage {
            width: 4,
            height: 2,
            data: (0..24).map(|v| (v * 10 + i) as u8).collect(),
        }
    }

    fn depth(i: usize) -> DepthImage {
        DepthImage {
            width: 4,
            height: 2,
            data: (0..8).map(|v| 0.5 + v as f32 * 0.25 + i as f32).collect(),
        }
    }

    /// A bag of rslam's camera layout, frames 1/30 s apart from 1e9 s on: a recorded bag's
    /// stand-in.
    fn recorded(folder: &Path) -> RecordedBag {
        std::fs::create_dir_all(folder).unwrap();
        let camera = Intrinsics::from_pinhole((4, 2), [3.0, 3.0, 2.0, 1.0]).unwrap();
        let mut bag =
            CameraBag::create(folder, camera, None, (None, false), Default::default()).unwrap();
        for i in 0..FRAMES {
            let t = 1e9 + i as f64 / 30.0;
            bag.write_rgb(t, &colour(i)).unwrap();
            bag.write_ground_truth(t, &Pose::IDENTITY).unwrap();
            bag.write_depth(t, &depth(i)).unwrap();
        }
        let closed = bag.finish().unwrap();
        std::fs::write(folder.join("metadata.yaml"), closed.metadata).unwrap();
        RecordedBag::open(folder).unwrap()
    }

    fn messages(bag: &RecordedBag) -> Vec<BagMessage> {
        bag.messages().unwrap().map(Result::unwrap).collect()
    }

    #[test]
    fn the_camera_is_found_with_its_rate_and_every_topic() {
        let dir = tempfile::tempdir().unwrap();
        let recorded = RecordedBagCameras::read(recorded(&dir.path().join("in"))).unwrap();
        let [camera] = &recorded.cameras[..] else {
            panic!("{} cameras", recorded.cameras.len());
        };
        assert_eq!(camera.frames().name, COLOR_TOPIC);
        assert_eq!(camera.depth.as_ref().unwrap().name, DEPTH_TOPIC);
        assert_eq!(camera.frames().messages.len(), FRAMES);
        assert!((camera.rate_hz - 30.0).abs() < 1e-3, "{}", camera.rate_hz);
        assert_eq!((camera.intrinsics.fx, camera.intrinsics.cy), (3.0, 1.0));
        assert_eq!(recorded.topics.len(), 6);
    }

    #[test]
    fn images_are_written_anew_and_every_other_message_copied_as_it_was() {
        let dir = tempfile::tempdir().unwrap();
        let input = recorded(&dir.path().join("in"));
        let recorded = Arc::new(RecordedBagCameras::read(input.clone()).unwrap());
        let camera = &recorded.cameras[0];
        let out = dir.path().join("out");
        std::fs::create_dir_all(&out).unwrap();
        let bag = PerturbedBag::create(&out, recorded.clone(), &[], BagCompression::None).unwrap();
        let inverted = |i| {
            let mut c = colour(i);
            c.data.iter_mut().for_each(|v| *v = 255 - *v);
            c
        };
        for i in 0..FRAMES {
            bag.write_colour(0, i, 0.0, &inverted(i)).unwrap();
            bag.write_depth(0, i, 0.010, &depth(i)).unwrap();
        }
        let closed = bag.finish().unwrap();
        std::fs::write(out.join("metadata.yaml"), closed.metadata).unwrap();
        let (before, after) = (
            messages(&input),
            messages(&RecordedBag::open(&out).unwrap()),
        );
        assert_eq!(before.len(), after.len());
        let on = |all: &[BagMessage], topic: &str| -> Vec<(u64, u32, Vec<u8>)> {
            all.iter()
                .filter(|m| m.topic() == topic)
                .map(|m| (m.log_time, m.sequence, m.data.clone()))
                .collect()
        };
        for topic in &recorded.topics {
            if topic.name != COLOR_TOPIC && topic.name != DEPTH_TOPIC {
                assert_eq!(
                    on(&before, &topic.name),
                    on(&after, &topic.name),
                    "{}",
                    topic.name
                );
            }
        }
        let colours = on(&after, COLOR_TOPIC);
        let depths = on(&after, DEPTH_TOPIC);
        for i in 0..FRAMES {
            let (log, _, data) = &colours[i];
            assert_eq!(*log, camera.frames().messages[i].times.log_time);
            let encoding = &camera.frames().encoding;
            assert_eq!(decode_colour(data, encoding).unwrap(), inverted(i));
            let (log, _, data) = &depths[i];
            let depth_topic = camera.depth.as_ref().unwrap();
            assert_eq!(*log, depth_topic.messages[i].times.log_time + 10_000_000);
            assert_eq!(decode_depth(data, &depth_topic.encoding).unwrap(), depth(i));
            let header: crate::dataset::ros2::Image = super::super::from_cdr(data).unwrap();
            let recorded = depth_topic.messages[i].stamp;
            assert_eq!(
                header.header.stamp.signed_nanoseconds(),
                recorded.signed_nanoseconds() + 10_000_000
            );
        }
    }

    #[test]
    fn a_truncated_bag_and_a_camera_without_its_info_are_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let input = recorded(&dir.path().join("in"));
        let bytes = std::fs::read(&input.storage).unwrap();
        std::fs::write(&input.storage, &bytes[..bytes.len() * 2 / 3]).unwrap();
        let error = RecordedBagCameras::read(input).unwrap_err().to_string();
        assert!(error.contains("not a whole MCAP file"), "{error}");
        assert!(error.contains("in_0.mcap"), "{error}");

        let folder = dir.path().join("no_info");
        std::fs::create_dir_all(&folder).unwrap();
        let topics = [Topic::new("/cam/image_raw", MessageType::Image)];
        let mut bag = BagWriter::create(&folder, "no_info", &topics, BagCompression::None).unwrap();
        for i in 0..2 {
            let stamp = Time::from_seconds(i as f64);
            let image = colour(i);
            let message = crate::dataset::ros2::Image {
                header: Header {
                    stamp,
                    frame_id: "cam".into(),
                },
                height: image.height,
                width: image.width,
                encoding: "rgb8".into(),
                is_bigendian: 0,
                step: 3 * image.width,
                data: crate::dataset::ros2::Bytes(&image.data),
            };
            bag.write(0, stamp, &message).unwrap();
        }
        let closed = bag.finish().unwrap();
        std::fs::write(folder.join("metadata.yaml"), closed.metadata).unwrap();
        let bag = RecordedBag::open(&folder).unwrap();
        let error = RecordedBagCameras::read(bag).unwrap_err().to_string();
        assert!(
            error.contains("no_info") && error.contains("on /cam/camera_info for /cam/image_raw"),
            "{error}"
        );
    }
}
