//! BLAKE3 checksums of every file of a generated dataset, in `b3sum`'s format
//! (`<hex>  <relative path>`), so a dataset can be checked later by `rslam verify` or by the
//! standalone `b3sum --check rslam.b3sum`. The manifest records the BLAKE3 of this list: one
//! digest stands for the whole dataset.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use rayon::prelude::*;

use crate::dataset::{write_atomically, Manifest, FRAMES_DELETED_FILE, MANIFEST_FILE};
use crate::{read_text_file, CoreError};

/// The checksum list beside the manifest.
pub const CHECKSUM_FILE: &str = "rslam.b3sum";

/// Files of an output folder that no checksum covers: the manifest and the checksum list name
/// the content, the run record marks a run in progress, the frames-deleted record a folder
/// whose frames went after use, partial files are never content.
pub fn is_bookkeeping(relative: &str) -> bool {
    relative == MANIFEST_FILE
        || relative == CHECKSUM_FILE
        || relative == RUN_FILE
        || relative == FRAMES_DELETED_FILE
        || relative.ends_with(PARTIAL_SUFFIX)
}

/// Whether a relative path written in a dataset file stays inside the dataset: no root, no
/// drive, no `..`.
pub fn is_inside(relative: &str) -> bool {
    Path::new(relative).components().all(|c| {
        matches!(
            c,
            std::path::Component::Normal(_) | std::path::Component::CurDir
        )
    })
}

/// Written first and removed last by a run: a folder holding it is an unfinished run.
pub const RUN_FILE: &str = "rslam.run.json";

/// Suffix of a file being written; renamed to its final name once complete.
pub const PARTIAL_SUFFIX: &str = ".partial";

/// Relative path (with `/`) → BLAKE3 hex, sorted by path.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Checksums {
    entries: BTreeMap<String, String>,
}

pub fn blake3_hex(bytes: &[u8]) -> String {
    blake3::hash(bytes).to_hex().to_string()
}

fn hash_file(path: &Path) -> Result<String, CoreError> {
    let mut hasher = blake3::Hasher::new();
    hasher
        .update_mmap_rayon(path)
        .map_err(|e| CoreError::io(path, e))?;
    Ok(hasher.finalize().to_hex().to_string())
}

