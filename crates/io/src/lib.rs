//! Input and output for flexdem: scene files, mesh import, VTK output for ParaView, CSV series
//! and checkpoints (mesh import so far).

pub mod mesh;
