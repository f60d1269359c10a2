//! `rslam suite init`: writes a suite file into a new suite folder.

use std::path::{Path, PathBuf};

use crate::preset::{init_suite, InitOptions};
use crate::suite_file::SUITE_FILE;
use crate::{Suite, SuiteError};

/// Writes `dir/suite.toml` for `options` (never over an existing one) and reads it back as
/// every later command will.
pub fn write_suite(dir: &Path, options: &InitOptions) -> Result<(PathBuf, Suite), SuiteError> {
    let path = dir.join(SUITE_FILE);
    if path.exists() {
        return Err(SuiteError::SuiteFile {
            path,
            line: 0,
            message: "already exists; edit it, or choose another --out".into(),
        });
    }
    let file = init_suite(options);
    let header = format!(
        "rslam suite: preset {}, {} sequences. One [[sequence]] per dataset, made into\n\
         datasets/<name>/ by `rslam suite run`; [defaults] fills what a row leaves out.\n\
         Row keys: name (<scene>__<setting>), scene, perturb, seed, frames, format, camera, rate, traj,\n\
         depth_png, rig (format = \"euroc\" with rig = \"stereo\" or \"stereo-imu\"; format = \"tum\" with\n\
         rig = \"rgbd-imu\": the camera and an IMU).\n\
         A row without a seed gets one derived from the suite seed and its name.",
        options.preset,
        file.sequences.len()
    );
    let text = file.to_text(&header)?;
    std::fs::create_dir_all(dir).map_err(|e| SuiteError::io(dir, e))?;
    std::fs::write(&path, text).map_err(|e| SuiteError::io(&path, e))?;
    Ok((path, Suite::open(dir)?))
}
