//! Scene errors. Every message names the file, the line and column, the key (as a dotted path
//! such as `materials.steel.young` or `structures.node_radius`) and what is expected.

use std::ops::Range;
use std::path::PathBuf;

/// Why a scene could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The scene file could not be read.
    #[error("{}: cannot read the scene file: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// Something is wrong at a place in the file: a TOML syntax error, a key of the wrong
    /// type, an unknown key, or a value that does not make sense.
    #[error("{}", located(file, *line, *column, key, message))]
    At {
        /// The scene file, as given.
        file: String,
        /// Line, 1-based.
        line: usize,
        /// Column (in characters), 1-based.
        column: usize,
        /// The key, as a dotted path (`simulation.dt`); empty when no key applies.
        key: String,
        /// What is wrong and what is expected.
        message: String,
    },
}

fn located(file: &str, line: usize, column: usize, key: &str, message: &str) -> String {
    if key.is_empty() {
        format!("{file}:{line}:{column}: {message}")
    } else {
        format!("{file}:{line}:{column}: `{key}`: {message}")
    }
}

/// The text being read and its name, to turn byte spans into located errors.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Ctx<'a> {
    /// Name of the file for messages.
    pub file: &'a str,
    /// The whole text.
    pub text: &'a str,
}

impl<'a> Ctx<'a> {
    /// 1-based line and column (in characters) of byte `offset` (clamped to the text).
    pub fn line_column(&self, offset: usize) -> (usize, usize) {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &self.text[..offset];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        (line, before[line_start..].chars().count() + 1)
    }

    /// An error at `span` about `key` (a dotted path).
    pub fn at(&self, span: Range<usize>, key: &str, message: impl Into<String>) -> SceneError {
        let (line, column) = self.line_column(span.start);
        SceneError::At {
            file: self.file.to_owned(),
            line,
            column,
            key: key.to_owned(),
            message: message.into(),
        }
    }

    /// A TOML syntax or schema error, with the key found from the text around its span and a
    /// suggestion for a misspelled key or value.
    pub fn toml_error(&self, e: &toml::de::Error) -> SceneError {
        let span = e.span().unwrap_or(0..0);
        let key = self.key_at(span.clone());
        let mut message = plain_types(e.message().trim_end());
        if let Some(hint) = suggestion_from_message(&message) {
            message.push_str(&hint);
        }
        self.at(span, &key, message)
    }

    /// The dotted key of the value or key at `span`: the enclosing `[table]` header and the
    /// key written before `=` on the same line (best effort; empty when none is found).
    fn key_at(&self, span: Range<usize>) -> String {
        let start = span.start.min(self.text.len());
        if !self.text.is_char_boundary(start) {
            return String::new();
        }
        let line_start = self.text[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = self.text[start..].find('\n').map_or(self.text.len(), |i| start + i);
        let line = &self.text[line_start..line_end];
        let col = start - line_start;
        let header = self.text[..line_start]
            .lines()
            .chain(std::iter::once(line))
            .rev()
            .find_map(table_header)
            .unwrap_or_default();
        // The span is a key itself (unknown field) when `=` follows it.
        let end = span.end.clamp(start, line_end);
        let spanned = self.text.get(start..end).unwrap_or("");
        let after = self.text.get(end..line_end).unwrap_or("");
        let key = if !spanned.is_empty() && after.trim_start().starts_with('=') {
            clean_key(spanned)
        } else {
            line.get(..col)
                .and_then(|prefix| last_assignment(prefix).map(|eq| &prefix[..eq]))
                .map_or(String::new(), |before| {
                    let before = before.trim_end();
                    // after the last character that cannot be part of a key (which may be
                    // several bytes long: `·`, `é`)
                    let from = before
                        .char_indices()
                        .rfind(|&(_, c)| !(c.is_alphanumeric() || "_-.\"'".contains(c)))
                        .map_or(0, |(i, c)| i + c.len_utf8());
                    clean_key(&before[from..])
                })
        };
        match (header.is_empty(), key.is_empty()) {
            (_, true) => header,
            (true, false) => key,
            (false, false) => format!("{header}.{key}"),
        }
    }
}

/// Byte index of the last `=` of `line` outside quoted strings (an `=` inside a string value,
/// even an unterminated one, is not an assignment).
fn last_assignment(line: &str) -> Option<usize> {
    let mut quote = None;
    let mut escaped = false;
    let mut last = None;
    for (i, c) in line.char_indices() {
        match quote {
            Some('"') if escaped => escaped = false,
            Some('"') if c == '\\' => escaped = true,
            Some(q) if c == q => quote = None,
            Some(_) => {}
            None if c == '"' || c == '\'' => quote = Some(c),
            None if c == '#' => break,
            None if c == '=' => last = Some(i),
            None => {}
        }
    }
    last
}

/// serde's type names in words an engineer reads.
fn plain_types(message: &str) -> String {
    message
        .replace("expected i64", "expected a whole number")
        .replace("expected u64", "expected a whole number >= 0")
        .replace("expected f64", "expected a number")
        .replace("expected an array of length 3", "expected three numbers [x, y, z]")
        .replace("expected an array of length 2", "expected two numbers [a, b]")
        .replace("expected a boolean", "expected true or false")
}

fn clean_key(k: &str) -> String {
    k.trim().trim_matches(|c| c == '"' || c == '\'').to_owned()
}

/// The name of a `[table]` or `[[array]]` header line.
fn table_header(line: &str) -> Option<String> {
    let t = line.trim_start();
    if !t.starts_with('[') {
        return None;
    }
    let t = t.split('#').next().unwrap_or("").trim();
    let name = t.trim_start_matches('[').trim_end_matches(']').trim();
    Some(name.split('.').map(|part| clean_key(part.trim())).collect::<Vec<_>>().join("."))
}

/// `" (did you mean `x`?)"` for serde's "unknown field `a`, expected one of `b`, `c`" and
/// "unknown variant" messages, when a known name is close.
fn suggestion_from_message(message: &str) -> Option<String> {
    if !message.starts_with("unknown field") && !message.starts_with("unknown variant") {
        return None;
    }
    let mut quoted = message.split('`').skip(1).step_by(2);
    let given = quoted.next()?;
    let known: Vec<&str> = quoted.collect();
    nearest(given, known.iter().copied()).map(|k| format!(" (did you mean `{k}`?)"))
}

/// The known name closest to `given` (edit distance at most a third of its length, at least
/// 2), if any.
pub(crate) fn nearest<'k>(
    given: &str,
    known: impl IntoIterator<Item = &'k str>,
) -> Option<&'k str> {
    let limit = (given.chars().count() / 3).max(2);
    known
        .into_iter()
        .map(|k| (edit_distance(&given.to_lowercase(), &k.to_lowercase()), k))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map(|(_, k)| k)
}

