use std::path::PathBuf;

use rslam_core::CoreError;
use rslam_eval::EvalError;
use rslam_gpu::GpuError;
use rslam_pipeline::PipelineError;

/// Errors of a suite command; each names the file, line, option or sequence that was wrong.
#[derive(Debug, thiserror::Error)]
pub enum SuiteError {
    #[error(transparent)]
    Core(#[from] CoreError),
    #[error(transparent)]
    Eval(#[from] EvalError),
    #[error(transparent)]
    Gpu(#[from] GpuError),
    #[error(transparent)]
    Pipeline(#[from] PipelineError),
    /// A suite file that does not say what it should (`line` is 1-based; 0 when unknown).
    #[error("{}{}: {message}", path.display(), line_suffix(*line))]
    SuiteFile {
        path: PathBuf,
        line: usize,
        message: String,
    },
    /// An option that cannot work (`option` is the user-facing name, e.g. `--shard`).
    #[error("{option}: {message}")]
    Option { option: String, message: String },
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error(
        "{}: {needed} needed for {sequences} sequence(s) but only {available} free; free space, \
         lower --frames in the suite, or choose a smaller depth encoding (see `rslam suite status --plan`)",
        path.display()
    )]
    NoSpace {
        path: PathBuf,
        needed: String,
        available: String,
        sequences: usize,
    },
    #[error("interrupted: runs without a record are run again by the same command")]
    BenchInterrupted,
    /// Sequences that could not be made; the run made every other one.
    #[error("{count} sequence(s) not made: {summary}")]
    SequencesFailed { count: usize, summary: String },
}

fn line_suffix(line: usize) -> String {
    if line == 0 {
        String::new()
    } else {
        format!(":{line}")
    }
}

impl SuiteError {
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Self::Io {
            path: path.into(),
            source,
        }
    }

    pub fn option(option: &str, message: impl Into<String>) -> Self {
        Self::Option {
            option: option.to_string(),
            message: message.into(),
        }
    }
}
