//! Helpers shared by the integration tests of `flexdem-io`.

/// The valid test meshes and every mesh reader, from `flexdem-mesh`'s tests.
#[path = "../../../mesh/tests/support/meshes.rs"]
pub mod meshes;
