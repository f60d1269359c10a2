//! The one life of every output folder ([`make_output`]): prepared for a job, skipped when that
//! job finished there, written, then marked finished. What the folder already holds decides what
//! a run does with it. A run writes its job (the manifest without the content digest) as
//! `rslam.run.json` before the first frame and removes it after `rslam.json`: the same job finds
//! its frames and goes on, another job is refused unless `force` starts over, and a folder that
//! is not rslam's is never touched. What a folder holds for a job ([`holding`]) is decided in one
//! place, for a run and for the suite.

use std::path::Path;

use rslam_core::dataset::{
    read_frames_deleted, refuse_symlinks, Checksums, Manifest, CHECKSUM_FILE, FRAMES_DELETED_FILE,
    MANIFEST_FILE, PARTIAL_SUFFIX, RUN_FILE,
};
use rslam_core::{remove_if_present, CoreError};

use crate::PipelineError;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FolderState {
    /// Nothing there yet.
    Fresh,
    /// An unfinished run of the same job: its complete files stay.
    Resume,
    /// The same job finished here already, every file it listed is there.
    Complete,
}

impl FolderState {
    /// Whether a run keeps the frames an unfinished run of the same job left: only when resuming,
    /// and not when an item carries a state from frame to frame (auto_exposure), whose every
    /// frame follows from the ones before it, so that the run makes them all again.
    pub fn keeps_written_frames(self, carries_state: bool) -> bool {
        self == FolderState::Resume && !carries_state
    }
}

/// What a run of a job found in its output folder and did there.
#[derive(Clone, Debug, PartialEq)]
pub struct Made {
    /// What the output folder held when the run began.
    pub found: FolderState,
    /// Source frames drawn (or perturbed, or copied) by this run: fewer than the output holds
    /// when it resumed, none when the folder was complete already.
    pub made: usize,
    /// The manifest as written (as found, when the folder was complete already).
    pub manifest: Manifest,
}

/// What a job writes into its output folder once it is prepared: given what the folder held
/// (`Fresh` or `Resume`) and the job's manifest to finish, the frames it made and the manifest
/// it wrote last.
pub struct Written {
    pub made: usize,
    pub manifest: Manifest,
}

/// The life of `out` for `job` (the manifest without its content digest): prepared (refused if
/// it holds another job's output and not `force`), left as it is when the same job finished
/// there, else written by `write`, then marked finished.
pub fn make_output(
    out: &Path,
    job: Manifest,
    force: bool,
    write: impl FnOnce(FolderState, Manifest) -> Result<Written, PipelineError>,
) -> Result<Made, PipelineError> {
    let found = prepare(out, &job, force)?;
    if found == FolderState::Complete {
        return Ok(Made {
            found,
            made: 0,
            manifest: Manifest::read(out)?,
        });
    }
    let written = write(found, job)?;
    finish(out)?;
    Ok(Made {
        found,
        made: written.made,
        manifest: written.manifest,
    })
}

/// What an output folder holds, seen from one job, read without changing anything: the one rule
/// for "this job's output is finished here", which a run ([`make_output`]) and the suite both
/// ask.
#[derive(Debug)]
pub enum Holding {
    /// No folder, or an empty one.
    Nothing,
    /// An unfinished run of this job: the files it finished stay.
    Unfinished,
    /// This job, finished: its checksum list is the one its manifest sealed, and every file the
    /// list names is there.
    Complete,
    /// This job finished here once, but `why` (files it listed are gone, its checksum list was
    /// changed): a run makes what is missing and seals it again.
    Broken(String),
    /// This job finished here once and its frames were deleted after use, the rest kept
    /// ([`rslam_core::dataset::delete_frames`]): a run makes them again and seals it again.
    FramesDeleted,
    /// Another job's output: `finished` or an unfinished run, `what` it is and how it differs
    /// from this job.
    OtherJob { finished: bool, what: String },
    /// An rslam record (`rslam.json`, `rslam.run.json`) that cannot be read.
    Unreadable(CoreError),
    /// Files, but no rslam record: not rslam's output.
    NotRslam,
}

