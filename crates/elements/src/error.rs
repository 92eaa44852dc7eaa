//! Errors of the model (`ModelError`) and of the builders (`BuildError`). Every message names
//! the element, triangle or vertex, the bad value, and what is expected.

use crate::{ConnectionId, Dofs, MaterialId, NodeId, PFacetId, ParticleId, StructureId, WallId};
use flexdem_contact::MaterialError;
use flexdem_geom::{Real, Vec3};
use std::fmt;

/// A model item, for error messages ("connection 12", "PFacet 3").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Item {
    /// A particle (free sphere or node).
    Particle(ParticleId),
    /// A connection.
    Connection(ConnectionId),
    /// A PFacet.
    PFacet(PFacetId),
    /// A wall.
    Wall(WallId),
    /// A structure.
    Structure(StructureId),
}

impl fmt::Display for Item {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Item::Particle(i) => write!(f, "particle {i}"),
            Item::Connection(i) => write!(f, "connection {i}"),
            Item::PFacet(i) => write!(f, "PFacet {i}"),
            Item::Wall(i) => write!(f, "wall {i}"),
            Item::Structure(i) => write!(f, "structure {i}"),
        }
    }
}

/// A vector formatted as `(x, y, z)` in messages.
pub(crate) struct V(pub Vec3);

impl fmt::Display for V {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "({}, {}, {})", self.0.x, self.0.y, self.0.z)
    }
}

/// An inconsistent model, or a model operation with bad arguments.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// A material that fails its own validation.
    #[error("material {material}: {source}")]
    Material {
        /// Its id (or the id it would have had).
        material: MaterialId,
        /// What is wrong with it.
        source: MaterialError,
    },
    /// A material id out of range.
    #[error(
        "{item} uses material {material}, but the model has {count} materials (ids 0..{count})"
    )]
    UnknownMaterial {
        /// The item that refers to it.
        item: Item,
        /// The bad id.
        material: MaterialId,
        /// Number of materials.
        count: usize,
    },
    /// A particle id out of range.
    #[error("{item} refers to particle {particle}, but the model has {count} particles (ids 0..{count})")]
    UnknownParticle {
        /// The item that refers to it (the particle itself for selections).
        item: Item,
        /// The bad id.
        particle: ParticleId,
        /// Number of particles.
        count: usize,
    },
    /// A particle id out of range given to a selection or constraint.
    #[error(
        "particle {particle} does not exist: the model has {count} particles (ids 0..{count})"
    )]
    NoSuchParticle {
        /// The bad id.
        particle: ParticleId,
        /// Number of particles.
        count: usize,
    },
    /// An element refers to a free sphere where a node is needed.
    #[error(
        "{item} refers to particle {particle}, which is a free sphere: expected a structure node"
    )]
    NotANode {
        /// The element.
        item: Item,
        /// The particle.
        particle: ParticleId,
    },
    /// A connection id out of range.
    #[error("{item} refers to connection {connection}, but the model has {count} connections (ids 0..{count})")]
    UnknownConnection {
        /// The PFacet that refers to it.
        item: Item,
        /// The bad id.
        connection: ConnectionId,
        /// Number of connections.
        count: usize,
    },
    /// A structure id out of range.
    #[error(
        "structure {structure} does not exist: the model has {count} structures (ids 0..{count})"
    )]
    UnknownStructure {
        /// The bad id.
        structure: StructureId,
        /// Number of structures.
        count: usize,
    },
    /// A radius that is not finite and positive.
    #[error("{item} has radius {radius}: expected a finite value > 0")]
    InvalidRadius {
        /// The item.
        item: Item,
        /// The bad radius.
        radius: Real,
    },
    /// A NaN or infinite value.
    #[error("{item} has a non-finite {field}: {value}")]
    NonFinite {
        /// The item.
        item: Item,
        /// The field.
        field: &'static str,
        /// The value, formatted.
        value: String,
    },
    /// A negative mass or inertia.
    #[error("{item} has {field} {value}: expected a finite value >= 0")]
    NegativeMass {
        /// The particle.
        item: Item,
        /// `mass` or `inertia`.
        field: &'static str,
        /// The bad value.
        value: Real,
    },
    /// A particle with zero mass (or inertia) whose DOFs are free would get a NaN
    /// acceleration (YADE's unconnected node).
    #[error(
        "{item} has {field} 0 but its DOFs {free} are free: connect it to an element (and lump \
         the structure's mass) or block those DOFs"
    )]
    MissingMass {
        /// The particle.
        item: Item,
        /// `mass` or `inertia`.
        field: &'static str,
        /// The free DOFs that need it.
        free: Dofs,
    },
    /// A connection whose two nodes are the same or coincide.
    #[error(
        "connection {connection} joins nodes {} and {} at distance {length}: expected two \
         distinct nodes at a non-zero distance", nodes[0], nodes[1]
    )]
    ZeroLengthConnection {
        /// The connection.
        connection: ConnectionId,
        /// Its nodes.
        nodes: [NodeId; 2],
        /// Their distance.
        length: Real,
    },
    /// A connection whose rest length is not finite and positive.
    #[error("connection {connection} has rest length {rest_length}: expected a finite value > 0")]
    InvalidRestLength {
        /// The connection.
        connection: ConnectionId,
        /// The bad value.
        rest_length: Real,
    },
    /// A PFacet with a repeated node.
    #[error("PFacet {pfacet} has nodes {nodes:?}: expected three distinct nodes")]
    RepeatedPFacetNode {
        /// The PFacet.
        pfacet: PFacetId,
        /// Its nodes.
        nodes: [NodeId; 3],
    },
    /// A PFacet whose edge connection does not join the edge's nodes.
    #[error(
        "PFacet {pfacet}: edge {edge} joins nodes {expected:?} but its connection {connection} \
         joins nodes {found:?} (connections[0] must join nodes 0-1, [1] 1-2, [2] 2-0)"
    )]
    PFacetEdgeMismatch {
        /// The PFacet.
        pfacet: PFacetId,
        /// The edge (0, 1, 2).
        edge: usize,
        /// The connection given for it.
        connection: ConnectionId,
        /// The edge's nodes.
        expected: [NodeId; 2],
        /// The connection's nodes.
        found: [NodeId; 2],
    },
    /// A wall normal that is not a finite unit vector (or, when adding, a zero vector).
    #[error("wall {wall} has normal {}: expected a finite non-zero vector (stored unit length)", V(*normal))]
    InvalidWallNormal {
        /// The wall.
        wall: WallId,
        /// The bad normal.
        normal: Vec3,
    },
    /// A vector argument that is not finite or is zero where a direction is needed.
    #[error("{what} is {}: expected {expected}", V(*value))]
    InvalidVector {
        /// The argument.
        what: &'static str,
        /// Its value.
        value: Vec3,
        /// What is expected.
        expected: &'static str,
    },
    /// A scalar argument out of its domain.
    #[error("{what} is {value}: expected {expected}")]
    InvalidScalar {
        /// The argument.
        what: &'static str,
        /// Its value.
        value: Real,
        /// What is expected.
        expected: &'static str,
    },
    /// A structure whose id ranges run past the arrays, or an item outside its structure's
    /// ranges.
    #[error("{item} is inconsistent with {structure}: {reason}")]
    StructureMismatch {
        /// The item.
        item: Item,
        /// The structure involved.
        structure: Item,
        /// What is wrong.
        reason: String,
    },
    /// Elements are appended to a structure that is not the last one, or after which other
    /// particles or elements were added (ranges must stay contiguous).
    #[error(
        "cannot add to structure {structure}: elements can be added only to the last structure, \
         and only while nothing else was added after it ({reason})"
    )]
    StructureClosed {
        /// The structure.
        structure: StructureId,
        /// What was added after it.
        reason: &'static str,
    },
    /// The particle arrays do not all have the same length.
    #[error("the particle arrays have different lengths: every array of `Particles` must have one entry per particle")]
    ParticleArrays,
    /// More items than ids can name.
    #[error("too many {what}: ids are u32 and u32::MAX is reserved")]
    TooMany {
        /// The kind of item.
        what: &'static str,
    },
}

