//! `rslam suite regen`: remakes one sequence's frames from the job its kept manifest records
//! (the suite row must still define that job: it is compared field by field, not replayed from
//! the recorded command line), then compares what was made with the kept checksum list, so that
//! a reviewer can look at the exact frames behind any number of a report.
//!
//! Bytes are reproducible for the same rslam version on the same adapter. Made by another
//! version or on another GPU (whose float rounding differs), the sequence is still remade, the
//! makers are named, and the files that differ are listed; the earlier checksum list is then
//! kept beside the dataset as `<name>.earlier.b3sum`.

use std::path::PathBuf;

use rslam_core::dataset::{ChecksumDifferences, Checksums, Manifest, CHECKSUM_FILE, MANIFEST_FILE};
use rslam_gpu::GpuContext;
use rslam_pipeline::output_folder::differing_fields;
use rslam_pipeline::SceneCache;

use crate::run::{lock, make_sequence, Replace, SuiteProgress};
use crate::sequence::DATASETS_DIR;
use crate::{Suite, SuiteError};

/// Which rslam on which adapter made a dataset.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Maker {
    pub version: String,
    pub adapter: String,
}

impl std::fmt::Display for Maker {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "rslam {} on {}", self.version, self.adapter)
    }
}

#[derive(Clone, Debug)]
pub struct Regenerated {
    pub dir: PathBuf,
    /// Files the kept checksum list names.
    pub files: usize,
    pub made_by: Maker,
    pub remade_by: Maker,
    /// The remade files against the kept checksum list: empty when every byte is the same.
    pub differences: ChecksumDifferences,
    /// Where the kept list went when the remade files differ from it.
    pub earlier_list: Option<PathBuf>,
}

/// Remakes sequence `name` of `suite` on `ctx`.
pub fn regen(
    ctx: &GpuContext,
    suite: &Suite,
    name: &str,
    progress: &dyn SuiteProgress,
) -> Result<Regenerated, SuiteError> {
    let Some(sequence) = suite.sequences.iter().find(|s| s.name == name) else {
        return Err(SuiteError::option(
            "NAME",
            format!("'{name}' is no sequence of {}", suite.dir.display()),
        ));
    };
    let dir = sequence.dir(&suite.dir);
    if !dir.join(MANIFEST_FILE).is_file() {
        return Err(SuiteError::option(
            "NAME",
            format!(
                "{} holds no finished dataset (no {MANIFEST_FILE}): there is nothing to remake; `rslam suite run` or `suite bench --ephemeral` makes it",
                dir.display()
            ),
        ));
    }
    let Some(_lock) = lock(&suite.dir, name)? else {
        return Err(SuiteError::option(
            "NAME",
            format!("'{name}' is being made or run by another process"),
        ));
    };
    let kept = Manifest::read(&dir)?;
    let kept_list = Checksums::read(&dir)?;
    let scenes = SceneCache::default();
    let made_by = Maker {
        version: kept.tool_version.clone(),
        adapter: kept.extra["adapter"].as_str().unwrap_or("").to_string(),
    };
    let ours = sequence
        .job(&suite.dir, false)
        .manifest_on(&ctx.describe(), &scenes)?;
    let remade_by = Maker {
        version: ours.tool_version.clone(),
        adapter: ctx.describe(),
    };
    let mut as_kept = ours;
    as_kept.tool_version = made_by.version.clone();
    as_kept.extra["adapter"] = made_by.adapter.clone().into();
    if as_kept.job() != kept.job() {
        return Err(SuiteError::option(
            "NAME",
            format!(
                "the row of '{name}' in suite.toml no longer defines the job its kept manifest records (they differ in {}): regen remakes only that job",
                differing_fields(&kept.job(), &as_kept.job()).join(", ")
            ),
        ));
    }
    // Another maker's output is another job's: it starts over.
    let replace = match made_by == remade_by {
        true => Replace::Nothing,
        false => Replace::Anything,
    };
    make_sequence(ctx, suite, sequence, &dir, replace, &scenes, progress)?;
    let remade_list = Checksums::read(&dir)?;
    let differences = kept_list.compare(&remade_list);
    let earlier_list = if differences.is_empty() {
        None
    } else {
        let path = suite
            .dir
            .join(DATASETS_DIR)
            .join(format!("{name}.earlier.b3sum"));
        std::fs::write(&path, kept_list.text()).map_err(|e| SuiteError::io(&path, e))?;
        Some(path)
    };
    Ok(Regenerated {
        files: kept_list.len(),
        dir,
        made_by,
        remade_by,
        differences,
        earlier_list,
    })
}

impl Regenerated {
    /// One line per file that differs from the kept list, naming the list.
    pub fn problems(&self) -> Vec<String> {
        let d = &self.differences;
        let changed = d
            .changed
            .iter()
            .map(|f| format!("{f}: other bytes than {CHECKSUM_FILE} kept"));
        let missing = d
            .missing
            .iter()
            .map(|f| format!("{f}: kept in the list, not remade"));
        let unlisted = d
            .unlisted
            .iter()
            .map(|f| format!("{f}: remade, not in the kept list"));
        changed.chain(missing).chain(unlisted).collect()
    }
}
