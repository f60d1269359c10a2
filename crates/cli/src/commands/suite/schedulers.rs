use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rslam_suite::schedulers::kubernetes::{write_kubernetes_job, KubernetesOptions};
use rslam_suite::schedulers::slurm::{write_slurm_script, SlurmOptions};
use rslam_suite::schedulers::{EphemeralTask, TaskOptions};
use rslam_suite::search::{plan, SearchOptions};
use rslam_suite::{Shard, Suite};

use super::search;

#[derive(clap::Args)]
pub struct TaskArgs {
    /// Sequences each task makes at once on its GPU (with --ephemeral: in flight).
    #[arg(long, default_value_t = 1)]
    jobs: usize,
    /// `--adapter` for every task (a GPU name fragment).
    #[arg(long)]
    adapter: Option<String>,
    /// Each task runs `suite bench --ephemeral` with --methods instead of `suite run`: no
    /// frames kept.
    #[arg(long, requires = "methods", conflicts_with = "search")]
    ephemeral: bool,
    /// Each task runs `suite search` with --methods and the search options (--families,
    /// --scenes, …) on its shard of the searches; DIR need not hold a suite.toml.
    #[arg(long, requires_all = ["methods", "families", "scenes"])]
    search: bool,
    /// A method file for the ephemeral or search tasks, repeatable.
    #[arg(long = "methods")]
    methods: Vec<PathBuf>,
    /// Node-local scratch for the ephemeral or search tasks' frames (default: each task's
    /// $TMPDIR, else in place; Kubernetes: the pod's emptyDir).
    #[arg(long, value_name = "DIR")]
    scratch: Option<String>,
    #[command(flatten)]
    search_options: SearchTaskArgs,
}

/// The options of `suite search` the search tasks pass on (see `rslam suite search --help`).
#[derive(clap::Args)]
pub struct SearchTaskArgs {
    #[arg(long, requires = "search")]
    families: Option<String>,
    #[arg(long, requires = "search")]
    scenes: Option<String>,
    #[arg(long, requires = "search")]
    frames: Option<usize>,
    #[arg(long, requires = "search")]
    criterion: Option<String>,
    #[arg(long, requires = "search")]
    resolution: Option<String>,
    #[arg(long, requires = "search")]
    repeats: Option<usize>,
    #[arg(long, requires = "search")]
    seeds: Option<usize>,
}

impl TaskArgs {
    /// With --search: the search every task will run, checked here so that a bad option is
    /// refused now rather than in each task's log.
    fn check_search(&self, dir: &std::path::Path) -> anyhow::Result<()> {
        if !self.search {
            return Ok(());
        }
        let o = &self.search_options;
        let list = |text: &Option<String>| -> Vec<String> {
            let text = text.as_deref().unwrap_or_default();
            text.split(',').map(str::to_string).collect()
        };
        let (criterion, resolution) = search::criterion_and_resolution(
            o.criterion.as_deref().unwrap_or(search::DEFAULT_CRITERION),
            o.resolution
                .as_deref()
                .unwrap_or(search::DEFAULT_RESOLUTION),
        )?;
        let options = SearchOptions {
            families: list(&o.families),
            scenes: list(&o.scenes),
            frames: o.frames,
            criterion,
            resolution,
            repeats: o.repeats,
            seeds: o.seeds.unwrap_or(1),
            shard: Shard::WHOLE,
            jobs: self.jobs,
            scratch: None,
            keep: false,
        };
        plan(dir, &search::read_methods(&self.methods)?, &options)?;
        Ok(())
    }
}

impl SearchTaskArgs {
    /// `--name value` for each option given, in `suite search`'s order.
    fn arguments(&self) -> Vec<String> {
        let numbers = |v: Option<usize>| v.map(|n| n.to_string());
        let given = [
            ("--families", self.families.clone()),
            ("--scenes", self.scenes.clone()),
            ("--frames", numbers(self.frames)),
            ("--criterion", self.criterion.clone()),
            ("--resolution", self.resolution.clone()),
            ("--repeats", numbers(self.repeats)),
            ("--seeds", numbers(self.seeds)),
        ];
        given
            .into_iter()
            .filter_map(|(name, value)| value.map(|v| [name.to_string(), v]))
            .flatten()
            .collect()
    }
}