/// A builder given bad parameters or a bad mesh. Nothing is added to the model when a builder
/// fails.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BuildError {
    /// The model rejected something (unknown material, ...).
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A parameter out of its domain.
    #[error("{name} = {value}: expected {expected}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// Its value, formatted.
        value: String,
        /// What is expected.
        expected: &'static str,
    },
    /// Too few points for a polyline.
    #[error("a polyline needs at least 2 points, got {count}")]
    TooFewPoints {
        /// Number of points given.
        count: usize,
    },
    /// A NaN or infinite point.
    #[error("point {index} is {}: expected finite coordinates", V(*point))]
    NonFinitePoint {
        /// Its index.
        index: usize,
        /// The point.
        point: Vec3,
    },
    /// Two consecutive polyline points (or two nodes of a generated skeleton) that coincide.
    #[error(
        "segment {segment} from point {} to point {} has length {length}: expected > {tolerance} \
         (1e-9 of the structure's size)", points[0], points[1]
    )]
    ZeroLengthSegment {
        /// Segment index.
        segment: usize,
        /// The point indices it joins.
        points: [usize; 2],
        /// Its length.
        length: Real,
        /// The length below which a segment is degenerate.
        tolerance: Real,
    },
    /// A mesh without triangles.
    #[error("the mesh has no triangles ({vertices} vertices)")]
    EmptyMesh {
        /// Number of vertices.
        vertices: usize,
    },
    /// A triangle index past the vertex list.
    #[error(
        "triangle {triangle} {vertices:?}: vertex index {index} is out of range, the mesh has \
         {vertex_count} vertices (indices 0..{vertex_count})"
    )]
    IndexOutOfRange {
        /// Triangle index.
        triangle: usize,
        /// Its vertex indices.
        vertices: [usize; 3],
        /// The bad index.
        index: usize,
        /// Number of vertices.
        vertex_count: usize,
    },
    /// A triangle that uses a vertex index twice.
    #[error(
        "triangle {triangle} {vertices:?} repeats a vertex index: expected three distinct vertices"
    )]
    RepeatedIndex {
        /// Triangle index.
        triangle: usize,
        /// Its vertex indices.
        vertices: [usize; 3],
    },
    /// A triangle with a NaN or infinite vertex.
    #[error("triangle {triangle} {vertices:?}: vertex {vertex} is {}: expected finite coordinates", V(*point))]
    NonFiniteVertex {
        /// Triangle index.
        triangle: usize,
        /// Its vertex indices.
        vertices: [usize; 3],
        /// The bad vertex index.
        vertex: usize,
        /// Its coordinates.
        point: Vec3,
    },
    /// A triangle edge whose two vertices coincide (closer than the merge tolerance, so merged
    /// into one node).
    #[error(
        "triangle {triangle} {vertices:?}: edge {edge} from vertex {} to vertex {} has length \
         {length}, within the merge tolerance {tolerance}: expected a non-zero edge", ends[0], ends[1]
    )]
    ZeroLengthEdge {
        /// Triangle index.
        triangle: usize,
        /// Its vertex indices.
        vertices: [usize; 3],
        /// Edge number (0 = ab, 1 = bc, 2 = ca).
        edge: usize,
        /// The edge's vertex indices.
        ends: [usize; 2],
        /// Its length.
        length: Real,
        /// The merge distance.
        tolerance: Real,
    },
    /// A flat (collinear) triangle.
    #[error(
        "triangle {triangle} {vertices:?} is degenerate: its height is {ratio:e} of its longest \
         edge, expected more than {min_ratio:e} (collinear vertices)"
    )]
    DegenerateTriangle {
        /// Triangle index.
        triangle: usize,
        /// Its vertex indices.
        vertices: [usize; 3],
        /// 2·area / (longest edge)²: the height over the longest edge, relative to it.
        ratio: Real,
        /// The threshold.
        min_ratio: Real,
    },
    /// Two triangles on the same three (merged) vertices.
    #[error(
        "triangle {triangle} {vertices:?} uses the same three vertices as triangle {other} \
         (after merging coincident vertices): expected each face once"
    )]
    DuplicateTriangle {
        /// Triangle index.
        triangle: usize,
        /// Its vertex indices.
        vertices: [usize; 3],
        /// The earlier triangle.
        other: usize,
    },
    /// Every vertex of a mesh at one point.
    #[error("all vertices of the mesh are at one point: expected a mesh of non-zero size")]
    ZeroSizeMesh,
}

