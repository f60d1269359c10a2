use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use rslam_suite::schedulers::kubernetes::{write_kubernetes_job, KubernetesOptions};
use rslam_suite::schedulers::slurm::{write_slurm_script, SlurmOptions};
use rslam_suite::schedulers::{EphemeralTask, TaskOptions};
use rslam_suite::Suite;

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
    #[arg(long, requires = "methods")]
    ephemeral: bool,
    /// A method file for the ephemeral tasks, repeatable.
    #[arg(long = "methods", requires = "ephemeral")]
    methods: Vec<PathBuf>,
    /// Node-local scratch for the ephemeral tasks' frames (default: each task's $TMPDIR, else in
    /// place; Kubernetes: the pod's emptyDir).
    #[arg(long, requires = "ephemeral", value_name = "DIR")]
    scratch: Option<String>,
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
        let ephemeral = if self.ephemeral {
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
    Suite::open(&args.dir)?;
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
    Suite::open(&args.dir)?;
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
