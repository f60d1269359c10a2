//! Suite files (`suite.toml`) and method files of `rslam suite` and `rslam bench`.

use std::path::{Component, Path};

use rslam_core::limits::{MAX_REPEATS, MAX_SUITE_SEQUENCES};
use rslam_suite::bench::Method;
use rslam_suite::{Suite, SUITE_FILE};

use crate::Scratch;

pub const SUITE: &str = SUITE_FILE;
pub const METHOD: &str = "method.toml";

/// What a suite row may point to: a mesh and a camera path beside the suite file.
const VALID_PLY: &str =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                         property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
                         end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
const VALID_TRAJ: &str = "0 0 0 0 0 0 0 1\n0.05 0.1 0 0 0 0 0 1\n";

pub fn prepare_suite(dir: &Path) -> std::io::Result<()> {
    std::fs::write(dir.join("mesh.ply"), VALID_PLY)?;
    std::fs::write(dir.join("path.txt"), VALID_TRAJ)
}

/// An accepted suite writes each sequence into its own folder under `datasets/`, never elsewhere.
pub fn suite(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(SUITE, input)?;
    let suite = Suite::open(&scratch.dir).map_err(|e| e.to_string())?;
    assert!(
        suite.sequences.len() <= MAX_SUITE_SEQUENCES,
        "accepted {} sequences",
        suite.sequences.len()
    );
    for sequence in &suite.sequences {
        assert!(
            is_one_folder(&sequence.name),
            "sequence '{}' writes outside datasets/",
            sequence.name
        );
        if let Err(problem) = sequence.camera.check() {
            panic!("sequence '{}': accepted camera: {problem}", sequence.name);
        }
        assert!(sequence.rate_hz.is_finite() && sequence.rate_hz > 0.0);
    }
    Ok(())
}

/// An accepted method writes its runs into one folder under `runs/`.
pub fn method(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    let path = scratch.write(METHOD, input)?;
    let method = Method::read(&path).map_err(|e| e.to_string())?;
    assert!(
        is_one_folder(&method.name),
        "method '{}' writes outside runs/",
        method.name
    );
    assert!(
        (1..=MAX_REPEATS).contains(&method.repeats),
        "accepted {} repeats",
        method.repeats
    );
    assert!(method.timeout_s.is_finite() && method.timeout_s > 0.0);
    Ok(())
}

/// A name that is exactly one ordinary path component.
fn is_one_folder(name: &str) -> bool {
    let mut components = Path::new(name).components();
    matches!(components.next(), Some(Component::Normal(_))) && components.next().is_none()
}
