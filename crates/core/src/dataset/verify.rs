//! `rslam verify`: does a finished output still hold what its manifest says it holds?

use std::path::Path;

use crate::dataset::{
    read_frames_deleted, ChecksumDifferences, Checksums, Manifest, CHECKSUM_FILE,
    FRAMES_DELETED_FILE, MANIFEST_FILE,
};
use crate::CoreError;

/// The outcome of checking one output folder.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Verification {
    /// Files the checksum list names.
    pub files: usize,
    /// The manifest's content digest.
    pub digest: String,
    /// Whether the checksum list is the one the manifest's digest stands for.
    pub list_matches_digest: bool,
    pub differences: ChecksumDifferences,
}

impl Verification {
    pub fn is_ok(&self) -> bool {
        self.list_matches_digest && self.differences.is_empty()
    }

    /// One line per problem found.
    pub fn problems(&self) -> Vec<String> {
        let mut lines = Vec::new();
        if !self.list_matches_digest {
            lines.push(format!(
                "{CHECKSUM_FILE}: does not match the content digest in {MANIFEST_FILE}"
            ));
        }
        let d = &self.differences;
        lines.extend(d.changed.iter().map(|f| format!("{f}: content changed")));
        lines.extend(d.missing.iter().map(|f| format!("{f}: missing")));
        lines.extend(
            d.unlisted
                .iter()
                .map(|f| format!("{f}: not part of the output")),
        );
        lines
    }
}

/// Hashes every file of `root` and compares with its checksum list and manifest.
pub fn verify_output(root: &Path) -> Result<Verification, CoreError> {
    if !root.join(MANIFEST_FILE).is_file() {
        return Err(CoreError::bad_file(
            root,
            "no rslam.json: not a finished rslam output (an interrupted run resumes when run again)",
        ));
    }
    if let Some(deleted) = read_frames_deleted(root)? {
        return Err(CoreError::bad_file(
            root.join(FRAMES_DELETED_FILE),
            format!(
                "its {} frames were deleted after use (`rslam suite bench --ephemeral`); `rslam suite regen SUITE NAME` remakes them, then verify",
                deleted.files
            ),
        ));
    }
    let manifest = Manifest::read(root)?;
    if manifest.content_digest.is_empty() {
        return Err(CoreError::bad_file(
            root.join(MANIFEST_FILE),
            "no content_digest: written by an rslam version without checksums",
        ));
    }
    let listed = Checksums::read(root)?;
    let actual = Checksums::complete(root, Checksums::default())?;
    Ok(Verification {
        files: listed.len(),
        list_matches_digest: listed.digest() == manifest.content_digest,
        digest: manifest.content_digest,
        differences: listed.compare(&actual),
    })
}
