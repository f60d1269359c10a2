//! A finished output whose frames were deleted after use (`rslam suite bench --ephemeral`): the
//! manifest, the checksum list and every file that is not a frame (ground truth, camera files,
//! timestamps, IMU samples) stay, with `rslam.frames-deleted.json` saying how much went. The
//! frames are remade from the manifest's job (`rslam suite regen`) and checked against the kept
//! checksum list.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::dataset::{write_atomically, Checksums, Manifest, CHECKSUM_FILE, MANIFEST_FILE};
use crate::{remove_if_present, CoreError};

/// Written before the first frame is deleted: a folder holding it is missing its frames on
/// purpose.
pub const FRAMES_DELETED_FILE: &str = "rslam.frames-deleted.json";

/// What was deleted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct FramesDeleted {
    pub files: usize,
    pub bytes: u64,
}

/// Frames are the image files of every layout (colour and depth, each rig camera's); what a
/// layout writes besides them is small text kept for evaluation.
pub fn is_frame_file(relative: &str) -> bool {
    let extension = relative
        .rsplit_once('.')
        .map(|(_, e)| e.to_ascii_lowercase());
    matches!(extension.as_deref(), Some("png" | "jpg" | "jpeg" | "exr"))
}

/// The record of a folder whose frames were deleted: `None` when it has none, an error naming
/// the file when it cannot be read.
pub fn read_frames_deleted(root: &Path) -> Result<Option<FramesDeleted>, CoreError> {
    let path = root.join(FRAMES_DELETED_FILE);
    if !path.is_file() {
        return Ok(None);
    }
    let text = std::fs::read_to_string(&path).map_err(|e| CoreError::io(&path, e))?;
    serde_json::from_str(&text).map(Some).map_err(|e| {
        CoreError::bad_file(
            &path,
            format!("expected {{\"files\": N, \"bytes\": N}}: {e}"),
        )
    })
}

/// Deletes the frames of the finished output `root`, keeping everything else.
pub fn delete_frames(root: &Path) -> Result<FramesDeleted, CoreError> {
    let (listed, deleted) = finished_list(root)?;
    write_record(root, &deleted)?;
    for relative in listed.paths().filter(|p| is_frame_file(p)) {
        remove_if_present(&root.join(relative))?;
    }
    remove_empty_folders(root)?;
    Ok(deleted)
}

/// Copies the finished output `from` without its frames to `to` (which must not exist), as a
/// folder whose frames were deleted.
pub fn copy_without_frames(from: &Path, to: &Path) -> Result<FramesDeleted, CoreError> {
    let (listed, deleted) = finished_list(from)?;
    let kept = listed.paths().filter(|p| !is_frame_file(p));
    for relative in kept.chain([CHECKSUM_FILE, MANIFEST_FILE]) {
        copy(&from.join(relative), &to.join(relative))?;
    }
    write_record(to, &deleted)?;
    Ok(deleted)
}

/// The checksum list of the finished output `root` (the one its manifest sealed), and the count
/// and size of the frames it names.
fn finished_list(root: &Path) -> Result<(Checksums, FramesDeleted), CoreError> {
    let manifest = Manifest::read(root)?;
    let listed = Checksums::read(root)?;
    if manifest.content_digest.is_empty() || listed.digest() != manifest.content_digest {
        return Err(CoreError::bad_file(
            root.join(CHECKSUM_FILE),
            "is not the list the manifest sealed: only a finished output's frames are deleted",
        ));
    }
    let mut frames = FramesDeleted { files: 0, bytes: 0 };
    for relative in listed.paths().filter(|p| is_frame_file(p)) {
        let path = root.join(relative);
        let meta = std::fs::metadata(&path).map_err(|e| CoreError::io(&path, e))?;
        frames.files += 1;
        frames.bytes += meta.len();
    }
    Ok((listed, frames))
}

fn write_record(root: &Path, deleted: &FramesDeleted) -> Result<(), CoreError> {
    let path = root.join(FRAMES_DELETED_FILE);
    let text =
        serde_json::to_string(deleted).map_err(|e| CoreError::bad_file(&path, e.to_string()))?;
    write_atomically(&path, (text + "\n").as_bytes())
}

fn copy(from: &Path, to: &Path) -> Result<(), CoreError> {
    if let Some(parent) = to.parent() {
        std::fs::create_dir_all(parent).map_err(|e| CoreError::io(parent, e))?;
    }
    std::fs::copy(from, to).map_err(|e| CoreError::io(from, e))?;
    Ok(())
}

