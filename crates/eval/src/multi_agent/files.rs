//! Where the agents' files are: repeated `EST GT` pairs, or one folder per agent.
//!
//! A folder of agents holds `<dir>/<agent>/estimate.txt` (the name a benchmark runner gives the
//! estimate it asks a method for) beside the agent's ground truth, `traj.txt`, `groundtruth.txt`,
//! EuRoC's `mav0/state_groundtruth_estimate0/data.csv` or TUM-VI's `mav0/mocap0/data.csv` (the
//! names `--runs` looks for in a dataset folder), all in one world frame.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use rslam_core::trajectory_io::{read_trajectory_with, ReadOptions, TimeSource, TrajectoryFile};

use super::evaluate::{evaluate_agents, Agent, MultiAgentEvaluation};
use crate::alignment::AlignMode;
use crate::association::Matching;
use crate::runs::GROUND_TRUTH_FILES;
use crate::EvalError;

/// The estimate's file name inside an agent's folder.
pub const AGENT_ESTIMATE_FILE: &str = "estimate.txt";

/// One agent's files.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AgentFiles {
    pub name: String,
    pub estimate: PathBuf,
    pub ground_truth: PathBuf,
}

/// Agents from `EST GT EST GT ...`, named after their estimate's file stem, or after the
/// estimate's path as given when two stems are the same (`a/estimate.txt`, `b/estimate.txt`).
pub fn agents_from_pairs(est_gt: &[PathBuf]) -> Result<Vec<AgentFiles>, EvalError> {
    if est_gt.is_empty() || !est_gt.len().is_multiple_of(2) {
        return Err(EvalError::BadOption {
            name: "agent",
            value: format!("{} files", est_gt.len()),
            expected: "pairs of files: --agent EST GT for each agent",
        });
    }
    let stem = |p: &Path| {
        p.file_stem().map_or_else(
            || p.display().to_string(),
            |s| s.to_string_lossy().into_owned(),
        )
    };
    let pairs: Vec<(&PathBuf, &PathBuf)> = est_gt.chunks_exact(2).map(|c| (&c[0], &c[1])).collect();
    let stems: HashSet<String> = pairs.iter().map(|(est, _)| stem(est)).collect();
    let by_stem = stems.len() == pairs.len();
    Ok(pairs
        .into_iter()
        .map(|(est, gt)| AgentFiles {
            name: if by_stem {
                stem(est)
            } else {
                est.display().to_string()
            },
            estimate: est.clone(),
            ground_truth: gt.clone(),
        })
        .collect())
}

/// The agents of `dir`: every folder in it (not hidden), by name, each with
/// [`AGENT_ESTIMATE_FILE`] and a ground truth (`traj.txt`, `groundtruth.txt`, EuRoC's
/// `mav0/state_groundtruth_estimate0/data.csv` or TUM-VI's `mav0/mocap0/data.csv`). A folder missing either is an error naming the
/// file; so is a `dir` without agent folders.
pub fn agents_in_folder(dir: &Path) -> Result<Vec<AgentFiles>, EvalError> {
    let entries = std::fs::read_dir(dir).map_err(|e| EvalError::io(dir, e))?;
    let mut folders = Vec::new();
    for entry in entries {
        let path = entry.map_err(|e| EvalError::io(dir, e))?.path();
        let hidden = path
            .file_name()
            .is_some_and(|n| n.to_string_lossy().starts_with('.'));
        if path.is_dir() && !hidden {
            folders.push(path);
        }
    }
    folders.sort();
    if folders.is_empty() {
        return Err(EvalError::BadAgents {
            path: dir.to_path_buf(),
            message: format!(
                "no agent folder; expected <dir>/<agent>/{AGENT_ESTIMATE_FILE} with \
                 <dir>/<agent>/traj.txt, groundtruth.txt, mav0/state_groundtruth_estimate0/data.csv or mav0/mocap0/data.csv"
            ),
        });
    }
    folders
        .into_iter()
        .map(|folder| {
            let estimate = folder.join(AGENT_ESTIMATE_FILE);
            if !estimate.is_file() {
                return Err(EvalError::BadAgents {
                    path: estimate,
                    message: "no such file: the agent's estimate".to_string(),
                });
            }
            let ground_truth = GROUND_TRUTH_FILES
                .iter()
                .map(|f| folder.join(f))
                .find(|p| p.is_file())
                .ok_or_else(|| EvalError::BadAgents {
                    path: folder.clone(),
                    message: "no ground truth: expected traj.txt, groundtruth.txt, mav0/state_groundtruth_estimate0/data.csv or mav0/mocap0/data.csv".to_string(),
                })?;
            Ok(AgentFiles {
                name: folder
                    .file_name()
                    .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
                estimate,
                ground_truth,
            })
        })
        .collect()
}

