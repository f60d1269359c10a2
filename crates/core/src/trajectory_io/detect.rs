//! Tells a trajectory file's format from its first data line.

use std::path::Path;

use super::lines::{data_lines, LineRef};
use super::TrajectoryFormat;
use crate::CoreError;

/// The format of `text` judged by its first data line: comma-separated is EuRoC, otherwise the
/// count of whitespace-separated fields (8 TUM, 12 KITTI, 16 Replica).
pub(super) fn detect(path: &Path, text: &str) -> Result<TrajectoryFormat, CoreError> {
    let Some((line, content)) = data_lines(text).next() else {
        return Err(CoreError::bad_file(
            path,
            "no poses (the file is empty or only comments)",
        ));
    };
    if content.contains(',') {
        return Ok(TrajectoryFormat::Euroc);
    }
    match content.split_whitespace().count() {
        8 => Ok(TrajectoryFormat::Tum),
        12 => Ok(TrajectoryFormat::Kitti),
        16 => Ok(TrajectoryFormat::Replica),
        n => Err(LineRef { path, line }.error(format!(
            "cannot tell the trajectory format from {n} field{}: expected 8 numbers (TUM), \
             12 (KITTI), 16 (Replica) or comma-separated EuRoC; or force a format",
            if n == 1 { "" } else { "s" }
        ))),
    }
}
