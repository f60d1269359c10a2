//! A suite folder: `suite.toml` resolved into sequences, each checked before any work starts.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use rslam_core::dataset::ros2::BagOptions;
use rslam_core::dataset::{DatasetFormat, DepthPng, Layout};
use rslam_core::limits::{MAX_POSES, MAX_SUITE_SEQUENCES};
use rslam_core::trajectory_io::ReadOptions;
use rslam_core::{read_text_file, Intrinsics};
use rslam_perturb::{PerturbError, PerturbSpec};
use rslam_pipeline::rig::{PRESET_NAMES, RIG_NAMES};
use rslam_pipeline::{JobPart, PipelineError, Rig, RigPreset, SceneCache, Sensors};

use crate::sequence::{sequence_seed, Sequence};
use crate::shard::Shard;
use crate::state::{inspect, SequenceState};
use crate::suite_file::{line_of, SequenceFields, SuiteFile, SUITE_FILE};
use crate::SuiteError;

/// The camera of a row that names none.
const DEFAULT_CAMERA: &str = "replica";

#[derive(Clone, Debug)]
pub struct Suite {
    /// The folder holding `suite.toml`; datasets go to `datasets/` inside it.
    pub dir: PathBuf,
    pub seed: u64,
    pub sequences: Vec<Sequence>,
}

impl Suite {
    /// Reads `dir/suite.toml` and checks every row.
    pub fn open(dir: &Path) -> Result<Self, SuiteError> {
        let path = dir.join(SUITE_FILE);
        if !path.is_file() {
            return Err(SuiteError::SuiteFile {
                path,
                line: 0,
                message:
                    "no such file: a suite folder holds suite.toml (`rslam suite init` writes one)"
                        .into(),
            });
        }
        let text = read_text_file(&path, "a suite in TOML")?;
        let file = SuiteFile::parse(&path, &text)?;
        let bad_row = |offset: usize, message: String| SuiteError::SuiteFile {
            path: path.clone(),
            line: line_of(&text, offset),
            message,
        };
        if file.defaults.name.is_some() || file.defaults.seed.is_some() {
            let at = text.find("[defaults]").unwrap_or(0);
            return Err(bad_row(
                at,
                "[defaults] may not set name or seed (they belong to one sequence)".into(),
            ));
        }
        if file.sequences.is_empty() {
            return Err(bad_row(0, "no [[sequence]] rows".into()));
        }
        if let Some(row) = file.sequences.get(MAX_SUITE_SEQUENCES) {
            return Err(bad_row(
                row.span().start,
                format!(
                    "more than {MAX_SUITE_SEQUENCES} [[sequence]] rows, the most a suite may hold"
                ),
            ));
        }
        let mut names = HashSet::new();
        let mut sequences = Vec::with_capacity(file.sequences.len());
        for row in &file.sequences {
            let at = row.span().start;
            let sequence = resolve(&row.get_ref().or(&file.defaults), file.seed, dir)
                .map_err(|message| bad_row(at, message))?;
            if !names.insert(sequence.name.clone()) {
                return Err(bad_row(
                    at,
                    format!("sequence '{}' is listed twice", sequence.name),
                ));
            }
            sequences.push(sequence);
        }
        Ok(Self {
            dir: dir.to_path_buf(),
            seed: file.seed,
            sequences,
        })
    }
}

impl Suite {
    /// The sequences of `shard` with what their folders hold, in suite order.
    pub fn shard_states(&self, shard: Shard) -> Vec<(&Sequence, SequenceState)> {
        // Each scene is loaded once for all its sequences.
        let scenes = SceneCache::default();
        self.sequences
            .iter()
            .filter(|s| shard.contains(&s.name))
            .map(|s| (s, inspect(s, &self.dir, &scenes)))
            .collect()
    }

    /// The rate at which Replica-layout ground truth (which has no timestamps) is stamped for
    /// evaluation: one rate for the whole suite, or an error naming two rows that differ.
    pub fn replica_rate_hz(&self) -> Result<f64, SuiteError> {
        let mut rates = self
            .sequences
            .iter()
            .filter(|s| s.layout() == Layout::Camera(DatasetFormat::Replica))
            .map(|s| (s.rate_hz, &s.name));
        let Some((rate, first)) = rates.next() else {
            return Ok(ReadOptions::DEFAULT_REPLICA_RATE_HZ);
        };
        match rates.find(|(r, _)| *r != rate) {
            None => Ok(rate),
            Some((other, name)) => Err(SuiteError::SuiteFile {
                path: self.dir.join(SUITE_FILE),
                line: 0,
                message: format!(
                    "Replica-layout sequences at {rate} Hz ({first}) and {other} Hz ({name}); a report reads one rate: make separate suites"
                ),
            }),
        }
    }
}

