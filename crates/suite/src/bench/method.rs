//! Method files: how to run one SLAM method on one sequence.
//!
//! ```toml
//! name = "opencv_rgbd"              # its folder under runs/
//! reads = "replica"                 # the dataset layout it reads: replica | tum | euroc
//! command = ["python3", "{method_dir}/odometry.py", "{dataset}", "{estimate}"]
//! timeout_s = 900                   # per run
//! repeats = 3                       # runs per sequence (default 1)
//! mesh = "{work}/mesh.ply"          # optional: the reconstruction it writes
//! renders = "{work}/renders"        # optional: its map rendered at the ground-truth poses
//! ```
//!
//! `renders` is a folder of frames named as the dataset's are (`results/frame000010.png` and
//! `results/depth000010.png`, or `rgb/<t>.png` and `depth/<t>.png`), each the map's view at that
//! frame's ground-truth pose, for any subset of the frames, colour and/or depth.
//!
//! Each argument may hold placeholders, replaced per run: `{dataset}` the dataset folder,
//! `{estimate}` the TUM trajectory to write, `{camera}` the layout's camera file
//! (`cam_params.json`, `orbslam3.yaml` or `orbslam3_stereo.yaml`), `{sequence}`, `{repeat}` (0-based), `{log}`,
//! `{work}` an empty scratch folder, `{method_dir}` the method file's folder; `{{` and `}}` are
//! literal braces. The command runs as a list, without a shell (write `sh -c` for one).

use std::path::{Path, PathBuf};

use rslam_core::dataset::Layout;
use rslam_core::limits::MAX_REPEATS;
use rslam_core::read_text_file;
use serde::Deserialize;

use crate::suite_file::line_of;
use crate::SuiteError;

pub const PLACEHOLDERS: [&str; 8] = [
    "dataset",
    "estimate",
    "camera",
    "sequence",
    "repeat",
    "log",
    "work",
    "method_dir",
];

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MethodFile {
    name: String,
    reads: String,
    command: Vec<String>,
    timeout_s: f64,
    #[serde(default = "one")]
    repeats: usize,
    mesh: Option<String>,
    renders: Option<String>,
}

fn one() -> usize {
    1
}

#[derive(Clone, Debug, PartialEq)]
pub struct Method {
    pub name: String,
    pub reads: Layout,
    pub command: Vec<String>,
    pub timeout_s: f64,
    pub repeats: usize,
    pub mesh: Option<String>,
    /// The folder of its rendered views (see the module's documentation).
    pub renders: Option<String>,
    /// The folder of the method file (`{method_dir}`).
    pub dir: PathBuf,
}

/// The values of one run's placeholders.
pub struct RunPlaces<'a> {
    pub dataset: &'a Path,
    pub estimate: &'a Path,
    pub camera: &'a Path,
    pub sequence: &'a str,
    pub repeat: usize,
    pub log: &'a Path,
    pub work: &'a Path,
}