/// What `root` holds for the job `job` gives (a manifest without its content digest; `command`
/// and the digest are not part of what a job is), asked for only when `root` holds a record to
/// compare it with, and given that record.
pub fn holding(
    root: &Path,
    job: impl FnOnce(&Manifest) -> Result<Manifest, PipelineError>,
) -> Result<Holding, PipelineError> {
    if !root.exists() || is_empty(root)? {
        return Ok(Holding::Nothing);
    }
    let (record, finished) = if root.join(RUN_FILE).is_file() {
        (RUN_FILE, false)
    } else if root.join(MANIFEST_FILE).is_file() {
        (MANIFEST_FILE, true)
    } else {
        return Ok(Holding::NotRslam);
    };
    let earlier = match Manifest::read_as(root, record) {
        Ok(earlier) => earlier,
        Err(e) => return Ok(Holding::Unreadable(e)),
    };
    let job = job(&earlier)?;
    Ok(match (earlier.job() == job.job(), finished) {
        (false, _) => Holding::OtherJob {
            finished,
            what: describe_other(&earlier, &job, finished),
        },
        (true, false) => Holding::Unfinished,
        (true, true) => match read_frames_deleted(root) {
            Err(e) => Holding::Unreadable(e),
            Ok(Some(_)) => Holding::FramesDeleted,
            Ok(None) => match sealed_files(root, &earlier) {
                Ok(()) => Holding::Complete,
                Err(why) => Holding::Broken(why),
            },
        },
    })
}

/// Prepares `root` for `job` and says what it holds.
fn prepare(root: &Path, job: &Manifest, force: bool) -> Result<FolderState, PipelineError> {
    refuse_symlinks(root, root)?;
    let state = match holding(root, |_| Ok(job.clone()))? {
        Holding::Nothing => FolderState::Fresh,
        Holding::NotRslam => {
            return Err(PipelineError::output(
                root,
                "not empty and holds no rslam output (rslam.json or rslam.run.json); choose an empty or new folder",
            ))
        }
        _ if force => clear(root)?,
        Holding::Complete => return Ok(FolderState::Complete),
        Holding::Unfinished => FolderState::Resume,
        Holding::Broken(_) | Holding::FramesDeleted => {
            // The run record first: killed at any point after it, the folder is an unfinished
            // run of this job, never a folder without a record.
            job.job().write_as(root, RUN_FILE)?;
            for name in [FRAMES_DELETED_FILE, MANIFEST_FILE] {
                remove_if_present(&root.join(name))?;
            }
            FolderState::Resume
        }
        Holding::OtherJob { what, .. } => {
            return Err(PipelineError::OtherJob {
                path: root.to_path_buf(),
                holds: what,
            })
        }
        Holding::Unreadable(e) => return Err(e.into()),
    };
    std::fs::create_dir_all(root).map_err(|e| CoreError::io(root, e))?;
    remove_partial_files(root)?;
    job.job().write_as(root, RUN_FILE)?;
    Ok(state)
}

/// Refuses an output folder that is the input itself: forcing would delete what is being read.
pub fn check_not_input(out: &Path, input: &Path) -> Result<(), PipelineError> {
    match (out.canonicalize(), input.canonicalize()) {
        (Ok(out_path), Ok(input_path)) if out_path == input_path => Err(PipelineError::output(
            out,
            "is the input itself; write the perturbed copy to another folder",
        )),
        _ => Ok(()),
    }
}

/// Marks the run finished: called after the manifest is written.
fn finish(root: &Path) -> Result<(), PipelineError> {
    let path = root.join(RUN_FILE);
    std::fs::remove_file(&path).map_err(|e| CoreError::io(&path, e))?;
    Ok(())
}

/// Another job's record, as an error or the suite names it: its command, perturbation, seed and
/// the fields in which it differs from `job`.
fn describe_other(earlier: &Manifest, job: &Manifest, finished: bool) -> String {
    let what = match finished {
        true => "the finished output",
        false => "an unfinished run",
    };
    format!(
        "{what} of another job (`{}`, perturbation '{}', seed {}; differs in {})",
        earlier.command.join(" "),
        earlier.perturbation,
        earlier.seed,
        differing_fields(&earlier.job(), &job.job()).join(", ")
    )
}

/// The manifest fields (`extra.adapter` and the like one level down) in which two jobs differ,
/// fields only one of them has included (a job of an older rslam lacks the newer ones).
pub fn differing_fields(a: &Manifest, b: &Manifest) -> Vec<String> {
    let (Ok(serde_json::Value::Object(a)), Ok(serde_json::Value::Object(b))) =
        (serde_json::to_value(a), serde_json::to_value(b))
    else {
        return Vec::new();
    };
    let mut fields = Vec::new();
    for key in union_of_keys(&a, &b) {
        match (a.get(key), b.get(key)) {
            (Some(serde_json::Value::Object(inner)), Some(serde_json::Value::Object(other))) => {
                fields.extend(
                    union_of_keys(inner, other)
                        .filter(|k| inner.get(*k) != other.get(*k))
                        .map(|k| format!("{key}.{k}")),
                );
            }
            (value, other) if value != other => fields.push(key.clone()),
            _ => {}
        }
    }
    fields
}

