//! What a sequence's folder holds, read without a GPU and without hashing the frames: a complete
//! sequence has the manifest of the sequence's own job, sealing a checksum list whose files are
//! all there.

use std::path::Path;

use rslam_pipeline::{Holding, SceneCache};
use serde::Serialize;

use crate::sequence::Sequence;

#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase", tag = "state", content = "reason")]
pub enum SequenceState {
    Complete,
    /// A run started it and did not finish; the next run resumes it.
    Partial,
    Missing,
    /// Made, used by its runs and its frames deleted (`suite bench --ephemeral`); its manifest,
    /// checksums and ground truth kept. `suite run` leaves it; `suite regen` remakes its frames.
    #[serde(rename = "frames-deleted")]
    FramesDeleted,
    /// Something other than this sequence's finished dataset: made from another definition of
    /// the row, damaged, or not rslam's. `suite run` leaves it alone unless `--force`.
    Conflict(String),
}

impl SequenceState {
    /// The labels, in the order tables print them.
    pub const LABELS: [&'static str; 5] = [
        "complete",
        "frames-deleted",
        "partial",
        "missing",
        "conflict",
    ];

    /// Made and finished: its frames there, or deleted after its runs.
    pub fn is_finished(&self) -> bool {
        matches!(self, Self::Complete | Self::FramesDeleted)
    }

    pub fn label(&self) -> &'static str {
        match self {
            Self::Complete => "complete",
            Self::Partial => "partial",
            Self::Missing => "missing",
            Self::FramesDeleted => "frames-deleted",
            Self::Conflict(_) => "conflict",
        }
    }
}

/// What `sequence`'s folder holds, by the rule a run uses for its job
/// ([`rslam_pipeline::Job::holding`]), its scene taken from `scenes`: made on whichever GPU made
/// it, since every GPU makes the same job (in its own float rounding).
pub fn inspect(sequence: &Sequence, suite_dir: &Path, scenes: &SceneCache) -> SequenceState {
    match sequence.job(suite_dir, false).holding(None, scenes) {
        Ok(Holding::Nothing) => SequenceState::Missing,
        Ok(Holding::Complete) => SequenceState::Complete,
        Ok(Holding::FramesDeleted) => SequenceState::FramesDeleted,
        // A run resumes it: it finishes what is missing and seals the folder again. An unfinished
        // run of another job (another GPU, an edited row) is never usable: a run starts it over.
        Ok(
            Holding::Unfinished
            | Holding::Broken(_)
            | Holding::OtherJob {
                finished: false, ..
            },
        ) => SequenceState::Partial,
        Ok(Holding::OtherJob { what, .. }) => SequenceState::Conflict(format!("holds {what}")),
        Ok(Holding::Unreadable(e)) => SequenceState::Conflict(e.to_string()),
        Ok(Holding::NotRslam) => {
            SequenceState::Conflict("holds files but no rslam.json: not rslam output".into())
        }
        Err(e) => SequenceState::Conflict(format!("its job cannot be planned: {e}")),
    }
}
