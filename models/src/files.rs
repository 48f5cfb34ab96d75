//! What the tool may overwrite: every output it writes (results, plots,
//! sweeps, FMUs) replaces a regular file or nothing, never a symbolic link,
//! a folder, a device, a FIFO or a socket at the output's name.

use std::path::Path;

/// What `path` is, in words, if it exists and is not a regular file (the
/// link itself, not what it points to); `None` for a regular file or no
/// file at all.
///
/// ```
/// use crane_models::files::not_a_regular_file;
///
/// let dir = std::env::temp_dir();
/// assert_eq!(not_a_regular_file(&dir), Some("a folder"));
/// assert_eq!(not_a_regular_file(&dir.join("no such file, surely")), None);
/// ```
pub fn not_a_regular_file(path: &Path) -> Option<&'static str> {
    let kind = std::fs::symlink_metadata(path).ok()?.file_type();
    if kind.is_symlink() {
        Some("a symbolic link")
    } else if kind.is_dir() {
        Some("a folder")
    } else if !kind.is_file() {
        Some("a device, a FIFO or a socket")
    } else {
        None
    }
}
