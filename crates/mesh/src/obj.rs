//! Wavefront OBJ: `v x y z [w]` vertices and `f` faces whose corners are written `v`, `v/vt`,
//! `v/vt/vn` or `v//vn` (only the vertex index is used). Indices are 1-based; negative ones
//! count back from the last vertex read so far (-1 is the last). A face with more than three
//! corners is split into a fan around its first corner: (0, 1, 2), (0, 2, 3), ...
//! Comments (`#` to the end of the line) and every other statement (`vt`, `vn`, `o`, `g`,
//! `usemtl`, `mtllib`, `s`, `l`, ...) are ignored. Positive indices may refer to vertices
//! defined later in the file; they are checked against the final vertex count.

use flexdem_geom::{TriMesh, Vec3};

use crate::text::{parse_i64, parse_point, NumberedLines};
use crate::vertices::drop_unused_vertices;
use crate::MeshError;

/// A triangle of 0-based vertex indices, unchecked (a positive index may name a vertex
/// defined later), with the line it came from.
struct Face {
    corners: [i64; 3],
    line: usize,
}

/// Reads a Wavefront OBJ file; `file` names it in errors. Vertices no face uses are dropped.
pub fn read_obj(text: &str, file: &str) -> Result<TriMesh, MeshError> {
    let mut lines = NumberedLines::new(text, file);
    let mut vertices: Vec<Vec3> = Vec::new();
    let mut triangles: Vec<Face> = Vec::new();
    while let Some((line, content)) = lines.next_content(Some('#')) {
        let content = content.split('#').next().unwrap_or_default();
        let mut tokens = content.split_whitespace();
        match tokens.next() {
            Some("v") => {
                let coordinates: Vec<&str> = tokens.collect();
                // x y z, x y z w, or x y z r g b (vertex colours) are all in use.
                let Some(xyz) = coordinates.get(..3).and_then(|c| <[&str; 3]>::try_from(c).ok())
                else {
                    return Err(MeshError::text(
                        file,
                        line,
                        format!(
                            "expected at least 3 numbers for a vertex (v x y z), found {}",
                            coordinates.len()
                        ),
                    ));
                };
                vertices.push(parse_point(file, line, xyz)?);
            }
            Some("f") => {
                let mut corners = Vec::new();
                for token in tokens {
                    corners.push(parse_corner(file, line, token, vertices.len())?);
                }
                if corners.len() < 3 {
                    return Err(MeshError::text(
                        file,
                        line,
                        format!("expected at least 3 vertices for a face, found {}", corners.len()),
                    ));
                }
                for pair in corners[1..].windows(2) {
                    triangles.push(Face { corners: [corners[0], pair[0], pair[1]], line });
                }
            }
            _ => {}
        }
    }
    if triangles.is_empty() {
        return Err(MeshError::text(file, lines.last_line(), "no face (f) found in the OBJ file"));
    }
    let count = vertices.len();
    let mut checked = Vec::with_capacity(triangles.len());
    for face in &triangles {
        let mut triangle = [0; 3];
        for (slot, &index) in triangle.iter_mut().zip(&face.corners) {
            *slot = usize::try_from(index).ok().filter(|&i| i < count).ok_or_else(|| {
                MeshError::text(
                    file,
                    face.line,
                    format!(
                        "face index {} out of range ({count} vertices)",
                        index.saturating_add(1)
                    ),
                )
            })?;
        }
        checked.push(triangle);
    }
    Ok(drop_unused_vertices(&vertices, checked))
}

/// The 0-based vertex index of a face corner `v`, `v/vt`, `v/vt/vn` or `v//vn`. A negative
/// index is resolved against the `defined` vertices read so far; a positive one is returned
/// as is (checked at the end of the file).
fn parse_corner(file: &str, line: usize, token: &str, defined: usize) -> Result<i64, MeshError> {
    let parts: Vec<&str> = token.split('/').collect();
    if parts.len() > 3 || parts.first().is_none_or(|v| v.is_empty()) {
        return Err(MeshError::text(
            file,
            line,
            format!("expected a face corner v, v/vt, v/vt/vn or v//vn, found {token:?}"),
        ));
    }
    for (position, part) in parts.iter().enumerate().skip(1) {
        if !part.is_empty() {
            let what = if position == 1 { "a texture index" } else { "a normal index" };
            parse_i64(file, line, part, what)?;
        }
    }
    let index = parse_i64(file, line, parts[0], "a vertex index")?;
    match index {
        0 => Err(MeshError::text(file, line, "face index 0 is invalid (indices start at 1)")),
        i if i > 0 => Ok(i - 1),
        negative => {
            let resolved = i64::try_from(defined).unwrap_or(i64::MAX).saturating_add(negative);
            if resolved < 0 {
                Err(MeshError::text(
                    file,
                    line,
                    format!(
                        "relative face index {negative} out of range ({defined} vertices so far)"
                    ),
                ))
            } else {
                Ok(resolved)
            }
        }
    }
}
