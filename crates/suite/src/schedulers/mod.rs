//! Scripts that run a suite on a cluster, one `rslam suite run` per array task or Job index,
//! each making its own shard.

pub mod kubernetes;
pub mod slurm;

/// What every task runs besides its shard.
#[derive(Clone, Debug, Default)]
pub struct TaskOptions {
    /// Sequences at once per task (`--jobs`).
    pub jobs: usize,
    /// `--adapter` of every task.
    pub adapter: Option<String>,
}

impl TaskOptions {
    fn run_arguments(&self) -> Vec<String> {
        let mut args = vec!["--jobs".to_string(), self.jobs.max(1).to_string()];
        if let Some(adapter) = &self.adapter {
            args.push("--adapter".into());
            args.push(adapter.clone());
        }
        args
    }
}
