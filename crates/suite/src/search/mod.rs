//! `rslam suite search`: for each method, perturbation family and scene, the lowest severity at
//! which the method breaks, found by bisection over real severities (whole ones for items that
//! take only those) rather than a grid scan. Everything lives under `DIR/search/`, a suite folder
//! of its own: each severity tried is a sequence made on demand, run and its frames deleted as
//! `suite bench --ephemeral` does (`datasets/`, `runs/`), so `suite report DIR/search` and `eval
//! --runs` read it too. The search keeps no state besides those runs: run again, it walks the
//! same bisection, finds each probe's runs recorded and goes on where it stopped. Shards split the
//! (method, family, scene) searches; a run without `--shard` once they are done writes the
//! profile (`search/profile.json`, `profile.csv`, `report.html`) without running anything.

mod bisection;
mod criterion;
mod probe;

use std::path::{Path, PathBuf};

use rslam_core::read_text_file;
use rslam_eval::profile::{write_profile, BreakingPoint, ProfileTable, RobustnessProfile};
use rslam_gpu::GpuContext;
use rslam_perturb::{find, Between, Severity};

pub use bisection::{bisect, Finding, Grid};
pub use criterion::{Criterion, RunOutcome};
use probe::Prober;

use crate::bench::{BenchProgress, Method};
use crate::suite_file::{SequenceFields, SuiteFile, SUITE_FILE};
use crate::{Shard, SuiteError, SuiteProgress};

/// The search's folder inside `DIR`.
pub const SEARCH_DIR: &str = "search";

#[derive(Clone, Debug)]
pub struct SearchOptions {
    /// Catalogue items (image and depth corruptions).
    pub families: Vec<String>,
    /// Built-in scenes or mesh files (relative to `DIR`).
    pub scenes: Vec<String>,
    /// Frames per sequence; `None`: `DIR/suite.toml`'s `[defaults]`, else the whole path.
    pub frames: Option<usize>,
    pub criterion: Criterion,
    /// The width the interval around each breaking severity is narrowed to.
    pub resolution: Severity,
    /// Runs of the method per sequence; `None`: the method file's `repeats`.
    pub repeats: Option<usize>,
    /// Sequences per severity, each drawn with its own seed.
    pub seeds: usize,
    pub shard: Shard,
    /// Sequences made at once (each run by the method in turn).
    pub jobs: usize,
    pub scratch: Option<PathBuf>,
    /// Keep every sequence's frames instead of deleting them once run.
    pub keep: bool,
}

/// Reports the making of sequences, each run, and each probe's verdict.
pub trait SearchProgress: SuiteProgress + BenchProgress {
    fn probed(&self, target: &Target, severity: Severity, broke: bool, runs: usize);
}

/// One search: a method under one family on one scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Target {
    pub method: String,
    pub family: String,
    pub scene: String,
}

