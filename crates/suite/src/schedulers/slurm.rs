//! `rslam suite slurm`: an sbatch array script, task i running shard i of N
//! (`suite run` reads `SLURM_ARRAY_TASK_ID` and `SLURM_ARRAY_TASK_COUNT`).

use std::path::{Path, PathBuf};

use super::TaskOptions;
use crate::SuiteError;

pub const SLURM_DIR: &str = "slurm";
const SCRIPT_FILE: &str = "suite.sbatch";

#[derive(Clone, Debug)]
pub struct SlurmOptions {
    pub tasks: usize,
    /// At most this many tasks at once (`%` in `--array`).
    pub throttle: Option<usize>,
    /// Further `#SBATCH` lines, e.g. `--partition=gpu`, `--gres=gpu:1`, `--time=04:00:00`.
    pub sbatch_args: Vec<String>,
    /// The rslam binary the tasks run (absolute).
    pub rslam: PathBuf,
    pub task: TaskOptions,
}

/// Writes `<suite>/slurm/suite.sbatch` (and the folder its logs go to); returns its path.
pub fn write_slurm_script(suite_dir: &Path, options: &SlurmOptions) -> Result<PathBuf, SuiteError> {
    if options.tasks == 0 {
        return Err(SuiteError::option(
            "--tasks",
            "0: expected at least one task",
        ));
    }
    if options.throttle == Some(0) {
        return Err(SuiteError::option(
            "--throttle",
            "0: expected at least one task at once",
        ));
    }
    let suite_dir = absolute(suite_dir)?;
    let dir = suite_dir.join(SLURM_DIR);
    let logs = dir.join("logs");
    std::fs::create_dir_all(&logs).map_err(|e| SuiteError::io(&logs, e))?;
    let path = dir.join(SCRIPT_FILE);
    std::fs::write(&path, slurm_script(&suite_dir, options))
        .map_err(|e| SuiteError::io(&path, e))?;
    Ok(path)
}

fn slurm_script(suite_dir: &Path, options: &SlurmOptions) -> String {
    let throttle = options.throttle.map_or(String::new(), |t| format!("%{t}"));
    let mut lines = vec![
        "#!/bin/bash".to_string(),
        format!(
            "# Written by `rslam suite slurm`: {} array tasks, task i {} shard i of the suite",
            options.tasks,
            match options.task.subcommand() {
                "search" =>
                    "searches (`rslam suite search` without --shard writes the profile after)",
                "bench" => "benches (makes, runs, deletes the frames of)",
                _ => "makes",
            }
        ),
        format!(
            "# in {}. Submit with `sbatch {}`;",
            suite_dir.display(),
            suite_dir.join(SLURM_DIR).join(SCRIPT_FILE).display()
        ),
        format!(
            "# follow with `rslam suite status {}`. A task that stops is resumed by",
            suite_dir.display()
        ),
        "# submitting again: finished sequences and runs are kept, unfinished ones resume."
            .to_string(),
        "#SBATCH --job-name=rslam-suite".to_string(),
        format!("#SBATCH --array=0-{}{throttle}", options.tasks - 1),
        format!(
            "#SBATCH --output={}",
            suite_dir
                .join(SLURM_DIR)
                .join("logs")
                .join("%A_%a.out")
                .display()
        ),
    ];
    lines.extend(
        options
            .sbatch_args
            .iter()
            .map(|arg| format!("#SBATCH {arg}")),
    );
    lines.push("set -euo pipefail".into());
    let mut command = vec![
        shell_quote(&options.rslam.display().to_string()),
        "suite".into(),
        options.task.subcommand().into(),
        shell_quote(&suite_dir.display().to_string()),
    ];
    command.extend(options.task.run_arguments().iter().map(|a| shell_quote(a)));
    lines.push(format!("exec {}", command.join(" ")));
    lines.join("\n") + "\n"
}

fn absolute(path: &Path) -> Result<PathBuf, SuiteError> {
    path.canonicalize().map_err(|e| SuiteError::io(path, e))
}

