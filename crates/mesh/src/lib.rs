//! Triangle-mesh import: Gmsh `.msh` (2.2 and 4.1, ASCII and binary), STL (ASCII and binary),
//! Wavefront OBJ, GTS and INRIA/MEDIT `.mesh`, each read into a [`TriMesh`].
//!
//! [`read_mesh`] picks the reader from the file extension; each format also has its own
//! function taking the file's contents and a name used in error messages.
//!
//! Common rules of every reader:
//! - only triangles are kept; other elements (points, lines, quadrilaterals of a `.mesh`,
//!   tetrahedra...) are skipped, and a file without any triangle is an error;
//! - for the indexed formats (msh, OBJ, GTS, MEDIT), vertices that no triangle uses are
//!   dropped, the others keep their order in the file (so a volume mesh gives its surface
//!   without interior nodes); STL is a triangle soup and gives 3 unmerged vertices per
//!   triangle, in file order (merging is the PFacet builder's job);
//! - triangles keep the vertex order of the file (so its orientation);
//! - the readers check structure (counts, indices, numbers), never geometry: degenerate
//!   triangles are left to the PFacet builder;
//! - no input makes them panic, declared counts are checked against the data before any
//!   allocation, and a non-finite coordinate is an error naming its line (or byte offset).
//!
//! This crate depends on `flexdem-geom` only (for [`TriMesh`]); `flexdem-io` re-exports it as
//! `flexdem_io::mesh` for the scene files. The readers are our own rather than `stl_io`,
//! `tobj` or `mshio`: `stl_io` reports errors as plain `io::Error`s without line or byte
//! offset, reads ASCII coordinates as `f32`, and reads a binary file whose header starts
//! with "solid " as ASCII (and fails); `tobj`'s errors are unit variants without the line,
//! and its coordinates `f32` unless a feature is on; `mshio` reads msh 4.1 only (not 2.2).

mod error;
mod gts;
mod medit;
mod msh;
mod msh_ascii;
mod msh_binary;
mod msh_data;
mod obj;
mod stl;
mod text;
mod vertices;

use std::path::Path;

use flexdem_geom::TriMesh;

pub use error::MeshError;
pub use gts::read_gts;
pub use medit::read_medit;
pub use msh::read_msh;
pub use obj::read_obj;
pub use stl::read_stl;

/// File extensions [`read_mesh`] understands, lower case, without the dot.
pub const SUPPORTED_EXTENSIONS: [&str; 5] = ["msh", "stl", "obj", "gts", "mesh"];

/// Reads a triangle mesh, choosing the format from the extension (case-insensitive): `.msh`
/// (Gmsh 2.2 or 4.1, ASCII or binary), `.stl` (ASCII or binary), `.obj`, `.gts`, `.mesh`
/// (INRIA/MEDIT). Error messages name the file as `path` displays.
pub fn read_mesh(path: &Path) -> Result<TriMesh, MeshError> {
    let extension =
        path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    if !SUPPORTED_EXTENSIONS.contains(&extension.as_str()) {
        return Err(MeshError::UnsupportedExtension { path: path.to_owned(), extension });
    }
    let bytes =
        std::fs::read(path).map_err(|source| MeshError::Io { path: path.to_owned(), source })?;
    let name = path.display().to_string();
    match extension.as_str() {
        "msh" => read_msh(&bytes, &name),
        "stl" => read_stl(&bytes, &name),
        // Invalid UTF-8 (a Latin-1 comment, say) becomes U+FFFD: harmless in comments, and a
        // number containing it fails to parse with its line number.
        "obj" => read_obj(&String::from_utf8_lossy(&bytes), &name),
        "gts" => read_gts(&String::from_utf8_lossy(&bytes), &name),
        _ => read_medit(&String::from_utf8_lossy(&bytes), &name),
    }
}
