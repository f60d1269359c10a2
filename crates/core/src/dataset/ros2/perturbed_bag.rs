//! A recorded bag written again with its camera's images perturbed: every other message is
//! copied byte for byte with its times and sequence number, read a second time from the input
//! and interleaved by log time with the images written anew. An image keeps its header (its
//! stamp moved where the plan re-stamps it, its log and publish times moved by as much) and its
//! encoding.

use std::path::Path;
use std::sync::Arc;

use super::bag::{BagWriter, ClosedBag, LogTimes};
use super::image_codec::{encode_colour, encode_depth};
use super::messages::{Header, Time};
use super::recorded::{BagMessage, BagMessages};
use super::recorded_camera::{ImageTopic, RecordedBagCamera};
use crate::{CoreError, DepthImage, RgbImage};

pub struct PerturbedBag {
    camera: Arc<RecordedBagCamera>,
    bag: BagWriter,
    /// The input, read again for the messages to copy.
    recorded: BagMessages,
    /// The next message to copy, read but logged after what was written last.
    waiting: Option<BagMessage>,
}

impl PerturbedBag {
    /// Starts the bag in `folder` with every topic of `camera`'s bag.
    pub fn create(folder: &Path, camera: Arc<RecordedBagCamera>) -> Result<Self, CoreError> {
        let name = folder
            .file_name()
            .map_or("rslam".into(), |n| n.to_string_lossy().into_owned());
        Ok(Self {
            bag: BagWriter::create(folder, &name, &camera.topics)?,
            recorded: camera.bag.messages()?,
            camera,
            waiting: None,
        })
    }

    /// Colour message `index` of the camera, its stamp moved by `shift_s` seconds.
    pub fn write_colour(
        &mut self,
        index: usize,
        shift_s: f64,
        colour: &RgbImage,
    ) -> Result<(), CoreError> {
        let topic = &self.camera.colour;
        let (header, times) = moved(topic, index, shift_s);
        let data =
            encode_colour(header, colour, &topic.encoding).map_err(|e| self.error(topic, e))?;
        self.write(topic.index, times, &data)
    }

    /// Depth message `index` of the camera, its stamp moved by `shift_s` seconds.
    pub fn write_depth(
        &mut self,
        index: usize,
        shift_s: f64,
        depth: &DepthImage,
    ) -> Result<(), CoreError> {
        let Some(topic) = &self.camera.depth else {
            return Err(CoreError::bad_file(
                &self.camera.bag.folder,
                "depth written to a bag without a depth topic",
            ));
        };
        let (header, times) = moved(topic, index, shift_s);
        let data =
            encode_depth(header, depth, &topic.encoding).map_err(|e| self.error(topic, e))?;
        self.write(topic.index, times, &data)
    }

    /// Copies what is left of the input and closes the bag.
    pub fn finish(mut self) -> Result<ClosedBag, CoreError> {
        self.copy_until(u64::MAX)?;
        self.bag.finish()
    }

    fn write(&mut self, topic: usize, times: LogTimes, data: &[u8]) -> Result<(), CoreError> {
        self.copy_until(times.log_time)?;
        self.bag.write_bytes(topic, times, data)
    }

    /// Copies the input's messages logged up to `log_time`, but the camera's images.
    fn copy_until(&mut self, log_time: u64) -> Result<(), CoreError> {
        loop {
            let message = match self.waiting.take() {
                Some(message) => message,
                None => match self.recorded.next() {
                    Some(message) => message?,
                    None => return Ok(()),
                },
            };
            if message.log_time > log_time {
                self.waiting = Some(message);
                return Ok(());
            }
            let topic = self.camera.topic_of_channel[&message.channel.id];
            if !self.camera.is_perturbed(topic) {
                let times = LogTimes {
                    log_time: message.log_time,
                    publish_time: message.publish_time,
                    sequence: message.sequence,
                };
                self.bag.write_bytes(topic, times, &message.data)?;
            }
        }
    }

    fn error(&self, topic: &ImageTopic, message: String) -> CoreError {
        CoreError::bad_file(
            &self.camera.bag.folder,
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
    use super::super::recorded::RecordedBag;
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
        let mut bag = CameraBag::create(folder, camera, None, None).unwrap();
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
        let camera = RecordedBagCamera::read(recorded(&dir.path().join("in"))).unwrap();
        assert_eq!(camera.colour.name, COLOR_TOPIC);
        assert_eq!(camera.depth.as_ref().unwrap().name, DEPTH_TOPIC);
        assert_eq!(camera.colour.messages.len(), FRAMES);
        assert!((camera.rate_hz - 30.0).abs() < 1e-3, "{}", camera.rate_hz);
        assert_eq!((camera.intrinsics.fx, camera.intrinsics.cy), (3.0, 1.0));
        assert_eq!(camera.topics.len(), 6);
    }

    #[test]
    fn images_are_written_anew_and_every_other_message_copied_as_it_was() {
        let dir = tempfile::tempdir().unwrap();
        let input = recorded(&dir.path().join("in"));
        let camera = Arc::new(RecordedBagCamera::read(input.clone()).unwrap());
        let out = dir.path().join("out");
        std::fs::create_dir_all(&out).unwrap();
        let mut bag = PerturbedBag::create(&out, camera.clone()).unwrap();
        let inverted = |i| {
            let mut c = colour(i);
            c.data.iter_mut().for_each(|v| *v = 255 - *v);
            c
        };
        for i in 0..FRAMES {
            bag.write_colour(i, 0.0, &inverted(i)).unwrap();
            bag.write_depth(i, 0.010, &depth(i)).unwrap();
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
        for topic in &camera.topics {
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
            assert_eq!(*log, camera.colour.messages[i].times.log_time);
            let encoding = &camera.colour.encoding;
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
        let error = RecordedBagCamera::read(input).unwrap_err().to_string();
        assert!(error.contains("not a whole MCAP file"), "{error}");
        assert!(error.contains("in_0.mcap"), "{error}");

        let folder = dir.path().join("no_info");
        std::fs::create_dir_all(&folder).unwrap();
        let topics = [Topic::new("/cam/image_raw", MessageType::Image)];
        let mut bag = BagWriter::create(&folder, "no_info", &topics).unwrap();
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
        let error = RecordedBagCamera::read(bag).unwrap_err().to_string();
        assert!(
            error.contains("no_info") && error.contains("on /cam/camera_info for /cam/image_raw"),
            "{error}"
        );
    }
}
