//! One rosbag2 in MCAP storage: messages go, in the order given, into `<name>_0.mcap.partial`
//! inside the bag folder; [`BagWriter::finish`] closes the MCAP (summary, indexes), renames it
//! to `<name>_0.mcap` and returns its checksum and the `metadata.yaml` text. A bag cut short
//! leaves only the `.partial` file, which no reader takes for a bag.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use serde::Serialize;

use super::messages::{cdr_bytes, Time};
use super::metadata::{metadata_yaml, TopicCount, LATCHED_QOS};
use super::options::BagCompression;
use super::schemas::MessageType;
use crate::dataset::PARTIAL_SUFFIX;
use crate::CoreError;

/// The name of the bag in `folder`: the folder's own, as `ros2 bag record -o` names it.
pub fn bag_name(folder: &Path) -> String {
    folder
        .file_name()
        .map_or("rslam".into(), |n| n.to_string_lossy().into_owned())
}

/// A topic to write: its name, its message type's name and MCAP schema (`ros2msg` text), and
/// rosbag2's `offered_qos_profiles` for it (YAML; empty for the subscriber's default).
#[derive(Clone, Debug, PartialEq)]
pub struct Topic {
    pub name: String,
    pub type_name: String,
    pub schema_encoding: String,
    pub schema: Vec<u8>,
    pub qos: String,
}

impl Topic {
    /// A topic of one of the message types rslam writes.
    pub fn new(name: &str, message_type: MessageType) -> Self {
        Self {
            name: name.to_string(),
            type_name: message_type.name(),
            schema_encoding: "ros2msg".into(),
            schema: message_type.schema().into_bytes(),
            qos: String::new(),
        }
    }

    /// A latched topic (`/tf_static`): late subscribers get its messages.
    pub fn latched(name: &str, message_type: MessageType) -> Self {
        Self {
            qos: LATCHED_QOS.into(),
            ..Self::new(name, message_type)
        }
    }

    /// A recorded bag's topic as it was: its schema and QoS copied.
    pub fn recorded(channel: &mcap::Channel) -> Self {
        let schema = channel.schema.as_deref();
        Self {
            name: channel.topic.clone(),
            type_name: schema.map_or(String::new(), |s| s.name.clone()),
            schema_encoding: schema.map_or(String::new(), |s| s.encoding.clone()),
            schema: schema.map_or(Vec::new(), |s| s.data.to_vec()),
            qos: channel
                .metadata
                .get("offered_qos_profiles")
                .cloned()
                .unwrap_or_default(),
        }
    }
}

/// When a message was logged and published, and its number on its topic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LogTimes {
    pub log_time: u64,
    pub publish_time: u64,
    pub sequence: u32,
}

/// The storage file, hashed as it is written: MCAP's non-seeking mode writes it front to back,
/// asking only where it is, so its checksum needs no second read of the bag.
struct HashedFile {
    out: BufWriter<File>,
    hasher: blake3::Hasher,
    position: u64,
}

impl Write for HashedFile {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        let written = self.out.write(bytes)?;
        self.hasher.update(&bytes[..written]);
        self.position += written as u64;
        Ok(written)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

impl Seek for HashedFile {
    fn seek(&mut self, to: SeekFrom) -> io::Result<u64> {
        match to {
            SeekFrom::Current(0) => Ok(self.position),
            _ => Err(io::Error::new(
                io::ErrorKind::Unsupported,
                "the bag is written front to back",
            )),
        }
    }
}

/// A bag closed: its storage file's name and BLAKE3 checksum, and the `metadata.yaml` text.
pub struct ClosedBag {
    pub file: String,
    pub blake3: String,
    pub metadata: String,
}

pub struct BagWriter {
    folder: PathBuf,
    file: String,
    mcap: mcap::Writer<HashedFile>,
    topics: Vec<(Topic, u16, u64)>,
    last_stamp: Option<Time>,
    /// The earliest and latest log time written, in nanoseconds.
    log_span: Option<(u64, u64)>,
}

/// Messages are written in chunks of this size, each assembled in memory: a few raw 1200 × 680
/// frames.
const CHUNK_BYTES: u64 = 8 << 20;

impl BagWriter {
    /// Starts the bag `<folder>/<name>_0.mcap` (as `.partial`) with `topics`, in that order, its
    /// chunks compressed by `compression`.
    pub fn create(
        folder: &Path,
        name: &str,
        topics: &[Topic],
        compression: BagCompression,
    ) -> Result<Self, CoreError> {
        Self::open(folder, &format!("{name}_0.mcap"), topics, compression)
    }

    /// Starts an MCAP file named `file` in `folder` (as `.partial`) with `topics`, uncompressed:
    /// a spool merged into the bag later.
    pub fn create_file(folder: &Path, file: &str, topics: &[Topic]) -> Result<Self, CoreError> {
        Self::open(folder, file, topics, BagCompression::None)
    }

