//! INRIA/MEDIT `.mesh` (ASCII), the format YADE's `gmshPFacet` reads: free-form tokens with
//! case-insensitive keywords. `MeshVersionFormatted n` and `Dimension 3` are checked,
//! `Vertices n` is followed by n × `x y z ref` and `Triangles n` by n × `i j k ref` (1-based
//! vertex indices), `End` (optional) ends the file. Every other section (`Edges`,
//! `Tetrahedra`, `Corners`, ...) is skipped up to the next keyword, and `#` starts a comment.

use flexdem_geom::{TriMesh, Vec3};

use crate::text::{parse_i64, parse_point, parse_usize};
use crate::vertices::drop_unused_vertices;
use crate::MeshError;

/// A whitespace-separated word of the file with its line number.
#[derive(Clone, Copy)]
struct Token<'a> {
    text: &'a str,
    line: usize,
}

/// A triangle's 0-based vertex indices and the line of its last index.
struct NumberedTriangle {
    corners: [usize; 3],
    line: usize,
}

/// The tokens of the file, comments removed.
fn tokenize(text: &str) -> Vec<Token<'_>> {
    let mut tokens = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let content = line.split('#').next().unwrap_or_default();
        tokens.extend(content.split_whitespace().map(|text| Token { text, line: index + 1 }));
    }
    tokens
}

/// A keyword starts with a letter (numbers start with a digit, a sign or a dot). "nan" and
/// "inf" look like keywords, but only inside a skipped section, where any word ends it.
fn is_keyword(token: &str) -> bool {
    token.starts_with(|c: char| c.is_ascii_alphabetic())
}

/// The tokens of a file with a cursor, giving errors at the right line.
struct Tokens<'a> {
    file: &'a str,
    tokens: Vec<Token<'a>>,
    next: usize,
    last_line: usize,
}

impl<'a> Tokens<'a> {
    fn next(&mut self) -> Option<Token<'a>> {
        let token = self.tokens.get(self.next).copied()?;
        self.next += 1;
        Some(token)
    }

    fn expect(&mut self, expected: &str) -> Result<Token<'a>, MeshError> {
        self.next().ok_or_else(|| {
            MeshError::text(
                self.file,
                self.last_line,
                format!("expected {expected}, found the end of the file"),
            )
        })
    }

    fn expect_usize(&mut self, what: &str) -> Result<(usize, usize), MeshError> {
        let token = self.expect(what)?;
        Ok((parse_usize(self.file, token.line, token.text, what)?, token.line))
    }

    fn remaining(&self) -> usize {
        self.tokens.len().saturating_sub(self.next)
    }
}

