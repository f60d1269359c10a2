//! The suites `rslam suite init` writes: the paper's matrix (docs/src/perturbations.md §7) and a small one
//! for smoke runs.

use std::fmt;
use std::str::FromStr;

use rslam_core::dataset::{DatasetFormat, DepthPng};
use rslam_perturb::PerturbSpec;

use crate::suite_file::{SequenceFields, SuiteFile};

/// The 16 RGB corruptions of the benchmark (the catalogue's other image entries are extras).
pub const BENCHMARK_RGB: [&str; 16] = [
    "gaussian_noise",
    "shot_noise",
    "impulse_noise",
    "speckle_noise",
    "gaussian_blur",
    "glass_blur",
    "defocus_blur",
    "motion_blur",
    "snow",
    "frost",
    "fog",
    "spatter",
    "brightness",
    "contrast",
    "jpeg_compression",
    "pixelate",
];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// 125 settings per scene over the eight built-in scenes: 1,000 sequences.
    RobustSlam,
    /// One setting of each kind on room0, 200 frames: a smoke run in minutes.
    Mini,
}

/// A column of the matrix: the folder suffix after `<scene>__` and the `--perturb` spec.
#[derive(Clone, Debug, PartialEq)]
pub struct Setting {
    pub name: String,
    pub spec: String,
}

/// What `rslam suite init` was asked for.
#[derive(Clone, Debug)]
pub struct InitOptions {
    pub preset: Preset,
    /// `None`: the preset's scenes.
    pub scenes: Option<Vec<String>>,
    /// `None`: the preset's frame count (all poses for robust-slam).
    pub frames: Option<usize>,
    pub format: DatasetFormat,
    pub depth_png: DepthPng,
    pub seed: u64,
}

impl Preset {
    pub fn settings(self) -> Vec<Setting> {
        match self {
            Self::RobustSlam => robust_slam_settings(),
            Self::Mini => [
                ("clean", ""),
                ("gaussian_noise-5", "gaussian_noise:5"),
                ("motion_blur-3-dynamic", "motion_blur:3@dynamic"),
                ("depth_noise-5", "depth_noise:5"),
                ("fast-4", "fast:4"),
                ("rot-1-trans-0.025", "rot:1,trans:0.025"),
                ("misalign-10", "misalign:10"),
            ]
            .map(|(name, spec)| setting(name, spec))
            .to_vec(),
        }
    }

    pub fn scenes(self) -> Vec<String> {
        match self {
            Self::RobustSlam => rslam_render::BUILTIN_SCENES.map(String::from).to_vec(),
            Self::Mini => vec!["room0".to_string()],
        }
    }

    fn frames(self) -> Option<usize> {
        match self {
            Self::RobustSlam => None,
            Self::Mini => Some(200),
        }
    }
}

impl FromStr for Preset {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "robust-slam" => Ok(Self::RobustSlam),
            "mini" => Ok(Self::Mini),
            _ => Err(format!(
                "unknown preset '{s}': expected robust-slam or mini"
            )),
        }
    }
}

impl fmt::Display for Preset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::RobustSlam => "robust-slam",
            Self::Mini => "mini",
        })
    }
}

/// The suite file of `options`: every setting on every scene, scene by scene.
pub fn init_suite(options: &InitOptions) -> SuiteFile {
    let scenes = options
        .scenes
        .clone()
        .unwrap_or_else(|| options.preset.scenes());
    let settings = options.preset.settings();
    let sequences = scenes
        .iter()
        .flat_map(|scene| {
            settings.iter().map(move |s| SequenceFields {
                name: Some(format!("{scene}__{}", s.name)),
                scene: Some(scene.clone()),
                perturb: (!s.spec.is_empty()).then(|| s.spec.clone()),
                ..SequenceFields::default()
            })
        })
        .map(|row| toml::Spanned::new(0..0, row))
        .collect();
    SuiteFile {
        seed: options.seed,
        defaults: SequenceFields {
            frames: options.frames.or(options.preset.frames()),
            format: Some(options.format.to_string()),
            camera: Some(camera_of(options.format).to_string()),
            depth_png: (options.depth_png != DepthPng::default())
                .then(|| options.depth_png.to_string()),
            ..SequenceFields::default()
        },
        sequences,
    }
}

