use std::path::PathBuf;

/// Errors of rslam-core: each names the file, line or value that was wrong.
#[derive(Debug, thiserror::Error)]
pub enum CoreError {
    #[error("camera '{text}': expected 'replica', 'tum' or W,H,FX,FY,CX,CY with sizes of 1 to {max} pixels, positive focal lengths and finite numbers", max = crate::limits::MAX_IMAGE_SIDE)]
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
    #[error("trajectory has {timestamps} timestamps for {poses} poses: expected one per pose")]
    TrajectoryLengths { timestamps: usize, poses: usize },
    #[error("a cubic B-spline needs at least 4 poses: got {poses}")]
    SplineTooShort { poses: usize },
    #[error("timestamp {time} of pose {index}: expected finite times in increasing order")]
    BadTimestamp { index: usize, time: f64 },
    #[error("spline control spacing {spacing} s: expected a positive finite number")]
    BadSplineSpacing { spacing: f64 },
    #[error("time {time} s is outside the spline's valid range [{start}, {end}] s")]
    TimeOutOfRange { time: f64, start: f64, end: f64 },
    #[error("IMU noise {name} = {value}: expected a finite number, 0 or more")]
    BadImuNoise { name: &'static str, value: f64 },
    #[error("{samples} IMU samples asked for: at most {max}")]
    TooManyImuSamples { samples: f64, max: usize },
}

/// `text` as it may be quoted in a one-line error: control characters (line breaks, tabs, NUL)
/// written as escapes, everything else as is.
pub fn printable(text: &str) -> String {
    text.chars()
        .flat_map(|c| {
            let escaped: Vec<char> = if c.is_control() {
                c.escape_default().collect()
            } else {
                vec![c]
            };
            escaped
        })
        .collect()
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
