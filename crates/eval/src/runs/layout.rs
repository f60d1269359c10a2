//! Finding the runs: `<runs>/<method>/<sequence>.txt` (or `<runs>/<method>/<sequence>/<repeat>.txt`)
//! and each sequence's ground truth in `<datasets>/<sequence>/`: `traj.txt`, `groundtruth.txt`,
//! EuRoC's `mav0/state_groundtruth_estimate0/data.csv` (the body's), TUM-VI's
//! `mav0/mocap0/data.csv` (the IMU's, which is its body), or a ROS 2 bag's pose topic.
//!
//! A runner records a run that failed as `<repeat>.failed` (or `<sequence>.failed`) beside where
//! the estimate would be: a text file whose first line is the reason. It wins over an estimate of
//! the same name, which is then a leftover of an earlier attempt and not evaluated. Other files
//! (the runner's `.json` and `.log`) are ignored.

use std::collections::{BTreeSet, HashSet};
use std::path::{Path, PathBuf};

use super::naming::scene_and_setting;
use crate::EvalError;

/// Ground-truth files looked for in a dataset folder, in this order (Replica, TUM, EuRoC layout,
/// TUM-VI's EuRoC-style export).
pub(crate) const GROUND_TRUTH_FILES: [&str; 4] = [
    "traj.txt",
    "groundtruth.txt",
    "mav0/state_groundtruth_estimate0/data.csv",
    "mav0/mocap0/data.csv",
];
/// A ROS 2 bag's folder holds this; its ground truth is its one pose topic
/// (`/ground_truth/pose` in the bags rslam writes).
const BAG_METADATA: &str = "metadata.yaml";
const ESTIMATE_EXTENSION: &str = "txt";
const FAILED_EXTENSION: &str = "failed";
/// The reason of a failed run whose `.failed` file gives none.
pub const NO_REASON: &str = "failed (no reason given)";

/// A dataset sequence with its ground truth.
#[derive(Clone, Debug, PartialEq)]
pub struct Sequence {
    pub name: String,
    pub scene: String,
    pub setting: String,
    pub ground_truth: PathBuf,
}

/// One run of a method on a sequence: its estimate file, or its `.failed` record.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// The file stem inside `<sequence>/`; `None` for `<sequence>.txt` (or `.failed`).
    pub repeat: Option<String>,
    /// The estimate (`.txt`), or the failure record (`.failed`).
    pub path: PathBuf,
    /// The reason of a `.failed` record (its first line, trimmed, or [`NO_REASON`]); `None` for
    /// an estimate to evaluate.
    pub failure: Option<String>,
}

/// The ground truth of the dataset folder `dir`: one of [`GROUND_TRUTH_FILES`], or the folder
/// itself when it is a ROS 2 bag.
pub fn ground_truth_of(dir: &Path) -> Option<PathBuf> {
    let file = GROUND_TRUTH_FILES
        .iter()
        .map(|f| dir.join(f))
        .find(|p| p.is_file());
    file.or_else(|| dir.join(BAG_METADATA).is_file().then(|| dir.to_path_buf()))
}

