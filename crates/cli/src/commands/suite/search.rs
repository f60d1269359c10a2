use std::path::PathBuf;
use std::process::ExitCode;

use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_perturb::Severity;
use rslam_suite::bench::Method;
use rslam_suite::search::{plan, search, Criterion, SearchOptions, SearchProgress, Target};

use super::shard_args::ShardArgs;

use crate::suite_progress::SuiteBars;

pub(super) const DEFAULT_CRITERION: &str = "ate>3×clean";
pub(super) const DEFAULT_RESOLUTION: &str = "0.1";

#[derive(clap::Args)]
#[command(
    after_help = "For each method, family and scene: is the method broken on the clean sequences, at \
severity 5, then bisection between the highest severity seen not to break it and the lowest seen to, \
until they are --resolution apart (about log2(5 / resolution) + 2 severities: 8 at 0.1). Items that \
take whole severities only (saturate, spatter, snow, glass_blur) are searched on 1..5. Broken means \
the --criterion on the median of the runs at that severity (repeats × seeds); a failed run counts as \
the worst value. A method whose runs spread wants more --repeats (the median of 3 or 5), not another \
rule.

Everything goes under DIR/search/: each severity tried is a sequence (`<scene>__<family>-<severity>`, \
made from DIR/suite.toml's [defaults] when there is one), run and its frames deleted as `suite bench \
--ephemeral` does; runs already recorded are not run again, so a killed search resumes. With --shard \
each process takes the (method, family, scene) searches hashing to it; a run without --shard once all \
are done writes DIR/search/profile.json ({method: {family: {scene: {breaking_severity, low, high, \
runs}}}}, breaking_severity null when the method did not break at 5), profile.csv and report.html."
)]
pub struct SearchArgs {
    /// The folder to search in (its suite.toml's [defaults], if any, shape the sequences).
    dir: PathBuf,
    /// A method file (TOML), repeatable; all must read the same layout.
    #[arg(long = "methods", required = true)]
    methods: Vec<PathBuf>,
    /// Perturbation families: image and depth corruptions, comma-separated.
    #[arg(long, required = true, value_delimiter = ',')]
    families: Vec<String>,
    /// Scenes: built-in names or mesh files (relative to DIR), comma-separated.
    #[arg(long, required = true, value_delimiter = ',')]
    scenes: Vec<String>,
    /// Frames per sequence (default: DIR/suite.toml's [defaults], else the whole path).
    #[arg(long)]
    frames: Option<usize>,
    /// What breaks a method: failed (more than half of the runs failed), sr<X (median SR below
    /// X), or ate>K×clean (median ATE above K times the clean median; also written ate>Kx).
    #[arg(long, default_value = DEFAULT_CRITERION)]
    criterion: String,
    /// How narrow the interval around each breaking severity gets (0.01 to 5).
    #[arg(long, default_value = DEFAULT_RESOLUTION)]
    resolution: String,
    /// Runs per sequence (default: each method file's repeats).
    #[arg(long)]
    repeats: Option<usize>,
    /// Sequences per severity, each with its own seed for the perturbation's randomness.
    #[arg(long, default_value_t = 1)]
    seeds: usize,
    #[command(flatten)]
    shard: ShardArgs,
    /// Sequences made at once, each run by the method in turn.
    #[arg(long, default_value_t = 1)]
    jobs: usize,
    /// Make the frames in this node-local folder (default: $TMPDIR when set, else in place).
    #[arg(long, value_name = "DIR", conflicts_with = "keep")]
    scratch: Option<PathBuf>,
    /// Keep every sequence's frames under DIR/search/datasets (default: deleted once run).
    #[arg(long)]
    keep: bool,
    /// Use the GPU whose name contains this text.
    #[arg(long)]
    adapter: Option<String>,
}

impl SearchProgress for SuiteBars {
    fn probed(&self, target: &Target, severity: Severity, broke: bool, runs: usize) {
        let verdict = if broke { "breaks" } else { "holds" };
        self.line(&format!(
            "{} {} {} at {severity}: {verdict} ({runs} runs)",
            target.method, target.family, target.scene
        ));
    }
}

/// `--criterion` and `--resolution` as the search takes them (also checked by `suite slurm
/// --search` and `suite k8s --search` before they write a job).
pub(super) fn criterion_and_resolution(
    criterion: &str,
    resolution: &str,
) -> anyhow::Result<(Criterion, Severity)> {
    let criterion: Criterion = criterion
        .parse()
        .map_err(|e: String| anyhow::anyhow!("--criterion: {e}"))?;
    let resolution = Severity::parse(resolution)
        .filter(|r| !r.is_clean())
        .ok_or_else(|| {
            anyhow::anyhow!(
                "--resolution {resolution}: expected a width from 0.01 to 5, at most two decimals"
            )
        })?;
    Ok((criterion, resolution))
}

/// Reads the method files.
pub(super) fn read_methods(paths: &[PathBuf]) -> anyhow::Result<Vec<Method>> {
    Ok(paths
        .iter()
        .map(|path| Method::read(path))
        .collect::<Result<Vec<_>, _>>()?)
}

pub fn run(args: SearchArgs) -> anyhow::Result<ExitCode> {
    let methods = read_methods(&args.methods)?;
    let (criterion, resolution) = criterion_and_resolution(&args.criterion, &args.resolution)?;
    let (shard, _) = args.shard.resolve()?;
    let options = SearchOptions {
        families: args.families.clone(),
        scenes: args.scenes.clone(),
        frames: args.frames,
        criterion,
        resolution,
        repeats: args.repeats,
        seeds: args.seeds,
        shard,
        jobs: args.jobs,
        scratch: args
            .scratch
            .clone()
            .or_else(|| std::env::var_os("TMPDIR").map(PathBuf::from)),
        keep: args.keep,
    };
    let plan = plan(&args.dir, &methods, &options)?;
    let ctx = GpuContext::new(&AdapterChoice {
        name_contains: args.adapter.clone(),
    })?;
    let bars = SuiteBars::new();
    bars.line(&format!("adapter: {}", ctx.describe()));
    bars.line(&format!("breaking means: {criterion}"));
    let summary = search(&ctx, &plan, &bars)?;
    bars.finish();
    for (target, finding, runs) in &summary.findings {
        let found = match finding.breaking {
            Some(s) => format!("breaks at {s} (holds at {})", finding.low),
            None => "> 5 (holds at 5)".to_string(),
        };
        eprintln!(
            "{} {} {}: {found}, {} severities, {runs} runs",
            target.method,
            target.family,
            target.scene,
            finding.probes.len()
        );
    }
    let profile = (summary.written.iter()).find(|p| p.ends_with("profile.json"));
    match profile {
        Some(profile) => eprintln!("profile: {}", profile.display()),
        None => eprintln!(
            "shard {shard} done; once every shard is, `rslam suite search` without --shard writes the profile"
        ),
    }
    Ok(ExitCode::SUCCESS)
}
