//! The CSV series file: a header row, then rows appended and flushed one by one.

use crate::error::OutputError;
use crate::files::write_atomically;
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

    /// Continues the series at `path` written by an earlier run: checks that its header is
    /// `columns`, keeps its first `rows` rows (dropping any later ones, written after a
    /// checkpoint), and opens it for appending. Returns the kept rows' values.
    pub fn resume(
        path: &Path,
        columns: &[String],
        rows: usize,
    ) -> Result<(CsvSeries, Vec<Vec<Real>>), OutputError> {
        let problem = |problem: String| OutputError::Resume { path: path.to_path_buf(), problem };
        let text = std::fs::read_to_string(path)
            .map_err(|e| problem(format!("cannot read the series: {e}")))?;
        let mut lines = text.lines();
        let header = columns.join(",");
        if lines.next() != Some(header.as_str()) {
            return Err(problem(format!("its header is not the expected `{header}`")));
        }
        let mut kept_text = format!("{header}\n");
        let mut kept = Vec::with_capacity(rows);
        for (i, line) in lines.take(rows).enumerate() {
            let values = line
                .split(',')
                .map(|v| v.parse::<Real>())
                .collect::<Result<Vec<Real>, _>>()
                .map_err(|e| problem(format!("row {} is not numbers: {e}", i + 1)))?;
            if values.len() != columns.len() {
                return Err(problem(format!(
                    "row {} has {} values for {} columns",
                    i + 1,
                    values.len(),
                    columns.len()
                )));
            }
            kept_text.push_str(line);
            kept_text.push('\n');
            kept.push(values);
        }
        if kept.len() < rows {
            return Err(problem(format!(
                "it has {} rows, the checkpoint expects at least {rows}",
                kept.len()
            )));
        }
        write_atomically(path, kept_text.as_bytes())?;
        let file = OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(|source| OutputError::Write { path: path.to_path_buf(), source })?;
        let csv = CsvSeries {
            path: path.to_path_buf(),
            columns: columns.len(),
            file: BufWriter::new(file),
        };
        Ok((csv, kept))
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
