//! Where a closest point lies on a segment or a triangle.

use crate::Real;

/// Where a point lies on a segment `[a, b]`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SegmentLocation {
    /// On an end: 0 = `a`, 1 = `b`.
    OnVertex(usize),
    /// Strictly inside, at `a + t (b - a)` with `0 < t < 1`.
    OnEdge {
        /// Parameter along the segment.
        t: Real,
    },
}

/// Where a point lies on a triangle `(a, b, c)`.
///
/// Vertices are numbered 0 = a, 1 = b, 2 = c; edges 0 = ab, 1 = bc, 2 = ca, and the edge
/// parameter `t` runs from the edge's first vertex to its second.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum TriangleLocation {
    /// On a vertex (0, 1 or 2).
    OnVertex(usize),
    /// Strictly inside an edge.
    OnEdge {
        /// Edge index: 0 = ab, 1 = bc, 2 = ca.
        edge: usize,
        /// Parameter along the edge, from its first vertex (0) to its second (1).
        t: Real,
    },
    /// Strictly inside the face: all three barycentric weights are positive.
    OnFace,
}

impl TriangleLocation {
    /// The vertex indices `(first, second)` of edge `edge` (0 = ab, 1 = bc, 2 = ca).
    pub const fn edge_vertices(edge: usize) -> (usize, usize) {
        match edge {
            0 => (0, 1),
            1 => (1, 2),
            _ => (2, 0),
        }
    }
}
