//! A recorded rosbag2 folder read: `metadata.yaml` beside one MCAP storage file, streamed
//! message by message in file order (zstd and lz4 chunks decompressed, their CRCs checked first),
//! memory bounded by the largest chunk, not the bag. The `mcap` crate reads the records; rslam
//! links messages to their channels itself so that it can check each schema and channel record's
//! lengths before the crate parses it ([`super::record_lengths`]).

use std::fs::File;
use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use mcap::read::ChannelAccumulator;
use mcap::records::{op, Record};
use mcap::sans_io::{LinearReadEvent, LinearReader, LinearReaderOptions};

use super::record_lengths::{channel_fits, schema_fits};

use crate::CoreError;

/// The largest record read: a damaged length field is refused, not allocated. A raw 8K frame of
/// 32-bit depth is 136 MB.
const MAX_RECORD_BYTES: usize = 1 << 30;

/// A rosbag2 folder and its storage file.
#[derive(Clone, Debug)]
pub struct RecordedBag {
    pub folder: PathBuf,
    pub storage: PathBuf,
}

/// One message as recorded: its topic (with its schema), times and CDR bytes.
pub struct BagMessage {
    pub channel: Arc<mcap::Channel<'static>>,
    pub log_time: u64,
    pub publish_time: u64,
    pub sequence: u32,
    pub data: Vec<u8>,
}

impl BagMessage {
    pub fn topic(&self) -> &str {
        &self.channel.topic
    }

    /// The message type, `package/msg/Name` (every message has one: [`BagMessages`] refuses a
    /// topic without a schema).
    pub fn type_name(&self) -> &str {
        self.channel.schema.as_ref().map_or("", |s| &s.name)
    }
}

impl RecordedBag {
    /// The bag in `folder`: `metadata.yaml` and exactly one `.mcap` file.
    pub fn open(folder: &Path) -> Result<Self, CoreError> {
        if !folder.join("metadata.yaml").is_file() {
            return Err(CoreError::bad_file(
                folder,
                "no metadata.yaml: expected a rosbag2 folder",
            ));
        }
        let mut files: Vec<PathBuf> = std::fs::read_dir(folder)
            .map_err(|e| CoreError::io(folder, e))?
            .filter_map(|entry| entry.ok().map(|e| e.path()))
            .collect();
        files.sort();
        let with = |extension: &str| -> Vec<PathBuf> {
            files
                .iter()
                .filter(|f| f.extension().is_some_and(|e| e == extension))
                .cloned()
                .collect()
        };
        match with("mcap").as_slice() {
            [storage] => Ok(Self {
                folder: folder.to_path_buf(),
                storage: storage.clone(),
            }),
            [] if !with("db3").is_empty() => Err(CoreError::bad_file(
                folder,
                "SQLite storage (.db3): rslam reads MCAP bags; convert it with `ros2 bag convert`",
            )),
            [] => Err(CoreError::bad_file(folder, "no .mcap storage file")),
            split => Err(CoreError::bad_file(
                folder,
                format!(
                    "a bag split into {} storage files: reading split bags is not built yet",
                    split.len()
                ),
            )),
        }
    }

    /// Every message in file order.
    pub fn messages(&self) -> Result<BagMessages, CoreError> {
        let file = File::open(&self.storage).map_err(|e| CoreError::io(&self.storage, e))?;
        let options = LinearReaderOptions::default()
            .with_record_length_limit(MAX_RECORD_BYTES)
            .with_prevalidate_chunk_crcs(true);
        Ok(BagMessages {
            storage: self.storage.clone(),
            file: BufReader::with_capacity(1 << 20, file),
            reader: LinearReader::new_with_options(options),
            channels: ChannelAccumulator::default(),
            past_data_end: false,
            done: false,
        })
    }
}

/// The messages of a bag in file order; a message on a topic
/// without a schema, or a damaged or truncated storage file, is an error naming the file (and the
/// topic).
pub struct BagMessages {
    storage: PathBuf,
    file: BufReader<File>,
    reader: LinearReader,
    channels: ChannelAccumulator<'static>,
    past_data_end: bool,
    done: bool,
}

impl BagMessages {
    fn next_message(&mut self) -> Result<Option<BagMessage>, String> {
        loop {
            let event = match self.reader.next_event() {
                None => return Ok(None),
                Some(event) => event.map_err(|e| e.to_string())?,
            };
            let (opcode, body) = match event {
                LinearReadEvent::ReadRequest(wanted) => {
                    let read = self
                        .file
                        .read(self.reader.insert(wanted))
                        .map_err(|e| e.to_string())?;
                    self.reader.notify_read(read);
                    continue;
                }
                LinearReadEvent::Record { opcode, data } => (opcode, data),
            };
            // The summary after the data section repeats it: its records are read to the end of
            // the file (a cut file is an error) but not parsed; the other records of the data
            // section hold no messages.
            let fits = match opcode {
                _ if self.past_data_end => continue,
                op::SCHEMA => schema_fits(body),
                op::CHANNEL => channel_fits(body),
                op::MESSAGE => true,
                op::DATA_END => {
                    self.past_data_end = true;
                    continue;
                }
                _ => continue,
            };
            if !fits {
                return Err(format!(
                    "a record (opcode {opcode:#04x}) states a length beyond its end"
                ));
            }
            match mcap::parse_record(opcode, body).map_err(|e| e.to_string())? {
                Record::Schema { header, data } => self
                    .channels
                    .add_schema_from_slice(header, &data)
                    .map_err(|e| e.to_string())?,
                Record::Channel(channel) => self
                    .channels
                    .add_channel(channel)
                    .map_err(|e| e.to_string())?,
                Record::Message { header, data } => {
                    let channel = self.channels.get(header.channel_id).ok_or_else(|| {
                        format!(
                            "a message on channel {}, which no record defines",
                            header.channel_id
                        )
                    })?;
                    return Ok(Some(BagMessage {
                        channel,
                        log_time: header.log_time,
                        publish_time: header.publish_time,
                        sequence: header.sequence,
                        data: data.into_owned(),
                    }));
                }
                _ => {}
            }
        }
    }
}

impl Iterator for BagMessages {
    type Item = Result<BagMessage, CoreError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        let message = match self.next_message() {
            Ok(Some(message)) => message,
            Ok(None) => {
                self.done = true;
                return None;
            }
            Err(error) => {
                self.done = true;
                let error = crate::printable(&error);
                return Some(Err(CoreError::bad_file(
                    &self.storage,
                    format!("not a whole MCAP file: {error}"),
                )));
            }
        };
        if message.channel.schema.is_none() {
            self.done = true;
            return Some(Err(CoreError::bad_file(
                &self.storage,
                format!(
                    "topic {} has no schema: its messages cannot be read",
                    crate::printable(&message.channel.topic)
                ),
            )));
        }
        Some(Ok(message))
    }
}
