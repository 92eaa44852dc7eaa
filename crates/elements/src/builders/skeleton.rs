//! What every builder shares: the options of a structure ([`StructureOptions`]), its
//! skeleton (points, edges, triangles) and how a skeleton becomes a structure of the model
//! (checked, numbered, its mass lumped).

use crate::error::{positive, BuildError, Item};
use crate::{MassLumping, MaterialId, Model, StructureId};
use flexdem_geom::{Real, Vec3};
use std::collections::HashMap;

/// A skeleton edge is degenerate when shorter than this fraction of the structure's size
/// (the diagonal of its points' bounding box).
pub(crate) const ZERO_EDGE_RELATIVE: Real = 1e-9;

/// What every builder needs besides its geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct StructureOptions {
    /// Name of the structure.
    pub name: String,
    /// Radius of the nodes and of the connections and PFacets (half the thickness).
    pub radius: Real,
    /// Material of nodes, connections and PFacets (its density lumps the mass).
    pub material: MaterialId,
    /// Collision group bits of every element.
    pub mask: u32,
    /// How the elements' mass is lumped into the nodes.
    pub mass: MassLumping,
    /// Whether the structure's elements touch one another ([`crate::Structure::self_contact`]).
    pub self_contact: bool,
}

impl StructureOptions {
    /// Options with mask 1, YADE's mass lumping ([`MassLumping::Connections`]) and
    /// self-contact on.
    pub fn new(name: impl Into<String>, radius: Real, material: MaterialId) -> Self {
        StructureOptions {
            name: name.into(),
            radius,
            material,
            mask: 1,
            mass: MassLumping::Connections,
            self_contact: true,
        }
    }

    /// The same options with self-contact on or off.
    pub fn with_self_contact(mut self, on: bool) -> Self {
        self.self_contact = on;
        self
    }

    /// The same options with collision mask `mask`.
    pub fn with_mask(mut self, mask: u32) -> Self {
        self.mask = mask;
        self
    }

    /// The same options with mass lumping `mass`.
    pub fn with_mass(mut self, mass: MassLumping) -> Self {
        self.mass = mass;
        self
    }
}

/// The topology and geometry of a structure before it is added: node positions, explicit
/// edges (connections without faces, e.g. a chain or a net) and faces (node triples, whose
/// edges become connections shared between faces).
#[derive(Clone, Debug, Default)]
pub(crate) struct Skeleton {
    pub points: Vec<Vec3>,
    pub edges: Vec<[u32; 2]>,
    pub faces: Vec<[u32; 3]>,
}

/// The edges of a skeleton with the faces' edges included, and each face's three edge ids
/// (edge 0 = nodes 0–1, 1 = 1–2, 2 = 2–0). Explicit edges come first, then the faces' new
/// edges in order of first appearance; an edge is stored in the direction it first appears.
pub(crate) fn unique_edges(skeleton: &Skeleton) -> (Vec<[u32; 2]>, Vec<[u32; 3]>) {
    let mut edges = Vec::with_capacity(skeleton.edges.len() + skeleton.faces.len() * 3 / 2);
    let mut index: HashMap<(u32, u32), u32> = HashMap::with_capacity(edges.capacity());
    let mut add = |a: u32, b: u32, edges: &mut Vec<[u32; 2]>| -> u32 {
        *index.entry((a.min(b), a.max(b))).or_insert_with(|| {
            edges.push([a, b]);
            (edges.len() - 1) as u32
        })
    };
    for &[a, b] in &skeleton.edges {
        add(a, b, &mut edges);
    }
    let face_edges = skeleton
        .faces
        .iter()
        .map(|f| [0, 1, 2].map(|k| add(f[k], f[(k + 1) % 3], &mut edges)))
        .collect();
    (edges, face_edges)
}

/// Diagonal of the bounding box of `points` (0 for no point).
pub(crate) fn bounding_diagonal(points: &[Vec3]) -> Real {
    let Some(first) = points.first() else { return 0.0 };
    let (lo, hi) = points.iter().fold((*first, *first), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    (hi - lo).norm()
}

/// Adds `skeleton` as a new structure: checks the options and the geometry, then adds the
/// nodes, connections and PFacets and lumps the mass. Nothing is added on error.
pub(crate) fn add_skeleton(
    model: &mut Model,
    skeleton: &Skeleton,
    opts: &StructureOptions,
) -> Result<StructureId, BuildError> {
    positive("radius", opts.radius)?;
    model.density(Item::Structure(model.structures.len() as u32), opts.material)?;
    for (index, p) in skeleton.points.iter().enumerate() {
        if !p.iter().all(|c| c.is_finite()) {
            return Err(BuildError::NonFinitePoint { index, point: *p });
        }
    }
    let (edges, face_edges) = unique_edges(skeleton);
    let tolerance = ZERO_EDGE_RELATIVE * bounding_diagonal(&skeleton.points);
    for (segment, &[a, b]) in edges.iter().enumerate() {
        let length = (skeleton.points[b as usize] - skeleton.points[a as usize]).norm();
        if a == b || length.is_nan() || length <= tolerance {
            return Err(BuildError::ZeroLengthSegment {
                segment,
                points: [a as usize, b as usize],
                length,
                tolerance,
            });
        }
    }
    let snapshot = model.snapshot();
    let result = add_checked_skeleton(model, skeleton, &edges, &face_edges, opts);
    if result.is_err() {
        model.rollback(snapshot);
    }
    result
}

fn add_checked_skeleton(
    model: &mut Model,
    skeleton: &Skeleton,
    edges: &[[u32; 2]],
    face_edges: &[[u32; 3]],
    opts: &StructureOptions,
) -> Result<StructureId, BuildError> {
    let (r, m, mask) = (opts.radius, opts.material, opts.mask);
    let s = model.add_structure(&opts.name)?;
    model.set_self_contact(s, opts.self_contact)?;
    let first_node = model.particles.len() as u32;
    for &p in &skeleton.points {
        model.add_node(s, p, r, m, mask)?;
    }
    let first_connection = model.connections.len() as u32;
    for &[a, b] in edges {
        model.add_connection(s, [first_node + a, first_node + b], r, m, mask)?;
    }
    for (face, fe) in skeleton.faces.iter().zip(face_edges) {
        let nodes = face.map(|n| first_node + n);
        let connections = fe.map(|e| first_connection + e);
        model.add_pfacet(s, nodes, connections, r, m, mask)?;
    }
    model.lump_structure_mass(s, opts.mass)?;
    Ok(s)
}

/// Two unit vectors `(e1, e2)` with `e1 × e2 = n` for a unit vector `n`, so that angles
/// measured from `e1` towards `e2` turn counterclockwise about `n`.
pub(crate) fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    // Cross with the world axis least aligned with n.
    let helper = if n.x.abs() <= n.y.abs() && n.x.abs() <= n.z.abs() {
        Vec3::x()
    } else if n.y.abs() <= n.z.abs() {
        Vec3::y()
    } else {
        Vec3::z()
    };
    let e1 = helper.cross(&n).normalize();
    let e2 = n.cross(&e1);
    (e1, e2)
}
