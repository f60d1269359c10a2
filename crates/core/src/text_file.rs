//! Text inputs read whole, refused past [`MAX_TEXT_FILE_BYTES`] before any byte is read.

use std::path::Path;

use crate::limits::MAX_TEXT_FILE_BYTES;
use crate::CoreError;

/// The contents of `path` as UTF-8; `what` says what the file should hold, for the errors.
pub fn read_text_file(path: &Path, what: &str) -> Result<String, CoreError> {
    let size = std::fs::metadata(path)
        .map_err(|e| CoreError::io(path, e))?
        .len();
    if size > MAX_TEXT_FILE_BYTES {
        return Err(CoreError::bad_file(
            path,
            format!("{size} bytes, over the limit of {MAX_TEXT_FILE_BYTES} bytes for {what}"),
        ));
    }
    let bytes = std::fs::read(path).map_err(|e| CoreError::io(path, e))?;
    String::from_utf8(bytes).map_err(|e| {
        CoreError::bad_file(
            path,
            format!(
                "not a text file (invalid UTF-8 at byte {}); expected {what}",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}
