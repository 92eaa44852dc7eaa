//! What the Gmsh readers share: the nodes and triangles read so far ([`MshData`]), where an
//! item was read ([`At`]) and the cursor over the file's bytes ([`Cursor`]), used by the
//! section reader (`msh`) and by its ASCII and binary halves (`msh_ascii`, `msh_binary`).

use std::collections::HashMap;

use flexdem_geom::{TriMesh, Vec3};

use crate::MeshError;

/// Where an item was read: a byte position in a text line, or a byte offset in binary data.
#[derive(Clone, Copy, Debug)]
pub(crate) enum At {
    /// In the text line containing this byte.
    Text(usize),
    /// At this byte of binary data.
    Byte(usize),
}

/// A node as read: its tag and position.
#[derive(Debug)]
pub(crate) struct Node {
    pub(crate) tag: u64,
    pub(crate) position: Vec3,
    pub(crate) at: At,
}

/// A triangle as read: the tags of its corner nodes.
#[derive(Debug)]
pub(crate) struct Triangle {
    pub(crate) nodes: [u64; 3],
    pub(crate) at: At,
}

/// The nodes and triangles of a file, by tag.
#[derive(Default, Debug)]
pub(crate) struct MshData {
    pub(crate) nodes: Vec<Node>,
    pub(crate) triangles: Vec<Triangle>,
}

impl MshData {
    /// Maps node tags to indices, keeping only the nodes the triangles use.
    pub(crate) fn into_mesh(self, cursor: &Cursor<'_>) -> Result<TriMesh, MeshError> {
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
        Ok(crate::vertices::drop_unused_vertices(&vertices, triangles))
    }
}

/// Element types read as triangles (3-node and 6-node).
pub(crate) fn is_triangle(element_type: i64) -> bool {
    element_type == 2 || element_type == 9
}

/// Number of nodes of a Gmsh element type (needed to skip elements in binary files).
pub(crate) fn nodes_per_element(element_type: i64) -> Option<usize> {
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
pub(crate) struct Cursor<'a> {
    pub(crate) data: &'a [u8],
    pub(crate) pos: usize,
    pub(crate) file: &'a str,
}

impl<'a> Cursor<'a> {
    /// Line number (1-based) of the byte at `pos`.
    fn line_number(&self, pos: usize) -> usize {
        let end = pos.min(self.data.len());
        self.data[..end].iter().filter(|&&b| b == b'\n').count() + 1
    }

    /// An error at the line containing byte `pos`.
    pub(crate) fn text_error(&self, pos: usize, message: impl Into<String>) -> MeshError {
        MeshError::text(self.file, self.line_number(pos), message)
    }

    /// An error at a text line or binary offset.
    pub(crate) fn error_at(&self, at: At, message: impl Into<String>) -> MeshError {
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
    pub(crate) fn next_line(&mut self) -> Result<Option<(usize, &'a str)>, MeshError> {
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
    pub(crate) fn expect_line(&mut self, expected: &str) -> Result<(usize, &'a str), MeshError> {
        self.next_line()?.ok_or_else(|| {
            self.text_error(
                self.data.len(),
                format!("expected {expected}, found the end of the file"),
            )
        })
    }

    /// Reads a data line of `expected` items; a section marker (`$...`) in its place means the
    /// section holds fewer items than it declares.
    pub(crate) fn expect_data_line(
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
    pub(crate) fn expect_section_end(&mut self, name: &str) -> Result<usize, MeshError> {
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
    pub(crate) fn skip_section(&mut self, start: usize, name: &str) -> Result<(), MeshError> {
        let end = format!("$End{name}");
        while let Some((_, raw)) = self.next_raw_line() {
            if raw.trim_ascii() == end.as_bytes() {
                return Ok(());
            }
        }
        Err(self.text_error(start, format!("section ${name} has no {end} line")))
    }

    /// The next `count` bytes of binary data; `what` names them in the error.
    pub(crate) fn take(&mut self, count: usize, what: &str) -> Result<&'a [u8], MeshError> {
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
    pub(crate) fn remaining(&self) -> usize {
        self.data.len().saturating_sub(self.pos)
    }
}
