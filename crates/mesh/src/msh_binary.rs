//! Binary data of Gmsh `.msh` files (2.2 and 4.1). The byte order is the one of the integer 1
//! written after the format line; 2.2 uses 4-byte ints and 8-byte doubles, 4.1 4-byte ints,
//! 8-byte doubles and `size_t` of the size named in `$MeshFormat` (4 or 8).
//!
//! Every declared count is checked against the bytes left before anything is allocated or
//! looped over.

use flexdem_geom::Vec3;

use crate::msh_data::{is_triangle, nodes_per_element, At, Cursor, MshData, Node, Triangle};
use crate::MeshError;

/// Layout of binary data.
#[derive(Clone, Copy, Debug)]
pub(super) struct Binary {
    big_endian: bool,
    /// Bytes of a `size_t` (4.1 only).
    size_t: usize,
}

/// Reads the integer 1 that follows a binary format line and tells the byte order.
pub(super) fn read_binary_header(
    cursor: &mut Cursor<'_>,
    is_v4: bool,
    data_size: usize,
) -> Result<Binary, MeshError> {
    let at = cursor.pos;
    let sizes_ok = if is_v4 { data_size == 4 || data_size == 8 } else { data_size == 8 };
    if !sizes_ok {
        let expected =
            if is_v4 { "4 or 8 (the size of size_t)" } else { "8 (the size of a double)" };
        return Err(cursor.text_error(
            at.saturating_sub(1),
            format!("expected data-size {expected}, found {data_size}"),
        ));
    }
    let one: [u8; 4] = read_array(cursor, "the binary header (the integer 1)")?;
    let big_endian = match (i32::from_le_bytes(one), i32::from_be_bytes(one)) {
        (1, _) => false,
        (_, 1) => true,
        _ => {
            return Err(MeshError::binary(
                cursor.file,
                at,
                format!("expected the integer 1 to tell the byte order, found bytes {one:?}"),
            ))
        }
    };
    Ok(Binary { big_endian, size_t: data_size })
}

fn read_array<const N: usize>(cursor: &mut Cursor<'_>, what: &str) -> Result<[u8; N], MeshError> {
    let bytes = cursor.take(N, what)?;
    let mut array = [0; N];
    array.copy_from_slice(bytes);
    Ok(array)
}

fn read_i32(cursor: &mut Cursor<'_>, b: Binary, what: &str) -> Result<i32, MeshError> {
    let bytes = read_array::<4>(cursor, what)?;
    Ok(if b.big_endian { i32::from_be_bytes(bytes) } else { i32::from_le_bytes(bytes) })
}

/// A non-negative 4-byte int, as usize.
fn read_count_i32(cursor: &mut Cursor<'_>, b: Binary, what: &str) -> Result<usize, MeshError> {
    let at = cursor.pos;
    let value = read_i32(cursor, b, what)?;
    usize::try_from(value).map_err(|_| {
        MeshError::binary(cursor.file, at, format!("expected a non-negative {what}, found {value}"))
    })
}

fn read_size(cursor: &mut Cursor<'_>, b: Binary, what: &str) -> Result<u64, MeshError> {
    if b.size_t == 4 {
        let bytes = read_array::<4>(cursor, what)?;
        Ok(u64::from(if b.big_endian {
            u32::from_be_bytes(bytes)
        } else {
            u32::from_le_bytes(bytes)
        }))
    } else {
        let bytes = read_array::<8>(cursor, what)?;
        Ok(if b.big_endian { u64::from_be_bytes(bytes) } else { u64::from_le_bytes(bytes) })
    }
}

/// Three finite doubles.
fn read_point(cursor: &mut Cursor<'_>, b: Binary, tag: u64) -> Result<Vec3, MeshError> {
    let mut xyz = [0.0; 3];
    for value in &mut xyz {
        let at = cursor.pos;
        let bytes = read_array::<8>(cursor, "a node coordinate")?;
        *value = if b.big_endian { f64::from_be_bytes(bytes) } else { f64::from_le_bytes(bytes) };
        if !value.is_finite() {
            return Err(MeshError::binary(
                cursor.file,
                at,
                format!("node {tag}: expected a finite coordinate, found {value}"),
            ));
        }
    }
    Ok(Vec3::from(xyz))
}

