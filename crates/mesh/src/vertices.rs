//! Dropping the vertices no triangle uses.

use flexdem_geom::{TriMesh, Vec3};

/// Keeps only the vertices some triangle uses, in their original order, and renumbers the
/// triangles. Callers check every index is `< vertices.len()` first; an index that is not
/// (never produced by the readers) would be kept as is.
pub(crate) fn drop_unused_vertices(vertices: &[Vec3], triangles: Vec<[usize; 3]>) -> TriMesh {
    let mut used = vec![false; vertices.len()];
    for triangle in &triangles {
        for &v in triangle {
            if let Some(flag) = used.get_mut(v) {
                *flag = true;
            }
        }
    }
    let mut new_index = vec![usize::MAX; vertices.len()];
    let mut kept = Vec::new();
    for (old, (&vertex, &is_used)) in vertices.iter().zip(&used).enumerate() {
        if is_used {
            new_index[old] = kept.len();
            kept.push(vertex);
        }
    }
    let triangles =
        triangles.into_iter().map(|t| t.map(|v| new_index.get(v).copied().unwrap_or(v))).collect();
    TriMesh::new(kept, triangles)
}
