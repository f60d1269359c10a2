//! Flags' text: `--perturb` specs, `--camera`, `--shard`.

use rslam_core::Intrinsics;
use rslam_perturb::PerturbSpec;
use rslam_suite::Shard;

use crate::Scratch;

/// An accepted spec prints a canonical form that parses back to the same spec.
pub fn spec(_: &Scratch, input: &[u8]) -> Result<(), String> {
    let text = String::from_utf8_lossy(input);
    let spec = PerturbSpec::parse(&text).map_err(|e| e.to_string())?;
    let canonical = spec.to_string();
    let again = PerturbSpec::parse(&canonical)
        .unwrap_or_else(|e| panic!("canonical form '{canonical}' does not parse: {e}"));
    assert_eq!(
        again, spec,
        "canonical form '{canonical}' parses to another spec"
    );
    Ok(())
}

/// An accepted camera is one rslam can use.
pub fn camera(_: &Scratch, input: &[u8]) -> Result<(), String> {
    let camera = Intrinsics::parse(&String::from_utf8_lossy(input)).map_err(|e| e.to_string())?;
    if let Err(problem) = camera.check() {
        panic!("accepted camera {camera:?}: {problem}");
    }
    Ok(())
}

pub fn shard(_: &Scratch, input: &[u8]) -> Result<(), String> {
    let shard = Shard::parse(&String::from_utf8_lossy(input)).map_err(|e| e.to_string())?;
    assert!(shard.index < shard.count, "accepted shard {shard:?}");
    Ok(())
}
