//! The CSV series file: a header row, then rows appended and flushed one by one.

use super::files::write_atomically;
use super::OutputError;
use flexdem_geom::Real;
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// An open CSV series: `path` holds the header and every row appended so far.
#[derive(Debug)]
pub struct CsvSeries {
    path: PathBuf,
    columns: usize,
    file: BufWriter<File>,
}

/// A number as CSV text that parses back to the same `f64`: plain decimals between 1e-4 and
/// 1e15 in magnitude (and for 0 and integers such as step counts), scientific notation
/// otherwise; `NaN`, `inf` and `-inf` as Rust prints them.
pub fn format_number(x: Real) -> String {
    let a = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

impl CsvSeries {
    /// Writes the header `columns` to `path` (replacing any older file) and opens it for
    /// appending rows.
    pub fn create(path: &Path, columns: &[String]) -> Result<CsvSeries, OutputError> {
        let header = format!("{}\n", columns.join(","));
        write_atomically(path, header.as_bytes())?;
        let file = OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(|source| OutputError::Write { path: path.to_path_buf(), source })?;
        Ok(CsvSeries {
            path: path.to_path_buf(),
            columns: columns.len(),
            file: BufWriter::new(file),
        })
    }

    /// The file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Appends one row (as many values as header columns) and flushes it to the file.
    pub fn append(&mut self, row: &[Real]) -> Result<(), OutputError> {
        if row.len() != self.columns {
            return Err(OutputError::Write {
                path: self.path.clone(),
                source: std::io::Error::other(format!(
                    "a row of {} values for {} columns",
                    row.len(),
                    self.columns
                )),
            });
        }
        let line: Vec<String> = row.iter().map(|&x| format_number(x)).collect();
        writeln!(self.file, "{}", line.join(","))
            .and_then(|()| self.file.flush())
            .map_err(|source| OutputError::Write { path: self.path.clone(), source })
    }

    /// Flushes the rows written so far to the file.
    pub fn flush(&mut self) -> Result<(), OutputError> {
        self.file.flush().map_err(|source| OutputError::Write { path: self.path.clone(), source })
    }
}
