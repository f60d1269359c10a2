//! Names the built-in scenes' texture generator for the texture cache
//! (src/scene/builtin/textures/cache.rs): a hash of every source file the textures are made by,
//! so that a changed generator never reads textures an older one made. (std's SipHash with its
//! fixed keys: the name only has to differ between sources, and no build dependency is needed.)

use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

const SOURCES: [&str; 2] = ["src/scene/builtin", "../core/src/hash.rs"];

fn main() {
    let mut files = Vec::new();
    for source in SOURCES {
        println!("cargo:rerun-if-changed={source}");
        collect(Path::new(source), &mut files);
    }
    files.sort();
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    for file in &files {
        let bytes = std::fs::read(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        file.hash(&mut hasher);
        bytes.hash(&mut hasher);
    }
    println!(
        "cargo:rustc-env=RSLAM_TEXTURE_GENERATOR={:016x}",
        hasher.finish()
    );
}

/// The `.rs` files at `path`, a file or a folder searched through; a path that is not there (a
/// crate packaged without its workspace) adds nothing.
fn collect(path: &Path, files: &mut Vec<PathBuf>) {
    if path.is_dir() {
        let entries = std::fs::read_dir(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for entry in entries {
            collect(&entry.expect("a directory entry").path(), files);
        }
    } else if path.is_file() && path.extension().is_some_and(|e| e == "rs") {
        files.push(path.to_path_buf());
    }
}