/// The camera a layout's consumers expect: Replica's for the Replica layout, TUM's for TUM; a
/// bag carries the camera it was rendered with, Replica's by default.
fn camera_of(format: DatasetFormat) -> &'static str {
    match format {
        DatasetFormat::Replica | DatasetFormat::Ros2 => "replica",
        DatasetFormat::Tum => "tum",
    }
}

fn setting(name: &str, spec: &str) -> Setting {
    Setting {
        name: name.to_string(),
        spec: spec.to_string(),
    }
}

/// docs/src/perturbations.md §7: clean; 16 RGB × {1,3,5} × {static, dynamic}; 4 depth settings;
/// fast ∈ {2,4,8}; rot {0,1,3,5} × trans {0,0.0125,0.025,0.05} without (0,0); misalign
/// {5,10,20} × {static, dynamic}. 125 in all.
fn robust_slam_settings() -> Vec<Setting> {
    let mut settings = vec![setting("clean", "")];
    for name in BENCHMARK_RGB {
        for severity in [1, 3, 5] {
            settings.push(setting(
                &format!("{name}-{severity}"),
                &format!("{name}:{severity}"),
            ));
            settings.push(setting(
                &format!("{name}-{severity}-dynamic"),
                &format!("{name}:{severity}@dynamic"),
            ));
        }
    }
    for (name, spec) in [
        ("depth_noise-1", "depth_noise:1"),
        ("depth_edge_erosion-1", "depth_edge_erosion:1"),
        ("depth_missing-5", "depth_missing:5"),
        ("depth_range-0.42-10", "depth_range:0.42-10"),
    ] {
        settings.push(setting(name, spec));
    }
    for k in [2, 4, 8] {
        settings.push(setting(&format!("fast-{k}"), &format!("fast:{k}")));
    }
    for rot in ["0", "1", "3", "5"] {
        for trans in ["0", "0.0125", "0.025", "0.05"] {
            let parts: Vec<(&str, &str)> = [("rot", rot), ("trans", trans)]
                .into_iter()
                .filter(|(_, v)| *v != "0")
                .collect();
            if parts.is_empty() {
                continue;
            }
            let name: Vec<String> = parts.iter().map(|(k, v)| format!("{k}-{v}")).collect();
            let spec: Vec<String> = parts.iter().map(|(k, v)| format!("{k}:{v}")).collect();
            settings.push(setting(&name.join("-"), &spec.join(",")));
        }
    }
    for frames in [5, 10, 20] {
        settings.push(setting(
            &format!("misalign-{frames}"),
            &format!("misalign:{frames}"),
        ));
        settings.push(setting(
            &format!("misalign-{frames}-dynamic"),
            &format!("misalign:{frames}@dynamic"),
        ));
    }
    settings
}

/// The kind of perturbation a spec is, as the benchmark groups its settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Category {
    Clean,
    Rgb,
    Depth,
    FastMotion,
    TrajectoryDeviation,
    Misalignment,
    /// More than one kind at once.
    Combined,
}

pub fn category(spec: &PerturbSpec) -> Category {
    let kinds = [
        (!spec.image.is_empty(), Category::Rgb),
        (!spec.depth.is_empty(), Category::Depth),
        (spec.fast.is_some(), Category::FastMotion),
        (
            spec.rotation.is_some() || spec.translation.is_some(),
            Category::TrajectoryDeviation,
        ),
        (spec.misalign.is_some(), Category::Misalignment),
    ];
    let mut present = kinds.iter().filter(|(on, _)| *on).map(|(_, k)| *k);
    match (present.next(), present.next()) {
        (None, _) => Category::Clean,
        (Some(kind), None) => kind,
        _ => Category::Combined,
    }
}

#[cfg(test)]
mod tests {
    use std::collections::{BTreeMap, HashSet};

    use rslam_core::dataset::{DatasetFormat, DepthPng};
    use rslam_perturb::{find, Group, PerturbSpec};

