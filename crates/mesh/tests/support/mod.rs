//! Helpers shared by the integration tests of `flexdem-mesh`.

pub mod meshes;
