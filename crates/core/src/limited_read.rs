//! Files read whole, refused past a size limit before any byte is read.

use std::path::Path;

use crate::limits::MAX_TEXT_FILE_BYTES;
use crate::CoreError;

/// The bytes of `path`, or an error when it is over `limit` bytes; `what` says what the file
/// should hold, for the errors.
pub fn read_limited(path: &Path, limit: u64, what: &str) -> Result<Vec<u8>, CoreError> {
    let size = std::fs::metadata(path)
        .map_err(|e| CoreError::io(path, e))?
        .len();
    if size > limit {
        return Err(CoreError::bad_file(
            path,
            format!("{size} bytes, over the limit of {limit} bytes for {what}"),
        ));
    }
    std::fs::read(path).map_err(|e| CoreError::io(path, e))
}

/// The contents of `path` as UTF-8, at most [`MAX_TEXT_FILE_BYTES`].
pub fn read_text_file(path: &Path, what: &str) -> Result<String, CoreError> {
    let bytes = read_limited(path, MAX_TEXT_FILE_BYTES, what)?;
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