impl Target {
    /// The name shards are drawn from.
    fn name(&self) -> String {
        format!("{}/{}/{}", self.method, self.family, self.scene)
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct SearchSummary {
    pub findings: Vec<(Target, Finding, usize)>,
    /// The profile's files, when the search covered every target (no shard).
    pub written: Vec<PathBuf>,
}

/// A search checked before any work starts: every family, method and probe row.
pub struct SearchPlan {
    methods: Vec<Method>,
    grids: Vec<(String, Grid)>,
    /// (scene as the rows name it, scene as the user wrote it).
    scenes: Vec<(String, String)>,
    /// Makes and runs the probes in `DIR/search`.
    prober: Prober,
    options: SearchOptions,
}

/// Checks the search of `methods` in `dir` (see the module's documentation).
pub fn plan(
    dir: &Path,
    methods: &[Method],
    options: &SearchOptions,
) -> Result<SearchPlan, SuiteError> {
    let grids = grids(&options.families, options.resolution)?;
    let methods = with_repeats(methods, options.repeats)?;
    let (template, seed) = template(dir, &methods, options.frames)?;
    let scenes = (options.scenes.iter())
        .map(|s| (scene_path(dir, s), s.clone()))
        .collect();
    let prober = Prober {
        dir: dir.join(SEARCH_DIR),
        template,
        seed,
        seeds: options.seeds.max(1),
        jobs: options.jobs.max(1),
        scratch: options.scratch.clone(),
        keep: options.keep,
    };
    let plan = SearchPlan {
        methods,
        grids,
        scenes,
        prober,
        options: options.clone(),
    };
    for (scene, _) in &plan.scenes {
        for (family, _) in &plan.grids {
            plan.prober.row_check(scene, family)?;
        }
    }
    Ok(plan)
}

/// Searches every target of the plan's shard; writes the profile when the plan is not sharded.
pub fn search(
    ctx: &GpuContext,
    plan: &SearchPlan,
    progress: &dyn SearchProgress,
) -> Result<SearchSummary, SuiteError> {
    let (options, prober) = (&plan.options, &plan.prober);
    std::fs::create_dir_all(&prober.dir).map_err(|e| SuiteError::io(&prober.dir, e))?;
    let probe = |method, scene, family, severity| {
        prober.run(
            ctx,
            progress,
            method,
            prober.sequences(scene, family, severity)?,
        )
    };
    let mut findings = Vec::new();
    for method in &plan.methods {
        for (family, grid) in &plan.grids {
            for (scene, shown) in &plan.scenes {
                let target = Target {
                    method: method.name.clone(),
                    family: family.clone(),
                    scene: shown.clone(),
                };
                if !options.shard.contains(&target.name()) {
                    continue;
                }
                let clean = probe(method, scene, family, Severity::CLEAN)?;
                let mut runs = 0;
                let finding = bisect(*grid, |severity| {
                    let outcomes = match severity.is_clean() {
                        true => clean.clone(),
                        false => probe(method, scene, family, severity)?,
                    };
                    runs += outcomes.len();
                    let broke = options.criterion.breaks(&outcomes, &clean);
                    progress.probed(&target, severity, broke, outcomes.len());
                    Ok::<bool, SuiteError>(broke)
                })?;
                findings.push((target, finding, runs));
            }
        }
    }
    let written = match options.shard == Shard::WHOLE {
        true => {
            let mut written = vec![write_suite_file(plan, &findings)?];
            written.extend(write_profile(&profile(&findings, options), &prober.dir)?);
            written
        }
        false => Vec::new(),
    };
    Ok(SearchSummary { findings, written })
}

/// `search/suite.toml`: a row for every sequence the search made, so that `suite status`,
/// `suite report` and `suite regen` work on `search/` as on any suite.
fn write_suite_file(
    plan: &SearchPlan,
    findings: &[(Target, Finding, usize)],
) -> Result<PathBuf, SuiteError> {
    let prober = &plan.prober;
    let mut sequences = Vec::new();
    for (target, finding, _) in findings {
        let (scene, _) = (plan.scenes.iter())
            .find(|(_, shown)| *shown == target.scene)
            .expect("a target's scene is one of the plan's");
        for (severity, _) in &finding.probes {
            for row in prober.rows(scene, &target.family, *severity) {
                if !sequences
                    .iter()
                    .any(|s: &toml::Spanned<SequenceFields>| s.get_ref().name == row.name)
                {
                    sequences.push(toml::Spanned::new(0..0, row));
                }
            }
        }
    }
    let file = SuiteFile {
        seed: plan.prober.seed,
        defaults: plan.prober.template.clone(),
        sequences,
    };
    let header =
        "Written by `rslam suite search`: every sequence it made, each severity it tried. \
                  `rslam suite search` writes it again; `suite status`, `suite report` and \
                  `suite regen` read it.";
    let path = plan.prober.dir.join(SUITE_FILE);
    let partial = plan.prober.dir.join(format!(".{SUITE_FILE}.partial"));
    std::fs::write(&partial, file.to_text(header)?).map_err(|e| SuiteError::io(&partial, e))?;
    std::fs::rename(&partial, &path).map_err(|e| SuiteError::io(&path, e))?;
    Ok(path)
}

/// Each family's grid; unknown names and items without severities are refused.
fn grids(families: &[String], resolution: Severity) -> Result<Vec<(String, Grid)>, SuiteError> {
    if resolution.is_clean() {
        return Err(SuiteError::option(
            "--resolution",
            "0: expected a width of at least 0.01",
        ));
    }
    families
        .iter()
        .map(|name| {
            let entry = find(name).ok_or_else(|| {
                SuiteError::option(
                    "--families",
                    format!(
                        "'{name}': not an image or depth corruption; valid: {}",
                        rslam_perturb::names()
                    ),
                )
            })?;
            let grid = match entry.between {
                Between::Interpolated(_) => Grid::Real {
                    resolution: resolution.hundredths(),
                },
                Between::WholeOnly(_) => Grid::Whole,
            };
            Ok((name.clone(), grid))
        })
        .collect()
}

fn with_repeats(methods: &[Method], repeats: Option<usize>) -> Result<Vec<Method>, SuiteError> {
    if methods.is_empty() {
        return Err(SuiteError::option("--methods", "no method file given"));
    }
    let first = methods[0].reads;
    if let Some(other) = methods.iter().find(|m| m.reads != first) {
        return Err(SuiteError::option(
            "--methods",
            format!(
                "method '{}' reads {} and '{}' reads {}: a search makes one layout, search them apart",
                methods[0].name, first, other.name, other.reads
            ),
        ));
    }
    Ok(methods
        .iter()
        .map(|m| Method {
            repeats: repeats.unwrap_or(m.repeats).max(1),
            ..m.clone()
        })
        .collect())
}

/// What every probe's row shares: `DIR/suite.toml`'s `[defaults]` and seed when there is one,
/// the methods' layout, and `frames`.
fn template(
    dir: &Path,
    methods: &[Method],
    frames: Option<usize>,
) -> Result<(SequenceFields, u64), SuiteError> {
    let path = dir.join(SUITE_FILE);
    let (mut defaults, seed) = match path.is_file() {
        true => {
            let file = SuiteFile::parse(&path, &read_text_file(&path, "a suite in TOML")?)?;
            (file.defaults, file.seed)
        }
        false => (SequenceFields::default(), 0),
    };
    let layout = methods[0].reads.to_string();
    match &defaults.format {
        Some(format) if *format != layout => {
            return Err(SuiteError::option(
                "--methods",
                format!(
                    "{}: [defaults] format = \"{format}\" but the methods read {layout}",
                    path.display()
                ),
            ))
        }
        _ => defaults.format = Some(layout),
    }
    defaults.frames = frames.or(defaults.frames);
    // What the search sets per row: [defaults] may not decide the scene or the perturbation.
    (
        defaults.name,
        defaults.scene,
        defaults.perturb,
        defaults.seed,
    ) = (None, None, None, None);
    Ok((defaults, seed))
}

/// A mesh file named relative to `DIR` as the search's rows need it (their folder is
/// `DIR/search`); built-in scene names as they are.
fn scene_path(dir: &Path, scene: &str) -> String {
    let relative = Path::new(scene);
    match rslam_render::builtin_path_length(scene) {
        None if relative.is_relative() => dir.join(relative).display().to_string(),
        _ => scene.to_string(),
    }
}

fn profile(findings: &[(Target, Finding, usize)], options: &SearchOptions) -> RobustnessProfile {
    let mut table = ProfileTable::new();
    for (target, finding, runs) in findings {
        let point = BreakingPoint {
            breaking_severity: finding.breaking.map(Severity::value),
            low: finding.low.value(),
            high: finding.breaking.map(Severity::value),
            runs: *runs,
        };
        table
            .entry(target.method.clone())
            .or_default()
            .entry(target.family.clone())
            .or_default()
            .insert(target.scene.clone(), point);
    }
    RobustnessProfile {
        criterion: options.criterion.to_string(),
        resolution: options.resolution.value(),
        sequences_per_severity: options.seeds.max(1),
        methods: table,
    }
}
