//! `rslam suite`: one file per subcommand.

mod bench;
mod init;
mod regen;
mod report;
mod run;
mod schedulers;
mod search;
mod shard_args;
mod status;

use std::process::ExitCode;

#[derive(clap::Args)]
pub struct SuiteArgs {
    #[command(subcommand)]
    command: SuiteCommand,
}

#[derive(clap::Subcommand)]
enum SuiteCommand {
    /// Write a suite file: the paper's 1,000-sequence matrix (robust-slam) or a small one (mini).
    Init(init::InitArgs),
    /// Make every sequence of this shard that is not complete; resume partial ones.
    Run(run::RunArgs),
    /// Complete / partial / missing per setting and scene, disk used, and the plan (--plan).
    /// Exit code 1 while anything is not complete.
    Status(status::StatusArgs),
    /// Write an sbatch array script, one `suite run` (or `suite bench --ephemeral`) shard per
    /// array task.
    Slurm(schedulers::SlurmArgs),
    /// Write a Kubernetes Indexed Job, one `suite run` (or `suite bench --ephemeral`) shard per
    /// completion index.
    K8s(schedulers::KubernetesArgs),
    /// Run SLAM methods (method files) on every made sequence, each repeat once, resumably;
    /// --ephemeral makes each sequence, runs it and deletes its frames.
    Bench(bench::BenchArgs),
    /// Remake one sequence's frames from its kept manifest and check them against its kept
    /// checksums.
    Regen(regen::RegenArgs),
    /// The benchmark's tables, CSR curves, plots and an HTML page over the bench's runs.
    Report(report::ReportArgs),
    /// Per method, perturbation family and scene, the lowest severity that breaks the method,
    /// found by bisection: a robustness profile (DIR/search/profile.json, report.html).
    Search(search::SearchArgs),
}

pub fn run(args: SuiteArgs) -> anyhow::Result<ExitCode> {
    match args.command {
        SuiteCommand::Init(args) => init::run(args),
        SuiteCommand::Run(args) => run::run(args),
        SuiteCommand::Status(args) => status::run(args),
        SuiteCommand::Slurm(args) => schedulers::run_slurm(args),
        SuiteCommand::K8s(args) => schedulers::run_kubernetes(args),
        SuiteCommand::Bench(args) => bench::run(args),
        SuiteCommand::Regen(args) => regen::run(args),
        SuiteCommand::Report(args) => report::run(args),
        SuiteCommand::Search(args) => search::run(args),
    }
}