pub(crate) fn resolve(
    row: &SequenceFields,
    suite_seed: u64,
    dir: &Path,
) -> Result<Sequence, String> {
    let name = row.name.clone().ok_or("a sequence without a name")?;
    check_name(&name)?;
    let scene = row
        .scene
        .clone()
        .ok_or(format!("sequence '{name}': no scene"))?;
    let in_row = |what: String| format!("sequence '{name}': {what}");
    let spec = match row.perturb.as_deref().map(str::trim) {
        None | Some("") => PerturbSpec::default(),
        Some(text) => PerturbSpec::parse(text).map_err(|e| in_row(format!("perturb: {e}")))?,
    };
    let layout: Layout = row
        .format
        .as_deref()
        .unwrap_or("replica")
        .parse()
        .map_err(|e| in_row(format!("format: {e}")))?;
    let (sensors, camera, camera_text) = sensors(row, layout, &spec).map_err(in_row)?;
    let rate_hz = row.rate.unwrap_or_else(|| {
        Intrinsics::preset_rate_hz(row.camera.as_deref().unwrap_or(DEFAULT_CAMERA))
    });
    if !(rate_hz.is_finite() && rate_hz > 0.0) {
        return Err(in_row(format!(
            "rate {rate_hz}: expected a positive number of Hz"
        )));
    }
    if let Some(frames) = row.frames.filter(|f| !(1..=MAX_POSES).contains(f)) {
        return Err(in_row(format!(
            "frames = {frames}: expected 1 to {MAX_POSES} frames"
        )));
    }
    let is_builtin = rslam_render::builtin_path_length(&scene).is_some();
    if row.traj.is_none() && !is_builtin {
        let known = rslam_render::BUILTIN_SCENES.join(", ");
        if Path::new(&scene).extension().is_none_or(|e| e.is_empty()) {
            return Err(in_row(format!(
                "scene '{scene}': neither a built-in scene ({known}) nor a mesh file"
            )));
        }
        return Err(in_row(format!(
            "scene '{scene}' is a mesh file: give the row a traj (its camera path)"
        )));
    }
    let missing = |path: &Path| !dir.join(path).is_file();
    if !is_builtin && missing(Path::new(&scene)) {
        return Err(in_row(format!(
            "scene '{scene}': no such file (relative to the suite folder)"
        )));
    }
    if let Some(traj) = row.traj.as_deref().filter(|t| missing(t)) {
        return Err(in_row(format!(
            "traj '{}': no such file (relative to the suite folder)",
            traj.display()
        )));
    }
    Ok(Sequence {
        seed: row.seed.unwrap_or_else(|| sequence_seed(suite_seed, &name)),
        name,
        scene,
        spec,
        frames: row.frames,
        sensors,
        camera,
        camera_text,
        rate_hz,
        traj: row.traj.clone(),
    })
}

/// One camera (`camera`, `depth_png`) in a core layout, that camera with an IMU (`rig =
/// "rgbd-imu"`, TUM), or a `rig` in EuRoC's, with the camera (a rig's cam0) and the camera as
/// written; the row's spec checked against them.
fn sensors(
    row: &SequenceFields,
    layout: Layout,
    spec: &PerturbSpec,
) -> Result<(Sensors, Intrinsics, Option<String>), String> {
    let preset = match row.rig.as_deref() {
        None | Some("rgbd") => RigPreset::Rgbd,
        Some("rgbd-imu") => RigPreset::RgbdImu,
        Some(name) => RigPreset::Euroc(Rig::preset(name).map_err(|_| {
            format!(
                "rig '{}': expected one of {}",
                rslam_core::printable(name),
                PRESET_NAMES.join(", ")
            )
        })?),
    };
    if let RigPreset::Euroc(_) = preset {
        let given = [
            ("camera", row.camera.is_some()),
            ("depth_png", row.depth_png.is_some()),
        ];
        if let Some((key, _)) = given.iter().find(|(_, given)| *given) {
            return Err(format!(
                "{key}: a rig has its own cameras (without depth); leave {key} out of its rows and [defaults]"
            ));
        }
    }
    let depth_png = match row.depth_png.as_deref() {
        None => DepthPng::default(),
        Some(text) => text.parse().map_err(|e| format!("depth_png: {e}"))?,
    };
    let sensors = Sensors::new(preset, layout, depth_png, bag_options(row)?).map_err(worded)?;
    sensors.check_spec(spec).map_err(worded)?;
    if let Sensors::Rig(rig, ..) = &sensors {
        let cam0 = rig
            .cameras
            .first()
            .ok_or("the rig has no camera")?
            .intrinsics;
        return Ok((sensors, cam0, None));
    }
    let camera_text = row.camera.clone().unwrap_or_else(|| DEFAULT_CAMERA.into());
    let camera = Intrinsics::parse(&camera_text).map_err(|e| format!("camera: {e}"))?;
    Ok((sensors, camera, Some(camera_text)))
}

