//! Line-level parsing shared by the readers: lenient on whitespace and comments, strict on numbers.

use std::path::Path;

use glam::DQuat;

use crate::limits::MAX_POSES;
use crate::{printable, CoreError, Pose};

/// The data lines of a text file, as (1-based line number, trimmed text): a UTF-8 byte order
/// mark, blank lines and lines starting with `#` are skipped.
pub(crate) fn data_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    text.lines()
        .enumerate()
        .map(|(i, line)| (i + 1, line.trim()))
        .filter(|(_, line)| !line.is_empty() && !line.starts_with('#'))
}

/// Refuses a file of more than [`MAX_POSES`] data lines, before any is parsed.
pub(super) fn check_line_count(path: &Path, text: &str) -> Result<(), CoreError> {
    if let Some((line, _)) = data_lines(text).nth(MAX_POSES) {
        return Err(LineRef { path, line }.error(format!(
            "more than {MAX_POSES} poses, the most a trajectory may hold"
        )));
    }
    Ok(())
}

/// Where a line came from, to name it in errors.
#[derive(Clone, Copy)]
pub(crate) struct LineRef<'a> {
    pub path: &'a Path,
    pub line: usize,
}

impl LineRef<'_> {
    pub fn error(&self, message: impl Into<String>) -> CoreError {
        CoreError::BadLine {
            path: self.path.to_path_buf(),
            line: self.line,
            message: message.into(),
        }
    }

    /// Parses the first `N` fields as finite numbers. With `exact`, there must be exactly `N`
    /// fields; otherwise at least `N` (the rest is ignored). `layout` says what a line holds.
    pub fn numbers<'t, const N: usize>(
        &self,
        fields: impl Iterator<Item = &'t str>,
        exact: bool,
        layout: &str,
    ) -> Result<[f64; N], CoreError> {
        let fields: Vec<&str> = fields.collect();
        let count_ok = if exact {
            fields.len() == N
        } else {
            fields.len() >= N
        };
        if !count_ok {
            return Err(self.error(format!(
                "expected {layout}, found {} field{}",
                fields.len(),
                if fields.len() == 1 { "" } else { "s" }
            )));
        }
        let mut values = [0.0; N];
        for (i, (value, text)) in values.iter_mut().zip(&fields).enumerate() {
            let parsed: f64 = text.parse().map_err(|_| {
                self.error(format!(
                    "field {} '{}' is not a number (expected {layout})",
                    i + 1,
                    printable(text)
                ))
            })?;
            if !parsed.is_finite() {
                return Err(self.error(format!(
                    "field {} is '{}'; expected a finite number",
                    i + 1,
                    printable(text)
                )));
            }
            *value = parsed;
        }
        Ok(values)
    }

    /// Field `field` (1-based) as a timestamp in integer nanoseconds, digits only, as EuRoC files
    /// store them. `layout` says what a line holds.
    pub fn nanoseconds(&self, field: usize, text: &str, layout: &str) -> Result<u64, CoreError> {
        if text.is_empty() || !text.bytes().all(|b| b.is_ascii_digit()) {
            return Err(self.error(format!(
                "field {field} '{}' is not a timestamp in integer nanoseconds (expected {layout})",
                printable(text)
            )));
        }
        text.parse().map_err(|_| {
            self.error(format!(
                "field {field} '{text}' is past the largest timestamp, {} ns",
                u64::MAX
            ))
        })
    }

    /// A unit quaternion from possibly unnormalised components; all zero is an error, and so
    /// are components whose squares overflow or underflow (no finite unit quaternion from them).
    pub fn quaternion(&self, x: f64, y: f64, z: f64, w: f64) -> Result<DQuat, CoreError> {
        let q = DQuat::from_xyzw(x, y, z, w);
        let norm = q.length();
        if norm == 0.0 {
            return Err(self.error("zero quaternion (qx qy qz qw all 0); expected a rotation"));
        }
        let unit = q / norm;
        if !(norm.is_finite() && unit.is_finite()) {
            return Err(self.error(format!(
                "quaternion ({x:e} {y:e} {z:e} {w:e}) cannot be normalised in 64-bit floats; \
                 expected a rotation"
            )));
        }
        Ok(unit)
    }

    /// A pose from a row-major rigid matrix: `[R | t]` (12 numbers) or 4×4 with its last row
    /// `0 0 0 1` (16), see [`Pose::rigid_from_rows`].
    pub fn pose_from_rows(&self, rows: &[f64]) -> Result<Pose, CoreError> {
        Pose::rigid_from_rows(rows).map_err(|message| self.error(message))
    }
}
