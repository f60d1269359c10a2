//! Scripts that run a suite on a cluster, one `rslam suite run` (or, with method files, one
//! `rslam suite bench --ephemeral`, or one `rslam suite search`) per array task or Job index,
//! each on its own shard.

pub mod kubernetes;
pub mod slurm;

/// What every task runs besides its shard.
#[derive(Clone, Debug, Default)]
pub struct TaskOptions {
    /// Sequences at once per task (`--jobs`).
    pub jobs: usize,
    /// `--adapter` of every task.
    pub adapter: Option<String>,
    /// Bench these methods ephemerally instead of keeping the datasets.
    pub ephemeral: Option<EphemeralTask>,
}

/// What an ephemeral task runs.
#[derive(Clone, Debug, Default)]
pub struct EphemeralTask {
    /// Method files, as the tasks see them.
    pub methods: Vec<String>,
    /// `--scratch` of every task; `None`: each task's `$TMPDIR`, else in place.
    pub scratch: Option<String>,
    /// The arguments of `suite search` (`--families …`, `--scenes …`, …): each task searches its
    /// shard of the (method, family, scene) searches instead of benching the suite's sequences.
    pub search: Option<Vec<String>>,
}

impl TaskOptions {
    /// The `suite` subcommand every task runs.
    fn subcommand(&self) -> &'static str {
        match &self.ephemeral {
            Some(EphemeralTask {
                search: Some(_), ..
            }) => "search",
            Some(_) => "bench",
            None => "run",
        }
    }

    /// The arguments after the suite folder.
    fn run_arguments(&self) -> Vec<String> {
        let mut args = Vec::new();
        if let Some(ephemeral) = &self.ephemeral {
            if ephemeral.search.is_none() {
                args.push("--ephemeral".to_string());
            }
            for method in &ephemeral.methods {
                args.extend(["--methods".to_string(), method.clone()]);
            }
            args.extend(ephemeral.search.iter().flatten().cloned());
            if let Some(scratch) = &ephemeral.scratch {
                args.extend(["--scratch".to_string(), scratch.clone()]);
            }
        }
        args.extend(["--jobs".to_string(), self.jobs.max(1).to_string()]);
        if let Some(adapter) = &self.adapter {
            args.push("--adapter".into());
            args.push(adapter.clone());
        }
        args
    }
}
