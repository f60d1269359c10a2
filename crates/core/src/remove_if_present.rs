//! Removing what an earlier run may or may not have left.

use std::path::Path;

use crate::CoreError;

/// Removes the file or folder (with everything in it) at `path`; nothing there is no error. A
/// symbolic link is removed itself, never what it points to.
pub fn remove_if_present(path: &Path) -> Result<(), CoreError> {
    let removed = match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => Err(e),
        Ok(meta) if meta.is_dir() => std::fs::remove_dir_all(path),
        Ok(_) => std::fs::remove_file(path),
    };
    removed.map_err(|e| CoreError::io(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_and_folders_go_and_nothing_there_is_fine() {
        let dir = tempfile::tempdir().unwrap();
        let (file, folder) = (dir.path().join("f"), dir.path().join("d"));
        std::fs::write(&file, "x").unwrap();
        std::fs::create_dir_all(folder.join("inner")).unwrap();
        std::fs::write(folder.join("inner/g"), "y").unwrap();
        for path in [&file, &folder, &file] {
            remove_if_present(path).unwrap();
            assert!(!path.exists());
        }
    }
}
