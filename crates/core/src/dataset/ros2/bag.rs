//! One rosbag2 in MCAP storage: messages go, in the order given, into `<name>_0.mcap.partial`
//! inside the bag folder; [`BagWriter::finish`] closes the MCAP (summary, indexes), renames it
//! to `<name>_0.mcap` and returns the `metadata.yaml` text. A bag cut short leaves only the
//! `.partial` file, which no reader takes for a bag.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use serde::Serialize;

use super::messages::{cdr_bytes, Time};
use super::metadata::{metadata_yaml, TopicCount, LATCHED_QOS};
use super::schemas::MessageType;
use crate::dataset::PARTIAL_SUFFIX;
use crate::CoreError;

/// A topic to write: its name, message type and whether it is latched (`/tf_static`).
#[derive(Clone, Debug, PartialEq)]
pub struct Topic {
    pub name: String,
    pub message_type: MessageType,
    pub latched: bool,
}

impl Topic {
    pub fn new(name: &str, message_type: MessageType) -> Self {
        Self {
            name: name.to_string(),
            message_type,
            latched: false,
        }
    }

    pub fn latched(name: &str, message_type: MessageType) -> Self {
        Self {
            latched: true,
            ..Self::new(name, message_type)
        }
    }
}

pub struct BagWriter {
    folder: PathBuf,
    file: String,
    mcap: mcap::Writer<BufWriter<File>>,
    topics: Vec<(Topic, u16, u64)>,
    last_stamp: Option<Time>,
    first_stamp: Option<Time>,
}

/// Messages are written in chunks of this size, uncompressed: a few raw 1200 × 680 frames.
const CHUNK_BYTES: u64 = 8 << 20;

impl BagWriter {
    /// Starts the bag `<folder>/<name>_0.mcap` (as `.partial`) with `topics`, in that order.
    pub fn create(folder: &Path, name: &str, topics: &[Topic]) -> Result<Self, CoreError> {
        let file = format!("{name}_0.mcap");
        let partial = folder.join(format!("{file}{PARTIAL_SUFFIX}"));
        let out = File::create(&partial).map_err(|e| CoreError::io(&partial, e))?;
        let mcap_error = |e: mcap::McapError| CoreError::bad_file(&partial, e.to_string());
        let mut mcap = mcap::WriteOptions::new()
            .profile("ros2")
            .library(concat!("rslam ", env!("CARGO_PKG_VERSION")))
            .compression(None)
            .chunk_size(Some(CHUNK_BYTES))
            .create(BufWriter::new(out))
            .map_err(mcap_error)?;
        let mut channels = Vec::new();
        for topic in topics {
            let kind = topic.message_type;
            let schema = mcap
                .add_schema(&kind.name(), "ros2msg", kind.schema().as_bytes())
                .map_err(mcap_error)?;
            let qos = if topic.latched { LATCHED_QOS } else { "" };
            let metadata = BTreeMap::from([("offered_qos_profiles".into(), qos.into())]);
            let id = mcap
                .add_channel(schema, &topic.name, "cdr", &metadata)
                .map_err(mcap_error)?;
            channels.push((topic.clone(), id, 0));
        }
        Ok(Self {
            folder: folder.to_path_buf(),
            file,
            mcap,
            topics: channels,
            last_stamp: None,
            first_stamp: None,
        })
    }

    /// Writes `message` on topic `topic` (its index in the list given to `create`), logged at
    /// its stamp; stamps may not go back.
    pub fn write<M: Serialize>(
        &mut self,
        topic: usize,
        stamp: Time,
        message: &M,
    ) -> Result<(), CoreError> {
        let partial = self.partial();
        if self.last_stamp.is_some_and(|last| stamp < last) {
            return Err(CoreError::bad_file(
                &partial,
                format!(
                    "a message on {} is stamped {}.{:09} s, before the one written last",
                    self.topics[topic].0.name, stamp.sec, stamp.nanosec
                ),
            ));
        }
        let data = cdr_bytes(message).map_err(|e| CoreError::bad_file(&partial, e))?;
        let (_, channel_id, count) = &mut self.topics[topic];
        let header = mcap::records::MessageHeader {
            channel_id: *channel_id,
            sequence: *count as u32,
            log_time: stamp.nanoseconds(),
            publish_time: stamp.nanoseconds(),
        };
        *count += 1;
        self.mcap
            .write_to_known_channel(&header, &data)
            .map_err(|e| CoreError::bad_file(&partial, e.to_string()))?;
        self.first_stamp.get_or_insert(stamp);
        self.last_stamp = Some(stamp);
        Ok(())
    }

