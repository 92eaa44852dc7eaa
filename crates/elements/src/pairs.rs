//! Closest features of each pair kind (model.md §3 "Pairs"): for two elements, the sites of
//! the two virtual spheres and the distance between their centres.
//!
//! | pair | closest features |
//! |---|---|
//! | sphere–sphere | centres |
//! | sphere–connection | point–segment, `t` clamped (end caps come from clamping) |
//! | connection–connection | segment–segment (eq 9–14), middle of the overlap when parallel |
//! | sphere–PFacet | point–triangle: face inside, otherwise the nearest edge or vertex |
//! | connection–PFacet | segment–triangle (a cylinder across a face's interior is found) |
//! | PFacet–PFacet | triangle–triangle |
//!
//! A closest point at a segment's end or a triangle's vertex is reported on the node
//! (`Feature::Particle`), one inside a PFacet's edge on the edge's connection
//! (`Feature::Edge`), so that all elements sharing a node or an edge report the same feature.

use crate::virtual_sphere::Site;
use flexdem_geom::{
    closest_points_segment_segment, closest_points_segment_triangle,
    closest_points_triangle_triangle, project_point_segment, project_point_triangle, Real,
    SegmentLocation, TriangleLocation, Vec3,
};

/// A sphere (free particle, or a node seen as a sphere) as a pair input.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereRef {
    /// Particle id.
    pub id: u32,
    /// Centre.
    pub center: Vec3,
    /// Radius.
    pub radius: Real,
}

/// A connection (cylinder) as a pair input.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConnectionRef {
    /// Connection id.
    pub id: u32,
    /// Its two nodes (particle ids).
    pub nodes: [u32; 2],
    /// Current positions of the two nodes.
    pub ends: [Vec3; 2],
    /// Cylinder radius.
    pub radius: Real,
}

/// A PFacet as a pair input.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PFacetRef {
    /// PFacet id.
    pub id: u32,
    /// Its three nodes (particle ids).
    pub nodes: [u32; 3],
    /// Its connections: `[0]` joins nodes 0–1, `[1]` joins 1–2, `[2]` joins 2–0.
    pub connections: [u32; 3],
    /// Current positions of the three nodes.
    pub corners: [Vec3; 3],
    /// PFacet radius (its nodes' radius).
    pub radius: Real,
}

/// A candidate contact: the two sites, the centres of their virtual spheres and the distance
/// between the centres. The bodies touch when `overlap() > 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Candidate {
    /// Site on body 1.
    pub site1: Site,
    /// Site on body 2.
    pub site2: Site,
    /// Centre of the virtual sphere on body 1.
    pub center1: Vec3,
    /// Centre of the virtual sphere on body 2.
    pub center2: Vec3,
    /// Distance between the centres.
    pub distance: Real,
}

impl Candidate {
    fn new(site1: Site, center1: Vec3, site2: Site, center2: Vec3) -> Self {
        Candidate { site1, site2, center1, center2, distance: (center2 - center1).norm() }
    }

    /// Overlap `r1 + r2 − distance` (positive when touching).
    pub fn overlap(&self) -> Real {
        self.site1.radius + self.site2.radius - self.distance
    }
}

/// Relative distance (as a weight) under which a closest point is reported on the lower
/// feature it is next to: a point within 1e-9 of a node (relative to the edge) is on the node,
/// within 1e-9 of an edge (as the opposite barycentric weight) is on the edge. Neighbouring
/// elements compute the same point with different round-off; snapping makes them report the
/// same feature, so a touching exactly over a node or an edge is one contact.
pub const SNAP: Real = 1e-9;

/// The site on connection `c` for a closest point at `location` (snapped to a node within
/// [`SNAP`]).
fn connection_site(c: &ConnectionRef, location: SegmentLocation) -> Site {
    match location {
        SegmentLocation::OnEdge { t } if t > SNAP && t < 1.0 - SNAP => {
            Site::edge(c.id, c.nodes, t, c.radius)
        }
        SegmentLocation::OnEdge { t } => Site::particle(c.nodes[usize::from(t >= 0.5)], c.radius),
        SegmentLocation::OnVertex(k) => Site::particle(c.nodes[k], c.radius),
    }
}

