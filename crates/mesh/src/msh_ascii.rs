//! ASCII data of Gmsh `.msh` files: `$Nodes` and `$Elements` of versions 2.2 and 4.1.
//!
//! Line numbers are only counted when an error is reported (counting them for every field
//! would make reading quadratic in the file size).

use flexdem_geom::Vec3;

use crate::msh_data::{is_triangle, nodes_per_element, At, Cursor, MshData, Node, Triangle};
use crate::text;
use crate::MeshError;

/// Whitespace-separated fields of a line, with an error unless there are `N`.
fn fields<'a, const N: usize>(
    cursor: &Cursor<'_>,
    pos: usize,
    line: &'a str,
    what: &str,
) -> Result<[&'a str; N], MeshError> {
    let tokens: Vec<&str> = line.split_whitespace().collect();
    <[&str; N]>::try_from(tokens.as_slice()).map_err(|_| {
        cursor.text_error(pos, format!("expected {N} numbers for {what}, found {}", tokens.len()))
    })
}

/// A non-negative integer field.
fn integer(cursor: &Cursor<'_>, pos: usize, token: &str, what: &str) -> Result<u64, MeshError> {
    token.parse().map_err(|_| {
        cursor
            .text_error(pos, format!("expected a non-negative integer for {what}, found {token:?}"))
    })
}

/// A count field, as usize. (The line number is only counted on error: counting it for every
/// field would make reading quadratic in the file size.)
pub(super) fn count(
    cursor: &Cursor<'_>,
    pos: usize,
    token: &str,
    what: &str,
) -> Result<usize, MeshError> {
    text::unsigned(token, what).map_err(|message| cursor.text_error(pos, message))
}

/// A node's coordinates.
fn point(cursor: &Cursor<'_>, pos: usize, xyz: [&str; 3]) -> Result<Vec3, MeshError> {
    text::point(xyz).map_err(|message| cursor.text_error(pos, message))
}

/// `$Nodes` of 2.2 ASCII: a count, then `tag x y z` lines.
pub(super) fn read_nodes_v2(cursor: &mut Cursor<'_>, data: &mut MshData) -> Result<(), MeshError> {
    let (pos, line) = cursor.expect_data_line("the number of nodes")?;
    let [n] = fields::<1>(cursor, pos, line, "the number of nodes")?;
    let total = count(cursor, pos, n, "the number of nodes")?;
    for k in 0..total {
        let what = format!("node {} of {total} (tag x y z)", k + 1);
        let (pos, line) = cursor.expect_data_line(&what)?;
        let [tag, x, y, z] = fields::<4>(cursor, pos, line, "a node (tag x y z)")?;
        let tag = integer(cursor, pos, tag, "a node tag")?;
        let position = point(cursor, pos, [x, y, z])?;
        data.nodes.push(Node { tag, position, at: At::Text(pos) });
    }
    Ok(())
}

/// `$Elements` of 2.2 ASCII: a count, then `tag type ntags tags... nodes...` lines.
pub(super) fn read_elements_v2(
    cursor: &mut Cursor<'_>,
    data: &mut MshData,
) -> Result<(), MeshError> {
    let (pos, line) = cursor.expect_data_line("the number of elements")?;
    let [n] = fields::<1>(cursor, pos, line, "the number of elements")?;
    let total = count(cursor, pos, n, "the number of elements")?;
    for k in 0..total {
        let what = format!("element {} of {total} (tag type ntags tags... nodes...)", k + 1);
        let (pos, line) = cursor.expect_data_line(&what)?;
        let tokens: Vec<&str> = line.split_whitespace().collect();
        let [_tag, element_type, tag_count] =
            tokens.get(..3).and_then(|t| t.try_into().ok()).ok_or_else(|| {
                cursor.text_error(
                    pos,
                    format!(
                        "expected at least 3 numbers for an element (tag type ntags ...), found {}",
                        tokens.len()
                    ),
                )
            })?;
        let element_type = integer(cursor, pos, element_type, "an element type")?;
        let tag_count = count(cursor, pos, tag_count, "the number of element tags")?;
        let element_type = i64::try_from(element_type).unwrap_or(i64::MAX);
        let Some(node_count) = nodes_per_element(element_type) else { continue };
        let expected = tag_count.saturating_add(3).saturating_add(node_count);
        if tokens.len() != expected {
            return Err(cursor.text_error(
                pos,
                format!(
                    "expected {expected} numbers for an element of type {element_type} with \
                     {tag_count} tags, found {}",
                    tokens.len()
                ),
            ));
        }
        if is_triangle(element_type) {
            let nodes = &tokens[3 + tag_count..];
            let mut tags = [0; 3];
            for (slot, token) in tags.iter_mut().zip(nodes) {
                *slot = integer(cursor, pos, token, "a node tag")?;
            }
            data.triangles.push(Triangle { nodes: tags, at: At::Text(pos) });
        }
    }
    Ok(())
}