    use super::*;

    fn robust_slam(scenes: Option<Vec<String>>) -> SuiteFile {
        init_suite(&InitOptions {
            preset: Preset::RobustSlam,
            scenes,
            frames: None,
            format: DatasetFormat::Replica,
            depth_png: DepthPng::Fast,
            seed: 0,
        })
    }

    #[test]
    fn robust_slam_is_the_1000_sequences_of_section_7() {
        let file = robust_slam(None);
        assert_eq!(file.sequences.len(), 1000);
        let mut per_category: BTreeMap<Category, usize> = BTreeMap::new();
        let mut names = HashSet::new();
        for row in &file.sequences {
            let row = row.get_ref();
            let spec = row
                .perturb
                .as_deref()
                .map_or_else(PerturbSpec::default, |text| {
                    PerturbSpec::parse(text).unwrap()
                });
            *per_category.entry(category(&spec)).or_default() += 1;
            assert!(
                names.insert(row.name.clone().unwrap()),
                "{:?} twice",
                row.name
            );
        }
        let expected = [
            (Category::Clean, 1),
            (Category::Rgb, 16 * 3 * 2),
            (Category::Depth, 4),
            (Category::FastMotion, 3),
            (Category::TrajectoryDeviation, 15),
            (Category::Misalignment, 6),
        ]
        .map(|(c, n)| (c, n * 8));
        assert_eq!(per_category, BTreeMap::from(expected));
        let scenes: HashSet<_> = file
            .sequences
            .iter()
            .map(|r| r.get_ref().scene.clone().unwrap())
            .collect();
        assert_eq!(scenes.len(), 8);
    }

    #[test]
    fn the_benchmark_rgb_corruptions_are_catalogue_image_entries() {
        for name in BENCHMARK_RGB {
            let entry = find(name).unwrap_or_else(|| panic!("{name} not in the catalogue"));
            assert_eq!(entry.group, Group::Image, "{name}");
        }
        let unique: HashSet<_> = BENCHMARK_RGB.iter().collect();
        assert_eq!(unique.len(), 16);
    }

    #[test]
    fn deviation_settings_combine_rotation_and_translation_without_the_origin() {
        let settings = Preset::RobustSlam.settings();
        let deviations: Vec<&Setting> = settings
            .iter()
            .filter(|s| {
                category(&PerturbSpec::parse(&s.spec).unwrap_or_default())
                    == Category::TrajectoryDeviation
            })
            .collect();
        assert_eq!(deviations.len(), 15);
        let find = |name: &str| {
            deviations
                .iter()
                .find(|s| s.name == name)
                .map(|s| s.spec.as_str())
        };
        assert_eq!(find("rot-1"), Some("rot:1"));
        assert_eq!(find("trans-0.05"), Some("trans:0.05"));
        assert_eq!(find("rot-5-trans-0.0125"), Some("rot:5,trans:0.0125"));
    }

    #[test]
    fn narrowing_keeps_the_settings_and_takes_the_scenes_given() {
        let file = robust_slam(Some(vec!["office2".into()]));
        assert_eq!(file.sequences.len(), 125);
        assert!(file.sequences.iter().all(|r| r
            .get_ref()
            .name
            .as_ref()
            .unwrap()
            .starts_with("office2__")));
        let mini = init_suite(&InitOptions {
            preset: Preset::Mini,
            scenes: None,
            frames: None,
            format: DatasetFormat::Tum,
            depth_png: DepthPng::Small,
            seed: 1,
        });
        assert_eq!(mini.defaults.frames, Some(200));
        assert_eq!(mini.defaults.camera.as_deref(), Some("tum"));
        assert_eq!(mini.defaults.depth_png.as_deref(), Some("small"));
        let kinds: HashSet<Category> = Preset::Mini
            .settings()
            .iter()
            .map(|s| {
                if s.spec.is_empty() {
                    Category::Clean
                } else {
                    category(&PerturbSpec::parse(&s.spec).unwrap())
                }
            })
            .collect();
        assert_eq!(kinds.len(), 6, "one setting of each kind");
    }
}
