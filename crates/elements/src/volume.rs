//! The volume a structure's PFacets enclose: their mid-surface (the triangles of node
//! centres, oriented by each PFacet's node order, whose normal `(x₁ − x₀) × (x₂ − x₀)` the
//! builders point outward), closed where it is open by planes (walls), by the divergence
//! theorem of [`flexdem_geom::volume_closed_by_planes`]. Also the boundary loops of a set of
//! PFacets: the edges used by one PFacet only, chained into loops.
//!
//! The builders' closed shells (`sphere_shell`) need no plane; a tube needs one per end
//! (its two end rings), a disc or rectangular membrane one. The PFacets' thickness (their
//! radius) is not part of the volume: it is the volume inside the mid-surface.

use crate::{Model, NodeId, PFacetId, StructureId, Wall};
use flexdem_geom::{volume_closed_by_planes, Plane, PlaneClosure, Real};
use std::collections::{HashMap, HashSet};

/// Why a volume cannot be measured.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum VolumeError {
    /// No PFacet to enclose anything.
    #[error("{what} has no PFacets: a volume needs a surface of PFacets")]
    NoPFacets {
        /// The structure or selection, for messages ("structure `net`").
        what: String,
    },
    /// A PFacet id out of range.
    #[error("PFacet {pfacet} does not exist: the model has {count} PFacets (ids 0..{count})")]
    UnknownPFacet {
        /// The bad id.
        pfacet: PFacetId,
        /// Number of PFacets.
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
    /// A closing plane with a non-finite point or a zero or non-finite normal.
    #[error(
        "closing plane {index} has point {point:?} and normal {normal:?}: expected a finite \
         point and a finite non-zero normal"
    )]
    InvalidPlane {
        /// Its index in the list given.
        index: usize,
        /// Its point.
        point: [Real; 3],
        /// Its normal.
        normal: [Real; 3],
    },
    /// An edge shared by more than two PFacets: the surface is not a manifold there.
    #[error(
        "the edge between nodes {} and {} is used by {count} PFacets (at least): a surface \
         that encloses a volume has each edge on one PFacet (its boundary) or two",
        nodes[0], nodes[1]
    )]
    NonManifoldEdge {
        /// The edge's nodes.
        nodes: [NodeId; 2],
        /// How many PFacets use it (counted up to the first excess).
        count: usize,
    },
    /// Two PFacets run along their shared edge in the same direction: their normals point
    /// to opposite sides of the surface.
    #[error(
        "PFacets {} and {} run along their shared edge from node {} to node {} in the same \
         direction: their normals point to opposite sides (reorder the nodes of one of them)",
        pfacets[0], pfacets[1], nodes[0], nodes[1]
    )]
    InconsistentOrientation {
        /// The edge, in the direction both run along it.
        nodes: [NodeId; 2],
        /// The two PFacets.
        pfacets: [PFacetId; 2],
    },
    /// Boundary edges that do not chain into loops: a node where two boundary edges start or
    /// end (two parts of the surface touching at a node), or an open chain.
    #[error(
        "the boundary edges cannot be chained into loops at node {node} ({reason}): the \
         surface is not a manifold there"
    )]
    UnchainedBoundary {
        /// The node.
        node: NodeId,
        /// What is wrong there.
        reason: &'static str,
    },
    /// An open surface with fewer closing planes than boundary loops.
    #[error(
        "the surface is not closed: it has {loops} boundary loops (edges of one PFacet only) \
         and {planes} closing planes were given; give one plane (a wall) per open end"
    )]
    NotClosed {
        /// Boundary loops.
        loops: usize,
        /// Planes given.
        planes: usize,
    },
    /// More closing planes than boundary loops.
    #[error(
        "{planes} closing planes were given for {loops} boundary loops: give one plane per \
         open end (a closed surface needs none)"
    )]
    TooManyPlanes {
        /// Boundary loops.
        loops: usize,
        /// Planes given.
        planes: usize,
    },
    /// Two boundary loops nearest the same plane.
    #[error(
        "boundary loops {} and {} are both nearest closing plane {plane}: each plane closes \
         one loop, the one whose nodes are nearest it on average",
        loops[0], loops[1]
    )]
    PlaneSharedByLoops {
        /// The plane's index.
        plane: usize,
        /// The two loops' indices.
        loops: [usize; 2],
    },
}

