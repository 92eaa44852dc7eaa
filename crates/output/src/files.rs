//! File system helpers: the output folder, writes that never leave a half-written file in
//! place of a good one, and whether two paths name the same file.

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

/// Whether paths `a` and `b` name the same file, whether they exist or not: each made
/// absolute, its longest existing ancestor resolved (symbolic links, `.` and `..` as the
/// system reads them), then the rest of it with `.` dropped and `..` taken as the folder
/// above; so `./x.csv`, `x.csv`, `out/../x.csv` and the same file through a linked folder
/// match. For the guards that keep one output file from being written over another.
pub fn same_file(a: &Path, b: &Path) -> bool {
    resolved(a) == resolved(b)
}

/// [`same_file`]'s form of `path`.
fn resolved(path: &Path) -> PathBuf {
    use std::path::Component;
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let parts: Vec<Component<'_>> = absolute.components().collect();
    // the longest ancestor that exists (the root at least, for an absolute path)
    let (mut out, first_missing) = (0..=parts.len())
        .rev()
        .find_map(|k| {
            let prefix: PathBuf = parts[..k].iter().collect();
            prefix.canonicalize().ok().map(|real| (real, k))
        })
        .unwrap_or((PathBuf::new(), 0));
    for c in &parts[first_missing..] {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_file_sees_through_dots_and_linked_folders() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::create_dir(d.join("out")).unwrap();
        let x = d.join("out/x.csv");
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(d.join("out"), d.join("link")).unwrap();
            assert!(same_file(&x, &d.join("link/x.csv")));
            // `..` after a link is the link target's parent, as the system reads it
            std::fs::create_dir_all(d.join("far/away")).unwrap();
            std::os::unix::fs::symlink(d.join("far/away"), d.join("out/deep")).unwrap();
            assert!(same_file(&d.join("far/x.csv"), &d.join("out/deep/../x.csv")));
            assert!(!same_file(&x, &d.join("out/deep/../x.csv")));
        }
        for same in ["out/./x.csv", "out/../out/x.csv", "new/../out/x.csv"] {
            assert!(same_file(&x, &d.join(same)), "{same}");
        }
        for other in ["out/y.csv", "x.csv", "out/x.csv/..", "new/x.csv"] {
            assert!(!same_file(&x, &d.join(other)), "{other}");
        }
        // not yet there, below folders not yet there
        assert!(same_file(&d.join("a/b/c.csv"), &d.join("a/./b/../b/c.csv")));
        // relative to the current folder
        assert!(same_file(Path::new("x.csv"), Path::new("./x.csv")));
    }
}
