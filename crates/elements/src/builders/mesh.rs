//! Any triangle mesh to PFacets (YADE's `gtsPFacet` / `gmshPFacet`, done robustly): merge
//! coincident vertices, one connection per unique edge, reject bad triangles with errors that
//! name them.
//!
//! Policy for meshes that are valid but unusual:
//! - **Non-manifold edges** (shared by more than two triangles, e.g. a fin on a plate) are
//!   allowed: the edge is one connection, shared by all its PFacets (YADE's `pfacetCreator4`
//!   can build the same), and the adjacency lists all of them.
//! - **T-junctions** and **open boundaries** are fine.
//! - **Orientation** is kept as given; PFacets are two-sided (thickness 2r), so an
//!   inconsistently oriented mesh is simulated the same way.
//! - **Unreferenced vertices** are dropped (they would be nodes without mass).
//! - **Duplicate triangles** (the same three vertices after merging, in any order) are
//!   rejected: two coincident PFacets are a meshing error.

use super::skeleton::{
    add_skeleton, bounding_diagonal, Skeleton, StructureOptions, ZERO_EDGE_RELATIVE,
};
use crate::error::BuildError;
use crate::{Model, StructureId};
use flexdem_geom::{Real, TriMesh, Vec3};
use std::collections::HashMap;

/// A triangle is degenerate when its height over its longest edge is below this fraction of
/// that edge (2·area/L²_max, ≈ the smallest angle in radians for a thin triangle).
pub const DEGENERATE_TRIANGLE_RATIO: Real = 1e-8;

/// Largest relative merge tolerance accepted.
pub const MAX_MERGE_TOLERANCE: Real = 0.1;

/// Adds the triangles of `mesh` as PFacets. Vertices closer than
/// `merge_tolerance × (diagonal of the mesh's bounding box)` are merged into one node (a
/// relative tolerance in [0, 0.1]; 1e-6 suits meshes written as triangle soups, 0 merges only
/// identical coordinates). Nodes are the merged vertices that some triangle uses, in
/// increasing order of their lowest vertex index; PFacet i is triangle i, with its vertices in
/// the given order; each unique edge is one connection. Rejected, naming the triangle and its
/// vertices: an index out of range, a repeated index, a non-finite vertex, an edge whose ends
/// merge (zero-length edge), a flat triangle (see [`DEGENERATE_TRIANGLE_RATIO`]), a duplicate
/// triangle. See the module documentation for what is allowed.
pub fn pfacets_from_mesh(
    model: &mut Model,
    mesh: &TriMesh,
    merge_tolerance: Real,
    opts: &StructureOptions,
) -> Result<StructureId, BuildError> {
    if !(merge_tolerance.is_finite() && (0.0..=MAX_MERGE_TOLERANCE).contains(&merge_tolerance)) {
        return Err(BuildError::InvalidParameter {
            name: "merge_tolerance",
            value: merge_tolerance.to_string(),
            expected: "a relative tolerance in [0, 0.1] (e.g. 1e-6)",
        });
    }
    if mesh.triangles.is_empty() {
        return Err(BuildError::EmptyMesh { vertices: mesh.vertices.len() });
    }
    check_triangle_indices(mesh)?;
    let mut used = vec![false; mesh.vertices.len()];
    for t in &mesh.triangles {
        for &v in t {
            used[v] = true;
        }
    }
    let used_points: Vec<Vec3> =
        mesh.vertices.iter().zip(&used).filter(|(_, &u)| u).map(|(p, _)| *p).collect();
    let size = bounding_diagonal(&used_points);
    if size.is_nan() || size <= 0.0 {
        return Err(BuildError::ZeroSizeMesh);
    }
    let tolerance = merge_tolerance * size;
    let representative = merge_vertices(&mesh.vertices, &used, tolerance, size);
    // Node numbering: representatives in increasing index order.
    let mut node_of = vec![u32::MAX; mesh.vertices.len()];
    let mut points = Vec::new();
    for v in 0..mesh.vertices.len() {
        if used[v] && representative[v] == v {
            node_of[v] = points.len() as u32;
            points.push(mesh.vertices[v]);
        }
    }
    let min_edge = tolerance.max(ZERO_EDGE_RELATIVE * size);
    let mut seen: HashMap<[u32; 3], usize> = HashMap::with_capacity(mesh.triangles.len());
    let mut faces = Vec::with_capacity(mesh.triangles.len());
    for (triangle, &vertices) in mesh.triangles.iter().enumerate() {
        let face = vertices.map(|v| node_of[representative[v]]);
        let corners = face.map(|n| points[n as usize]);
        check_triangle_shape(triangle, vertices, &face, &corners, &mesh.vertices, min_edge)?;
        let mut key = face;
        key.sort_unstable();
        if let Some(&other) = seen.get(&key) {
            return Err(BuildError::DuplicateTriangle { triangle, vertices, other });
        }
        seen.insert(key, triangle);
        faces.push(face);
    }
    add_skeleton(model, &Skeleton { points, edges: vec![], faces }, opts)
}