impl Wall {
    /// The wall's plane (its current point and normal).
    pub fn plane(&self) -> Plane {
        Plane { point: self.point, normal: self.normal }
    }
}

/// How a PFacet edge is used, while counting.
#[derive(Clone, Copy)]
struct EdgeUse {
    /// The direction and PFacet of its first use.
    first: ([NodeId; 2], PFacetId),
    /// How many PFacets use it.
    count: usize,
}

/// The boundary edges of `pfacets` (edges used by one of them only), each in the direction
/// its PFacet runs along it (`nodes[k] → nodes[k + 1]`), in the order of the PFacets and
/// their edges. Errors for an edge used by more than two PFacets or by two in the same
/// direction. The PFacet ids must exist.
fn boundary_edges(model: &Model, pfacets: &[PFacetId]) -> Result<Vec<[NodeId; 2]>, VolumeError> {
    let mut uses: HashMap<(NodeId, NodeId), EdgeUse> = HashMap::with_capacity(pfacets.len() * 2);
    let mut order = Vec::with_capacity(pfacets.len() * 3 / 2);
    for &f in pfacets {
        let facet = &model.pfacets[f as usize];
        for e in 0..3 {
            let [a, b] = facet.edge_nodes(e);
            let key = (a.min(b), a.max(b));
            match uses.get_mut(&key) {
                None => {
                    uses.insert(key, EdgeUse { first: ([a, b], f), count: 1 });
                    order.push(key);
                }
                Some(u) if u.count == 1 => {
                    if u.first.0 == [a, b] {
                        return Err(VolumeError::InconsistentOrientation {
                            nodes: [a, b],
                            pfacets: [u.first.1, f],
                        });
                    }
                    u.count = 2;
                }
                Some(u) => {
                    return Err(VolumeError::NonManifoldEdge { nodes: [a, b], count: u.count + 1 })
                }
            }
        }
    }
    Ok(order.iter().map(|k| uses[k]).filter(|u| u.count == 1).map(|u| u.first.0).collect())
}

/// The boundary loops of `pfacets`: their boundary edges (used by one PFacet only) chained
/// into closed loops, each listing its nodes in the direction the PFacets run along them
/// (for outward normals, clockwise seen from outside the open end), starting at the first
/// node of its first edge; loops in the order of their first edges. A closed surface has
/// none, a tube two, a membrane one. Errors (never a panic) for a PFacet id out of range, an
/// edge of more than two PFacets or of two PFacets running the same way, and boundary edges
/// that do not chain into loops (two starting or ending at one node).
pub fn boundary_loops(
    model: &Model,
    pfacets: &[PFacetId],
) -> Result<Vec<Vec<NodeId>>, VolumeError> {
    check_pfacets(model, pfacets)?;
    let edges = boundary_edges(model, pfacets)?;
    let mut next: HashMap<NodeId, NodeId> = HashMap::with_capacity(edges.len());
    let mut has_previous: HashSet<NodeId> = HashSet::with_capacity(edges.len());
    for &[a, b] in &edges {
        if next.insert(a, b).is_some() {
            return Err(VolumeError::UnchainedBoundary {
                node: a,
                reason: "two boundary edges start there",
            });
        }
        if !has_previous.insert(b) {
            return Err(VolumeError::UnchainedBoundary {
                node: b,
                reason: "two boundary edges end there",
            });
        }
    }
    let mut loops = Vec::new();
    for &[start, _] in &edges {
        if !next.contains_key(&start) {
            continue; // on a loop already chained
        }
        let mut nodes = vec![start];
        let mut node = start;
        loop {
            let Some(following) = next.remove(&node) else {
                return Err(VolumeError::UnchainedBoundary {
                    node,
                    reason: "the boundary ends there without closing",
                });
            };
            if following == start {
                break;
            }
            nodes.push(following);
            node = following;
        }
        loops.push(nodes);
    }
    Ok(loops)
}

/// Errors for an empty list or a PFacet id out of range.
fn check_pfacets(model: &Model, pfacets: &[PFacetId]) -> Result<(), VolumeError> {
    let count = model.pfacets.len();
    match pfacets.iter().find(|&&f| f as usize >= count) {
        Some(&pfacet) => Err(VolumeError::UnknownPFacet { pfacet, count }),
        None => Ok(()),
    }
}