/// `text` as one word for bash: unchanged when plain, else in single quotes.
fn shell_quote(text: &str) -> String {
    let plain = !text.is_empty()
        && text
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./=:,+@%".contains(c));
    if plain {
        text.to_string()
    } else {
        format!("'{}'", text.replace('\'', r"'\''"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_script_is_an_array_of_suite_runs() {
        let dir = tempfile::tempdir().unwrap();
        let options = SlurmOptions {
            tasks: 8,
            throttle: Some(2),
            sbatch_args: vec!["--gres=gpu:1".into(), "--time=04:00:00".into()],
            rslam: PathBuf::from("/opt/rslam it's/rslam"),
            task: TaskOptions {
                jobs: 2,
                adapter: Some("H100".into()),
                ephemeral: None,
            },
        };
        let path = write_slurm_script(dir.path(), &options).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let suite = dir.path().canonicalize().unwrap();
        assert!(text.starts_with("#!/bin/bash\n"));
        assert!(text.contains("\n#SBATCH --array=0-7%2\n"), "{text}");
        assert!(text.contains("\n#SBATCH --gres=gpu:1\n#SBATCH --time=04:00:00\n"));
        assert!(text.contains(&format!(
            "#SBATCH --output={}/slurm/logs/%A_%a.out",
            suite.display()
        )));
        assert!(
            suite.join("slurm/logs").is_dir(),
            "Slurm does not make the log folder"
        );
        let last = text.lines().last().unwrap();
        assert_eq!(
            last,
            format!(
                "exec '/opt/rslam it'\\''s/rslam' suite run {} --jobs 2 --adapter H100",
                suite.display()
            )
        );
    }

    #[test]
    fn with_method_files_each_task_benches_its_shard_ephemerally() {
        let dir = tempfile::tempdir().unwrap();
        let options = SlurmOptions {
            tasks: 2,
            throttle: None,
            sbatch_args: vec![],
            rslam: PathBuf::from("/usr/bin/rslam"),
            task: TaskOptions {
                jobs: 3,
                adapter: None,
                ephemeral: Some(super::super::EphemeralTask {
                    methods: vec!["/m/orb.toml".into(), "/m/dense.toml".into()],
                    scratch: Some("/local/scratch".into()),
                    search: None,
                }),
            },
        };
        let text =
            std::fs::read_to_string(write_slurm_script(dir.path(), &options).unwrap()).unwrap();
        assert_eq!(
            text.lines().last().unwrap(),
            format!(
                "exec /usr/bin/rslam suite bench {} --ephemeral --methods /m/orb.toml --methods /m/dense.toml --scratch /local/scratch --jobs 3",
                dir.path().canonicalize().unwrap().display()
            )
        );
    }

    #[test]
    fn a_search_runs_its_shard_of_the_searches_in_each_task() {
        let dir = tempfile::tempdir().unwrap();
        let search = ["--families", "fog,gaussian_noise", "--scenes", "room0"];
        let options = SlurmOptions {
            tasks: 4,
            throttle: None,
            sbatch_args: vec![],
            rslam: PathBuf::from("/usr/bin/rslam"),
            task: TaskOptions {
                jobs: 1,
                adapter: None,
                ephemeral: Some(super::super::EphemeralTask {
                    methods: vec!["/m/orb.toml".into()],
                    scratch: None,
                    search: Some(search.map(String::from).to_vec()),
                }),
            },
        };
        let text =
            std::fs::read_to_string(write_slurm_script(dir.path(), &options).unwrap()).unwrap();
        assert!(
            text.contains("without --shard writes the profile"),
            "{text}"
        );
        assert_eq!(
            text.lines().last().unwrap(),
            format!(
                "exec /usr/bin/rslam suite search {} --methods /m/orb.toml --families fog,gaussian_noise --scenes room0 --jobs 1",
                dir.path().canonicalize().unwrap().display()
            )
        );
    }

    #[test]
    fn zero_tasks_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let options = SlurmOptions {
            tasks: 0,
            throttle: None,
            sbatch_args: vec![],
            rslam: PathBuf::from("/usr/bin/rslam"),
            task: TaskOptions::default(),
        };
        assert!(write_slurm_script(dir.path(), &options)
            .unwrap_err()
            .to_string()
            .starts_with("--tasks"));
    }
}
