//! Input and output for flexdem: scene files, mesh import, VTK output for ParaView, CSV series
//! and checkpoints.

pub mod checkpoint;

/// Scene files (TOML → model, settings, loads, output settings, run length): the
/// `flexdem-scene` crate, re-exported so that `flexdem_io::scene::load_scene` and the other
/// paths keep working.
pub use flexdem_scene as scene;

/// Output of a run (VTK, CSV, PNG charts): the `flexdem-output` crate, re-exported so that
/// `flexdem_io::output::Output` and the other paths keep working.
pub use flexdem_output as output;

/// Triangle-mesh import (Gmsh msh 2.2/4.1, STL, OBJ, GTS, MEDIT): the `flexdem-mesh` crate,
/// re-exported so that `flexdem_io::mesh::read_mesh` and the other paths keep working.
pub use flexdem_mesh as mesh;
