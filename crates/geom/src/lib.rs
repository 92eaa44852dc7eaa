//! Pure geometry for flexdem: closest points between points, segments and triangles, with the
//! location (vertex, edge, face) and barycentric weights a contact needs to share a force among
//! nodes, and axis-aligned boxes of swept shapes. No physics lives here.
//!
//! Conventions (see `docs/architecture.md`):
//! - a triangle (a, b, c) has vertices 0, 1, 2 and edges 0 = ab, 1 = bc, 2 = ca; an edge
//!   parameter `t` runs from the edge's first vertex (0) to its second (1);
//! - tolerances are relative to the sizes of the inputs, never absolute, and no result is
//!   decided by an exact float comparison;
//! - degenerate inputs (zero-length segments, flat triangles) fall back to the
//!   lower-dimensional problem and never produce NaN.

mod aabb;
pub mod lanes;
mod location;
mod point_segment;
mod point_triangle;
mod segment_segment;
mod segment_triangle;
mod triangle_closest_point;
mod triangle_triangle;
mod trimesh;
mod types;
mod volume;

#[cfg(any(test, feature = "proptest-support"))]
pub mod proptest_support;

pub use aabb::*;
pub use location::*;
pub use point_segment::*;
pub use point_triangle::*;
pub use segment_segment::*;
pub use segment_triangle::*;
pub use triangle_closest_point::*;
pub use triangle_triangle::*;
pub use trimesh::*;
pub use types::{Real, Vec3};
pub use volume::*;
