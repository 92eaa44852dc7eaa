//! File system helpers: the output folder, and writes that never leave a half-written file
//! in place of a good one.

use crate::error::OutputError;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Creates `directory` and its parents if missing; an existing path that is not a folder is
/// an error.
pub(crate) fn create_directory(directory: &Path) -> Result<(), OutputError> {
    if directory.exists() && !directory.is_dir() {
        return Err(OutputError::Directory {
            path: directory.to_path_buf(),
            source: std::io::Error::other("the path exists and is not a folder"),
        });
    }
    fs::create_dir_all(directory)
        .map_err(|source| OutputError::Directory { path: directory.to_path_buf(), source })
}

/// The temporary file next to `path` that [`write_atomically`] writes first:
/// `.NAME.tmp` in the same folder (so the rename stays on one file system). Files whose name
/// ends in `.png` keep that ending (`.NAME.tmp.png`), for writers that pick the format from it.
pub(crate) fn temporary_path(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let temp = match name.strip_suffix(".png") {
        Some(stem) => format!(".{stem}.tmp.png"),
        None => format!(".{name}.tmp"),
    };
    path.with_file_name(temp)
}

/// Moves the finished temporary file `temp` over `path`; removes `temp` if that fails.
fn replace_with(temp: &Path, path: &Path) -> Result<(), OutputError> {
    fs::rename(temp, path).map_err(|source| {
        let _ = fs::remove_file(temp);
        OutputError::Write { path: path.to_path_buf(), source }
    })
}

/// Writes `bytes` to `path` through a temporary file in the same folder renamed over `path`:
/// a failure leaves any previous `path` as it was (and removes the temporary file).
pub(crate) fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    let temp = temporary_path(path);
    let written = fs::File::create(&temp).and_then(|mut file| {
        file.write_all(bytes)?;
        file.flush()
    });
    if let Err(source) = written {
        let _ = fs::remove_file(&temp);
        return Err(OutputError::Write { path: path.to_path_buf(), source });
    }
    replace_with(&temp, path)
}