impl Method {
    pub fn read(path: &Path) -> Result<Self, SuiteError> {
        let text = read_text_file(path, "a method in TOML")?;
        let bad = |line: usize, message: String| SuiteError::SuiteFile {
            path: path.to_path_buf(),
            line,
            message,
        };
        let file: MethodFile = toml::from_str(&text).map_err(|e| {
            bad(
                e.span().map_or(0, |s| line_of(&text, s.start)),
                e.message().trim_end().replace('\n', "; "),
            )
        })?;
        let line_with = |key: &str| {
            text.lines()
                .position(|l| l.trim_start().starts_with(key))
                .map_or(0, |i| i + 1)
        };
        let name_ok = !file.name.is_empty()
            && !file.name.starts_with('.')
            && file
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "_-.".contains(c));
        if !name_ok {
            return Err(bad(
                line_with("name"),
                format!(
                    "name '{}': expected letters, digits, '_', '-', '.' (a folder name)",
                    file.name
                ),
            ));
        }
        let reads = file
            .reads
            .parse()
            .map_err(|e| bad(line_with("reads"), format!("reads: {e}")))?;
        if file.command.is_empty() {
            return Err(bad(
                line_with("command"),
                "command is empty: expected [program, arguments...]".into(),
            ));
        }
        for argument in &file.command {
            check_placeholders(argument).map_err(|m| bad(line_with("command"), m))?;
        }
        for (key, value) in [("mesh", &file.mesh), ("renders", &file.renders)] {
            if let Some(value) = value {
                check_placeholders(value).map_err(|m| bad(line_with(key), m))?;
            }
        }
        if !(file.timeout_s.is_finite() && file.timeout_s > 0.0) {
            return Err(bad(
                line_with("timeout_s"),
                format!(
                    "timeout_s {}: expected a positive number of seconds",
                    file.timeout_s
                ),
            ));
        }
        if !(1..=MAX_REPEATS).contains(&file.repeats) {
            return Err(bad(
                line_with("repeats"),
                format!(
                    "repeats = {}: expected 1 to {MAX_REPEATS} runs per sequence",
                    file.repeats
                ),
            ));
        }
        let dir = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
            .canonicalize()
            .map_err(|e| SuiteError::io(path, e))?;
        Ok(Self {
            name: file.name,
            reads,
            command: file.command,
            timeout_s: file.timeout_s,
            repeats: file.repeats,
            mesh: file.mesh,
            renders: file.renders,
            dir,
        })
    }

    /// The command of one run, every placeholder replaced.
    pub fn command_for(&self, places: &RunPlaces) -> Vec<String> {
        self.command.iter().map(|a| self.fill(a, places)).collect()
    }

    /// Where this run's reconstruction will be, if the method writes one.
    pub fn mesh_for(&self, places: &RunPlaces) -> Option<PathBuf> {
        self.mesh
            .as_ref()
            .map(|m| PathBuf::from(self.fill(m, places)))
    }

    /// Where this run's rendered views will be, if the method renders its map.
    pub fn renders_for(&self, places: &RunPlaces) -> Option<PathBuf> {
        self.renders
            .as_ref()
            .map(|r| PathBuf::from(self.fill(r, places)))
    }

    fn fill(&self, template: &str, places: &RunPlaces) -> String {
        let value = |name: &str| -> String {
            match name {
                "dataset" => places.dataset.display().to_string(),
                "estimate" => places.estimate.display().to_string(),
                "camera" => places.camera.display().to_string(),
                "sequence" => places.sequence.to_string(),
                "repeat" => places.repeat.to_string(),
                "log" => places.log.display().to_string(),
                "work" => places.work.display().to_string(),
                _ => self.dir.display().to_string(),
            }
        };
        pieces(template)
            .into_iter()
            .map(|piece| match piece {
                Piece::Text(text) => text.to_string(),
                Piece::Brace(c) => c.to_string(),
                Piece::Placeholder(name) => value(name),
            })
            .collect()
    }
}

enum Piece<'a> {
    Text(&'a str),
    Brace(char),
    Placeholder(&'a str),
}

/// Splits a template into text, `{{`/`}}` escapes and `{name}` placeholders; a lone brace
/// comes back as text for [`check_placeholders`] to reject.
fn pieces(template: &str) -> Vec<Piece<'_>> {
    let mut out = Vec::new();
    let mut rest = template;
    while let Some(i) = rest.find(['{', '}']) {
        out.push(Piece::Text(&rest[..i]));
        let tail = &rest[i..];
        if tail.starts_with("{{") || tail.starts_with("}}") {
            out.push(Piece::Brace(tail.as_bytes()[0] as char));
            rest = &tail[2..];
        } else if let (true, Some(end)) = (tail.starts_with('{'), tail.find('}')) {
            out.push(Piece::Placeholder(&tail[1..end]));
            rest = &tail[end + 1..];
        } else {
            out.push(Piece::Text(&tail[..1]));
            rest = &tail[1..];
        }
    }
    out.push(Piece::Text(rest));
    out
}

