//! Where the built-in scenes keep what they make once per machine (baked lighting, textures):
//! `$RSLAM_CACHE_DIR`, else `$XDG_CACHE_HOME/rslam`, else `~/.cache/rslam`.

use std::path::PathBuf;

/// The cache folder, if the environment names one.
pub fn cache_root() -> Option<PathBuf> {
    let env = |k| {
        std::env::var_os(k)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    env("RSLAM_CACHE_DIR")
        .or_else(|| env("XDG_CACHE_HOME").map(|p| p.join("rslam")))
        .or_else(|| env("HOME").map(|p| p.join(".cache").join("rslam")))
}
