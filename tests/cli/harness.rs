//! A tiny harness: a temp dir, a command builder, and output that reads well on failure.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub struct Workspace {
    dir: tempfile::TempDir,
}

impl Workspace {
    pub fn new() -> Self {
        Self {
            dir: tempfile::tempdir().expect("temp dir"),
        }
    }

    pub fn path(&self, rel: &str) -> PathBuf {
        self.dir.path().join(rel)
    }

    pub fn write(&self, rel: &str, contents: &str) -> PathBuf {
        let p = self.path(rel);
        if let Some(parent) = p.parent() {
            std::fs::create_dir_all(parent).expect("mkdir");
        }
        std::fs::write(&p, contents).expect("write fixture");
        p
    }

    /// `rslam render --scene room0 --out OUT ARGS [--perturb SPEC]`, which must succeed.
    pub fn render_room0(&self, out: &str, args: &[&str], spec: Option<&str>) {
        let mut all = vec!["render", "--scene", "room0", "--out", out];
        all.extend(args);
        all.extend(spec.iter().flat_map(|s| ["--perturb", s]));
        self.rslam(&all).success();
    }

    /// Runs `rslam ARGS` inside the workspace.
    pub fn rslam(&self, args: &[&str]) -> Run {
        let output = Command::new(env!("CARGO_BIN_EXE_rslam"))
            .args(args)
            .current_dir(self.dir.path())
            .output()
            .expect("spawn rslam");
        Run {
            args: args.join(" "),
            output,
        }
    }
}

impl Workspace {
    /// Starts `rslam ARGS` inside the workspace without waiting, its stderr thrown away (to be
    /// killed part-way).
    pub fn spawn_rslam(&self, args: &[&str]) -> std::process::Child {
        Command::new(env!("CARGO_BIN_EXE_rslam"))
            .args(args)
            .current_dir(self.dir.path())
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("spawn rslam")
    }
}

pub struct Run {
    args: String,
    pub output: Output,
}

impl Run {
    pub fn stdout(&self) -> String {
        String::from_utf8_lossy(&self.output.stdout).into_owned()
    }

    pub fn stderr(&self) -> String {
        String::from_utf8_lossy(&self.output.stderr).into_owned()
    }

    fn describe(&self) -> String {
        format!(
            "rslam {}\n--- exit: {:?}\n--- stdout:\n{}\n--- stderr:\n{}",
            self.args,
            self.output.status.code(),
            self.stdout(),
            self.stderr()
        )
    }

    /// Asserts exit 0 and returns stdout.
    pub fn success(&self) -> String {
        assert!(
            self.output.status.success(),
            "expected success:\n{}",
            self.describe()
        );
        self.stdout()
    }

    /// Asserts the given exit code and that stderr contains every fragment; returns stderr.
    pub fn fails_with(&self, code: i32, fragments: &[&str]) -> String {
        assert_eq!(self.output.status.code(), Some(code), "{}", self.describe());
        let err = self.stderr();
        for f in fragments {
            assert!(err.contains(f), "stderr lacks '{f}':\n{}", self.describe());
        }
        assert!(
            !err.contains("panicked"),
            "panic instead of an error:\n{}",
            self.describe()
        );
        err
    }
}

/// The names of the entries of `dir`, sorted.
pub fn sorted_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}
