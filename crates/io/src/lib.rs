//! Input and output for flexdem (to come): scene files, mesh import, VTK output for ParaView,
//! CSV series and checkpoints.