    fn open(
        folder: &Path,
        file: &str,
        topics: &[Topic],
        compression: BagCompression,
    ) -> Result<Self, CoreError> {
        let file = file.to_string();
        let partial = folder.join(format!("{file}{PARTIAL_SUFFIX}"));
        let out = HashedFile {
            out: BufWriter::new(File::create(&partial).map_err(|e| CoreError::io(&partial, e))?),
            hasher: blake3::Hasher::new(),
            position: 0,
        };
        let mcap_error = |e: mcap::McapError| CoreError::bad_file(&partial, e.to_string());
        let mut mcap = mcap::WriteOptions::new()
            .profile("ros2")
            .library(concat!("rslam ", env!("CARGO_PKG_VERSION")))
            .compression(compression.mcap())
            .chunk_size(Some(CHUNK_BYTES))
            .disable_seeking(true)
            .create(out)
            .map_err(mcap_error)?;
        let mut channels = Vec::new();
        for topic in topics {
            let schema = mcap
                .add_schema(&topic.type_name, &topic.schema_encoding, &topic.schema)
                .map_err(mcap_error)?;
            let metadata = BTreeMap::from([("offered_qos_profiles".into(), topic.qos.clone())]);
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
            log_span: None,
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
        if self.last_stamp.is_some_and(|last| stamp < last) {
            return Err(CoreError::bad_file(
                self.partial(),
                format!(
                    "a message on {} is stamped {}.{:09} s, before the one written last",
                    self.topics[topic].0.name, stamp.sec, stamp.nanosec
                ),
            ));
        }
        let data = cdr_bytes(message).map_err(|e| CoreError::bad_file(self.partial(), e))?;
        let sequence = self.topics[topic].2 as u32;
        let times = LogTimes {
            log_time: stamp.nanoseconds(),
            publish_time: stamp.nanoseconds(),
            sequence,
        };
        self.write_bytes(topic, times, &data)?;
        self.last_stamp = Some(stamp);
        Ok(())
    }

    /// Writes a message already serialised (`data`: CDR with its header) on topic `topic`, at
    /// `times`, in any order.
    pub fn write_bytes(
        &mut self,
        topic: usize,
        times: LogTimes,
        data: &[u8],
    ) -> Result<(), CoreError> {
        let (_, channel_id, count) = &mut self.topics[topic];
        let header = mcap::records::MessageHeader {
            channel_id: *channel_id,
            sequence: times.sequence,
            log_time: times.log_time,
            publish_time: times.publish_time,
        };
        *count += 1;
        self.mcap
            .write_to_known_channel(&header, data)
            .map_err(|e| CoreError::bad_file(self.partial(), e.to_string()))?;
        let t = times.log_time;
        self.log_span = Some(self.log_span.map_or((t, t), |(a, b)| (a.min(t), b.max(t))));
        Ok(())
    }

    /// Closes the MCAP and gives it its final name; the caller writes `metadata.yaml` beside it.
    pub fn finish(mut self) -> Result<ClosedBag, CoreError> {
        let partial = self.partial();
        self.mcap
            .finish()
            .map_err(|e| CoreError::bad_file(&partial, e.to_string()))?;
        let mut out = self.mcap.into_inner();
        out.flush().map_err(|e| CoreError::io(&partial, e))?;
        let blake3 = out.hasher.finalize().to_hex().to_string();
        drop(out);
        let done = self.folder.join(&self.file);
        std::fs::rename(&partial, &done).map_err(|e| CoreError::io(&done, e))?;
        let topics: Vec<TopicCount> = self
            .topics
            .iter()
            .map(|(topic, _, messages)| TopicCount {
                name: topic.name.clone(),
                message_type: topic.type_name.clone(),
                qos: topic.qos.clone(),
                messages: *messages,
            })
            .collect();
        let (start, end) = self.log_span.unwrap_or_default();
        let metadata = metadata_yaml(&self.file, start, end, &topics);
        Ok(ClosedBag {
            file: self.file,
            blake3,
            metadata,
        })
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

    /// A bag of one pose topic in `dir`.
    fn pose_bag(dir: &Path) -> BagWriter {
        let topics = [Topic::new("/pose", MessageType::PoseStamped)];
        BagWriter::create(dir, "b", &topics, BagCompression::None).unwrap()
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
        let mut bag = pose_bag(dir.path());
        let (stamp, pose) = pose_at(1.0);
        bag.write(0, stamp, &pose).unwrap();
        drop(bag);
        assert_eq!(names(dir.path()), ["b_0.mcap.partial"]);
    }

    #[test]
    fn a_finished_bag_has_its_final_name_and_counts_its_messages_and_time_span() {
        let dir = tempfile::tempdir().unwrap();
        let mut bag = pose_bag(dir.path());
        for t in [1.0, 1.5, 2.25] {
            let (stamp, pose) = pose_at(t);
            bag.write(0, stamp, &pose).unwrap();
        }
        let closed = bag.finish().unwrap();
        assert_eq!(closed.file, "b_0.mcap");
        assert_eq!(names(dir.path()), ["b_0.mcap"]);
        let written = std::fs::read(dir.path().join("b_0.mcap")).unwrap();
        assert_eq!(closed.blake3, blake3::hash(&written).to_hex().to_string());
        let yaml = closed.metadata;
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
        let mut bag = pose_bag(dir.path());
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
