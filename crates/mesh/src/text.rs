//! Helpers shared by the text readers: numbered lines, number parsing with messages that name
//! the file and line.

use flexdem_geom::Vec3;

use crate::MeshError;

/// The lines of a text, numbered from 1, with optional skipping of blank and comment lines.
pub(crate) struct NumberedLines<'a> {
    file: &'a str,
    lines: std::str::Lines<'a>,
    line: usize,
}

impl<'a> NumberedLines<'a> {
    /// The lines of `text`; `file` names it in errors.
    pub(crate) fn new(text: &'a str, file: &'a str) -> Self {
        Self { file, lines: text.lines(), line: 0 }
    }

    /// The number of the last line returned (at least 1, so that an error at the end of an
    /// empty file still names a line).
    pub(crate) fn last_line(&self) -> usize {
        self.line.max(1)
    }

    /// The next line (trimmed) that is neither blank nor a comment starting with `comment`.
    pub(crate) fn next_content(&mut self, comment: Option<char>) -> Option<(usize, &'a str)> {
        for raw in self.lines.by_ref() {
            self.line += 1;
            let line = raw.trim();
            let is_comment = comment.is_some_and(|c| line.starts_with(c));
            if !line.is_empty() && !is_comment {
                return Some((self.line, line));
            }
        }
        None
    }

    /// Like [`Self::next_content`], but the end of the file is an error saying `expected` was
    /// expected.
    pub(crate) fn expect_content(
        &mut self,
        comment: Option<char>,
        expected: &str,
    ) -> Result<(usize, &'a str), MeshError> {
        self.next_content(comment).ok_or_else(|| {
            MeshError::text(
                self.file,
                self.last_line(),
                format!("expected {expected}, found the end of the file"),
            )
        })
    }
}

/// Parses a finite real number; `what` names it in the error message.
pub(crate) fn real(token: &str, what: &str) -> Result<f64, String> {
    let value: f64 =
        token.parse().map_err(|_| format!("expected a number for {what}, found {token:?}"))?;
    if !value.is_finite() {
        return Err(format!("expected a finite number for {what}, found {token:?}"));
    }
    Ok(value)
}

/// Parses a non-negative integer (a count or an index); `what` names it in the error message.
pub(crate) fn unsigned(token: &str, what: &str) -> Result<usize, String> {
    token
        .parse()
        .map_err(|_| format!("expected a non-negative integer for {what}, found {token:?}"))
}

/// A point from three coordinate tokens.
pub(crate) fn point(tokens: [&str; 3]) -> Result<Vec3, String> {
    let [x, y, z] = tokens;
    Ok(Vec3::new(real(x, "coordinate x")?, real(y, "coordinate y")?, real(z, "coordinate z")?))
}

/// [`unsigned`] with the error at a line of a file.
pub(crate) fn parse_usize(
    file: &str,
    line: usize,
    token: &str,
    what: &str,
) -> Result<usize, MeshError> {
    unsigned(token, what).map_err(|message| MeshError::text(file, line, message))
}

/// Parses a signed integer; `what` names it in the error.
pub(crate) fn parse_i64(
    file: &str,
    line: usize,
    token: &str,
    what: &str,
) -> Result<i64, MeshError> {
    token.parse().map_err(|_| {
        MeshError::text(file, line, format!("expected an integer for {what}, found {token:?}"))
    })
}

/// [`point`] with the error at a line of a file.
pub(crate) fn parse_point(file: &str, line: usize, tokens: [&str; 3]) -> Result<Vec3, MeshError> {
    point(tokens).map_err(|message| MeshError::text(file, line, message))
}

/// Converts a 1-based index to 0-based, checking it against `count` items; `what` names the
/// items in the error ("vertices", "edges").
pub(crate) fn one_based(
    file: &str,
    line: usize,
    index: usize,
    count: usize,
    what: &str,
) -> Result<usize, MeshError> {
    if index == 0 || index > count {
        return Err(MeshError::text(
            file,
            line,
            format!("index {index} out of range (1-based, {count} {what})"),
        ));
    }
    Ok(index - 1)
}

/// The first `N` tokens of a line, with an error if there are fewer (extra tokens allowed).
pub(crate) fn leading_tokens<'a, const N: usize>(
    file: &str,
    line: usize,
    text: &'a str,
    what: &str,
) -> Result<[&'a str; N], MeshError> {
    let tokens: Vec<&str> = text.split_whitespace().take(N).collect();
    <[&str; N]>::try_from(tokens.as_slice()).map_err(|_| {
        MeshError::text(
            file,
            line,
            format!("expected at least {N} numbers for {what}, found {}", tokens.len()),
        )
    })
}
