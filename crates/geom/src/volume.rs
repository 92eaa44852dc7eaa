//! Volumes enclosed by triangulated surfaces, by the divergence theorem.
//!
//! With `div(x − o) = 3` for any point `o`, the volume enclosed by a closed surface `S` is
//! `V = (1/3)∮_S (x − o)·n dA`. Over a flat triangle `(a, b, c)` the integrand's integral is
//! exact from its vertices, so a closed triangle mesh whose triangles all turn
//! counterclockwise seen from outside (normals `(b − a) × (c − a)` pointing out) encloses
//!
//! ```text
//! V = Σ_f (1/6)·(a − o)·((b − o) × (c − o))
//! ```
//!
//! the sum of the signed volumes of the tetrahedra `(o, a, b, c)`, independent of `o` for a
//! closed surface. Taking `o` on the surface (a vertex of the mesh) keeps the terms at the
//! size of the mesh, so that moving the whole mesh far from the origin changes nothing but
//! round-off. Inward-oriented meshes give `−V`.
//!
//! An **open** surface (a tube) is closed by planes, one per boundary loop: see
//! [`volume_closed_by_planes`].

use crate::{Real, Vec3};

/// A plane through `point` with normal `normal` (non-zero, any length; its sign does not
/// matter to the closing of a surface, whose orientation comes from the surface).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Plane {
    /// A point of the plane.
    pub point: Vec3,
    /// Its normal (non-zero).
    pub normal: Vec3,
}

impl Plane {
    /// The orthogonal projection of `x` onto the plane: `x − ((x − p)·n̂) n̂`.
    pub fn project(&self, x: &Vec3) -> Vec3 {
        let n = self.normal.normalize();
        x - n * (x - self.point).dot(&n)
    }
}

/// A boundary loop of an open surface and the plane that closes it.
///
/// `boundary` lists vertex indices in the order the surface's own triangles run along its
/// boundary edges: each `(boundary[i], boundary[i + 1])` (cyclically) is an edge of one
/// triangle, traversed in that direction by it.
#[derive(Clone, Debug, PartialEq)]
pub struct PlaneClosure {
    /// The loop's vertices (indices into the mesh's vertices), in the surface's direction.
    pub boundary: Vec<usize>,
    /// The closing plane.
    pub plane: Plane,
}