/// The dataset folders of `datasets` that hold a ground truth, sorted by name.
pub fn find_sequences(datasets: &Path) -> Result<Vec<Sequence>, EvalError> {
    let mut sequences = Vec::new();
    for (name, dir) in subdirectories(datasets)? {
        let Some(ground_truth) = ground_truth_of(&dir) else {
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
            message: "no dataset folder holding a ground truth; expected \
                      <datasets>/<sequence>/traj.txt (Replica), .../groundtruth.txt (TUM), \
                      .../mav0/state_groundtruth_estimate0/data.csv (EuRoC), \
                      .../mav0/mocap0/data.csv (TUM-VI) or .../metadata.yaml (a ROS 2 bag)"
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

/// The runs of one method on one sequence: `<sequence>.txt` or `.failed`, then those of
/// `<sequence>/` (one per repeat) by name. Of a `.txt` and a `.failed` with the same stem, the
/// `.failed` is taken.
pub fn find_estimates(method_dir: &Path, sequence: &str) -> Result<Vec<Estimate>, EvalError> {
    let mut estimates: Vec<Estimate> = run_file(method_dir, sequence, None).into_iter().collect();
    let repeats = method_dir.join(sequence);
    if repeats.is_dir() {
        let stems: BTreeSet<String> = sorted_entries(&repeats)?
            .iter()
            .filter(|p| is_run_file(p))
            .filter_map(|p| Some(p.file_stem()?.to_string_lossy().into_owned()))
            .collect();
        for stem in stems {
            estimates.extend(run_file(&repeats, &stem, Some(stem.clone())));
        }
    }
    Ok(estimates)
}

/// `dir/<stem>.failed` if it exists, else `dir/<stem>.txt` if it exists.
fn run_file(dir: &Path, stem: &str, repeat: Option<String>) -> Option<Estimate> {
    let failed = dir.join(format!("{stem}.{FAILED_EXTENSION}"));
    if failed.is_file() {
        return Some(Estimate {
            repeat,
            failure: Some(failure_reason(&failed)),
            path: failed,
        });
    }
    let estimate = dir.join(format!("{stem}.{ESTIMATE_EXTENSION}"));
    estimate.exists().then_some(Estimate {
        repeat,
        path: estimate,
        failure: None,
    })
}

/// The first line of a `.failed` record, trimmed; unreadable, it still marks a failed run.
fn failure_reason(record: &Path) -> String {
    match std::fs::read(record) {
        Ok(bytes) => {
            let text = String::from_utf8_lossy(&bytes);
            let first_line = text.lines().next().map(str::trim).unwrap_or("");
            if first_line.is_empty() {
                NO_REASON.to_string()
            } else {
                first_line.to_string()
            }
        }
        Err(e) => format!("{}: {e}", record.display()),
    }
}

fn is_run_file(path: &Path) -> bool {
    path.is_file()
        && path
            .extension()
            .is_some_and(|e| e == ESTIMATE_EXTENSION || e == FAILED_EXTENSION)
}

/// Entries of a method folder (folders, estimates and `.failed` records) that belong to no
/// known sequence.
pub fn find_unmatched(
    method_dir: &Path,
    sequences: &HashSet<&str>,
) -> Result<Vec<PathBuf>, EvalError> {
    Ok(sorted_entries(method_dir)?
        .into_iter()
        .filter(|p| {
            let name = if p.is_dir() {
                p.file_name()
            } else {
                p.file_stem()
            };
            (p.is_dir() || is_run_file(p))
                && !name.is_some_and(|n| sequences.contains(n.to_string_lossy().as_ref()))
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

#[cfg(test)]
mod tests {
    use super::*;

    fn write(path: &Path, text: &str) {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }

    #[test]
    fn each_layout_s_ground_truth_is_found_in_its_dataset_folder() {
        let dir = tempfile::tempdir().unwrap();
        let euroc_truth = "mav0/state_groundtruth_estimate0/data.csv";
        let tum_vi_truth = "mav0/mocap0/data.csv";
        write(&dir.path().join("room1__tum_vi").join(tum_vi_truth), "x");
        write(&dir.path().join("room1__both").join(tum_vi_truth), "x");
        write(&dir.path().join("room1__both").join(euroc_truth), "x");
        write(&dir.path().join("room0__replica/traj.txt"), "x");
        write(&dir.path().join("room0__tum/groundtruth.txt"), "x");
        write(&dir.path().join("room0__euroc").join(euroc_truth), "x");
        write(&dir.path().join("room0__none/mav0/imu0/data.csv"), "x");
        write(&dir.path().join("room0__ros2/metadata.yaml"), "x");
        let found: Vec<(String, PathBuf)> = find_sequences(dir.path())
            .unwrap()
            .into_iter()
            .map(|s| (s.name, s.ground_truth))
            .collect();
        let at = |name: &str, file: &str| (name.to_string(), dir.path().join(name).join(file));
        assert_eq!(
            found,
            [
                at("room0__euroc", euroc_truth),
                at("room0__replica", "traj.txt"),
                at("room0__ros2", ""),
                at("room0__tum", "groundtruth.txt"),
                at("room1__both", euroc_truth),
                at("room1__tum_vi", tum_vi_truth),
            ]
        );
    }

    #[test]
    fn failed_records_are_runs_with_their_first_line_as_reason() {
        let dir = tempfile::tempdir().unwrap();
        let seq = dir.path().join("room0__fog-3");
        write(&seq.join("1.txt"), "0 0 0 0 0 0 0 1\n");
        write(&seq.join("2.failed"), "  timed out after 60 s  \nkilled\n");
        write(&seq.join("3.failed"), "");
        write(&seq.join("4.failed"), "\n\nexit status 3\n");
        write(&seq.join("2.json"), "{}");
        write(&seq.join("2.log"), "log");
        let found = find_estimates(dir.path(), "room0__fog-3").unwrap();
        let summary: Vec<(Option<&str>, Option<&str>)> = found
            .iter()
            .map(|e| (e.repeat.as_deref(), e.failure.as_deref()))
            .collect();
        assert_eq!(
            summary,
            vec![
                (Some("1"), None),
                (Some("2"), Some("timed out after 60 s")),
                (Some("3"), Some(NO_REASON)),
                (Some("4"), Some(NO_REASON)),
            ]
        );
        assert_eq!(found[1].path, seq.join("2.failed"));
    }

    #[test]
    fn a_failed_record_wins_over_a_stale_estimate() {
        let dir = tempfile::tempdir().unwrap();
        write(&dir.path().join("room0/1.txt"), "0 0 0 0 0 0 0 1\n");
        write(&dir.path().join("room0/1.failed"), "exit status 3");
        write(&dir.path().join("office0.txt"), "0 0 0 0 0 0 0 1\n");
        write(&dir.path().join("office0.failed"), "estimate unreadable: x");
        let room = find_estimates(dir.path(), "room0").unwrap();
        assert_eq!(room.len(), 1);
        assert_eq!(room[0].failure.as_deref(), Some("exit status 3"));
        let office = find_estimates(dir.path(), "office0").unwrap();
        assert_eq!(
            office,
            vec![Estimate {
                repeat: None,
                path: dir.path().join("office0.failed"),
                failure: Some("estimate unreadable: x".to_string()),
            }]
        );
    }

    #[test]
    fn unmatched_failed_records_are_reported_and_other_files_ignored() {
        let dir = tempfile::tempdir().unwrap();
        for name in [
            "room0.failed",
            "kitchen.failed",
            "kitchen.json",
            "notes.log",
        ] {
            write(&dir.path().join(name), "x");
        }
        let known = HashSet::from(["room0"]);
        assert_eq!(
            find_unmatched(dir.path(), &known).unwrap(),
            vec![dir.path().join("kitchen.failed")]
        );
    }
}