/// Checks that `count` items of `item_bytes` each fit in the rest of the file.
fn check_fits(
    cursor: &Cursor<'_>,
    at: At,
    count: u64,
    item_bytes: usize,
    what: &str,
) -> Result<usize, MeshError> {
    let remaining = cursor.remaining();
    let needed = u128::from(count) * item_bytes as u128;
    if needed > remaining as u128 {
        return Err(cursor.error_at(
            at,
            format!(
                "declared {count} {what} ({item_bytes} bytes each) but only {remaining} bytes follow"
            ),
        ));
    }
    // needed <= remaining, so count fits in usize.
    Ok(count as usize)
}

/// The count line (text) that starts a 2.2 binary section.
fn count_line(cursor: &mut Cursor<'_>, what: &str) -> Result<(usize, u64), MeshError> {
    let (pos, line) = cursor.expect_data_line(what)?;
    let count = line.parse::<u64>().map_err(|_| {
        cursor
            .text_error(pos, format!("expected a non-negative integer for {what}, found {line:?}"))
    })?;
    Ok((pos, count))
}

/// `$Nodes` of 2.2 binary: a text count line, then per node an int tag and 3 doubles.
pub(super) fn read_nodes_v2(
    cursor: &mut Cursor<'_>,
    b: Binary,
    data: &mut MshData,
) -> Result<(), MeshError> {
    let (pos, total) = count_line(cursor, "the number of nodes")?;
    let total = check_fits(cursor, At::Text(pos), total, 4 + 3 * 8, "nodes")?;
    for _ in 0..total {
        let at = cursor.pos;
        let tag = read_count_i32(cursor, b, "node tag")? as u64;
        let position = read_point(cursor, b, tag)?;
        data.nodes.push(Node { tag, position, at: At::Byte(at) });
    }
    Ok(())
}

/// `$Elements` of 2.2 binary: a text count line, then blocks of elements of one type, each
/// with a header `type count ntags` and per element `tag tags... nodes...` (all ints).
pub(super) fn read_elements_v2(
    cursor: &mut Cursor<'_>,
    b: Binary,
    data: &mut MshData,
) -> Result<(), MeshError> {
    let (_, total) = count_line(cursor, "the number of elements")?;
    let mut read: u64 = 0;
    while read < total {
        let header = cursor.pos;
        let element_type = read_i32(cursor, b, "element type")?;
        let count = read_count_i32(cursor, b, "element count")? as u64;
        let tag_count = read_count_i32(cursor, b, "number of element tags")?;
        let node_count = nodes_per_element(i64::from(element_type)).ok_or_else(|| {
            MeshError::binary(
                cursor.file,
                header,
                format!("unknown element type {element_type}: its size is needed to skip it"),
            )
        })?;
        if count > total - read {
            return Err(MeshError::binary(
                cursor.file,
                header,
                format!(
                    "block of {count} elements, but only {} of the {total} declared remain",
                    total - read
                ),
            ));
        }
        let element_bytes = 4 * (1 + tag_count.saturating_add(node_count));
        let count = check_fits(cursor, At::Byte(header), count, element_bytes, "elements")?;
        for _ in 0..count {
            let at = cursor.pos;
            cursor.take(4 * (1 + tag_count), "element tag and tags")?;
            let mut tags = Vec::with_capacity(node_count);
            for _ in 0..node_count {
                tags.push(read_count_i32(cursor, b, "node tag")? as u64);
            }
            if is_triangle(i64::from(element_type)) {
                if let [a, b, c, ..] = tags[..] {
                    data.triangles.push(Triangle { nodes: [a, b, c], at: At::Byte(at) });
                }
            }
        }
        read += count as u64;
    }
    Ok(())
}

/// The 4 `size_t` header of a 4.1 `$Nodes` or `$Elements` section.
fn header_v4(cursor: &mut Cursor<'_>, b: Binary, what: &str) -> Result<[u64; 4], MeshError> {
    let mut numbers = [0; 4];
    for slot in &mut numbers {
        *slot = read_size(cursor, b, what)?;
    }
    Ok(numbers)
}

