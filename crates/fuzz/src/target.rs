//! What a fuzz target is: a name, the file it writes, and the parser call.

use std::path::{Path, PathBuf};

/// One parser under test.
pub struct Target {
    pub name: &'static str,
    /// The file name the input is written as (errors must name a file or folder of the
    /// input); `None` for a flag's text.
    pub file: Option<&'static str>,
    /// Writes what else the parser needs into a fresh scratch folder, once.
    pub prepare: fn(&Path) -> std::io::Result<()>,
    /// Feeds the input to the parser: `Err` is its error message; a broken invariant of an
    /// accepted value panics (the harness reports it as a finding).
    pub check: fn(&Scratch, &[u8]) -> Result<(), String>,
}

/// The folder a target's inputs are written to.
pub struct Scratch {
    pub dir: PathBuf,
}

impl Scratch {
    /// Writes `bytes` as `name` in the scratch folder and returns its path.
    pub fn write(&self, name: &str, bytes: &[u8]) -> Result<PathBuf, String> {
        let path = self.dir.join(name);
        std::fs::write(&path, bytes)
            .map_err(|e| format!("scratch file {}: {e}", path.display()))?;
        Ok(path)
    }
}

/// For targets that need nothing else.
pub fn nothing(_dir: &Path) -> std::io::Result<()> {
    Ok(())
}