/// Reads every agent's files (see [`read_trajectory_with`]) and evaluates them with
/// [`evaluate_agents`]. An agent whose file has no timestamps (KITTI without a times file) is
/// matched by index whatever `matching` says. Errors name the agent and its two files.
pub fn read_and_evaluate_agents(
    files: &[AgentFiles],
    read: &ReadOptions,
    matching: Matching,
    align: AlignMode,
) -> Result<MultiAgentEvaluation, EvalError> {
    let in_files = |f: &AgentFiles, error: EvalError| EvalError::AgentFiles {
        agent: f.name.clone(),
        estimate: f.estimate.clone(),
        ground_truth: f.ground_truth.clone(),
        error: Box::new(error),
    };
    let agents = files
        .iter()
        .map(|f| {
            let read_one =
                |path: &Path| read_trajectory_with(path, read).map_err(|e| in_files(f, e.into()));
            let estimate = read_one(&f.estimate)?;
            let ground_truth = read_one(&f.ground_truth)?;
            Ok(agent(f, estimate, ground_truth, matching))
        })
        .collect::<Result<Vec<_>, EvalError>>()?;
    evaluate_agents(&agents, align).map_err(|error| match error {
        EvalError::Agent { agent, error } => match files.iter().find(|f| f.name == agent) {
            Some(f) => in_files(f, *error),
            None => EvalError::Agent { agent, error },
        },
        other => other,
    })
}

fn agent(
    files: &AgentFiles,
    estimate: TrajectoryFile,
    ground_truth: TrajectoryFile,
    matching: Matching,
) -> Agent {
    let untimed = |t: TimeSource| t == TimeSource::FrameIndex;
    Agent {
        name: files.name.clone(),
        matching: if untimed(estimate.time_source) || untimed(ground_truth.time_source) {
            Matching::Index
        } else {
            matching
        },
        estimate: estimate.trajectory,
        ground_truth: ground_truth.trajectory,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(path: &Path, text: &str) {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }

    /// A TUM trajectory on a planar square (non-degenerate), `t0` its first timestamp.
    fn square(t0: f64) -> String {
        [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.2]]
            .iter()
            .enumerate()
            .map(|(i, [x, y])| format!("{} {x} {y} 0 0 0 0 1\n", t0 + i as f64))
            .collect()
    }

    #[test]
    fn pairs_are_named_by_stem_unless_stems_repeat() {
        let paths = |names: &[&str]| names.iter().map(PathBuf::from).collect::<Vec<_>>();
        let agents = agents_from_pairs(&paths(&["a.txt", "gt_a.txt", "b.txt", "gt_b.txt"]));
        let names: Vec<String> = agents.unwrap().into_iter().map(|a| a.name).collect();
        assert_eq!(names, ["a", "b"]);
        let agents = agents_from_pairs(&paths(&["x/est.txt", "x/gt.txt", "y/est.txt", "y/gt.txt"]));
        let names: Vec<String> = agents.unwrap().into_iter().map(|a| a.name).collect();
        assert_eq!(names, ["x/est.txt", "y/est.txt"]);
        let err = agents_from_pairs(&paths(&["a.txt", "gt.txt", "b.txt"])).unwrap_err();
        assert_eq!(
            err.to_string(),
            "agent = 3 files: expected pairs of files: --agent EST GT for each agent"
        );
    }

    #[test]
    fn folders_give_agents_and_missing_files_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path();
        write(&root.join("b/estimate.txt"), &square(0.0));
        write(&root.join("b/groundtruth.txt"), &square(0.0));
        write(&root.join("a/estimate.txt"), &square(0.0));
        write(&root.join("a/traj.txt"), &square(0.0));
        write(&root.join(".hidden/estimate.txt"), "");
        let agents = agents_in_folder(root).unwrap();
        assert_eq!(agents.len(), 2);
        assert_eq!(agents[0].name, "a");
        assert_eq!(agents[0].ground_truth, root.join("a/traj.txt"));
        assert_eq!(agents[1].ground_truth, root.join("b/groundtruth.txt"));
        let e = read_and_evaluate_agents(
            &agents,
            &ReadOptions::default(),
            Matching::default(),
            AlignMode::Se3,
        )
        .unwrap();
        assert!(e.joint.ate.rmse < 1e-12);

        write(&root.join("c/groundtruth.txt"), &square(0.0));
        let err = agents_in_folder(root).unwrap_err().to_string();
        assert!(err.contains("c/estimate.txt: no such file"), "{err}");
        let empty = tempfile::tempdir().unwrap();
        let err = agents_in_folder(empty.path()).unwrap_err().to_string();
        assert!(err.contains("no agent folder"), "{err}");
    }

    #[test]
    fn an_agent_without_pairs_names_its_files() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path();
        write(&root.join("a/estimate.txt"), &square(0.0));
        write(&root.join("a/groundtruth.txt"), &square(0.0));
        write(&root.join("b/estimate.txt"), &square(50.0));
        write(&root.join("b/groundtruth.txt"), &square(0.0));
        let agents = agents_in_folder(root).unwrap();
        let err = read_and_evaluate_agents(
            &agents,
            &ReadOptions::default(),
            Matching::default(),
            AlignMode::Se3,
        )
        .unwrap_err()
        .to_string();
        let expected = format!(
            "agent b ({} against {}): no matching timestamps",
            root.join("b/estimate.txt").display(),
            root.join("b/groundtruth.txt").display()
        );
        assert!(err.starts_with(&expected), "{err}");
    }
}