/// Levenshtein distance between two strings (in characters).
pub(crate) fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let next = (diagonal + usize::from(ca != cb)).min(row[j] + 1).min(row[j + 1] + 1);
            diagonal = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

/// "unknown <what> `given`; expected one of a, b, c (did you mean `b`?)".
pub(crate) fn unknown_name(what: &str, given: &str, known: &[&str]) -> String {
    let hint = nearest(given, known.iter().copied())
        .map(|k| format!(" (did you mean `{k}`?)"))
        .unwrap_or_default();
    format!("unknown {what} `{given}`; expected one of: {}{hint}", known.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_and_nearest() {
        assert_eq!(edit_distance("stel", "steel"), 1);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(nearest("stel", ["rubber", "steel"]), Some("steel"));
        assert_eq!(nearest("xyz", ["rubber", "steel"]), None);
    }

    #[test]
    fn line_column_and_keys() {
        let text = "[simulation]\nsteps = 10\n\n[materials.steel]\nyoung = -1 # bad\n";
        let ctx = Ctx { file: "a.toml", text };
        let at = text.find("-1").unwrap();
        assert_eq!(ctx.line_column(at), (5, 9));
        assert_eq!(ctx.key_at(at..at + 2), "materials.steel.young");
        let k = text.find("young").unwrap();
        assert_eq!(ctx.key_at(k..k + 5), "materials.steel.young");
        assert_eq!(ctx.key_at(0..1), "simulation");
    }

    /// The key finder used to cut a line in the middle of `·` (two bytes) and panic with
    /// "byte index is not a char boundary"; an `=` inside a string is not the assignment.
    #[test]
    fn keys_next_to_non_ascii_characters() {
        let text = "[simulation]\nsteps = 10\ndt = \"a·b = 1\n";
        let ctx = Ctx { file: "a.toml", text };
        let at = text.len() - 1;
        assert_eq!(ctx.key_at(at..at + 1), "simulation.dt");
        let text = "[simulation]\nré·x = 1\n";
        let ctx = Ctx { file: "a.toml", text };
        let at = text.find('1').unwrap();
        assert_eq!(ctx.key_at(at..at + 1), "simulation.x");
        assert_eq!(last_assignment("a = \"x = \\\" = y\" # = z"), Some(2));
    }

    #[test]
    fn suggestion_for_unknown_field() {
        let m = "unknown field `yung`, expected one of `young`, `poisson`";
        assert_eq!(suggestion_from_message(m).unwrap(), " (did you mean `young`?)");
        assert!(suggestion_from_message("invalid type").is_none());
    }
}
