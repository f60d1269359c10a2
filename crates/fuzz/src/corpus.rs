//! The checked-in seed files: `corpus/<target>/*`, small valid (and a few nearly valid) inputs.

use std::path::{Path, PathBuf};

/// `crates/fuzz/corpus`.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus")
}

/// The seeds of `target`, sorted by file name; an error when there are none (a target without
/// seeds would fuzz nothing but random bytes, unnoticed).
pub fn seeds(target: &str) -> Result<Vec<Vec<u8>>, String> {
    let dir = root().join(target);
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|p| p.is_file())
        .collect();
    paths.sort();
    let seeds = paths
        .iter()
        .map(|p| std::fs::read(p).map_err(|e| format!("{}: {e}", p.display())))
        .collect::<Result<Vec<_>, _>>()?;
    if seeds.is_empty() {
        return Err(format!("{}: no seed files", dir.display()));
    }
    Ok(seeds)
}