#[derive(clap::Args)]
pub struct SlurmArgs {
    /// The suite folder, on storage every node sees.
    dir: PathBuf,
    /// Array tasks (= shards); one GPU each is the usual choice.
    #[arg(long)]
    tasks: usize,
    /// At most this many tasks at once.
    #[arg(long)]
    throttle: Option<usize>,
    /// An extra `#SBATCH` line, repeatable: --sbatch-arg=--partition=gpu --sbatch-arg=--gres=gpu:1
    #[arg(long = "sbatch-arg", allow_hyphen_values = true)]
    sbatch_args: Vec<String>,
    /// The rslam binary the tasks run; default: this one.
    #[arg(long)]
    rslam: Option<PathBuf>,
    #[command(flatten)]
    task: TaskArgs,
}

#[derive(clap::Args)]
pub struct KubernetesArgs {
    /// The suite folder (its copy on the claim is what the pods make).
    dir: PathBuf,
    /// Completions (= shards).
    #[arg(long)]
    tasks: usize,
    /// Container image with rslam on its PATH.
    #[arg(long)]
    image: String,
    /// PersistentVolumeClaim holding the suite folder.
    #[arg(long, default_value = "rslam-suite")]
    claim: String,
    /// Where the pods mount the claim (the suite folder inside them).
    #[arg(long, default_value = "/suite")]
    mount: String,
    /// GPUs per pod (nvidia.com/gpu); 0 runs on the CPU (lavapipe).
    #[arg(long, default_value_t = 1)]
    gpus: usize,
    /// Pods at once; default: all.
    #[arg(long)]
    parallelism: Option<usize>,
    #[command(flatten)]
    task: TaskArgs,
}

impl TaskArgs {
    /// The task options; `absolute`: method files as absolute paths (they are read where the
    /// task runs, in another working folder).
    fn options(self, absolute: bool) -> anyhow::Result<TaskOptions> {
        if !(self.ephemeral || self.search) && (!self.methods.is_empty() || self.scratch.is_some())
        {
            anyhow::bail!("--methods and --scratch are for --ephemeral or --search tasks");
        }
        let ephemeral = if self.ephemeral || self.search {
            let methods = self
                .methods
                .iter()
                .map(|path| {
                    let path = match absolute {
                        true => path
                            .canonicalize()
                            .with_context(|| format!("--methods {}", path.display()))?,
                        false => path.clone(),
                    };
                    Ok(path.display().to_string())
                })
                .collect::<anyhow::Result<_>>()?;
            Some(EphemeralTask {
                methods,
                scratch: self.scratch,
                search: self.search.then(|| self.search_options.arguments()),
            })
        } else {
            None
        };
        Ok(TaskOptions {
            jobs: self.jobs,
            adapter: self.adapter,
            ephemeral,
        })
    }
}

pub fn run_slurm(args: SlurmArgs) -> anyhow::Result<ExitCode> {
    if args.task.search {
        args.task.check_search(&args.dir)?;
    } else {
        Suite::open(&args.dir)?;
    }
    let rslam = match args.rslam {
        Some(path) => path
            .canonicalize()
            .with_context(|| format!("--rslam {}", path.display()))?,
        None => std::env::current_exe().context("the path of this rslam binary")?,
    };
    let options = SlurmOptions {
        tasks: args.tasks,
        throttle: args.throttle,
        sbatch_args: args.sbatch_args,
        rslam,
        task: args.task.options(true)?,
    };
    let path = write_slurm_script(&args.dir, &options)?;
    eprintln!("submit with: sbatch {}", path.display());
    println!("{}", path.display());
    Ok(ExitCode::SUCCESS)
}

pub fn run_kubernetes(args: KubernetesArgs) -> anyhow::Result<ExitCode> {
    if args.task.search {
        args.task.check_search(&args.dir)?;
    } else {
        Suite::open(&args.dir)?;
    }
    let options = KubernetesOptions {
        tasks: args.tasks,
        parallelism: args.parallelism,
        image: args.image,
        claim: args.claim,
        mount: args.mount,
        gpus: args.gpus,
        task: args.task.options(false)?,
    };
    let path = write_kubernetes_job(&args.dir, &options)?;
    eprintln!(
        "copy the suite folder onto the claim '{}', then: kubectl apply -f {}",
        options.claim,
        path.display()
    );
    println!("{}", path.display());
    Ok(ExitCode::SUCCESS)
}