/// Reads an INRIA/MEDIT `.mesh` file; `file` names it in errors. Vertices no triangle uses
/// are dropped.
pub fn read_medit(text: &str, file: &str) -> Result<TriMesh, MeshError> {
    let tokens = tokenize(text);
    let last_line = tokens.last().map_or(1, |t| t.line);
    let mut tokens = Tokens { file, tokens, next: 0, last_line };
    let mut vertices: Option<Vec<Vec3>> = None;
    let mut triangles: Option<(Vec<NumberedTriangle>, usize)> = None;
    let mut seen_keyword = false;
    while let Some(token) = tokens.next() {
        if !is_keyword(token.text) {
            return Err(MeshError::text(
                file,
                token.line,
                format!(
                    "expected a keyword (Vertices, Triangles, End, ...), found {:?}",
                    token.text
                ),
            ));
        }
        let keyword = token.text.to_ascii_lowercase();
        if !seen_keyword && keyword != "meshversionformatted" {
            return Err(MeshError::text(
                file,
                token.line,
                format!("expected \"MeshVersionFormatted\" first, found {:?}", token.text),
            ));
        }
        seen_keyword = true;
        match keyword.as_str() {
            "meshversionformatted" => {
                let (version, line) = tokens.expect_usize("the mesh version")?;
                if !(1..=4).contains(&version) {
                    return Err(MeshError::text(
                        file,
                        line,
                        format!("expected mesh version 1 to 4, found {version}"),
                    ));
                }
            }
            "dimension" => {
                let (dimension, line) = tokens.expect_usize("the dimension")?;
                if dimension != 3 {
                    return Err(MeshError::text(
                        file,
                        line,
                        format!("expected Dimension 3, found {dimension}"),
                    ));
                }
            }
            "vertices" => {
                if vertices.is_some() {
                    return Err(MeshError::text(file, token.line, "second Vertices section"));
                }
                vertices = Some(read_vertices(&mut tokens)?);
            }
            "triangles" => {
                if triangles.is_some() {
                    return Err(MeshError::text(file, token.line, "second Triangles section"));
                }
                triangles = Some((read_triangles(&mut tokens)?, token.line));
            }
            "end" => break,
            _ => {
                while tokens.tokens.get(tokens.next).is_some_and(|t| !is_keyword(t.text)) {
                    tokens.next += 1;
                }
            }
        }
    }
    let Some((triangles, triangles_line)) = triangles else {
        return Err(MeshError::text(file, last_line, "no Triangles section in the .mesh file"));
    };
    let vertices = vertices.unwrap_or_default();
    for (k, triangle) in triangles.iter().enumerate() {
        if let Some(&bad) = triangle.corners.iter().find(|&&v| v >= vertices.len()) {
            return Err(MeshError::text(
                file,
                triangle.line,
                format!(
                    "triangle {} uses vertex {} but the file has {} vertices",
                    k + 1,
                    bad.saturating_add(1),
                    vertices.len()
                ),
            ));
        }
    }
    if triangles.is_empty() {
        return Err(MeshError::text(file, triangles_line, "the Triangles section is empty"));
    }
    let triangles = triangles.into_iter().map(|t| t.corners).collect();
    Ok(drop_unused_vertices(&vertices, triangles))
}

/// `n` then n × `x y z ref`.
fn read_vertices(tokens: &mut Tokens<'_>) -> Result<Vec<Vec3>, MeshError> {
    let (count, line) = tokens.expect_usize("the number of vertices")?;
    check_count(tokens, count, 4, line, "vertices")?;
    let mut vertices = Vec::with_capacity(count);
    for k in 0..count {
        let what = format!("vertex {} of {count} (x y z ref)", k + 1);
        let x = tokens.expect(&what)?;
        let y = tokens.expect(&what)?;
        let z = tokens.expect(&what)?;
        let reference = tokens.expect(&what)?;
        vertices.push(parse_point(tokens.file, x.line, [x.text, y.text, z.text])?);
        parse_i64(tokens.file, reference.line, reference.text, "a vertex reference")?;
    }
    Ok(vertices)
}

/// `n` then n × `i j k ref`, returned 0-based with the line of each (not yet checked against
/// the vertex count, as the Vertices section may come later).
fn read_triangles(tokens: &mut Tokens<'_>) -> Result<Vec<NumberedTriangle>, MeshError> {
    let (count, mut line) = tokens.expect_usize("the number of triangles")?;
    check_count(tokens, count, 4, line, "triangles")?;
    let mut triangles = Vec::with_capacity(count);
    for k in 0..count {
        let what = format!("triangle {} of {count} (i j k ref)", k + 1);
        let mut triangle = [0; 3];
        for corner in &mut triangle {
            let token = tokens.expect(&what)?;
            let index = parse_usize(tokens.file, token.line, token.text, "a vertex index")?;
            if index == 0 {
                return Err(MeshError::text(
                    tokens.file,
                    token.line,
                    "vertex index 0 is invalid (indices start at 1)",
                ));
            }
            *corner = index - 1;
            line = token.line;
        }
        let reference = tokens.expect(&what)?;
        parse_i64(tokens.file, reference.line, reference.text, "a triangle reference")?;
        triangles.push(NumberedTriangle { corners: triangle, line });
    }
    Ok(triangles)
}

/// Rejects a declared count that the rest of the file cannot hold (`per_item` tokens each).
fn check_count(
    tokens: &Tokens<'_>,
    count: usize,
    per_item: usize,
    line: usize,
    what: &str,
) -> Result<(), MeshError> {
    let available = tokens.remaining() / per_item;
    if count > available {
        return Err(MeshError::text(
            tokens.file,
            line,
            format!("declared {count} {what} but the rest of the file holds at most {available}"),
        ));
    }
    Ok(())
}
