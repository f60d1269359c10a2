use rslam_suite::{Shard, ShardSource, SuiteError};

/// Which shard a `suite run` or `suite bench` process takes.
#[derive(clap::Args)]
pub struct ShardArgs {
    /// Shard I of N (I from 0): the sequences whose name hashes to I. Default: from
    /// SLURM_ARRAY_TASK_ID / SLURM_ARRAY_TASK_COUNT, else JOB_COMPLETION_INDEX with
    /// --shard-count, else the whole suite.
    #[arg(long)]
    shard: Option<String>,
    /// Number of shards when the index comes from JOB_COMPLETION_INDEX (Kubernetes).
    #[arg(long)]
    shard_count: Option<usize>,
}

impl ShardArgs {
    pub fn resolve(&self) -> Result<(Shard, ShardSource), SuiteError> {
        Shard::resolve(self.shard.as_deref(), self.shard_count, |name| {
            std::env::var(name).ok()
        })
    }
}