/// Removes the folders the deleted frames leave empty (`results/`, `rgb/`, `mav0/cam0/data/`).
fn remove_empty_folders(root: &Path) -> Result<(), CoreError> {
    for entry in std::fs::read_dir(root).map_err(|e| CoreError::io(root, e))? {
        let path = entry.map_err(|e| CoreError::io(root, e))?.path();
        if path.is_dir() && !path.is_symlink() {
            remove_empty_folders(&path)?;
            let empty = std::fs::read_dir(&path)
                .map_err(|e| CoreError::io(&path, e))?
                .next()
                .is_none();
            if empty {
                std::fs::remove_dir(&path).map_err(|e| CoreError::io(&path, e))?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dataset::ContentWriter;

    fn finished_output(root: &Path) -> Manifest {
        for folder in ["results", "mav0/imu0"] {
            std::fs::create_dir_all(root.join(folder)).unwrap();
        }
        let writer = ContentWriter::new(root);
        writer.write("results/frame000000.jpg", &[1; 100]).unwrap();
        writer.write("results/depth000000.png", &[2; 50]).unwrap();
        writer.write("traj.txt", b"1 0 0 0\n").unwrap();
        writer.write("mav0/imu0/data.csv", b"#t\n").unwrap();
        let manifest: Manifest = serde_json::from_value(serde_json::json!({
            "tool": "rslam", "tool_version": "0.1.0", "command": [], "source": "room0",
            "source_hash": "", "format": "replica", "camera": null, "rate_hz": 20.0,
            "frame_count": 1, "seed": 0, "perturbation": "", "perturbation_parsed": null,
            "severities": [], "rgb_source": [], "depth_source": [], "extra": null
        }))
        .unwrap();
        writer.finish(manifest).unwrap()
    }

    #[test]
    fn deleting_frames_keeps_everything_else_and_says_how_much_went() {
        let dir = tempfile::tempdir().unwrap();
        finished_output(dir.path());
        let deleted = delete_frames(dir.path()).unwrap();
        assert_eq!(
            deleted,
            FramesDeleted {
                files: 2,
                bytes: 150
            }
        );
        assert_eq!(read_frames_deleted(dir.path()).unwrap(), Some(deleted));
        assert!(
            !dir.path().join("results").exists(),
            "its emptied folder goes too"
        );
        for kept in [
            "traj.txt",
            "mav0/imu0/data.csv",
            MANIFEST_FILE,
            CHECKSUM_FILE,
        ] {
            assert!(dir.path().join(kept).is_file(), "{kept}");
        }
    }

    #[test]
    fn a_copy_without_frames_is_the_same_as_deleting_them_in_place() {
        let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
        finished_output(a.path());
        let copy = b.path().join("copy");
        let copied = copy_without_frames(a.path(), &copy).unwrap();
        assert_eq!(copied, delete_frames(a.path()).unwrap());
        let files = |root: &Path| crate::dataset::content_files(root).unwrap();
        assert_eq!(files(a.path()), files(&copy));
        for name in [
            MANIFEST_FILE,
            CHECKSUM_FILE,
            "traj.txt",
            FRAMES_DELETED_FILE,
        ] {
            assert_eq!(
                std::fs::read(a.path().join(name)).unwrap(),
                std::fs::read(copy.join(name)).unwrap(),
                "{name}"
            );
        }
    }

    #[test]
    fn a_damaged_record_is_an_error_naming_it_and_none_is_none() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(read_frames_deleted(dir.path()).unwrap(), None);
        std::fs::write(dir.path().join(FRAMES_DELETED_FILE), "{\"files\": 2").unwrap();
        let err = read_frames_deleted(dir.path()).unwrap_err().to_string();
        assert!(
            err.contains("rslam.frames-deleted.json: expected {\"files\""),
            "{err}"
        );
    }

    #[test]
    fn an_unfinished_output_keeps_its_frames() {
        let dir = tempfile::tempdir().unwrap();
        finished_output(dir.path());
        std::fs::write(dir.path().join(CHECKSUM_FILE), "").unwrap();
        let err = delete_frames(dir.path()).unwrap_err().to_string();
        assert!(
            err.contains("rslam.b3sum: is not the list the manifest sealed"),
            "{err}"
        );
        assert!(dir.path().join("results/frame000000.jpg").is_file());
    }

    #[test]
    fn frames_are_the_image_files() {
        for frame in [
            "results/frame000001.jpg",
            "rgb/0.05.png",
            "mav0/cam1/data/1.PNG",
            "d.exr",
        ] {
            assert!(is_frame_file(frame), "{frame}");
        }
        for kept in [
            "traj.txt",
            "mav0/cam0/data.csv",
            "orbslam3.yaml",
            "rslam.json",
            "png",
        ] {
            assert!(!is_frame_file(kept), "{kept}");
        }
    }
}
