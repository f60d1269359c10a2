//! The baked irradiance (and its layers) on disk, named by a BLAKE3 hash of everything the bake reads (geometry,
//! normals, albedo, lights and the bake's version), so a scene is baked once per version and
//! machine. The folder is `baked-lighting/` in [`super::super::cache_root`]. The cache only saves
//! time: a missing or unwritable folder means baking again.

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::Baked;

/// Where baked irradiance is kept, if the environment names a folder.
pub fn folder() -> Option<PathBuf> {
    Some(super::super::cache_root()?.join("baked-lighting"))
}

fn path(folder: &Path, key: &blake3::Hash) -> PathBuf {
    folder.join(format!("{}.bin", key.to_hex()))
}

/// The bake stored under `key`, if it is there with `count` vertices and `layers` layers.
pub fn load(folder: &Path, key: &blake3::Hash, count: usize, layers: usize) -> Option<Baked> {
    let bytes = std::fs::read(path(folder, key)).ok()?;
    if bytes.len() != count * (1 + layers) * 12 {
        return None;
    }
    let mut vectors = bytes.chunks_exact(12).map(|c| {
        let f = |i: usize| f32::from_le_bytes([c[i], c[i + 1], c[i + 2], c[i + 3]]);
        Vec3::new(f(0), f(4), f(8))
    });
    let mut take = || vectors.by_ref().take(count).collect::<Vec<Vec3>>();
    let total = take();
    let layers = (0..layers).map(|_| take()).collect();
    Some(Baked { total, layers })
}

/// Keeps `baked` under `key` (the total, then each layer); failures only cost a bake next time.
pub fn store(folder: &Path, key: &blake3::Hash, baked: &Baked) {
    let path = path(folder, key);
    let bytes: Vec<u8> = std::iter::once(&baked.total)
        .chain(&baked.layers)
        .flatten()
        .flat_map(|e| e.to_array())
        .flat_map(f32::to_le_bytes)
        .collect();
    if std::fs::create_dir_all(folder).is_ok() {
        let _ = rslam_core::dataset::write_atomically(&path, &bytes);
    }
}
