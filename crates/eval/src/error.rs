use std::path::PathBuf;

use rslam_core::CoreError;

/// Errors of rslam-eval: each says what was wrong and, where a file is involved, which one.
#[derive(Debug, thiserror::Error)]
pub enum EvalError {
    #[error(transparent)]
    Core(#[from] CoreError),
    #[error(
        "no matching timestamps: no estimate pose lies within {max_diff} s of a ground-truth pose \
         (t-offset {t_offset} s); the estimate spans {est_start:.6} .. {est_end:.6} s, the ground \
         truth {gt_start:.6} .. {gt_end:.6} s{hint}"
    )]
    NoMatches {
        max_diff: f64,
        t_offset: f64,
        est_start: f64,
        est_end: f64,
        gt_start: f64,
        gt_end: f64,
        hint: &'static str,
    },
    #[error("the {which} has no poses")]
    EmptyTrajectory { which: &'static str },
    #[error(
        "cannot align: the {positions} associated positions are degenerate ({reason}); \
         Umeyama alignment needs them to span a plane (or evaluate without alignment)"
    )]
    Degenerate {
        positions: usize,
        reason: &'static str,
    },
    #[error(
        "RPE: delta = {delta} ({unit}) gives no pose pair among {poses} associated poses; \
         try a smaller delta"
    )]
    NoRpePairs {
        delta: f64,
        unit: &'static str,
        poses: usize,
    },
    #[error("{name} = {value}: expected {expected}")]
    BadOption {
        name: &'static str,
        value: String,
        expected: &'static str,
    },
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: {message}")]
    BadMesh { path: PathBuf, message: String },
    #[error("{path}: cannot draw the plot: {message}")]
    Plot { path: PathBuf, message: String },
    #[error("{path}: {message}")]
    BadRuns { path: PathBuf, message: String },
    #[error("{path}: {message}")]
    BadAgents { path: PathBuf, message: String },
    /// An error of one agent of a multi-agent evaluation.
    #[error("agent {agent}: {error}")]
    Agent {
        agent: String,
        error: Box<EvalError>,
    },
    /// An error of one agent of a multi-agent evaluation read from files.
    #[error("agent {agent} ({estimate} against {ground_truth}): {error}")]
    AgentFiles {
        agent: String,
        estimate: PathBuf,
        ground_truth: PathBuf,
        error: Box<EvalError>,
    },
}

impl EvalError {
    pub(crate) fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        EvalError::Io {
            path: path.into(),
            source,
        }
    }
}