/// Errors for a plane with a non-finite point or a zero or non-finite normal.
fn check_planes(planes: &[Plane]) -> Result<(), VolumeError> {
    for (index, p) in planes.iter().enumerate() {
        let finite = p.point.iter().chain(p.normal.iter()).all(|x| x.is_finite());
        if !(finite && p.normal.norm() > 0.0) {
            return Err(VolumeError::InvalidPlane {
                index,
                point: p.point.into(),
                normal: p.normal.into(),
            });
        }
    }
    Ok(())
}

/// Each boundary loop with the plane its nodes are nearest on average (mean of `|(x − p)·n̂|`).
/// As many planes as loops are needed, and no plane may be the nearest of two loops.
fn assign_planes(
    model: &Model,
    loops: Vec<Vec<NodeId>>,
    planes: &[Plane],
) -> Result<Vec<PlaneClosure>, VolumeError> {
    let (n_loops, n_planes) = (loops.len(), planes.len());
    if n_loops > n_planes {
        return Err(VolumeError::NotClosed { loops: n_loops, planes: n_planes });
    }
    if n_planes > n_loops {
        return Err(VolumeError::TooManyPlanes { loops: n_loops, planes: n_planes });
    }
    let pos = &model.particles.pos;
    let mean_distance = |nodes: &[NodeId], plane: &Plane| {
        let n = plane.normal.normalize();
        nodes.iter().map(|&i| (pos[i as usize] - plane.point).dot(&n).abs()).sum::<Real>()
            / nodes.len() as Real
    };
    let mut owner: Vec<Option<usize>> = vec![None; n_planes];
    let mut closures = Vec::with_capacity(n_loops);
    for (l, nodes) in loops.into_iter().enumerate() {
        let nearest = (0..n_planes)
            .min_by(|&a, &b| {
                mean_distance(&nodes, &planes[a]).total_cmp(&mean_distance(&nodes, &planes[b]))
            })
            .unwrap_or(0);
        if let Some(other) = owner[nearest] {
            return Err(VolumeError::PlaneSharedByLoops { plane: nearest, loops: [other, l] });
        }
        owner[nearest] = Some(l);
        let boundary = nodes.iter().map(|&i| i as usize).collect();
        closures.push(PlaneClosure { boundary, plane: planes[nearest] });
    }
    Ok(closures)
}

/// The volume enclosed by the mid-surface of `pfacets` (their node centres, oriented by
/// their node order), each of its boundary loops closed by the plane among `planes` its
/// nodes are nearest (one plane per loop; none for a closed surface):
///
/// ```text
/// V = Σ_f (1/6)(x_a − o)·((x_b − o) × (x_c − o)) + Σ_loops (ribbon + cap)
/// ```
///
/// over the PFacets `f = (a, b, c)`, with the closing of each loop as in
/// [`flexdem_geom::plane_closure_flux`]. Positive when the PFacets' normals
/// `(x_b − x_a) × (x_c − x_a)` point out of the enclosed region (the builders' shells and
/// tubes), negative when they point in. Errors (never a panic) as [`boundary_loops`], for an
/// empty list, a bad plane, and loops and planes that do not match one to one.
pub fn pfacets_volume(
    model: &Model,
    pfacets: &[PFacetId],
    planes: &[Plane],
) -> Result<Real, VolumeError> {
    if pfacets.is_empty() {
        return Err(VolumeError::NoPFacets { what: "the selection".into() });
    }
    check_planes(planes)?;
    let loops = boundary_loops(model, pfacets)?;
    let closures = assign_planes(model, loops, planes)?;
    let triangles: Vec<[usize; 3]> =
        pfacets.iter().map(|&f| model.pfacets[f as usize].nodes.map(|n| n as usize)).collect();
    Ok(volume_closed_by_planes(&model.particles.pos, &triangles, &closures))
}

/// The volume enclosed by all the PFacets of structure `structure`, closed by `planes` where
/// it is open (see [`pfacets_volume`]).
pub fn structure_volume(
    model: &Model,
    structure: StructureId,
    planes: &[Plane],
) -> Result<Real, VolumeError> {
    let count = model.structures.len();
    let Some(st) = model.structures.get(structure as usize) else {
        return Err(VolumeError::UnknownStructure { structure, count });
    };
    let pfacets: Vec<PFacetId> = st.pfacets.clone().collect();
    if pfacets.is_empty() {
        return Err(VolumeError::NoPFacets { what: format!("structure `{}`", st.name) });
    }
    pfacets_volume(model, &pfacets, planes)
}

#[cfg(test)]
mod tests;