/// The site on PFacet `f` for a closest point at `location` with barycentric `weights`
/// (snapped to an edge or a node within [`SNAP`]).
fn pfacet_site(f: &PFacetRef, location: TriangleLocation, weights: [Real; 3]) -> Site {
    let edge_site = |edge: usize, t: Real| {
        let (i, j) = TriangleLocation::edge_vertices(edge);
        if t <= SNAP {
            Site::particle(f.nodes[i], f.radius)
        } else if t >= 1.0 - SNAP {
            Site::particle(f.nodes[j], f.radius)
        } else {
            Site::edge(f.connections[edge], [f.nodes[i], f.nodes[j]], t, f.radius)
        }
    };
    match location {
        TriangleLocation::OnVertex(k) => Site::particle(f.nodes[k], f.radius),
        TriangleLocation::OnEdge { edge, t } => edge_site(edge, t),
        TriangleLocation::OnFace => {
            let [wa, wb, wc] = weights;
            // the smallest weight decides the edge it may lie on: wc ~ 0 is edge 0 (a → b),
            // wa ~ 0 edge 1 (b → c), wb ~ 0 edge 2 (c → a)
            let (min, edge, t) =
                [(wc, 0, wb / (wa + wb)), (wa, 1, wc / (wb + wc)), (wb, 2, wa / (wc + wa))]
                    .into_iter()
                    .min_by(|x, y| x.0.total_cmp(&y.0))
                    .unwrap_or((1.0, 0, 0.0));
            if min <= SNAP {
                edge_site(edge, t)
            } else {
                Site::face(f.id, f.nodes, weights, f.radius)
            }
        }
    }
}

/// Sphere–sphere: the two centres.
pub fn sphere_sphere(a: &SphereRef, b: &SphereRef) -> Candidate {
    Candidate::new(
        Site::particle(a.id, a.radius),
        a.center,
        Site::particle(b.id, b.radius),
        b.center,
    )
}

/// Sphere–connection: the sphere's centre projected on the axis, `t` clamped to [0, 1]
/// (paper §3; the end caps are the clamped cases).
pub fn sphere_connection(s: &SphereRef, c: &ConnectionRef) -> Candidate {
    let proj = project_point_segment(&s.center, &c.ends[0], &c.ends[1]);
    Candidate::new(
        Site::particle(s.id, s.radius),
        s.center,
        connection_site(c, proj.location),
        proj.point,
    )
}

/// Connection–connection: closest points of the two axes (paper eq 9–14), the middle of the
/// overlapping stretch for parallel axes.
pub fn connection_connection(a: &ConnectionRef, b: &ConnectionRef) -> Candidate {
    let cp = closest_points_segment_segment(&a.ends[0], &a.ends[1], &b.ends[0], &b.ends[1]);
    Candidate::new(
        connection_site(a, cp.location_a),
        cp.point_a,
        connection_site(b, cp.location_b),
        cp.point_b,
    )
}

/// Sphere–PFacet: the sphere's centre projected on the triangle (paper eq 15); inside the
/// face the weights are the barycentric coordinates, outside the nearest edge or vertex.
pub fn sphere_pfacet(s: &SphereRef, f: &PFacetRef) -> Candidate {
    let [a, b, c] = &f.corners;
    let proj = project_point_triangle(&s.center, a, b, c);
    Candidate::new(
        Site::particle(s.id, s.radius),
        s.center,
        pfacet_site(f, proj.location, proj.weights),
        proj.point,
    )
}

/// Connection–PFacet: closest points of the axis and the triangle. Unlike YADE's node–face
/// plus edge–edge split, a cylinder lying across the face's interior is found.
pub fn connection_pfacet(c: &ConnectionRef, f: &PFacetRef) -> Candidate {
    let [a, b, d] = &f.corners;
    let cp = closest_points_segment_triangle(&c.ends[0], &c.ends[1], a, b, d);
    Candidate::new(
        connection_site(c, cp.location_segment),
        cp.point_segment,
        pfacet_site(f, cp.location_triangle, cp.weights),
        cp.point_triangle,
    )
}

/// PFacet–PFacet: closest points of the two triangles (the centroid of the overlap for
/// coplanar-parallel triangles over each other).
pub fn pfacet_pfacet(f: &PFacetRef, g: &PFacetRef) -> Candidate {
    let [a0, b0, c0] = &f.corners;
    let [a1, b1, c1] = &g.corners;
    let cp = closest_points_triangle_triangle(a0, b0, c0, a1, b1, c1);
    Candidate::new(
        pfacet_site(f, cp.location_0, cp.weights_0),
        cp.point_0,
        pfacet_site(g, cp.location_1, cp.weights_1),
        cp.point_1,
    )
}
