//! Gmsh `.msh`, versions 2.2 (2.x) and 4.1, ASCII and binary (either byte order).
//!
//! Only `$MeshFormat`, `$Nodes` and `$Elements` are read; every other section
//! (`$PhysicalNames`, `$Entities`, `$NodeData`, ...) is skipped up to its `$End` line.
//! Triangles are the elements of type 2 (3-node) and 9 (6-node, whose first three nodes are
//! the corners); other element types are skipped. Node tags may be any distinct positive
//! numbers; nodes no triangle uses are dropped, the others keep their order in the file.
//! Text parts give errors with a line number, binary data with a byte offset.

use flexdem_geom::TriMesh;

use crate::msh_ascii::{self, count};
use crate::msh_binary;
use crate::msh_data::{Cursor, MshData};
use crate::MeshError;

/// Reads a Gmsh `.msh` file (2.2 or 4.1, ASCII or binary); `file` names it in errors.
pub fn read_msh(bytes: &[u8], file: &str) -> Result<TriMesh, MeshError> {
    let mut cursor = Cursor { data: bytes, pos: 0, file };
    let mut format: Option<Format> = None;
    let mut data = MshData::default();
    let mut nodes_read = false;
    let mut elements_end: Option<usize> = None;
    while let Some((pos, line)) = cursor.next_line()? {
        let Some(name) = line.strip_prefix('$') else {
            return Err(cursor.text_error(
                pos,
                format!("expected a section header such as $Nodes, found {line:?}"),
            ));
        };
        if name.starts_with("End") {
            return Err(cursor.text_error(pos, format!("{line} outside of its section")));
        }
        match (name, format) {
            ("MeshFormat", None) => format = Some(read_format(&mut cursor)?),
            ("MeshFormat", Some(_)) => {
                return Err(cursor.text_error(pos, "second $MeshFormat section"));
            }
            (_, None) => {
                return Err(cursor.text_error(
                    pos,
                    format!("expected $MeshFormat as the first section, found {line}"),
                ));
            }
            ("Nodes", Some(format)) => {
                if nodes_read {
                    return Err(cursor.text_error(pos, "second $Nodes section"));
                }
                nodes_read = true;
                match (format.version, format.binary) {
                    (Version::V2, None) => msh_ascii::read_nodes_v2(&mut cursor, &mut data)?,
                    (Version::V4, None) => msh_ascii::read_nodes_v4(&mut cursor, &mut data)?,
                    (Version::V2, Some(b)) => msh_binary::read_nodes_v2(&mut cursor, b, &mut data)?,
                    (Version::V4, Some(b)) => msh_binary::read_nodes_v4(&mut cursor, b, &mut data)?,
                }
                cursor.expect_section_end("Nodes")?;
            }
            ("Elements", Some(format)) => {
                if elements_end.is_some() {
                    return Err(cursor.text_error(pos, "second $Elements section"));
                }
                match (format.version, format.binary) {
                    (Version::V2, None) => msh_ascii::read_elements_v2(&mut cursor, &mut data)?,
                    (Version::V4, None) => msh_ascii::read_elements_v4(&mut cursor, &mut data)?,
                    (Version::V2, Some(b)) => {
                        msh_binary::read_elements_v2(&mut cursor, b, &mut data)?
                    }
                    (Version::V4, Some(b)) => {
                        msh_binary::read_elements_v4(&mut cursor, b, &mut data)?
                    }
                }
                elements_end = Some(cursor.expect_section_end("Elements")?);
            }
            (other, Some(_)) => cursor.skip_section(pos, other)?,
        }
    }
    let end = cursor.data.len();
    if format.is_none() {
        return Err(cursor.text_error(end, "no $MeshFormat section (not a Gmsh .msh file?)"));
    }
    if !nodes_read {
        return Err(cursor.text_error(end, "no $Nodes section"));
    }
    let Some(elements_end) = elements_end else {
        return Err(cursor.text_error(end, "no $Elements section"));
    };
    if data.triangles.is_empty() {
        return Err(cursor.text_error(
            elements_end,
            "no triangle (element type 2 or 9) in the $Elements section",
        ));
    }
    data.into_mesh(&cursor)
}

/// The two format families.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Version {
    /// 2.0, 2.1, 2.2 (the same layout).
    V2,
    /// 4.1.
    V4,
}

/// What `$MeshFormat` says.
#[derive(Clone, Copy, Debug)]
struct Format {
    version: Version,
    /// `None` for ASCII.
    binary: Option<msh_binary::Binary>,
}

/// Reads the `$MeshFormat` content and its `$EndMeshFormat`.
fn read_format(cursor: &mut Cursor<'_>) -> Result<Format, MeshError> {
    let (pos, line) = cursor.expect_data_line("the format line (version file-type data-size)")?;
    let tokens: Vec<&str> = line.split_whitespace().collect();
    let [version, file_type, data_size] =
        <[&str; 3]>::try_from(tokens.as_slice()).map_err(|_| {
            cursor.text_error(
                pos,
                format!(
                    "expected 3 fields for the format (version file-type data-size), found {}",
                    tokens.len()
                ),
            )
        })?;
    let version = match version {
        "2" | "2.0" | "2.1" | "2.2" => Version::V2,
        "4.1" => Version::V4,
        other => {
            return Err(cursor.text_error(
                pos,
                format!("unsupported msh version {other} (supported: 2.2 and 4.1)"),
            ))
        }
    };
    let file_type = count(cursor, pos, file_type, "the file type")?;
    let data_size = count(cursor, pos, data_size, "the data size")?;
    let binary = match file_type {
        0 => None,
        1 => Some(msh_binary::read_binary_header(cursor, version == Version::V4, data_size)?),
        other => {
            return Err(cursor.text_error(
                pos,
                format!("expected file type 0 (ASCII) or 1 (binary), found {other}"),
            ))
        }
    };
    cursor.expect_section_end("MeshFormat")?;
    Ok(Format { version, binary })
}