/// The row's bag options (`bag_depth`, `bag_tf`, `bag_compression`), defaults where left out.
fn bag_options(row: &SequenceFields) -> Result<BagOptions, String> {
    let mut options = BagOptions::default();
    if let Some(text) = &row.bag_depth {
        options.depth = text.parse().map_err(|e| format!("bag_depth: {e}"))?;
    }
    if let Some(text) = &row.bag_compression {
        options.compression = text.parse().map_err(|e| format!("bag_compression: {e}"))?;
    }
    options.tf = row.bag_tf.unwrap_or_default();
    Ok(options)
}

/// A library error in the words of `suite.toml`: the key of the row that sets the part of the
/// job it names.
fn worded(error: PipelineError) -> String {
    match error {
        PipelineError::Option { part, message } => {
            let key = match part {
                JobPart::Spec => "perturb",
                JobPart::Trajectory => "traj",
                JobPart::Bag => "bag_depth/bag_tf/bag_compression",
                _ => return format!("{part}: {message}"),
            };
            format!("{key}: {message}")
        }
        PipelineError::RigLayout { rig, layout } => match (rig.as_str(), layout) {
            (_, Layout::Euroc) => format!(
                "format euroc: needs rig = one of {} (the EuRoC layout is for rigs)",
                RIG_NAMES.join(", ")
            ),
            ("rgbd-imu", _) => format!(
                "rig rgbd-imu: needs format = \"tum\" (the TUM layout with imu0/ beside it), not {layout}"
            ),
            _ => format!(
                "rig: needs format = \"euroc\" (a stereo rig is written in the EuRoC layout), not {layout}; with {layout}, rig = \"rgbd\" or (tum) \"rgbd-imu\""
            ),
        },
        PipelineError::Perturb(PerturbError::Spec { item, message }) => {
            format!("perturb item '{item}': {message}")
        }
        other => other.to_string(),
    }
}

