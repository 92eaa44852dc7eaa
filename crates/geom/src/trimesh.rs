//! A plain triangle mesh: what mesh readers produce and the PFacet builder consumes.

use crate::Vec3;

/// An indexed triangle mesh: vertex positions and triangles as triples of vertex indices.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriMesh {
    /// Vertex positions.
    pub vertices: Vec<Vec3>,
    /// Triangles, each three indices into `vertices`.
    pub triangles: Vec<[usize; 3]>,
}

impl TriMesh {
    /// A mesh from its vertices and triangles (no validation: see the PFacet mesh builder).
    pub fn new(vertices: Vec<Vec3>, triangles: Vec<[usize; 3]>) -> Self {
        Self { vertices, triangles }
    }
}