/// The keys of `a`, then those only `b` has.
fn union_of_keys<'a>(
    a: &'a serde_json::Map<String, serde_json::Value>,
    b: &'a serde_json::Map<String, serde_json::Value>,
) -> impl Iterator<Item = &'a String> {
    a.keys().chain(b.keys().filter(|k| !a.contains_key(*k)))
}

fn is_empty(root: &Path) -> Result<bool, PipelineError> {
    let mut entries = std::fs::read_dir(root).map_err(|e| CoreError::io(root, e))?;
    Ok(entries.next().is_none())
}

/// Whether the checksum list is the one `manifest` sealed and every file it names is there
/// (the files' bytes are not hashed again: `rslam verify` does that).
fn sealed_files(root: &Path, manifest: &Manifest) -> Result<(), String> {
    let listed = Checksums::read(root).map_err(|e| e.to_string())?;
    if listed.digest() != manifest.content_digest {
        return Err(format!(
            "{CHECKSUM_FILE} does not match the manifest's content_digest"
        ));
    }
    let missing = listed.paths().find(|p| !root.join(p).is_file());
    match missing {
        Some(missing) => Err(format!("{missing}, which {CHECKSUM_FILE} lists, is gone")),
        None => Ok(()),
    }
}

/// Removes everything in `root`, an earlier rslam output.
fn clear(root: &Path) -> Result<FolderState, PipelineError> {
    for entry in std::fs::read_dir(root).map_err(|e| CoreError::io(root, e))? {
        let path = entry.map_err(|e| CoreError::io(root, e))?.path();
        let removed = if path.is_dir() {
            std::fs::remove_dir_all(&path)
        } else {
            std::fs::remove_file(&path)
        };
        removed.map_err(|e| CoreError::io(&path, e))?;
    }
    Ok(FolderState::Fresh)
}

/// A file cut off mid-write keeps its temporary name: it is redone, never used.
fn remove_partial_files(root: &Path) -> Result<(), PipelineError> {
    let mut pending = vec![root.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(&dir).map_err(|e| CoreError::io(&dir, e))? {
            let path = entry.map_err(|e| CoreError::io(&dir, e))?.path();
            if path.is_dir() {
                pending.push(path);
            } else if path.to_string_lossy().ends_with(PARTIAL_SUFFIX) {
                std::fs::remove_file(&path).map_err(|e| CoreError::io(&path, e))?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job() -> Manifest {
        serde_json::from_value(serde_json::json!({
            "tool": "rslam", "tool_version": "0.1.0", "command": [], "source": "room0",
            "source_hash": "", "format": "replica", "camera": null, "rate_hz": 20.0,
            "frame_count": 0, "seed": 0, "perturbation": "", "perturbation_parsed": null,
            "severities": [], "rgb_source": [], "depth_source": [], "extra": null
        }))
        .unwrap()
    }

    /// A link planted in an output folder would take frames, or the clean-up of partial files,
    /// outside it: the folder is refused, forced or not, and nothing outside changes.
    #[test]
    fn an_output_folder_holding_a_symlink_is_refused_and_nothing_outside_is_touched() {
        let out = tempfile::tempdir().unwrap();
        let elsewhere = tempfile::tempdir().unwrap();
        let victim = elsewhere.path().join("notes.partial");
        std::fs::write(&victim, "keep me").unwrap();
        let root = out.path().join("fog3");
        std::fs::create_dir(&root).unwrap();
        job().write_as(&root, RUN_FILE).unwrap();
        std::os::unix::fs::symlink(elsewhere.path(), root.join("results")).unwrap();
        for force in [false, true] {
            let err = prepare(&root, &job(), force).unwrap_err().to_string();
            assert!(
                err.contains("results: is a symbolic link inside the output folder"),
                "{err}"
            );
        }
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep me");
        assert_eq!(std::fs::read_dir(elsewhere.path()).unwrap().count(), 1);
    }

    /// An output of an older rslam lacked fields the job has now; the refusal said "differs in )".
    #[test]
    fn fields_only_one_job_has_are_named_as_differing() {
        let mut older = serde_json::to_value(job()).unwrap();
        older["extra"] = serde_json::json!({"adapter": "a"});
        let mut newer = older.clone();
        newer["extra"]["rig"] = "rgbd-imu".into();
        let older: Manifest = serde_json::from_value(older).unwrap();
        let newer: Manifest = serde_json::from_value(newer).unwrap();
        assert_eq!(differing_fields(&older, &newer), ["extra.rig"]);
        assert_eq!(differing_fields(&newer, &older), ["extra.rig"]);
        assert!(differing_fields(&newer, &newer).is_empty());
    }
}
