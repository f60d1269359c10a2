//! Reads and decodes every PNG of a folder, then encodes and writes it again with rslam's own
//! PNG codec, frames spread over all cores: the pure decode + encode cost, the I/O limit that
//! `rslam perturb` of a folder of PNG frames cannot go below (`scripts/bench-corruptions.sh`
//! sets it beside the corruptions).
//!
//! cargo run --release -p rslam-core --example png_roundtrip -- IN_DIR OUT_DIR

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use rslam_core::dataset::{encode_png, read_rgb};

fn roundtrip(file: &Path, out: &Path) -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    let image = read_rgb(file)?;
    let name = file.file_name().ok_or("a file without a name")?;
    let target = out.join(name);
    std::fs::write(&target, encode_png(&image)?)
        .map_err(|e| format!("{}: {e}", target.display()))?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [input, out] = args.as_slice() else {
        return Err("usage: png_roundtrip IN_DIR OUT_DIR".into());
    };
    let mut files: Vec<PathBuf> = std::fs::read_dir(input)
        .map_err(|e| format!("{input}: {e}"))?
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "png"))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(format!("{input}: no .png files").into());
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{out}: {e}"))?;
    files
        .par_iter()
        .try_for_each(|file| roundtrip(file, Path::new(out)))
}