    /// Closes the MCAP, gives it its final name, and returns that name and the text of
    /// `metadata.yaml` for the caller to write beside it.
    pub fn finish(mut self) -> Result<(String, String), CoreError> {
        let partial = self.partial();
        self.mcap
            .finish()
            .map_err(|e| CoreError::bad_file(&partial, e.to_string()))?;
        let mut out = self.mcap.into_inner();
        std::io::Write::flush(&mut out).map_err(|e| CoreError::io(&partial, e))?;
        drop(out);
        let done = self.folder.join(&self.file);
        std::fs::rename(&partial, &done).map_err(|e| CoreError::io(&done, e))?;
        let topics: Vec<TopicCount> = self
            .topics
            .iter()
            .map(|(topic, _, messages)| TopicCount {
                name: topic.name.clone(),
                message_type: topic.message_type.name(),
                qos: if topic.latched { LATCHED_QOS } else { "" }.to_string(),
                messages: *messages,
            })
            .collect();
        let ns = |t: Option<Time>| t.map_or(0, Time::nanoseconds);
        let yaml = metadata_yaml(
            &self.file,
            ns(self.first_stamp),
            ns(self.last_stamp),
            &topics,
        );
        Ok((self.file, yaml))
    }

    fn partial(&self) -> PathBuf {
        self.folder.join(format!("{}{PARTIAL_SUFFIX}", self.file))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dataset::ros2::{Header, PoseStamped};

    fn pose_at(seconds: f64) -> (Time, PoseStamped) {
        let stamp = Time::from_seconds(seconds);
        let pose = PoseStamped {
            header: Header {
                stamp,
                frame_id: "world".into(),
            },
            pose: crate::dataset::ros2::Pose {
                position: crate::dataset::ros2::Vector3 {
                    x: 1.0,
                    y: 2.0,
                    z: 3.0,
                },
                orientation: crate::dataset::ros2::Quaternion {
                    x: 0.0,
                    y: 0.0,
                    z: 0.0,
                    w: 1.0,
                },
            },
        };
        (stamp, pose)
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_bag_cut_short_leaves_only_its_partial_file() {
        let dir = tempfile::tempdir().unwrap();
        let topics = [Topic::new("/pose", MessageType::PoseStamped)];
        let mut bag = BagWriter::create(dir.path(), "b", &topics).unwrap();
        let (stamp, pose) = pose_at(1.0);
        bag.write(0, stamp, &pose).unwrap();
        drop(bag);
        assert_eq!(names(dir.path()), ["b_0.mcap.partial"]);
    }

    #[test]
    fn a_finished_bag_has_its_final_name_and_counts_its_messages_and_time_span() {
        let dir = tempfile::tempdir().unwrap();
        let topics = [Topic::new("/pose", MessageType::PoseStamped)];
        let mut bag = BagWriter::create(dir.path(), "b", &topics).unwrap();
        for t in [1.0, 1.5, 2.25] {
            let (stamp, pose) = pose_at(t);
            bag.write(0, stamp, &pose).unwrap();
        }
        let (file, yaml) = bag.finish().unwrap();
        assert_eq!(file, "b_0.mcap");
        assert_eq!(names(dir.path()), ["b_0.mcap"]);
        assert!(yaml.contains("message_count: 3\n"), "{yaml}");
        assert!(yaml.contains("nanoseconds: 1250000000\n"), "{yaml}");
        assert!(
            yaml.contains("nanoseconds_since_epoch: 1000000000\n"),
            "{yaml}"
        );
    }

    #[test]
    fn a_message_stamped_before_the_last_is_refused_naming_its_topic() {
        let dir = tempfile::tempdir().unwrap();
        let topics = [Topic::new("/pose", MessageType::PoseStamped)];
        let mut bag = BagWriter::create(dir.path(), "b", &topics).unwrap();
        let (late, pose) = pose_at(2.0);
        bag.write(0, late, &pose).unwrap();
        let (early, pose) = pose_at(1.0);
        let error = bag.write(0, early, &pose).unwrap_err().to_string();
        assert!(
            error.contains("/pose") && error.contains("before"),
            "{error}"
        );
    }
}
