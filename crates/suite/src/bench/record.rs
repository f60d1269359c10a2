//! What one run left in `runs/<method>/<sequence>/`: `<repeat>.txt` (the estimate) or
//! `<repeat>.failed` (the reason, which `rslam eval --runs` counts as a failure), `<repeat>.log`,
//! `<repeat>.mesh.ply` when the method writes one, and `<repeat>.json`, this record, written
//! last: a run without it did not finish and is run again.

use std::path::{Path, PathBuf};

use rslam_core::dataset::write_atomically;
use serde::{Deserialize, Serialize};

use crate::SuiteError;

pub const RUNS_DIR: &str = "runs";

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    pub method: String,
    pub sequence: String,
    pub repeat: usize,
    pub command: Vec<String>,
    /// `None` when the run succeeded.
    pub failure: Option<String>,
    pub exit_code: Option<i32>,
    pub seconds: f64,
    pub peak_rss_mb: Option<f64>,
    /// The reconstruction kept beside the estimate, if the method wrote one.
    pub mesh: Option<PathBuf>,
}

/// The files of one (method, sequence, repeat).
pub struct RunFiles {
    pub dir: PathBuf,
    pub repeat: usize,
}

impl RunFiles {
    pub fn new(suite_dir: &Path, method: &str, sequence: &str, repeat: usize) -> Self {
        Self {
            dir: suite_dir.join(RUNS_DIR).join(method).join(sequence),
            repeat,
        }
    }

    fn file(&self, suffix: &str) -> PathBuf {
        self.dir.join(format!("{}{suffix}", self.repeat))
    }

    pub fn estimate(&self) -> PathBuf {
        self.file(".txt")
    }

    pub fn failed(&self) -> PathBuf {
        self.file(".failed")
    }

    pub fn log(&self) -> PathBuf {
        self.file(".log")
    }

    pub fn mesh(&self) -> PathBuf {
        self.file(".mesh.ply")
    }

    pub fn record(&self) -> PathBuf {
        self.file(".json")
    }

    /// The method's scratch folder for this run.
    pub fn work(&self) -> PathBuf {
        self.file(".work")
    }

    pub fn read_record(&self) -> Option<RunRecord> {
        let text = std::fs::read_to_string(self.record()).ok()?;
        serde_json::from_str(&text).ok()
    }

    /// Removes what an earlier, unfinished or failed, attempt left.
    pub fn clear(&self) -> Result<(), SuiteError> {
        for path in [
            self.estimate(),
            self.failed(),
            self.log(),
            self.mesh(),
            self.record(),
        ] {
            match std::fs::remove_file(&path) {
                Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                    return Err(SuiteError::io(&path, e))
                }
                _ => {}
            }
        }
        let work = self.work();
        if work.exists() {
            std::fs::remove_dir_all(&work).map_err(|e| SuiteError::io(&work, e))?;
        }
        Ok(())
    }

    pub fn write_record(&self, record: &RunRecord) -> Result<(), SuiteError> {
        let path = self.record();
        let text =
            serde_json::to_string_pretty(record).map_err(|e| SuiteError::io(&path, e.into()))?;
        Ok(write_atomically(&path, (text + "\n").as_bytes())?)
    }
}
