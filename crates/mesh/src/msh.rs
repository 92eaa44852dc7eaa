//! Gmsh `.msh`, versions 2.2 (2.x) and 4.1, ASCII and binary (either byte order).
//!
//! Only `$MeshFormat`, `$Nodes` and `$Elements` are read; every other section
//! (`$PhysicalNames`, `$Entities`, `$NodeData`, ...) is skipped up to its `$End` line.
//! Triangles are the elements of type 2 (3-node) and 9 (6-node, whose first three nodes are
//! the corners); other element types are skipped. Node tags may be any distinct positive
//! numbers; nodes no triangle uses are dropped, the others keep their order in the file.
//! Text parts give errors with a line number, binary data with a byte offset.

use std::collections::HashMap;

use flexdem_geom::{TriMesh, Vec3};

use crate::msh_ascii::{self, count};
use crate::msh_binary;
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

/// Where an item was read: a byte position in a text line, or a byte offset in binary data.
#[derive(Clone, Copy, Debug)]
pub(super) enum At {
    /// In the text line containing this byte.
    Text(usize),
    /// At this byte of binary data.
    Byte(usize),
}

/// A node as read: its tag and position.
#[derive(Debug)]
pub(super) struct Node {
    pub(super) tag: u64,
    pub(super) position: Vec3,
    pub(super) at: At,
}

/// A triangle as read: the tags of its corner nodes.
#[derive(Debug)]
pub(super) struct Triangle {
    pub(super) nodes: [u64; 3],
    pub(super) at: At,
}

/// The nodes and triangles of a file, by tag.
#[derive(Default, Debug)]
pub(super) struct MshData {
    pub(super) nodes: Vec<Node>,
    pub(super) triangles: Vec<Triangle>,
}

impl MshData {
    /// Maps node tags to indices, keeping only the nodes the triangles use.
    fn into_mesh(self, cursor: &Cursor<'_>) -> Result<TriMesh, MeshError> {
        let mut index_of_tag: HashMap<u64, usize> = HashMap::with_capacity(self.nodes.len());
        for (index, node) in self.nodes.iter().enumerate() {
            if let Some(first) = index_of_tag.insert(node.tag, index) {
                let first_at = self.nodes.get(first).map(|n| cursor.describe(n.at));
                return Err(cursor.error_at(
                    node.at,
                    format!(
                        "node tag {} defined twice (first {})",
                        node.tag,
                        first_at.unwrap_or_default()
                    ),
                ));
            }
        }
        let vertices: Vec<Vec3> = self.nodes.iter().map(|n| n.position).collect();
        let mut triangles = Vec::with_capacity(self.triangles.len());
        for triangle in &self.triangles {
            let mut indices = [0; 3];
            for (slot, tag) in indices.iter_mut().zip(triangle.nodes) {
                *slot = *index_of_tag.get(&tag).ok_or_else(|| {
                    cursor.error_at(
                        triangle.at,
                        format!("triangle uses node tag {tag}, which $Nodes does not define"),
                    )
                })?;
            }
            triangles.push(indices);
        }
        Ok(crate::drop_unused_vertices(&vertices, triangles))
    }
}

/// Element types read as triangles (3-node and 6-node).
pub(super) fn is_triangle(element_type: i64) -> bool {
    element_type == 2 || element_type == 9
}

/// Number of nodes of a Gmsh element type (needed to skip elements in binary files).
pub(super) fn nodes_per_element(element_type: i64) -> Option<usize> {
    Some(match element_type {
        1 => 2,
        2 => 3,
        3 | 4 => 4,
        5 => 8,
        6 => 6,
        7 => 5,
        8 => 3,
        9 => 6,
        10 => 9,
        11 => 10,
        12 => 27,
        13 => 18,
        14 => 14,
        15 => 1,
        16 => 8,
        17 => 20,
        18 => 15,
        19 => 13,
        20 => 9,
        21 => 10,
        22 => 12,
        23 | 24 => 15,
        25 => 21,
        26 => 4,
        27 => 5,
        28 => 6,
        29 => 20,
        30 => 35,
        31 => 56,
        92 => 64,
        93 => 125,
        _ => return None,
    })
}

/// A position in the bytes of a `.msh` file, reading text lines and binary data.
pub(super) struct Cursor<'a> {
    pub(super) data: &'a [u8],
    pub(super) pos: usize,
    pub(super) file: &'a str,
}

