//! Files that appear whole or not at all: written under a temporary name, then renamed. A run
//! killed mid-write leaves only the temporary name, which the next run removes.

use std::path::{Path, PathBuf};

use crate::dataset::PARTIAL_SUFFIX;
use crate::CoreError;

pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), CoreError> {
    let mut partial = PathBuf::from(path.as_os_str());
    partial.as_mut_os_string().push(PARTIAL_SUFFIX);
    std::fs::write(&partial, bytes).map_err(|e| CoreError::io(&partial, e))?;
    std::fs::rename(&partial, path).map_err(|e| CoreError::io(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_file_is_whole_and_no_temporary_stays() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.json");
        write_atomically(&path, b"first").unwrap();
        write_atomically(&path, b"second").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}
