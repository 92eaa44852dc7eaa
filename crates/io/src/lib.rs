//! Input and output for flexdem: scene files, mesh import, VTK output for ParaView, CSV series
//! and checkpoints.

pub mod checkpoint;
pub mod output;
pub mod scene;

/// Triangle-mesh import (Gmsh msh 2.2/4.1, STL, OBJ, GTS, MEDIT): the `flexdem-mesh` crate,
/// re-exported so that `flexdem_io::mesh::read_mesh` and the other paths keep working.
pub use flexdem_mesh as mesh;
