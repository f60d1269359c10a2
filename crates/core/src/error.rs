use std::path::PathBuf;

/// Errors of rslam-core: each names the file, line or value that was wrong.
#[derive(Debug, thiserror::Error)]
pub enum CoreError {
    #[error("camera '{text}': expected 'replica', 'tum' or W,H,FX,FY,CX,CY with positive sizes and focal lengths")]
    BadCamera { text: String },
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}:{line}: {message}")]
    BadLine {
        path: PathBuf,
        line: usize,
        message: String,
    },
    #[error("{path}: {message}")]
    BadFile { path: PathBuf, message: String },
    #[error("frame rate {hz} Hz: expected a positive number")]
    BadRate { hz: f64 },
    #[error("encoding {message}")]
    Encode { message: String },
}

impl CoreError {
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        CoreError::Io {
            path: path.into(),
            source,
        }
    }

    pub fn bad_file(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        CoreError::BadFile {
            path: path.into(),
            message: message.into(),
        }
    }
}
