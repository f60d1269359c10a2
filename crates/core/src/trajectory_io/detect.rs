//! Tells a trajectory file's format from its first data line.

use std::path::Path;

use super::lines::{data_lines, LineRef};
use super::TrajectoryFormat;
use super::{colmap, nerfstudio};
use crate::CoreError;

/// The format of `text`: a JSON object is nerfstudio's; otherwise judged by its first data line: comma-separated is EuRoC, two integer ids
/// around seven numbers and a name COLMAP's `images.txt`, otherwise the count of
/// whitespace-separated fields (8 TUM, 12 KITTI, 16 Replica).
pub(super) fn detect(path: &Path, text: &str) -> Result<TrajectoryFormat, CoreError> {
    if nerfstudio::is_json(text) {
        return Ok(TrajectoryFormat::Nerfstudio);
    }
    let Some((line, content)) = data_lines(text).next() else {
        return Err(CoreError::bad_file(
            path,
            "no poses (the file is empty or only comments)",
        ));
    };
    if content.contains(',') {
        return Ok(TrajectoryFormat::Euroc);
    }
    if colmap::is_image_line(content) {
        return Ok(TrajectoryFormat::Colmap);
    }
    match content.split_whitespace().count() {
        8 => Ok(TrajectoryFormat::Tum),
        12 => Ok(TrajectoryFormat::Kitti),
        16 => Ok(TrajectoryFormat::Replica),
        n => Err(LineRef { path, line }.error(format!(
            "cannot tell the trajectory format from {n} field{}: expected 8 numbers (TUM), \
             12 (KITTI), 16 (Replica), comma-separated EuRoC or a COLMAP images.txt line; or \
             force a format",
            if n == 1 { "" } else { "s" }
        ))),
    }
}
