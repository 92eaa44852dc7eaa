//! GTS surfaces (the GNU Triangulated Surface library's text format): a first line
//! `nV nE nF` (possibly followed by class names), then nV lines `x y z`, nE lines `a b`
//! (1-based vertex indices) and nF lines `e1 e2 e3` (1-based edge indices). Extra fields on a
//! line (of derived GTS classes) are ignored, as are blank lines, `#` comment lines and
//! anything after the last face.
//!
//! A face's vertices are ordered as GTS's `gts_triangle_vertices` orders them (what YADE's
//! `gtsPFacet` gets from the python gts module): (v1, v2) is edge e1 and v2 is the vertex e1
//! shares with e2, so v3 is e2's other end. The three edges must close a triangle.

use flexdem_geom::TriMesh;

use crate::text::{leading_tokens, one_based, parse_point, parse_usize, NumberedLines};
use crate::vertices::drop_unused_vertices;
use crate::MeshError;

/// Bytes each declared item needs at least ("0 0 0\n" for a vertex, "1 2\n" for an edge or
/// face): memory is reserved for no more items than the text can hold, whatever the header
/// declares (a count too large then fails at the end of the file).
const MIN_ITEM_BYTES: usize = 4;

/// Reads a GTS surface; `file` names it in errors. Vertices no face uses are dropped.
pub fn read_gts(text: &str, file: &str) -> Result<TriMesh, MeshError> {
    let mut lines = NumberedLines::new(text, file);
    let (line, header) = lines.expect_content(Some('#'), "the header line \"nV nE nF\"")?;
    let [nv, ne, nf] = leading_tokens::<3>(file, line, header, "the header (nV nE nF)")?;
    let vertex_count = parse_usize(file, line, nv, "the number of vertices")?;
    let edge_count = parse_usize(file, line, ne, "the number of edges")?;
    let face_count = parse_usize(file, line, nf, "the number of faces")?;
    let max_items = text.len() / MIN_ITEM_BYTES;
    if face_count == 0 {
        return Err(MeshError::text(file, line, "the GTS header declares no face"));
    }

    let mut vertices = Vec::with_capacity(vertex_count.min(max_items));
    for k in 0..vertex_count {
        let expected = format!("vertex {} of {vertex_count} (x y z)", k + 1);
        let (line, content) = lines.expect_content(Some('#'), &expected)?;
        let xyz = leading_tokens::<3>(file, line, content, "a vertex (x y z)")?;
        vertices.push(parse_point(file, line, xyz)?);
    }

    let mut edges = Vec::with_capacity(edge_count.min(max_items));
    for k in 0..edge_count {
        let expected = format!("edge {} of {edge_count} (a b)", k + 1);
        let (line, content) = lines.expect_content(Some('#'), &expected)?;
        let [a, b] = leading_tokens::<2>(file, line, content, "an edge (a b)")?;
        let a = parse_usize(file, line, a, "an edge's vertex index")?;
        let b = parse_usize(file, line, b, "an edge's vertex index")?;
        let a = one_based(file, line, a, vertex_count, "vertices")?;
        let b = one_based(file, line, b, vertex_count, "vertices")?;
        if a == b {
            return Err(MeshError::text(
                file,
                line,
                format!("edge {} joins vertex {} to itself", k + 1, a + 1),
            ));
        }
        edges.push([a, b]);
    }

    let mut triangles = Vec::with_capacity(face_count.min(max_items));
    for k in 0..face_count {
        let expected = format!("face {} of {face_count} (e1 e2 e3)", k + 1);
        let (line, content) = lines.expect_content(Some('#'), &expected)?;
        let tokens = leading_tokens::<3>(file, line, content, "a face (e1 e2 e3)")?;
        let mut face_edges = [[0; 2]; 3];
        for (edge, token) in face_edges.iter_mut().zip(tokens) {
            let index = parse_usize(file, line, token, "a face's edge index")?;
            let index = one_based(file, line, index, edge_count, "edges")?;
            *edge = edges.get(index).copied().unwrap_or_default();
        }
        let triangle = face_vertices(face_edges).ok_or_else(|| {
            MeshError::text(
                file,
                line,
                format!("face {}: edges {} do not form a triangle", k + 1, content.trim()),
            )
        })?;
        triangles.push(triangle);
    }
    Ok(drop_unused_vertices(&vertices, triangles))
}

/// The vertices of a face from its three edges, ordered as `gts_triangle_vertices` does, or
/// `None` if the edges do not close a triangle of three distinct vertices.
fn face_vertices([e1, e2, e3]: [[usize; 2]; 3]) -> Option<[usize; 3]> {
    let [a1, b1] = e1;
    let [a2, b2] = e2;
    let [v1, v2, v3] = if b1 == a2 {
        [a1, b1, b2]
    } else if b1 == b2 {
        [a1, b1, a2]
    } else if a1 == a2 {
        [b1, a1, b2]
    } else if a1 == b2 {
        [b1, a1, a2]
    } else {
        return None;
    };
    let closes = e3 == [v3, v1] || e3 == [v1, v3];
    let distinct = v1 != v2 && v2 != v3 && v3 != v1;
    (closes && distinct).then_some([v1, v2, v3])
}

#[cfg(test)]
mod tests {
    use super::face_vertices;

    #[test]
    fn face_order_follows_the_first_two_edges() {
        // e1 = 0->1, e2 = 1->2: (0, 1, 2).
        assert_eq!(face_vertices([[0, 1], [1, 2], [2, 0]]), Some([0, 1, 2]));
        // e1 = 0->1, e2 = 2->1: (0, 1, 2).
        assert_eq!(face_vertices([[0, 1], [2, 1], [0, 2]]), Some([0, 1, 2]));
        // e1 = 1->0 shares its first end with e2 = 1->2: (0, 1, 2).
        assert_eq!(face_vertices([[1, 0], [1, 2], [2, 0]]), Some([0, 1, 2]));
        // e1 = 1->0, e2 = 2->1: (0, 1, 2).
        assert_eq!(face_vertices([[1, 0], [2, 1], [0, 2]]), Some([0, 1, 2]));
        // Swapping e1 and e2 reverses the orientation.
        assert_eq!(face_vertices([[1, 2], [0, 1], [2, 0]]), Some([2, 1, 0]));
    }

    #[test]
    fn open_or_degenerate_faces_are_rejected() {
        assert_eq!(face_vertices([[0, 1], [2, 3], [3, 0]]), None);
        assert_eq!(face_vertices([[0, 1], [1, 2], [2, 3]]), None);
        assert_eq!(face_vertices([[0, 1], [1, 0], [0, 1]]), None);
    }
}
