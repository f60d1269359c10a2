//! What one run left in `runs/<method>/<sequence>/`: `<repeat>.txt` (the estimate) or
//! `<repeat>.failed` (the reason, which `rslam eval --runs` counts as a failure), `<repeat>.log`,
//! `<repeat>.mesh.ply` and `<repeat>.renders/` when the method writes them, and `<repeat>.json`,
//! this record, written
//! last: a run without it did not finish and is run again.

use std::path::{Path, PathBuf};

use rslam_core::dataset::write_atomically;
use rslam_core::remove_if_present;
use serde::{Deserialize, Serialize};

use crate::sequence::Sequence;
use crate::{Suite, SuiteError};

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
    /// The folder of its map's rendered views kept beside the estimate, if it wrote one.
    #[serde(default)]
    pub renders: Option<PathBuf>,
}

/// The record of every run under `runs/` that finished without failure, by method (in name
/// order), sequence (in the suite's order) and repeat.
pub fn succeeded_runs(suite: &Suite) -> Vec<(&Sequence, RunRecord)> {
    let mut runs = recorded_runs(suite);
    runs.retain(|(_, record)| record.failure.is_none());
    runs
}

/// Every run that succeeded and kept what `kept` takes from its record (its mesh, its
/// renders), as (sequence, method, repeat, what it kept), in the order of [`succeeded_runs`].
pub fn succeeded_runs_keeping<T>(
    suite: &Suite,
    kept: impl Fn(&RunRecord) -> Option<T>,
) -> Vec<(&Sequence, String, usize, T)> {
    succeeded_runs(suite)
        .into_iter()
        .filter_map(|(sequence, record)| {
            let what = kept(&record)?;
            Some((sequence, record.method, record.repeat, what))
        })
        .collect()
}

/// The record of every finished run under `runs/`, failed or not, in the order of
/// [`succeeded_runs`].
pub fn recorded_runs(suite: &Suite) -> Vec<(&Sequence, RunRecord)> {
    let Ok(methods) = std::fs::read_dir(suite.dir.join(RUNS_DIR)) else {
        return Vec::new();
    };
    let mut methods: Vec<String> = methods
        .flatten()
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    methods.sort();
    let mut found = Vec::new();
    for method in methods {
        for sequence in &suite.sequences {
            for repeat in 0.. {
                let files = RunFiles::new(&suite.dir, &method, &sequence.name, repeat);
                let Some(record) = files.read_record() else {
                    break;
                };
                found.push((sequence, record));
            }
        }
    }
    found
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

    pub fn renders(&self) -> PathBuf {
        self.file(".renders")
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
            remove_if_present(&path)?;
        }
        for dir in [self.work(), self.renders()] {
            remove_if_present(&dir)?;
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