/// `<scene>__<setting>`, usable as a folder name on every file system.
fn check_name(name: &str) -> Result<(), String> {
    let allowed = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.');
    let well_formed = name
        .split_once("__")
        .is_some_and(|(scene, setting)| !scene.is_empty() && !setting.is_empty());
    if !well_formed || !name.chars().all(allowed) || name.starts_with('.') {
        return Err(format!(
            "sequence name '{name}': expected <scene>__<setting> of letters, digits, '_', '-' and '.' (e.g. room0__fog-3)"
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn open(text: &str) -> Result<Suite, SuiteError> {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join(SUITE_FILE), text).unwrap();
        Suite::open(dir.path())
    }

    #[test]
    fn rows_take_defaults_and_a_seed_of_their_own_name() {
        let two = "seed = 7\n[defaults]\nframes = 10\nformat = \"tum\"\ncamera = \"tum\"\n\
                   [[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\n\
                   [[sequence]]\nname = \"room0__b\"\nscene = \"room0\"\nframes = 3\nseed = 99\nperturb = \"fog:2\"\n";
        let suite = open(two).unwrap();
        let (a, b) = (&suite.sequences[0], &suite.sequences[1]);
        assert_eq!(
            (a.frames, a.layout(), a.rate_hz),
            (Some(10), Layout::Camera(DatasetFormat::Tum), 30.0)
        );
        assert_eq!(
            (b.frames, b.seed, b.spec.to_string()),
            (Some(3), 99, "fog:2".to_string())
        );
        assert_eq!(a.seed, sequence_seed(7, "room0__a"));
        let reordered = "seed = 7\n[[sequence]]\nname = \"room0__z\"\nscene = \"room0\"\n\
                         [[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\n";
        let reordered = open(reordered).unwrap();
        assert_eq!(
            reordered.sequences[1].seed, a.seed,
            "a row's seed depends on its name alone"
        );
        assert_ne!(reordered.sequences[0].seed, a.seed);
    }

    #[test]
    fn the_command_a_sequence_records_is_the_render_that_makes_it() {
        let suite = open(
            "[[sequence]]\nname = \"room0__fog-3\"\nscene = \"room0\"\nframes = 5\nseed = 4\nperturb = \"fog:3\"\n",
        )
        .unwrap();
        assert_eq!(
            suite.sequences[0].command().join(" "),
            "rslam render --scene room0 --frames 5 --camera replica --rate 20 --format replica \
             --seed 4 --perturb fog:3 --out datasets/room0__fog-3"
        );
    }

    #[test]
    fn bag_options_are_part_of_a_ros2_rows_command_and_refused_elsewhere() {
        let suite = open("[defaults]\nformat = \"ros2\"\nbag_depth = \"32FC1\"\nbag_tf = true\n[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\nseed = 1\nbag_compression = \"zstd\"\n").unwrap();
        let command = suite.sequences[0].command().join(" ");
        assert!(
            command.contains(
                "--format ros2 --bag-depth 32FC1 --bag-tf --bag-compression zstd --seed 1"
            ),
            "{command}"
        );
        let Sensors::Camera { bag, .. } = &suite.sequences[0].sensors else {
            panic!("one camera");
        };
        assert_eq!(
            bag.compression,
            rslam_core::dataset::ros2::BagCompression::Zstd
        );
        let err = open("[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\nbag_tf = true\n")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("suite.toml:1: sequence 'room0__a': bag_depth/bag_tf/bag_compression: applies to a ROS 2 bag, not the replica layout"),
            "{err}"
        );
        let err = open("[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\nformat = \"ros2\"\nbag_depth = \"16uc1\"\n")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("bag_depth: unknown bag depth encoding '16uc1'"),
            "{err}"
        );
    }

    #[test]
    fn small_depth_pngs_are_part_of_the_command() {
        let suite = open("[defaults]\ndepth_png = \"small\"\n[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\nseed = 1\n").unwrap();
        assert!(suite.sequences[0]
            .command()
            .join(" ")
            .contains("--format replica --depth-png small --seed 1"));
        let err =
            open("[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\ndepth_png = \"tiny\"\n")
                .unwrap_err();
        assert!(
            err.to_string()
                .contains("suite.toml:1: sequence 'room0__a': depth_png"),
            "{err}"
        );
    }

    #[test]
    fn an_rgbd_imu_row_is_the_rgbd_imu_render_in_the_tum_layout() {
        let row = |keys: &str| {
            open(&format!(
                "[[sequence]]\nname = \"room0__imu\"\nscene = \"room0\"\nframes = 400\nseed = 2\ncamera = \"tum\"\n{keys}"
            ))
        };
        let suite =
            row("format = \"tum\"\nrig = \"rgbd-imu\"\nperturb = \"fog:3,imu_noise:2\"\n").unwrap();
        let sequence = &suite.sequences[0];
        assert_eq!(sequence.layout(), Layout::Camera(DatasetFormat::Tum));
        assert_eq!(
            sequence.command().join(" "),
            "rslam render --scene room0 --frames 400 --rig rgbd-imu --camera tum --rate 30 \
             --format tum --seed 2 --perturb fog:3,imu_noise:2 --out datasets/room0__imu"
        );
        // 400 poses at 30 Hz: 397 frames up to the IMU's last sample
        let counts = sequence.frame_counts(Path::new(".")).unwrap();
        assert_eq!((counts.rendered, counts.written), (397, 397));
        let plain = row("format = \"tum\"\nrig = \"rgbd\"\n").unwrap();
        assert!(!plain.sequences[0].command().contains(&"--rig".to_string()));
        for (keys, expected) in [
            ("format = \"replica\"\nrig = \"rgbd-imu\"\n", "rig rgbd-imu: needs format = \"tum\""),
            (
                "format = \"tum\"\nrig = \"rgbd-imu\"\nperturb = \"distortion:equidistant(0.1,0,0,0)\"\n",
                "perturb item 'distortion:equidistant",
            ),
        ] {
            let err = row(keys).unwrap_err().to_string();
            assert!(err.contains(&format!("suite.toml:1: sequence 'room0__imu': {expected}")), "{keys}: {err}");
        }
    }

    #[test]
    fn a_rig_row_is_the_rig_render_in_the_euroc_layout() {
        let suite = open(
            "[[sequence]]\nname = \"room0__stereo\"\nscene = \"room0\"\nframes = 400\nseed = 2\n\
             format = \"euroc\"\nrig = \"stereo-imu\"\nperturb = \"fog:3\"\n",
        )
        .unwrap();
        let sequence = &suite.sequences[0];
        assert_eq!(sequence.layout(), Layout::Euroc);
        assert_eq!(
            sequence.command().join(" "),
            "rslam render --scene room0 --frames 400 --rig stereo-imu --rate 20 --format euroc \
             --seed 2 --perturb fog:3 --out datasets/room0__stereo"
        );
        assert_eq!(sequence.camera.width, 752);
        // both cameras' frames: 398 each from 400 poses at 20 Hz
        let counts = sequence.frame_counts(Path::new(".")).unwrap();
        assert_eq!((counts.rendered, counts.written), (796, 796));
    }

    #[test]
    fn a_rig_row_needs_the_euroc_layout_and_nothing_of_one_camera() {
        let row = |keys: &str| {
            let text = format!("[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\n{keys}");
            open(&text).unwrap_err().to_string()
        };
        for (keys, expected) in [
            (
                "format = \"euroc\"\n",
                "sequence 'room0__a': format euroc: needs rig = one of stereo, stereo-imu",
            ),
            (
                "rig = \"stereo\"\nformat = \"tum\"\n",
                "sequence 'room0__a': rig: needs format = \"euroc\"",
            ),
            (
                "format = \"euroc\"\nrig = \"trinocular\"\n",
                "sequence 'room0__a': rig 'trinocular': expected one of rgbd, rgbd-imu, stereo, stereo-imu",
            ),
            (
                "format = \"euroc\"\nrig = \"stereo\"\ncamera = \"tum\"\n",
                "sequence 'room0__a': camera: a rig has its own cameras",
            ),
            (
                "format = \"euroc\"\nrig = \"stereo\"\ndepth_png = \"small\"\n",
                "sequence 'room0__a': depth_png: a rig has its own cameras",
            ),
            (
                "format = \"euroc\"\nrig = \"stereo\"\nperturb = \"misalign:2\"\n",
                "sequence 'room0__a': perturb item 'misalign:2': misalign delays depth against colour, and the 'stereo' rig's cameras have no depth stream",
            ),
        ] {
            let err = row(keys);
            assert!(
                err.contains(&format!("suite.toml:1: {expected}")),
                "{keys}: {err}"
            );
        }
    }

    #[test]
    fn defaults_may_not_name_a_sequence() {
        let err = open(
            "[defaults]\nname = \"x__y\"\n[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\n",
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("suite.toml:1: [defaults] may not set name"),
            "{err}"
        );
    }

    /// A sequence name is the folder under datasets/ that rslam writes (and, with --force,
    /// clears): nothing that climbs out, starts at the root or names a subfolder passes.
    #[test]
    fn sequence_names_that_would_leave_datasets_are_refused() {
        for name in [
            "../room0__x",
            "room0__../../x",
            "/tmp/room0__x",
            "room0__a/b",
            "..__x",
            ".hidden__x",
            "room0__x\\y",
            "room0__",
        ] {
            let text = format!("[[sequence]]\nname = {name:?}\nscene = \"room0\"\n");
            let err = open(&text).unwrap_err().to_string();
            assert!(
                err.contains("suite.toml:1: sequence name")
                    && err.contains("expected <scene>__<setting>"),
                "{name}: {err}"
            );
        }
    }

    #[test]
    fn suite_limits_are_errors_naming_the_row() {
        let rows = "[[sequence]]\nname = \"room0__a\"\nscene = \"room0\"\nframes = 20000000\n";
        let err = open(rows).unwrap_err().to_string();
        assert!(
            err.contains("suite.toml:1: sequence 'room0__a': frames = 20000000: expected 1 to 10000000 frames"),
            "{err}"
        );
    }
}
