//! Bytes on disk: what a folder holds, what its file system has free, and how to print it.

use std::path::Path;

use crate::SuiteError;

/// Summed size of the files under `dir` (0 when it does not exist).
pub fn folder_bytes(dir: &Path) -> Result<u64, SuiteError> {
    let mut total = 0;
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        let entries = match std::fs::read_dir(&dir) {
            Ok(entries) => entries,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => continue,
            Err(e) => return Err(SuiteError::io(&dir, e)),
        };
        for entry in entries {
            let entry = entry.map_err(|e| SuiteError::io(&dir, e))?;
            let meta = entry
                .metadata()
                .map_err(|e| SuiteError::io(entry.path(), e))?;
            if meta.is_dir() {
                pending.push(entry.path());
            } else {
                total += meta.len();
            }
        }
    }
    Ok(total)
}

/// Free bytes for an unprivileged user on the file system that holds `path` (or its nearest
/// existing ancestor).
pub fn available_bytes(path: &Path) -> Result<u64, SuiteError> {
    let existing = path
        .ancestors()
        .find(|p| p.exists())
        .unwrap_or(Path::new("."));
    fs4::available_space(existing).map_err(|e| SuiteError::io(existing, e))
}

/// `1.23 GB` (decimal units, like `df -H`).
pub fn format_bytes(bytes: u64) -> String {
    const UNITS: [&str; 5] = ["B", "kB", "MB", "GB", "TB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1000.0 && unit + 1 < UNITS.len() {
        value /= 1000.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} B")
    } else {
        format!("{value:.2} {}", UNITS[unit])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_print_in_decimal_units() {
        assert_eq!(format_bytes(999), "999 B");
        assert_eq!(format_bytes(2_100_000_000), "2.10 GB");
        assert_eq!(format_bytes(730_000), "730.00 kB");
    }

    #[test]
    fn a_folder_counts_every_file_below_it() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("a/b")).unwrap();
        std::fs::write(dir.path().join("a/b/x"), [0u8; 100]).unwrap();
        std::fs::write(dir.path().join("y"), [0u8; 23]).unwrap();
        assert_eq!(folder_bytes(dir.path()).unwrap(), 123);
        assert_eq!(folder_bytes(&dir.path().join("none")).unwrap(), 0);
        assert!(available_bytes(&dir.path().join("not/yet")).unwrap() > 0);
    }
}
