//! What a sequence's folder holds, read without a GPU and without hashing the frames: a complete
//! sequence has a manifest whose digest matches its checksum list and that records this
//! sequence's own command.

use std::path::Path;

use rslam_core::dataset::{Checksums, Manifest, MANIFEST_FILE, RUN_FILE};
use serde::Serialize;

use crate::sequence::Sequence;

#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase", tag = "state", content = "reason")]
pub enum SequenceState {
    Complete,
    /// A run started it and did not finish; the next run resumes it.
    Partial,
    Missing,
    /// Something other than this sequence's finished dataset: made from another definition of
    /// the row, damaged, or not rslam's. `suite run` leaves it alone unless `--force`.
    Conflict(String),
}

impl SequenceState {
    pub fn label(&self) -> &'static str {
        match self {
            Self::Complete => "complete",
            Self::Partial => "partial",
            Self::Missing => "missing",
            Self::Conflict(_) => "conflict",
        }
    }
}

pub fn inspect(sequence: &Sequence, suite_dir: &Path) -> SequenceState {
    let dir = sequence.dir(suite_dir);
    let is_empty = std::fs::read_dir(&dir).map_or(true, |mut entries| entries.next().is_none());
    if is_empty {
        return SequenceState::Missing;
    }
    if dir.join(RUN_FILE).is_file() {
        return SequenceState::Partial;
    }
    if !dir.join(MANIFEST_FILE).is_file() {
        return SequenceState::Conflict("holds files but no rslam.json: not rslam output".into());
    }
    match finished_state(sequence, &dir) {
        Ok(state) => state,
        Err(reason) => SequenceState::Conflict(reason),
    }
}

fn finished_state(sequence: &Sequence, dir: &Path) -> Result<SequenceState, String> {
    let manifest = Manifest::read(dir).map_err(|e| e.to_string())?;
    let listed = Checksums::read(dir).map_err(|e| e.to_string())?;
    if manifest.content_digest != listed.digest() {
        return Err("rslam.b3sum does not match the manifest's content_digest: damaged".into());
    }
    let expected = sequence.command();
    if manifest.command != expected {
        return Err(format!(
            "made by `{}`, the suite now says `{}`",
            manifest.command.join(" "),
            expected.join(" ")
        ));
    }
    Ok(SequenceState::Complete)
}
