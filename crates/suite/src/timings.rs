//! How long this suite's sequences took to make, one JSON line per run in `logs/timings.jsonl`
//! (appended by every process of a sharded run; a line is written whole, in one call), for the
//! time estimate of `rslam suite status --plan`.

use std::io::Write;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::SuiteError;

pub const LOGS_DIR: &str = "logs";
const TIMINGS_FILE: &str = "timings.jsonl";

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Timing {
    pub sequence: String,
    /// Frames drawn by that run (fewer than the sequence's when it resumed).
    pub frames: usize,
    pub seconds: f64,
    pub adapter: String,
}

#[derive(Clone, Debug, Default)]
pub struct Timings {
    runs: Vec<Timing>,
}

fn path(suite_dir: &Path) -> PathBuf {
    suite_dir.join(LOGS_DIR).join(TIMINGS_FILE)
}

impl Timings {
    /// The recorded runs; lines that do not parse (a run killed mid-write) are skipped.
    pub fn read(suite_dir: &Path) -> Result<Self, SuiteError> {
        let path = path(suite_dir);
        let text = match std::fs::read_to_string(&path) {
            Ok(text) => text,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Self::default()),
            Err(e) => return Err(SuiteError::io(&path, e)),
        };
        let runs = text
            .lines()
            .filter_map(|line| serde_json::from_str(line).ok())
            .collect();
        Ok(Self { runs })
    }

    pub fn append(suite_dir: &Path, timing: &Timing) -> Result<(), SuiteError> {
        let path = path(suite_dir);
        let dir = suite_dir.join(LOGS_DIR);
        std::fs::create_dir_all(&dir).map_err(|e| SuiteError::io(&dir, e))?;
        let mut line =
            serde_json::to_string(timing).map_err(|e| SuiteError::io(&path, e.into()))?;
        line.push('\n');
        let mut file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .map_err(|e| SuiteError::io(&path, e))?;
        file.write_all(line.as_bytes())
            .map_err(|e| SuiteError::io(&path, e))
    }

    pub fn len(&self) -> usize {
        self.runs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.runs.is_empty()
    }

    /// Frames over seconds, summed over every recorded run.
    pub fn frames_per_second(&self) -> Option<f64> {
        let frames: usize = self.runs.iter().map(|r| r.frames).sum();
        let seconds: f64 = self.runs.iter().map(|r| r.seconds).sum();
        (frames > 0 && seconds > 0.0).then(|| frames as f64 / seconds)
    }
}
