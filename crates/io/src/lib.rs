//! Input and output for flexdem: scene files, mesh import, VTK output for ParaView, CSV series
//! and checkpoints.

pub mod checkpoint;
pub mod mesh;
pub mod output;
pub mod scene;