/// The 4-number header line of a 4.1 block or section.
fn header4(cursor: &mut Cursor<'_>, what: &str) -> Result<(usize, [u64; 4]), MeshError> {
    let (pos, line) = cursor.expect_data_line(what)?;
    let tokens = fields::<4>(cursor, pos, line, what)?;
    let mut numbers = [0; 4];
    for (slot, token) in numbers.iter_mut().zip(tokens) {
        *slot = integer(cursor, pos, token, what)?;
    }
    Ok((pos, numbers))
}

/// `$Nodes` of 4.1 ASCII: `numEntityBlocks numNodes minTag maxTag`, then blocks of
/// `entityDim entityTag parametric n`, n tag lines and n coordinate lines.
pub(super) fn read_nodes_v4(cursor: &mut Cursor<'_>, data: &mut MshData) -> Result<(), MeshError> {
    let what = "the nodes header (numEntityBlocks numNodes minNodeTag maxNodeTag)";
    let (header_pos, [blocks, total, _, _]) = header4(cursor, what)?;
    let mut read: u64 = 0;
    for _ in 0..blocks {
        let what = "a node block header (entityDim entityTag parametric numNodesInBlock)";
        let (pos, [dim, _, parametric, n]) = header4(cursor, what)?;
        if dim > 3 || parametric > 1 {
            return Err(cursor.text_error(
                pos,
                format!(
                    "expected entityDim 0 to 3 and parametric 0 or 1, found {dim} and {parametric}"
                ),
            ));
        }
        let mut tags = Vec::new();
        for _ in 0..n {
            let (pos, line) = cursor.expect_data_line("a node tag")?;
            let [tag] = fields::<1>(cursor, pos, line, "a node tag")?;
            tags.push(integer(cursor, pos, tag, "a node tag")?);
        }
        let field_count = 3 + if parametric == 1 { dim as usize } else { 0 };
        for tag in tags {
            let (pos, line) = cursor.expect_data_line("node coordinates (x y z)")?;
            let tokens: Vec<&str> = line.split_whitespace().collect();
            let xyz = tokens
                .get(..3)
                .and_then(|t| <[&str; 3]>::try_from(t).ok())
                .filter(|_| tokens.len() == field_count)
                .ok_or_else(|| {
                    cursor.text_error(
                        pos,
                        format!(
                            "expected {field_count} numbers for the coordinates of node {tag}, found {}",
                            tokens.len()
                        ),
                    )
                })?;
            let position = point(cursor, pos, xyz)?;
            data.nodes.push(Node { tag, position, at: At::Text(pos) });
        }
        read = read.saturating_add(n);
    }
    if read != total {
        return Err(cursor.text_error(
            header_pos,
            format!("the header declares {total} nodes but the blocks hold {read}"),
        ));
    }
    Ok(())
}

/// `$Elements` of 4.1 ASCII: `numEntityBlocks numElements minTag maxTag`, then blocks of
/// `entityDim entityTag elementType n` and n lines `tag node...`.
pub(super) fn read_elements_v4(
    cursor: &mut Cursor<'_>,
    data: &mut MshData,
) -> Result<(), MeshError> {
    let what = "the elements header (numEntityBlocks numElements minElementTag maxElementTag)";
    let (header_pos, [blocks, total, _, _]) = header4(cursor, what)?;
    let mut read: u64 = 0;
    for _ in 0..blocks {
        let what = "an element block header (entityDim entityTag elementType numElementsInBlock)";
        let (_, [_, _, element_type, n]) = header4(cursor, what)?;
        let element_type = i64::try_from(element_type).unwrap_or(i64::MAX);
        let node_count = nodes_per_element(element_type);
        for _ in 0..n {
            let (pos, line) = cursor.expect_data_line("an element (tag node...)")?;
            let tokens: Vec<&str> = line.split_whitespace().collect();
            let Some(node_count) = node_count else { continue };
            if tokens.len() != node_count + 1 {
                return Err(cursor.text_error(
                    pos,
                    format!(
                        "expected {} numbers for an element of type {element_type} (tag and \
                         {node_count} nodes), found {}",
                        node_count + 1,
                        tokens.len()
                    ),
                ));
            }
            if is_triangle(element_type) {
                let mut tags = [0; 3];
                for (slot, token) in tags.iter_mut().zip(&tokens[1..]) {
                    *slot = integer(cursor, pos, token, "a node tag")?;
                }
                data.triangles.push(Triangle { nodes: tags, at: At::Text(pos) });
            }
        }
        read = read.saturating_add(n);
    }
    if read != total {
        return Err(cursor.text_error(
            header_pos,
            format!("the header declares {total} elements but the blocks hold {read}"),
        ));
    }
    Ok(())
}
