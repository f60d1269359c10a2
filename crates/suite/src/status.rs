//! `rslam suite status`: every sequence's state, the table of settings × scenes, disk used.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::disk::folder_bytes;
use crate::sequence::{Sequence, DATASETS_DIR};
use crate::state::SequenceState;
use crate::{Suite, SuiteError};

#[derive(Clone, Debug, Serialize)]
pub struct SequenceStatus {
    pub name: String,
    pub scene: String,
    pub setting: String,
    #[serde(flatten)]
    pub state: SequenceState,
}

#[derive(Clone, Debug, Serialize)]
pub struct SuiteStatus {
    pub sequences: Vec<SequenceStatus>,
    /// Sequences per state label.
    pub counts: BTreeMap<&'static str, usize>,
    /// Bytes under `datasets/`.
    pub bytes_used: u64,
}

impl SuiteStatus {
    /// The status of `states` (from [`Suite::shard_states`]) of `suite`.
    pub fn read(suite: &Suite, states: &[(&Sequence, SequenceState)]) -> Result<Self, SuiteError> {
        let sequences: Vec<SequenceStatus> = states
            .iter()
            .map(|(s, state)| SequenceStatus {
                name: s.name.clone(),
                scene: s.scene_label().to_string(),
                setting: s.setting().to_string(),
                state: state.clone(),
            })
            .collect();
        let mut counts = BTreeMap::new();
        for label in SequenceState::LABELS {
            counts.insert(label, 0);
        }
        for s in &sequences {
            *counts.entry(s.state.label()).or_default() += 1;
        }
        Ok(Self {
            sequences,
            counts,
            bytes_used: folder_bytes(&suite.dir.join(DATASETS_DIR))?,
        })
    }

    pub fn is_complete(&self) -> bool {
        self.sequences.iter().all(|s| s.state.is_finished())
    }

    /// Settings (rows, in suite order) × scenes (columns) with one mark per sequence:
    /// `✓` complete, `○` frames deleted after its runs, `~` partial, `·` missing, `!` conflict.
    pub fn table(&self) -> String {
        let mut scenes: Vec<&str> = Vec::new();
        let mut settings: Vec<&str> = Vec::new();
        let mut marks = BTreeMap::new();
        for s in &self.sequences {
            if !scenes.contains(&s.scene.as_str()) {
                scenes.push(&s.scene);
            }
            if !settings.contains(&s.setting.as_str()) {
                settings.push(&s.setting);
            }
            marks.insert((s.setting.as_str(), s.scene.as_str()), mark(&s.state));
        }
        let width = settings
            .iter()
            .map(|s| s.chars().count())
            .max()
            .unwrap_or(0)
            .max(7);
        let mut out = format!("{:width$}", "setting");
        for scene in &scenes {
            out.push_str(&format!("  {scene}"));
        }
        out.push('\n');
        for setting in &settings {
            out.push_str(&format!("{setting:width$}"));
            for scene in &scenes {
                let mark = marks.get(&(*setting, *scene)).copied().unwrap_or(" ");
                out.push_str(&format!("  {mark:^w$}", w = scene.chars().count()));
            }
            out.push('\n');
        }
        out
    }
}

fn mark(state: &SequenceState) -> &'static str {
    match state {
        SequenceState::Complete => "✓",
        SequenceState::FramesDeleted => "○",
        SequenceState::Partial => "~",
        SequenceState::Missing => "·",
        SequenceState::Conflict(_) => "!",
    }
}
