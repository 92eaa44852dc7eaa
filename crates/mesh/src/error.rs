//! Why a mesh could not be read.

use std::path::PathBuf;
use thiserror::Error;

/// Why a mesh could not be read. Every variant names the file; text formats give the line,
/// binary data the byte offset, and the message says what was expected and what was found.
#[derive(Debug, Error)]
pub enum MeshError {
    /// The file could not be read.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The extension names no supported format.
    #[error(
        "{}: unsupported mesh file extension {extension:?}; supported: .msh, .stl, .obj, .gts, .mesh",
        path.display()
    )]
    UnsupportedExtension {
        /// The file.
        path: PathBuf,
        /// Its extension (empty if it has none).
        extension: String,
    },
    /// A text file (or the text part of a Gmsh file) is malformed at a line.
    #[error("{file}:{line}: {message}")]
    Text {
        /// Name of the file (as given to the reader).
        file: String,
        /// Line number, 1-based.
        line: usize,
        /// What was expected and what was found.
        message: String,
    },
    /// Binary data is malformed at a byte offset.
    #[error("{file}: byte {offset}: {message}")]
    Binary {
        /// Name of the file (as given to the reader).
        file: String,
        /// Byte offset from the start of the file.
        offset: usize,
        /// What was expected and what was found.
        message: String,
    },
    /// The file as a whole is malformed (for instance its size does not match its header).
    #[error("{file}: {message}")]
    File {
        /// Name of the file (as given to the reader).
        file: String,
        /// What was expected and what was found.
        message: String,
    },
}

impl MeshError {
    pub(crate) fn text(file: &str, line: usize, message: impl Into<String>) -> Self {
        MeshError::Text { file: file.to_owned(), line, message: message.into() }
    }

    pub(crate) fn binary(file: &str, offset: usize, message: impl Into<String>) -> Self {
        MeshError::Binary { file: file.to_owned(), offset, message: message.into() }
    }
}
