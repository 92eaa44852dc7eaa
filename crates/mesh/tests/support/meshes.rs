//! The valid test meshes and every mesh reader, shared by the mesh fuzz tests
//! (`mesh_fuzz.rs`, proptest) and the seeded mutation fuzzer of every input
//! (`crates/io/tests/input_fuzz.rs`, which includes this file with `#[path]`).

#![allow(dead_code)]

use std::path::PathBuf;

use flexdem_geom::TriMesh;
use flexdem_mesh::{read_gts, read_medit, read_msh, read_obj, read_stl, MeshError};

/// The valid meshes of `crates/mesh/tests/data/meshes`, one per format and variant.
pub const VALID: [&str; 9] = [
    "cube_v22_ascii.msh",
    "cube_v22_binary.msh",
    "cube_v41_ascii.msh",
    "cube_v41_binary.msh",
    "cube_ascii.stl",
    "cube_binary.stl",
    "cube.obj",
    "cube.gts",
    "cube.mesh",
];

/// The bytes of a valid mesh.
pub fn valid_bytes(name: &str) -> Vec<u8> {
    // `../mesh` so that the path holds from flexdem-io's tests too.
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../mesh/tests/data/meshes").join(name);
    std::fs::read(path).unwrap()
}

/// A reader of one format, on bytes.
pub type Reader = fn(&[u8], &str) -> Result<TriMesh, MeshError>;

fn obj(bytes: &[u8], name: &str) -> Result<TriMesh, MeshError> {
    read_obj(&String::from_utf8_lossy(bytes), name)
}
fn gts(bytes: &[u8], name: &str) -> Result<TriMesh, MeshError> {
    read_gts(&String::from_utf8_lossy(bytes), name)
}
fn medit(bytes: &[u8], name: &str) -> Result<TriMesh, MeshError> {
    read_medit(&String::from_utf8_lossy(bytes), name)
}

/// Every reader with the extension it reads (text formats as `read_mesh` decodes them).
pub const READERS: [(&str, Reader); 5] =
    [("msh", read_msh), ("stl", read_stl), ("obj", obj), ("gts", gts), ("mesh", medit)];

/// The reader of a file name's extension.
pub fn reader_for(name: &str) -> Reader {
    READERS.iter().find(|(ext, _)| name.ends_with(&format!(".{ext}"))).unwrap().1
}

/// `Ok` when a result is an error naming the file, or a mesh that is safe to use (at least
/// one triangle, indices in range, finite coordinates); else what is wrong.
pub fn well_formed(result: Result<TriMesh, MeshError>, name: &str) -> Result<(), String> {
    match result {
        Err(error) => {
            let shown = error.to_string();
            if shown.contains(name) {
                Ok(())
            } else {
                Err(format!("the error does not name the file {name}: {shown}"))
            }
        }
        Ok(mesh) => {
            if mesh.triangles.is_empty() {
                return Err("a mesh without triangles".into());
            }
            if let Some(t) =
                mesh.triangles.iter().find(|t| t.iter().any(|&v| v >= mesh.vertices.len()))
            {
                return Err(format!(
                    "triangle {t:?} out of range ({} vertices)",
                    mesh.vertices.len()
                ));
            }
            if let Some(v) = mesh.vertices.iter().find(|v| !v.iter().all(|x| x.is_finite())) {
                return Err(format!("a vertex is not finite: {v:?}"));
            }
            Ok(())
        }
    }
}
