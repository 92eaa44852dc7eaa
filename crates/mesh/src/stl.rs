//! STL, ASCII and binary. STL is a triangle soup: every facet gives three new vertices, in file
//! order, with no merging (the PFacet builder merges coincident vertices). Facet normals are
//! ignored; the vertex order is kept.
//!
//! Detection: binary when the size is exactly 84 + 50·n for the triangle count n stored at
//! byte 80, even if the header starts with "solid" (many exporters write that); ASCII when the
//! file starts with "solid" and holds no NUL byte; anything else is read as binary, which then
//! fails on the size.

use flexdem_geom::{TriMesh, Vec3};

use crate::text::{parse_point, NumberedLines};
use crate::MeshError;

const HEADER_BYTES: usize = 80;
const BINARY_PREFIX_BYTES: usize = 84;
const FACET_BYTES: usize = 50;

/// Reads an STL file (ASCII or binary, detected from the contents); `file` names it in errors.
/// Returns three unmerged vertices per triangle.
pub fn read_stl(bytes: &[u8], file: &str) -> Result<TriMesh, MeshError> {
    let declared = declared_binary_count(bytes);
    let size_matches =
        declared.is_some_and(|n| (n as u128) * (FACET_BYTES as u128) + 84 == bytes.len() as u128);
    if size_matches {
        return read_binary(bytes, file);
    }
    let starts_with_solid =
        bytes.trim_ascii_start().get(..5).is_some_and(|s| s.eq_ignore_ascii_case(b"solid"));
    if starts_with_solid && !bytes.contains(&0) {
        let text = String::from_utf8_lossy(bytes);
        return read_ascii(&text, file);
    }
    read_binary(bytes, file)
}

/// The triangle count of a binary STL header, if the file is long enough to hold one.
fn declared_binary_count(bytes: &[u8]) -> Option<u32> {
    let count: [u8; 4] = bytes.get(HEADER_BYTES..BINARY_PREFIX_BYTES)?.try_into().ok()?;
    Some(u32::from_le_bytes(count))
}

fn read_binary(bytes: &[u8], file: &str) -> Result<TriMesh, MeshError> {
    let Some(declared) = declared_binary_count(bytes) else {
        return Err(MeshError::binary(
            file,
            bytes.len(),
            format!(
                "not an ASCII STL (does not start with \"solid\") and too short for a binary \
                 STL: the file ends after {} bytes, expected at least {BINARY_PREFIX_BYTES} (an \
                 80-byte header and the triangle count)",
                bytes.len()
            ),
        ));
    };
    let data = &bytes[BINARY_PREFIX_BYTES..];
    let held = data.len() / FACET_BYTES;
    let extra = data.len() % FACET_BYTES;
    if declared as usize != held || extra != 0 {
        let trailing = if extra == 0 { String::new() } else { format!(" and {extra} extra bytes") };
        // the count is at byte 80; the facets start at byte 84, 50 bytes each
        return Err(MeshError::binary(
            file,
            HEADER_BYTES,
            format!(
                "binary STL declares {declared} triangles ({} bytes of facets from byte \
                 {BINARY_PREFIX_BYTES}) but the file holds {held}{trailing} ({} bytes of facets)",
                declared as u64 * FACET_BYTES as u64,
                data.len()
            ),
        ));
    }
    if held == 0 {
        return Err(MeshError::binary(
            file,
            HEADER_BYTES,
            "binary STL declares 0 triangles: it holds no triangle",
        ));
    }
    let mut vertices = Vec::with_capacity(3 * held);
    for (facet_index, facet) in data.chunks_exact(FACET_BYTES).enumerate() {
        let facet_offset = BINARY_PREFIX_BYTES + facet_index * FACET_BYTES;
        // Bytes 0..12: the normal (ignored); 12..48: three vertices of three f32; 48..50:
        // attribute byte count (ignored).
        for corner in 0..3 {
            let start = 12 + 12 * corner;
            let mut coordinates = [0.0; 3];
            for (axis, value) in coordinates.iter_mut().enumerate() {
                let offset = start + 4 * axis;
                let raw: [u8; 4] =
                    facet.get(offset..offset + 4).and_then(|b| b.try_into().ok()).unwrap_or([0; 4]);
                let number = f32::from_le_bytes(raw);
                if !number.is_finite() {
                    return Err(MeshError::binary(
                        file,
                        facet_offset + offset,
                        format!(
                            "triangle {}: expected a finite coordinate, found {number}",
                            facet_index + 1
                        ),
                    ));
                }
                *value = f64::from(number);
            }
            vertices.push(Vec3::from(coordinates));
        }
    }
    let triangles = (0..held).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    Ok(TriMesh::new(vertices, triangles))
}

