//! Output folders without symbolic links: a link inside the folder rslam writes to (planted there,
//! or left by another tool) would send frames, manifests or `--force` deletions somewhere else.

use std::path::{Component, Path};

use crate::CoreError;

/// Refuses to write to `root` when any folder from `outer` (exclusive) down to `root`, or anything
/// inside `root`, is a symbolic link; `root` must lie inside `outer` (pass `outer == root` to
/// check only inside). Missing folders are fine: rslam makes them.
pub fn refuse_symlinks(outer: &Path, root: &Path) -> Result<(), CoreError> {
    let inside = root.strip_prefix(outer).map_err(|_| {
        CoreError::bad_file(
            root,
            format!("is not inside {}; rslam writes only there", outer.display()),
        )
    })?;
    let mut path = outer.to_path_buf();
    for component in inside.components() {
        let Component::Normal(name) = component else {
            return Err(CoreError::bad_file(
                root,
                format!(
                    "expected a folder inside {} without '..' or a root",
                    outer.display()
                ),
            ));
        };
        path.push(name);
        check(&path, outer)?;
    }
    let mut pending = vec![root.to_path_buf()];
    while let Some(dir) = pending.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue; // not there (yet) or not a folder: nothing inside to follow
        };
        for entry in entries {
            let entry = entry.map_err(|e| CoreError::io(&dir, e))?;
            let path = entry.path();
            let kind = entry.file_type().map_err(|e| CoreError::io(&path, e))?;
            if kind.is_symlink() {
                return Err(link_error(&path, outer));
            }
            if kind.is_dir() {
                pending.push(path);
            }
        }
    }
    Ok(())
}

fn check(path: &Path, outer: &Path) -> Result<(), CoreError> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) if meta.file_type().is_symlink() => Err(link_error(path, outer)),
        _ => Ok(()),
    }
}

fn link_error(path: &Path, outer: &Path) -> CoreError {
    CoreError::bad_file(
        path,
        format!(
            "is a symbolic link inside the output folder {}; rslam writes only inside it: remove the link",
            outer.display()
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn links_anywhere_on_the_way_or_inside_are_refused() {
        let outer = tempfile::tempdir().unwrap();
        let elsewhere = tempfile::tempdir().unwrap();
        let root = outer.path().join("datasets/room0__fog-3");
        assert!(
            refuse_symlinks(outer.path(), &root).is_ok(),
            "missing folders are made later"
        );
        std::fs::create_dir_all(root.join("results")).unwrap();
        assert!(refuse_symlinks(outer.path(), &root).is_ok());

        std::os::unix::fs::symlink(elsewhere.path(), root.join("results/frames")).unwrap();
        let err = refuse_symlinks(outer.path(), &root)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("results/frames: is a symbolic link inside the output folder"),
            "{err}"
        );
        std::fs::remove_file(root.join("results/frames")).unwrap();

        std::fs::remove_dir_all(outer.path().join("datasets")).unwrap();
        std::os::unix::fs::symlink(elsewhere.path(), outer.path().join("datasets")).unwrap();
        let err = refuse_symlinks(outer.path(), &root)
            .unwrap_err()
            .to_string();
        assert!(err.contains("datasets: is a symbolic link"), "{err}");
    }

    #[test]
    fn a_root_outside_or_climbing_out_is_refused() {
        let outer = tempfile::tempdir().unwrap();
        let err = refuse_symlinks(outer.path(), Path::new("/elsewhere")).unwrap_err();
        assert!(err.to_string().contains("is not inside"), "{err}");
        let climbing = outer.path().join("datasets/../../escape");
        let err = refuse_symlinks(outer.path(), &climbing).unwrap_err();
        assert!(err.to_string().contains("without '..'"), "{err}");
    }
}