/// Index range, repeated indices and finite coordinates of every triangle.
fn check_triangle_indices(mesh: &TriMesh) -> Result<(), BuildError> {
    let vertex_count = mesh.vertices.len();
    for (triangle, &vertices) in mesh.triangles.iter().enumerate() {
        if let Some(&index) = vertices.iter().find(|&&v| v >= vertex_count) {
            return Err(BuildError::IndexOutOfRange { triangle, vertices, index, vertex_count });
        }
        let [a, b, c] = vertices;
        if a == b || b == c || c == a {
            return Err(BuildError::RepeatedIndex { triangle, vertices });
        }
        for &vertex in &vertices {
            let point = mesh.vertices[vertex];
            if !point.iter().all(|x| x.is_finite()) {
                return Err(BuildError::NonFiniteVertex { triangle, vertices, vertex, point });
            }
        }
    }
    Ok(())
}

/// Zero-length edges (ends merged or closer than `min_edge`) and flat triangles.
fn check_triangle_shape(
    triangle: usize,
    vertices: [usize; 3],
    face: &[u32; 3],
    corners: &[Vec3; 3],
    original: &[Vec3],
    min_edge: Real,
) -> Result<(), BuildError> {
    let mut longest: Real = 0.0;
    for edge in 0..3 {
        let (p, q) = (edge, (edge + 1) % 3);
        let length = (corners[q] - corners[p]).norm();
        if face[p] == face[q] || length.is_nan() || length <= min_edge {
            let ends = [vertices[p], vertices[q]];
            return Err(BuildError::ZeroLengthEdge {
                triangle,
                vertices,
                edge,
                ends,
                length: (original[ends[1]] - original[ends[0]]).norm(),
                tolerance: min_edge,
            });
        }
        longest = longest.max(length);
    }
    let [a, b, c] = *corners;
    let ratio = (b - a).cross(&(c - a)).norm() / (longest * longest);
    if ratio.is_nan() || ratio <= DEGENERATE_TRIANGLE_RATIO {
        return Err(BuildError::DegenerateTriangle {
            triangle,
            vertices,
            ratio,
            min_ratio: DEGENERATE_TRIANGLE_RATIO,
        });
    }
    Ok(())
}

/// For each vertex, the index of the vertex it merges into: vertices are visited in index
/// order and each joins the lowest-index earlier representative within `tolerance`
/// (a distance), or becomes a representative. Vertices with `used[v] == false` are left
/// alone (their own representative). Grid hashing with cells of at least `tolerance`, so each
/// vertex looks at 27 cells: O(n) expected. `size` bounds the grid resolution.
fn merge_vertices(vertices: &[Vec3], used: &[bool], tolerance: Real, size: Real) -> Vec<usize> {
    let mut representative: Vec<usize> = (0..vertices.len()).collect();
    let origin = vertices
        .iter()
        .zip(used)
        .filter(|(_, &u)| u)
        .fold(Vec3::repeat(Real::INFINITY), |lo, (p, _)| lo.inf(p));
    // Cells no smaller than the tolerance (so neighbours cover it) nor than size / 2^20 (so
    // cell coordinates stay small integers).
    let cell = tolerance.max(size / (1u64 << 20) as Real);
    let key = |p: &Vec3| -> [i64; 3] {
        let k = (p - origin) / cell;
        [k.x.floor() as i64, k.y.floor() as i64, k.z.floor() as i64]
    };
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for v in 0..vertices.len() {
        if !used[v] {
            continue;
        }
        let p = vertices[v];
        let k = key(&p);
        let mut best: Option<usize> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(reps) = grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) else {
                        continue;
                    };
                    for &r in reps {
                        if (vertices[r] - p).norm() <= tolerance && best.is_none_or(|b| r < b) {
                            best = Some(r);
                        }
                    }
                }
            }
        }
        match best {
            Some(r) => representative[v] = r,
            None => grid.entry(k).or_default().push(v),
        }
    }
    representative
}

#[cfg(test)]
mod tests;
