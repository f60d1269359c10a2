//! The baked irradiance on disk, named by a BLAKE3 hash of everything the bake reads (geometry,
//! normals, albedo, lights and the bake's version), so a scene is baked once per version and
//! machine. The folder is `baked-lighting/` in [`super::super::cache_root`]. The cache only saves
//! time: a missing or unwritable folder means baking again.

use std::path::{Path, PathBuf};

use glam::Vec3;

/// Where baked irradiance is kept, if the environment names a folder.
pub fn folder() -> Option<PathBuf> {
    Some(super::super::cache_root()?.join("baked-lighting"))
}

fn path(folder: &Path, key: &blake3::Hash) -> PathBuf {
    folder.join(format!("{}.bin", key.to_hex()))
}

/// The irradiance stored under `key`, if it is there and has `count` vertices.
pub fn load(folder: &Path, key: &blake3::Hash, count: usize) -> Option<Vec<Vec3>> {
    let bytes = std::fs::read(path(folder, key)).ok()?;
    if bytes.len() != count * 12 {
        return None;
    }
    Some(
        bytes
            .chunks_exact(12)
            .map(|c| {
                let f = |i: usize| f32::from_le_bytes([c[i], c[i + 1], c[i + 2], c[i + 3]]);
                Vec3::new(f(0), f(4), f(8))
            })
            .collect(),
    )
}

/// Keeps `irradiance` under `key`; failures only cost a bake next time.
pub fn store(folder: &Path, key: &blake3::Hash, irradiance: &[Vec3]) {
    let path = path(folder, key);
    let bytes: Vec<u8> = irradiance
        .iter()
        .flat_map(|e| e.to_array())
        .flat_map(f32::to_le_bytes)
        .collect();
    if std::fs::create_dir_all(folder).is_ok() {
        let _ = rslam_core::dataset::write_atomically(&path, &bytes);
    }
}
