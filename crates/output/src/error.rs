//! Why output failed.

use std::path::PathBuf;

/// Why output failed; each names the file or setting and the cause.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The output folder could not be created (or is not a folder).
    #[error("cannot create the output folder {path}: {source}")]
    Directory {
        /// The folder.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A file could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The plot could not be drawn.
    #[error("cannot draw the plot {path}: {message}")]
    Plot {
        /// The PNG file.
        path: PathBuf,
        /// The cause.
        message: String,
    },
    /// A series is invalid for this simulation.
    #[error("output series '{series}': {problem}")]
    Series {
        /// The series' name.
        series: String,
        /// What is wrong.
        problem: String,
    },
    /// The output of an earlier run cannot be continued (see [`crate::Output::resume`]).
    #[error("cannot continue the output in {path}: {problem}")]
    Resume {
        /// The file that does not match the checkpoint.
        path: PathBuf,
        /// What does not match.
        problem: String,
    },
    /// An output setting is invalid.
    #[error("output setting {what} = {value}: expected {expected}")]
    Setting {
        /// The setting.
        what: String,
        /// Its value.
        value: String,
        /// What is accepted.
        expected: String,
    },
}
