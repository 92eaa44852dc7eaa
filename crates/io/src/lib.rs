//! The files of flexdem in one crate: checkpoints ([`checkpoint`], defined here), scene files
//! ([`scene`], the `flexdem-scene` crate), mesh import ([`mesh`], `flexdem-mesh`) and the
//! output of a run ([`output`], `flexdem-output`: VTK for ParaView, CSV series, PNG charts).
//!
//! Each of the re-exported crates can be used alone, with fewer dependencies: reading an STL
//! file needs only `flexdem-mesh`; reading a scene compiles neither plotters nor bincode. The
//! checkpoint format lives here because it stores types of both the scene (`RunLength`) and
//! the output (`OutputSettings`, `OutputProgress`), and neither of them depends on it.

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
