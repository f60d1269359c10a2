//! The output folder of a recorded EuRoC dataset's perturbed copy.

use std::path::Path;

use rslam_core::dataset::euroc::MAV_DIR;
use rslam_core::dataset::Manifest;
use rslam_core::CoreError;

use crate::output_folder::{self, FolderState};
use crate::PipelineError;

/// Prepares `out` for the job of `manifest` (see [`output_folder::prepare`]) and says what it
/// held. An unfinished run is started over, not resumed frame by frame: its `mav0/` is removed.
pub fn prepare(out: &Path, manifest: &Manifest, force: bool) -> Result<FolderState, PipelineError> {
    let found = output_folder::prepare(out, manifest, force)?;
    if found == FolderState::Resume {
        let mav = out.join(MAV_DIR);
        if mav.exists() {
            std::fs::remove_dir_all(&mav).map_err(|e| CoreError::io(&mav, e))?;
        }
    }
    Ok(found)
}
