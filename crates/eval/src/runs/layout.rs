//! Finding the runs: `<runs>/<method>/<sequence>.txt` (or `<runs>/<method>/<sequence>/<repeat>.txt`)
//! and each sequence's ground truth in `<datasets>/<sequence>/{traj.txt, groundtruth.txt}`.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use super::naming::scene_and_setting;
use crate::EvalError;

/// Ground-truth files looked for in a dataset folder, in this order (Replica, TUM layout).
const GROUND_TRUTH_FILES: [&str; 2] = ["traj.txt", "groundtruth.txt"];
const ESTIMATE_EXTENSION: &str = "txt";

/// A dataset sequence with its ground truth.
#[derive(Clone, Debug, PartialEq)]
pub struct Sequence {
    pub name: String,
    pub scene: String,
    pub setting: String,
    pub ground_truth: PathBuf,
}

/// One estimate file of a method for a sequence; `repeat` is the file stem inside
/// `<sequence>/`, `None` for `<sequence>.txt`.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    pub repeat: Option<String>,
    pub path: PathBuf,
}

/// The dataset folders of `datasets` that hold a ground truth, sorted by name.
pub fn find_sequences(datasets: &Path) -> Result<Vec<Sequence>, EvalError> {
    let mut sequences = Vec::new();
    for (name, dir) in subdirectories(datasets)? {
        let Some(ground_truth) = GROUND_TRUTH_FILES
            .iter()
            .map(|f| dir.join(f))
            .find(|p| p.is_file())
        else {
            continue;
        };
        let (scene, setting) = scene_and_setting(&name);
        sequences.push(Sequence {
            name,
            scene,
            setting,
            ground_truth,
        });
    }
    if sequences.is_empty() {
        return Err(EvalError::BadRuns {
            path: datasets.to_path_buf(),
            message: "no dataset folder holding traj.txt or groundtruth.txt; expected \
                      <datasets>/<sequence>/traj.txt (Replica) or .../groundtruth.txt (TUM)"
                .to_string(),
        });
    }
    Ok(sequences)
}

/// The method folders of `runs` (not hidden, not `skip`), sorted by name.
pub fn find_methods(runs: &Path, skip: Option<&Path>) -> Result<Vec<(String, PathBuf)>, EvalError> {
    let skip = skip.and_then(|s| s.canonicalize().ok());
    let methods: Vec<_> = subdirectories(runs)?
        .into_iter()
        .filter(|(name, dir)| !name.starts_with('.') && dir.canonicalize().ok() != skip)
        .collect();
    if methods.is_empty() {
        return Err(EvalError::BadRuns {
            path: runs.to_path_buf(),
            message: "no method folder; expected <runs>/<method>/<sequence>.txt".to_string(),
        });
    }
    Ok(methods)
}

/// The estimates of one method for one sequence: `<sequence>.txt`, then the `.txt` files of
/// `<sequence>/` (one per repeat) by name.
pub fn find_estimates(method_dir: &Path, sequence: &str) -> Result<Vec<Estimate>, EvalError> {
    let mut estimates = Vec::new();
    let single = method_dir.join(format!("{sequence}.{ESTIMATE_EXTENSION}"));
    if single.exists() {
        estimates.push(Estimate {
            repeat: None,
            path: single,
        });
    }
    let repeats = method_dir.join(sequence);
    if repeats.is_dir() {
        for path in sorted_entries(&repeats)? {
            if path.extension().is_some_and(|e| e == ESTIMATE_EXTENSION) {
                let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned());
                estimates.push(Estimate { repeat: stem, path });
            }
        }
    }
    Ok(estimates)
}

/// Entries of a method folder that belong to no known sequence.
pub fn find_unmatched(
    method_dir: &Path,
    sequences: &HashSet<&str>,
) -> Result<Vec<PathBuf>, EvalError> {
    Ok(sorted_entries(method_dir)?
        .into_iter()
        .filter(|p| {
            let is_estimate = p.is_dir() || p.extension().is_some_and(|e| e == ESTIMATE_EXTENSION);
            let name = if p.is_dir() {
                p.file_name()
            } else {
                p.file_stem()
            };
            is_estimate && !name.is_some_and(|n| sequences.contains(n.to_string_lossy().as_ref()))
        })
        .collect())
}

fn subdirectories(dir: &Path) -> Result<Vec<(String, PathBuf)>, EvalError> {
    Ok(sorted_entries(dir)?
        .into_iter()
        .filter(|p| p.is_dir())
        .filter_map(|p| Some((p.file_name()?.to_string_lossy().into_owned(), p)))
        .collect())
}

fn sorted_entries(dir: &Path) -> Result<Vec<PathBuf>, EvalError> {
    let entries = std::fs::read_dir(dir).map_err(|e| EvalError::io(dir, e))?;
    let mut paths = entries
        .map(|entry| entry.map(|e| e.path()))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| EvalError::io(dir, e))?;
    paths.sort();
    Ok(paths)
}