/// `$Nodes` of 4.1 binary: `numEntityBlocks numNodes minTag maxTag` (size_t), then blocks of
/// `entityDim entityTag parametric` (int) `n` (size_t), n tags (size_t) and n × (3 + params)
/// doubles.
pub(super) fn read_nodes_v4(
    cursor: &mut Cursor<'_>,
    b: Binary,
    data: &mut MshData,
) -> Result<(), MeshError> {
    let header = cursor.pos;
    let [blocks, total, _, _] = header_v4(cursor, b, "the nodes header")?;
    let mut read: u64 = 0;
    for _ in 0..blocks {
        let block = cursor.pos;
        let dim = read_count_i32(cursor, b, "entity dimension")?;
        let _entity = read_i32(cursor, b, "entity tag")?;
        let parametric = read_count_i32(cursor, b, "parametric flag")?;
        let n = read_size(cursor, b, "number of nodes in the block")?;
        if dim > 3 || parametric > 1 {
            return Err(MeshError::binary(
                cursor.file,
                block,
                format!(
                    "expected entityDim 0 to 3 and parametric 0 or 1, found {dim} and {parametric}"
                ),
            ));
        }
        let parameters = if parametric == 1 { dim } else { 0 };
        let n = check_fits(cursor, At::Byte(block), n, b.size_t + 8 * (3 + parameters), "nodes")?;
        let mut tags = Vec::with_capacity(n);
        for _ in 0..n {
            tags.push(read_size(cursor, b, "node tag")?);
        }
        for tag in tags {
            let at = cursor.pos;
            let position = read_point(cursor, b, tag)?;
            cursor.take(8 * parameters, "parametric coordinates")?;
            data.nodes.push(Node { tag, position, at: At::Byte(at) });
        }
        read += n as u64;
    }
    if read != total {
        return Err(MeshError::binary(
            cursor.file,
            header,
            format!("the nodes header declares {total} nodes but the blocks hold {read}"),
        ));
    }
    Ok(())
}

/// `$Elements` of 4.1 binary: `numEntityBlocks numElements minTag maxTag` (size_t), then
/// blocks of `entityDim entityTag elementType` (int) `n` (size_t) and n × (tag, nodes...)
/// (size_t).
pub(super) fn read_elements_v4(
    cursor: &mut Cursor<'_>,
    b: Binary,
    data: &mut MshData,
) -> Result<(), MeshError> {
    let header = cursor.pos;
    let [blocks, total, _, _] = header_v4(cursor, b, "the elements header")?;
    let mut read: u64 = 0;
    for _ in 0..blocks {
        let block = cursor.pos;
        let _dim = read_i32(cursor, b, "entity dimension")?;
        let _entity = read_i32(cursor, b, "entity tag")?;
        let element_type = read_i32(cursor, b, "element type")?;
        let n = read_size(cursor, b, "number of elements in the block")?;
        let node_count = nodes_per_element(i64::from(element_type)).ok_or_else(|| {
            MeshError::binary(
                cursor.file,
                block,
                format!("unknown element type {element_type}: its size is needed to skip it"),
            )
        })?;
        let n = check_fits(cursor, At::Byte(block), n, b.size_t * (1 + node_count), "elements")?;
        for _ in 0..n {
            let at = cursor.pos;
            let _tag = read_size(cursor, b, "element tag")?;
            let mut tags = Vec::with_capacity(node_count);
            for _ in 0..node_count {
                tags.push(read_size(cursor, b, "node tag")?);
            }
            if is_triangle(i64::from(element_type)) {
                if let [a, b, c, ..] = tags[..] {
                    data.triangles.push(Triangle { nodes: [a, b, c], at: At::Byte(at) });
                }
            }
        }
        read += n as u64;
    }
    if read != total {
        return Err(MeshError::binary(
            cursor.file,
            header,
            format!("the elements header declares {total} elements but the blocks hold {read}"),
        ));
    }
    Ok(())
}
