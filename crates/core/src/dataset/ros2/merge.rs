//! Messages of several MCAP files, each in log-time order, written into one bag in log-time
//! order: a recorded bag's copied messages with the spools of its perturbed cameras, a rig's
//! cameras with its IMU and ground truth. A spool is an MCAP file of one stream, written while
//! the streams are made one after another and removed once merged.

use std::iter::Peekable;
use std::path::Path;

use super::bag::{BagWriter, LogTimes};
use super::recorded::{BagMessage, BagMessages, RecordedBag};
use crate::CoreError;

/// Closes `spool`, written in `folder`, for reading.
pub(super) fn close_spool(folder: &Path, spool: BagWriter) -> Result<RecordedBag, CoreError> {
    let closed = spool.finish()?;
    Ok(RecordedBag {
        folder: folder.to_path_buf(),
        storage: folder.join(closed.file),
    })
}

pub(super) fn remove_spools(spools: &[RecordedBag]) -> Result<(), CoreError> {
    for spool in spools {
        std::fs::remove_file(&spool.storage).map_err(|e| CoreError::io(&spool.storage, e))?;
    }
    Ok(())
}

/// Writes every message of `streams` into `bag`, the earliest logged first (on a tie, the
/// stream listed first); `topic_of(stream, message)` is the bag's topic index for it, `None` to
/// leave it out.
pub(super) fn merge_by_log_time(
    bag: &mut BagWriter,
    streams: Vec<BagMessages>,
    topic_of: impl Fn(usize, &BagMessage) -> Option<usize>,
) -> Result<(), CoreError> {
    let mut streams: Vec<Peekable<BagMessages>> =
        streams.into_iter().map(Iterator::peekable).collect();
    loop {
        let mut earliest: Option<(u64, usize)> = None;
        for (i, stream) in streams.iter_mut().enumerate() {
            let log_time = match stream.peek() {
                None => continue,
                // An error is taken at once, to be returned.
                Some(Err(_)) => 0,
                Some(Ok(message)) => message.log_time,
            };
            if earliest.is_none_or(|(t, _)| log_time < t) {
                earliest = Some((log_time, i));
            }
        }
        let Some((_, i)) = earliest else {
            return Ok(());
        };
        let Some(message) = streams[i].next() else {
            continue;
        };
        let message = message?;
        if let Some(topic) = topic_of(i, &message) {
            let times = LogTimes {
                log_time: message.log_time,
                publish_time: message.publish_time,
                sequence: message.sequence,
            };
            bag.write_bytes(topic, times, &message.data)?;
        }
    }
}