impl<'a> Cursor<'a> {
    /// Line number (1-based) of the byte at `pos`.
    fn line_number(&self, pos: usize) -> usize {
        let end = pos.min(self.data.len());
        self.data[..end].iter().filter(|&&b| b == b'\n').count() + 1
    }

    /// An error at the line containing byte `pos`.
    pub(super) fn text_error(&self, pos: usize, message: impl Into<String>) -> MeshError {
        MeshError::text(self.file, self.line_number(pos), message)
    }

    /// An error at a text line or binary offset.
    pub(super) fn error_at(&self, at: At, message: impl Into<String>) -> MeshError {
        match at {
            At::Text(pos) => self.text_error(pos, message),
            At::Byte(offset) => MeshError::binary(self.file, offset, message),
        }
    }

    /// "line 12" or "byte 340".
    fn describe(&self, at: At) -> String {
        match at {
            At::Text(pos) => format!("line {}", self.line_number(pos)),
            At::Byte(offset) => format!("byte {offset}"),
        }
    }

    /// The next line as raw bytes, without its end-of-line, and its start.
    fn next_raw_line(&mut self) -> Option<(usize, &'a [u8])> {
        let rest = self.data.get(self.pos..).filter(|r| !r.is_empty())?;
        let start = self.pos;
        let length = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        self.pos = (start + length + 1).min(self.data.len());
        let line = &rest[..length];
        Some((start, line.strip_suffix(b"\r").unwrap_or(line)))
    }

    /// The next non-blank line, trimmed, and its start; an error if it is not text.
    pub(super) fn next_line(&mut self) -> Result<Option<(usize, &'a str)>, MeshError> {
        while let Some((start, raw)) = self.next_raw_line() {
            let line = std::str::from_utf8(raw)
                .map_err(|_| self.text_error(start, "expected a line of text, found binary data"))?
                .trim();
            if !line.is_empty() {
                return Ok(Some((start, line)));
            }
        }
        Ok(None)
    }

    /// Like [`Self::next_line`], the end of the file being an error naming `expected`.
    pub(super) fn expect_line(&mut self, expected: &str) -> Result<(usize, &'a str), MeshError> {
        self.next_line()?.ok_or_else(|| {
            self.text_error(
                self.data.len(),
                format!("expected {expected}, found the end of the file"),
            )
        })
    }

    /// Reads a data line of `expected` items; a section marker (`$...`) in its place means the
    /// section holds fewer items than it declares.
    pub(super) fn expect_data_line(
        &mut self,
        expected: &str,
    ) -> Result<(usize, &'a str), MeshError> {
        let (pos, line) = self.expect_line(expected)?;
        if line.starts_with('$') {
            return Err(self.text_error(pos, format!("expected {expected}, found {line}")));
        }
        Ok((pos, line))
    }

    /// Reads the `$End<name>` line closing a section; returns its position.
    pub(super) fn expect_section_end(&mut self, name: &str) -> Result<usize, MeshError> {
        let expected = format!("$End{name}");
        let (pos, line) = self.expect_line(&expected)?;
        if line != expected {
            return Err(self.text_error(
                pos,
                format!(
                    "expected {expected} (or is the declared count too small?), found {line:?}"
                ),
            ));
        }
        Ok(pos)
    }

    /// Skips a section whose header `$name` started at `start`, up to its `$End<name>` line
    /// (its content may be binary).
    fn skip_section(&mut self, start: usize, name: &str) -> Result<(), MeshError> {
        let end = format!("$End{name}");
        while let Some((_, raw)) = self.next_raw_line() {
            if raw.trim_ascii() == end.as_bytes() {
                return Ok(());
            }
        }
        Err(self.text_error(start, format!("section ${name} has no {end} line")))
    }

    /// The next `count` bytes of binary data; `what` names them in the error.
    pub(super) fn take(&mut self, count: usize, what: &str) -> Result<&'a [u8], MeshError> {
        let bytes =
            self.pos.checked_add(count).and_then(|end| self.data.get(self.pos..end)).ok_or_else(
                || {
                    MeshError::binary(
                        self.file,
                        self.pos,
                        format!(
                            "expected {count} bytes for {what}, found the end of the file \
                         ({} bytes left)",
                            self.data.len().saturating_sub(self.pos)
                        ),
                    )
                },
            )?;
        self.pos += count;
        Ok(bytes)
    }

    /// Bytes left after the cursor.
    pub(super) fn remaining(&self) -> usize {
        self.data.len().saturating_sub(self.pos)
    }
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