/// Signed volume of the tetrahedron `(o, a, b, c)`: `(1/6)·(a − o)·((b − o) × (c − o))`,
/// positive when `(a, b, c)` turns counterclockwise seen from the side away from `o`.
pub fn tetrahedron_volume(o: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> Real {
    (a - o).dot(&(b - o).cross(&(c - o))) / 6.0
}

/// The point the tetrahedra of a mesh's volume start from: its first vertex used (the
/// origin for an empty mesh). On the surface, so every term has the size of the mesh.
fn reference_point(vertices: &[Vec3], triangles: &[[usize; 3]], closures: &[PlaneClosure]) -> Vec3 {
    triangles
        .first()
        .map(|t| t[0])
        .or_else(|| closures.iter().find_map(|c| c.boundary.first().copied()))
        .map_or_else(Vec3::zeros, |i| vertices[i])
}

/// `Σ_f (1/6)·(a − o)·((b − o) × (c − o))` over `triangles` (indices into `vertices`): the
/// flux of `(x − o)/3` through them.
fn triangles_flux(o: &Vec3, vertices: &[Vec3], triangles: &[[usize; 3]]) -> Real {
    triangles
        .iter()
        .map(|&[a, b, c]| tetrahedron_volume(o, &vertices[a], &vertices[b], &vertices[c]))
        .sum()
}

/// Volume enclosed by a closed, consistently oriented triangle mesh (see the module
/// documentation): `V = Σ_f (1/6)·(a − o)·((b − o) × (c − o))`, with `o` the mesh's first
/// vertex. Positive for outward normals `(b − a) × (c − a)`, negative for inward ones; for a
/// surface that is not closed the result depends on `o` and means nothing (close it with
/// [`volume_closed_by_planes`]). Panics on an index out of range.
pub fn closed_surface_volume(vertices: &[Vec3], triangles: &[[usize; 3]]) -> Real {
    let o = reference_point(vertices, triangles, &[]);
    triangles_flux(&o, vertices, triangles)
}

/// The flux of `(x − o)/3` through the surface that closes one boundary loop
/// `x₀ … x_{m−1}` (in the surface's direction) by its plane: with `x'ᵢ` the projection of
/// `xᵢ` onto the plane,
///
/// - the **ribbon** of quads `(x_{i+1}, xᵢ, x'ᵢ, x'_{i+1})` between the loop and its
///   projection, which runs along each boundary edge against the surface (so the edge is
///   shared with opposite directions). Each quad is planar, its sides `xᵢ − x'ᵢ` both being
///   along the plane's normal, so its split into the triangles `(x_{i+1}, xᵢ, x'ᵢ)` and
///   `(x_{i+1}, x'ᵢ, x'_{i+1})` is exact, whichever side of the plane the nodes are on;
/// - the **cap**, the projected loop run backwards `(x'_{m−1}, …, x'₀)`: a planar polygon,
///   whose flux is `−Σᵢ (1/6)(c − o)·((x'ᵢ − o) × (x'_{i+1} − o))` for any point `c` of the
///   plane (here `x'₀`), even when the polygon is not convex.
///
/// The ribbon vanishes when the loop lies on the plane (a tube cut flat, a platen touching
/// the membrane's end ring).
pub fn plane_closure_flux(o: &Vec3, vertices: &[Vec3], closure: &PlaneClosure) -> Real {
    let loop_nodes = &closure.boundary;
    let m = loop_nodes.len();
    if m == 0 {
        return 0.0;
    }
    let x = |i: usize| vertices[loop_nodes[i % m]];
    let projected: Vec<Vec3> = (0..m).map(|i| closure.plane.project(&x(i))).collect();
    let xp = |i: usize| projected[i % m];
    let ribbon: Real = (0..m)
        .map(|i| {
            tetrahedron_volume(o, &x(i + 1), &x(i), &xp(i))
                + tetrahedron_volume(o, &x(i + 1), &xp(i), &xp(i + 1))
        })
        .sum();
    let c = xp(0);
    let cap: Real = (0..m).map(|i| -tetrahedron_volume(o, &c, &xp(i), &xp(i + 1))).sum();
    ribbon + cap
}

/// Volume enclosed by an open triangle mesh whose boundary loops are each closed by a plane
/// (a tube of PFacets between two platens): the flux of `(x − o)/3` through the triangles
/// plus, for each loop, through its ribbon and cap ([`plane_closure_flux`]):
///
/// ```text
/// V = Σ_f (1/6)(a − o)·((b − o) × (c − o))
///   + Σ_loops Σᵢ [(1/6)(x_{i+1} − o)·((xᵢ − o) × (x'ᵢ − o))
///               + (1/6)(x_{i+1} − o)·((x'ᵢ − o) × (x'_{i+1} − o))
///               − (1/6)(x'₀ − o)·((x'ᵢ − o) × (x'_{i+1} − o))]
/// ```
///
/// with `o` the mesh's first vertex. The closed surface is exact wherever the boundary
/// nodes are (on, inside or outside the planes), so `V` does not depend on `o`. With the
/// triangles facing out (closing planes included) `V > 0`. Every boundary loop must be given
/// exactly once, each boundary edge in the direction its triangle runs along it; with no
/// closure this is [`closed_surface_volume`]. Panics on an index out of range.
pub fn volume_closed_by_planes(
    vertices: &[Vec3],
    triangles: &[[usize; 3]],
    closures: &[PlaneClosure],
) -> Real {
    let o = reference_point(vertices, triangles, closures);
    let caps: Real = closures.iter().map(|c| plane_closure_flux(&o, vertices, c)).sum();
    triangles_flux(&o, vertices, triangles) + caps
}

/// The vector area `½ Σᵢ xᵢ × x_{i+1}` of the closed polygon `points` (cyclic): its normal
/// times its area for a planar polygon (counterclockwise about the normal), independent of
/// the origin for any closed polygon.
pub fn polygon_vector_area(points: &[Vec3]) -> Vec3 {
    let m = points.len();
    let Some(first) = points.first() else { return Vec3::zeros() };
    (0..m).fold(Vec3::zeros(), |sum, i| {
        let (a, b) = (points[i] - first, points[(i + 1) % m] - first);
        sum + a.cross(&b) * 0.5
    })
}

#[cfg(test)]
mod tests;