impl Checksums {
    pub fn insert(&mut self, relative: String, hex: String) {
        self.entries.insert(relative, hex);
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// The relative paths listed, sorted.
    pub fn paths(&self) -> impl Iterator<Item = &str> {
        self.entries.keys().map(String::as_str)
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Hashes every content file under `root` (see [`is_bookkeeping`]) that `known` does not
    /// already hold, reading them in parallel; `known` entries for files that no longer exist
    /// are dropped.
    pub fn complete(root: &Path, known: Checksums) -> Result<Self, CoreError> {
        let files = content_files(root)?;
        let hashed: Vec<(String, String)> = files
            .par_iter()
            .map(|relative| {
                let hex = match known.entries.get(relative) {
                    Some(hex) => hex.clone(),
                    None => hash_file(&root.join(relative))?,
                };
                Ok((relative.clone(), hex))
            })
            .collect::<Result<_, CoreError>>()?;
        Ok(Self {
            entries: hashed.into_iter().collect(),
        })
    }

    /// The `b3sum` text: one `<hex>  <path>` line per file.
    pub fn text(&self) -> String {
        self.entries
            .iter()
            .map(|(path, hex)| format!("{hex}  {path}\n"))
            .collect()
    }

    /// The digest of the whole dataset: BLAKE3 of [`Checksums::text`].
    pub fn digest(&self) -> String {
        blake3_hex(self.text().as_bytes())
    }

    pub fn parse(path: &Path, text: &str) -> Result<Self, CoreError> {
        let mut entries = BTreeMap::new();
        for (i, line) in text.lines().enumerate() {
            let parsed = line.split_once("  ").filter(|(hex, name)| {
                hex.len() == 64 && hex.bytes().all(|b| b.is_ascii_hexdigit()) && !name.is_empty()
            });
            let bad = |message: &str| CoreError::BadLine {
                path: path.to_path_buf(),
                line: i + 1,
                message: message.into(),
            };
            let Some((hex, name)) = parsed else {
                return Err(bad("expected '<64 hex digits>  <file>' (b3sum format)"));
            };
            if !is_inside(name) {
                return Err(bad(
                    "expected a path relative to the dataset, without '..' (b3sum format)",
                ));
            }
            entries.insert(name.to_string(), hex.to_string());
        }
        Ok(Self { entries })
    }

    pub fn read(root: &Path) -> Result<Self, CoreError> {
        let path = root.join(CHECKSUM_FILE);
        let text = read_text_file(&path, "b3sum lines")?;
        Self::parse(&path, &text)
    }

    fn write(&self, root: &Path) -> Result<(), CoreError> {
        let path = root.join(CHECKSUM_FILE);
        std::fs::write(&path, self.text()).map_err(|e| CoreError::io(&path, e))
    }

    /// Files whose recorded hash differs from `actual`'s, files missing from `actual`, and files
    /// `actual` has that this list does not.
    pub fn compare(&self, actual: &Checksums) -> ChecksumDifferences {
        let mut differences = ChecksumDifferences::default();
        for (path, hex) in &self.entries {
            match actual.entries.get(path) {
                None => differences.missing.push(path.clone()),
                Some(other) if other != hex => differences.changed.push(path.clone()),
                Some(_) => {}
            }
        }
        differences.unlisted = actual
            .entries
            .keys()
            .filter(|path| !self.entries.contains_key(*path))
            .cloned()
            .collect();
        differences
    }
}

/// Writes the content files of one output folder from many threads (`&self`), each through a
/// temporary name and a rename so that no reader sees half a file, hashing each on the way.
pub struct ContentWriter {
    root: PathBuf,
    written: Mutex<Checksums>,
}

impl ContentWriter {
    pub fn new(root: &Path) -> Self {
        Self {
            root: root.to_path_buf(),
            written: Mutex::new(Checksums::default()),
        }
    }

    pub fn root(&self) -> &Path {
        &self.root
    }

    /// Writes `bytes` to `root/relative` (relative with `/`).
    pub fn write(&self, relative: &str, bytes: &[u8]) -> Result<(), CoreError> {
        write_atomically(&self.root.join(relative), bytes)?;
        self.record(relative, blake3_hex(bytes));
        Ok(())
    }

    /// Records the checksum of a content file written whole by someone else, hashed as it was
    /// written.
    pub fn record(&self, relative: &str, blake3_hex: String) {
        self.written
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .insert(relative.to_string(), blake3_hex);
    }

    /// The checksum list of every content file (those an earlier, interrupted run wrote are
    /// hashed now), then `manifest` with the content digest, last. Returns the manifest written.
    pub fn finish(self, mut manifest: Manifest) -> Result<Manifest, CoreError> {
        let written = self.written.into_inner().unwrap_or_else(|p| p.into_inner());
        let checksums = Checksums::complete(&self.root, written)?;
        checksums.write(&self.root)?;
        manifest.content_digest = checksums.digest();
        manifest.write(&self.root)?;
        Ok(manifest)
    }
}

#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ChecksumDifferences {
    pub changed: Vec<String>,
    pub missing: Vec<String>,
    pub unlisted: Vec<String>,
}

impl ChecksumDifferences {
    pub fn is_empty(&self) -> bool {
        self.changed.is_empty() && self.missing.is_empty() && self.unlisted.is_empty()
    }
}

/// Every content file under `root`, as sorted relative paths with `/`.
pub fn content_files(root: &Path) -> Result<Vec<String>, CoreError> {
    let mut files = Vec::new();
    let mut pending: Vec<PathBuf> = vec![root.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(&dir).map_err(|e| CoreError::io(&dir, e))? {
            let path = entry.map_err(|e| CoreError::io(&dir, e))?.path();
            if path.is_dir() {
                pending.push(path);
                continue;
            }
            let relative = path
                .strip_prefix(root)
                .map_err(|_| CoreError::bad_file(&path, "outside the dataset folder"))?
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect::<Vec<_>>()
                .join("/");
            if !is_bookkeeping(&relative) {
                files.push(relative);
            }
        }
    }
    files.sort();
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blake3_matches_the_published_empty_input_vector() {
        assert_eq!(
            blake3_hex(b""),
            "af1349b9f5f9a1a6a0404dea36dcc9499bcb25c9adc112b7cc9a93cae41f3262"
        );
    }

    #[test]
    fn lists_round_trip_and_differences_name_each_file() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path();
        std::fs::create_dir_all(root.join("rgb")).unwrap();
        std::fs::write(root.join("rgb/a.png"), b"a").unwrap();
        std::fs::write(root.join("b.txt"), b"b").unwrap();
        std::fs::write(root.join(MANIFEST_FILE), b"{}").unwrap();
        std::fs::write(root.join("rgb/c.png.partial"), b"half").unwrap();
        let sums = Checksums::complete(root, Checksums::default()).unwrap();
        assert_eq!(
            sums.len(),
            2,
            "bookkeeping and partial files are not content"
        );
        let text = sums.text();
        assert_eq!(
            text,
            format!(
                "{}  b.txt\n{}  rgb/a.png\n",
                blake3_hex(b"b"),
                blake3_hex(b"a")
            )
        );
        assert_eq!(Checksums::parse(Path::new("x"), &text).unwrap(), sums);

        std::fs::write(root.join("rgb/a.png"), b"A").unwrap();
        std::fs::remove_file(root.join("b.txt")).unwrap();
        std::fs::write(root.join("new.txt"), b"n").unwrap();
        let now = Checksums::complete(root, Checksums::default()).unwrap();
        let differences = sums.compare(&now);
        assert_eq!(differences.changed, vec!["rgb/a.png"]);
        assert_eq!(differences.missing, vec!["b.txt"]);
        assert_eq!(differences.unlisted, vec!["new.txt"]);
    }

    #[test]
    fn known_hashes_are_reused_and_malformed_lines_name_the_line() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("f"), b"x").unwrap();
        let mut known = Checksums::default();
        known.insert("f".into(), "0".repeat(64));
        let sums = Checksums::complete(dir.path(), known).unwrap();
        assert_eq!(sums.entries["f"], "0".repeat(64));
        let error = Checksums::parse(Path::new("sums"), "abc  f\n").unwrap_err();
        assert!(error.to_string().starts_with("sums:1:"), "{error}");
    }
}