/// Where the ASCII parser is in the `solid / facet / outer loop / vertex` nesting.
#[derive(Clone, Copy, PartialEq, Eq)]
enum State {
    /// Before `solid` or after `endsolid`.
    Outside,
    /// Inside a solid, between facets.
    InSolid,
    /// After `facet normal ...`, before `outer loop`.
    InFacet,
    /// Inside `outer loop`.
    InLoop,
    /// After `endloop`, before `endfacet`.
    AfterLoop,
}

fn read_ascii(text: &str, file: &str) -> Result<TriMesh, MeshError> {
    let mut lines = NumberedLines::new(text, file);
    let mut state = State::Outside;
    let mut vertices: Vec<Vec3> = Vec::new();
    let mut corners_in_loop = 0;
    while let Some((line, content)) = lines.next_content(None) {
        let mut tokens = content.split_whitespace();
        let keyword = tokens.next().unwrap_or_default().to_ascii_lowercase();
        let unexpected = |expected: &str| {
            MeshError::text(file, line, format!("expected {expected}, found {content:?}"))
        };
        state = match (state, keyword.as_str()) {
            (State::Outside, "solid") => State::InSolid,
            (State::Outside, _) => return Err(unexpected("\"solid\"")),
            (State::InSolid, "facet") => State::InFacet,
            (State::InSolid, "endsolid") => State::Outside,
            (State::InSolid, _) => return Err(unexpected("\"facet\" or \"endsolid\"")),
            (State::InFacet, "outer") => {
                corners_in_loop = 0;
                State::InLoop
            }
            (State::InFacet, _) => return Err(unexpected("\"outer loop\"")),
            (State::InLoop, "vertex") => {
                let coordinates: Vec<&str> = tokens.collect();
                let Ok(xyz) = <[&str; 3]>::try_from(coordinates.as_slice()) else {
                    return Err(MeshError::text(
                        file,
                        line,
                        format!(
                            "expected 3 numbers for a vertex (x y z), found {}",
                            coordinates.len()
                        ),
                    ));
                };
                if corners_in_loop == 3 {
                    return Err(unexpected("\"endloop\" after 3 vertices"));
                }
                vertices.push(parse_point(file, line, xyz)?);
                corners_in_loop += 1;
                State::InLoop
            }
            (State::InLoop, "endloop") if corners_in_loop == 3 => State::AfterLoop,
            (State::InLoop, "endloop") => {
                return Err(MeshError::text(
                    file,
                    line,
                    format!("expected 3 vertices in a facet's loop, found {corners_in_loop}"),
                ))
            }
            (State::InLoop, _) => return Err(unexpected("\"vertex\" or \"endloop\"")),
            (State::AfterLoop, "endfacet") => State::InSolid,
            (State::AfterLoop, _) => return Err(unexpected("\"endfacet\"")),
        };
    }
    let end = lines.last_line();
    match state {
        State::Outside if vertices.is_empty() => {
            Err(MeshError::text(file, end, "no facet found in the ASCII STL file"))
        }
        State::Outside => {
            let triangles =
                (0..vertices.len() / 3).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
            Ok(TriMesh::new(vertices, triangles))
        }
        _ => Err(MeshError::text(
            file,
            end,
            "expected \"endsolid\", found the end of the file (truncated STL?)",
        )),
    }
}
