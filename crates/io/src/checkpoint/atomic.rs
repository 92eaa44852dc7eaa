//! Atomic replacement of a file: write a temporary file in the same folder, flush it to disk,
//! rename it over the target, then flush the folder.

use std::ffi::OsString;
use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Serializes the atomic writes of this process: the temporary file name is unique per process
/// (it holds the process id), so two threads must not use it at the same time.
static WRITE_LOCK: Mutex<()> = Mutex::new(());

/// The temporary file used while `path` is written: `.NAME.tmp-PID` in the same folder, so
/// that the final rename stays on one file system. `None` if `path` has no file name.
pub(crate) fn temp_path(path: &Path) -> Option<PathBuf> {
    let name = path.file_name()?;
    let mut temp = OsString::from(".");
    temp.push(name);
    temp.push(format!(".tmp-{}", std::process::id()));
    Some(path.with_file_name(temp))
}

/// Replaces the file at `path` by `parts` (written one after the other) so that, whatever
/// fails and whenever the process dies, `path` holds either its previous content or the new
/// one in full. On error the temporary file is removed (if it was created) and `path` is left
/// as it was.
pub(crate) fn write_atomically(path: &Path, parts: &[&[u8]]) -> io::Result<()> {
    let temp = temp_path(path)
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "the path has no file name"))?;
    // A poisoned lock only means another writer panicked: the files are still consistent.
    let _guard = WRITE_LOCK.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let file = OpenOptions::new().write(true).create(true).truncate(true).open(&temp)?;
    let written = fill_and_rename(file, &temp, path, parts);
    if written.is_err() {
        // Best effort: the error that matters is the one of the write.
        let _ = std::fs::remove_file(&temp);
        return written;
    }
    sync_folder(path);
    Ok(())
}

/// Writes `parts` to `file` (the temporary file at `temp`), flushes it to disk, closes it and
/// renames it to `path`.
fn fill_and_rename(mut file: File, temp: &Path, path: &Path, parts: &[&[u8]]) -> io::Result<()> {
    for part in parts {
        file.write_all(part)?;
    }
    file.flush()?;
    file.sync_all()?;
    drop(file);
    std::fs::rename(temp, path)
}

/// Flushes the folder of `path` so that the rename itself survives a power cut. Best effort:
/// not every platform or file system can open or sync a folder.
fn sync_folder(path: &Path) {
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if let Ok(dir) = File::open(folder) {
        let _ = dir.sync_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_temporary_file_is_hidden_beside_the_target() {
        let t = temp_path(Path::new("runs/a/state.ckp")).unwrap();
        assert_eq!(t.parent(), Some(Path::new("runs/a")));
        let name = t.file_name().unwrap().to_str().unwrap();
        assert_eq!(name, format!(".state.ckp.tmp-{}", std::process::id()));
        assert!(temp_path(Path::new("/")).is_none());
    }

    #[test]
    fn a_write_replaces_the_whole_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f");
        write_atomically(&path, &[b"a long first content", b"!"]).unwrap();
        write_atomically(&path, &[b"short"]).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"short");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap()).collect();
        assert_eq!(names.len(), 1, "temporary file left behind");
    }
}