fn check_placeholders(template: &str) -> Result<(), String> {
    for piece in pieces(template) {
        match piece {
            Piece::Placeholder(name) if !PLACEHOLDERS.contains(&name) => {
                return Err(format!(
                    "'{template}': unknown placeholder {{{name}}}; expected one of {} (write {{{{ for a literal brace)",
                    PLACEHOLDERS.map(|p| format!("{{{p}}}")).join(" ")
                ))
            }
            Piece::Text(t) if t == "{" || t == "}" => {
                return Err(format!("'{template}': a lone '{t}'; write {{{{ or }}}} for a literal brace"))
            }
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn method(text: &str) -> Result<Method, SuiteError> {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.toml");
        std::fs::write(&path, text).unwrap();
        Method::read(&path)
    }

    #[test]
    fn placeholders_are_filled_per_run_and_braces_escape() {
        let m = method(
            "name = \"vo\"\nreads = \"tum\"\ncommand = [\"run\", \"--in={dataset}\", \"{estimate}\", \"{{x}}\", \"{sequence}#{repeat}\", \"{method_dir}/a\"]\ntimeout_s = 5\nmesh = \"{work}/m.ply\"\n",
        )
        .unwrap();
        let places = RunPlaces {
            dataset: Path::new("/s/datasets/room0__clean"),
            estimate: Path::new("/w/est.txt"),
            camera: Path::new("/s/datasets/room0__clean/orbslam3.yaml"),
            sequence: "room0__clean",
            repeat: 2,
            log: Path::new("/r/2.log"),
            work: Path::new("/w"),
        };
        let command = m.command_for(&places);
        assert_eq!(
            command[..5],
            [
                "run",
                "--in=/s/datasets/room0__clean",
                "/w/est.txt",
                "{x}",
                "room0__clean#2"
            ]
        );
        assert!(command[5].ends_with("/a") && command[5].starts_with('/'));
        assert_eq!(m.mesh_for(&places), Some(PathBuf::from("/w/m.ply")));
        assert_eq!(
            (m.repeats, m.reads),
            (1, Layout::Camera(rslam_core::dataset::DatasetFormat::Tum))
        );
    }

    #[test]
    fn a_method_may_read_the_euroc_layout() {
        let m = method(
            "name = \"s\"\nreads = \"euroc\"\ncommand = [\"run\", \"{camera}\"]\ntimeout_s = 5\n",
        )
        .unwrap();
        assert_eq!(m.reads, Layout::Euroc);
    }

    #[test]
    fn bad_method_files_name_the_line_and_the_problem() {
        let cases = [
            (
                "name = \"a\"\nreads = \"tum\"\ncommand = [\"x\", \"{datset}\"]\ntimeout_s = 1\n",
                ":3",
                "unknown placeholder {datset}",
            ),
            (
                "name = \"a\"\nreads = \"kitti\"\ncommand = [\"x\"]\ntimeout_s = 1\n",
                ":2",
                "reads: unknown dataset layout 'kitti': expected replica, tum, ros2 or euroc",
            ),
            (
                "name = \"a\"\nreads = \"tum\"\ncommand = []\ntimeout_s = 1\n",
                ":3",
                "command is empty",
            ),
            (
                "name = \"a\"\nreads = \"tum\"\ncommand = [\"x\"]\ntimeout_s = 0\n",
                ":4",
                "timeout_s 0",
            ),
            (
                "name = \"a/b\"\nreads = \"tum\"\ncommand = [\"x\"]\ntimeout_s = 1\n",
                ":1",
                "name 'a/b'",
            ),
            (
                "name = \"../../etc\"\nreads = \"tum\"\ncommand = [\"x\"]\ntimeout_s = 1\n",
                ":1",
                "name '../../etc': expected letters, digits",
            ),
            (
                "name = \"/abs\"\nreads = \"tum\"\ncommand = [\"x\"]\ntimeout_s = 1\n",
                ":1",
                "name '/abs'",
            ),
            (
                "name = \"..\"\nreads = \"tum\"\ncommand = [\"x\"]\ntimeout_s = 1\n",
                ":1",
                "name '..'",
            ),
            (
                "name = \"a\"\nreads = \"tum\"\ncommand = [\"x\"]\ntimeout_s = 1\nrepeats = 1000000\n",
                ":5",
                "repeats = 1000000: expected 1 to 1000 runs per sequence",
            ),
            (
                "name = \"a\"\nreads = \"tum\"\ncommand = [\"x {\"]\ntimeout_s = 1\n",
                ":3",
                "a lone '{'",
            ),
            (
                "name = \"a\"\nreads = \"tum\"\ncommand = [\"x\"]\ntimeout = 1\n",
                ":4",
                "unknown field `timeout`",
            ),
        ];
        for (text, line, fragment) in cases {
            let err = method(text).unwrap_err().to_string();
            assert!(
                err.contains(&format!("m.toml{line}:")) && err.contains(fragment),
                "{err}"
            );
        }
    }
}
