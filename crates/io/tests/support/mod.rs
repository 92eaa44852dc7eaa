//! Helpers shared by the integration tests of `flexdem-io`.

pub mod meshes;