/// Checks that a scalar parameter is finite and > 0.
pub(crate) fn positive(name: &'static str, value: Real) -> Result<Real, BuildError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(BuildError::InvalidParameter {
            name,
            value: value.to_string(),
            expected: "a finite value > 0",
        })
    }
}

/// Checks that a count parameter is ≥ `min` and small enough for u32 ids.
pub(crate) fn count(name: &'static str, value: usize, min: usize) -> Result<usize, BuildError> {
    const MAX: usize = 1 << 24;
    if (min..=MAX).contains(&value) {
        Ok(value)
    } else {
        Err(BuildError::InvalidParameter {
            name,
            value: value.to_string(),
            expected: if min == 1 {
                "an integer >= 1 (and <= 2^24)"
            } else if min == 2 {
                "an integer >= 2 (and <= 2^24)"
            } else {
                "an integer >= 3 (and <= 2^24)"
            },
        })
    }
}

/// Checks that a point is finite.
pub(crate) fn finite_point(name: &'static str, p: Vec3) -> Result<Vec3, BuildError> {
    if p.iter().all(|c| c.is_finite()) {
        Ok(p)
    } else {
        Err(BuildError::InvalidParameter {
            name,
            value: V(p).to_string(),
            expected: "finite coordinates",
        })
    }
}

/// Checks that a direction is finite and non-zero, and returns it normalized.
pub(crate) fn direction(name: &'static str, d: Vec3) -> Result<Vec3, BuildError> {
    let n = d.norm();
    if d.iter().all(|c| c.is_finite()) && n.is_finite() && n > 0.0 {
        Ok(d / n)
    } else {
        Err(BuildError::InvalidParameter {
            name,
            value: V(d).to_string(),
            expected: "a finite non-zero direction",
        })
    }
}
