//! Random mutations of the example scenes: the loader returns Ok or Err, never panics.

use flexdem_scene::parse_scene;
use proptest::prelude::*;
use std::path::PathBuf;

fn examples() -> Vec<(PathBuf, String)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut out: Vec<(PathBuf, String)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (p, text)
        })
        .collect();
    out.sort();
    out
}

/// Values a mutation may write over a token.
const VALUES: [&str; 16] = [
    "0",
    "-1",
    "1e300",
    "nan",
    "inf",
    "-inf",
    "\"x\"",
    "[1, 2]",
    "[]",
    "true",
    "3",
    "1e-300",
    "{ }",
    "\"auto\"",
    "[0, 0, 0]",
    "9223372036854775807",
];

#[derive(Clone, Debug)]
enum Mutation {
    /// Delete `len` bytes at a fraction of the text.
    Delete(f64, usize),
    /// Insert a string at a fraction of the text.
    Insert(f64, String),
    /// Replace the value of the line at a fraction of the lines.
    ReplaceValue(f64, usize),
    /// Duplicate a line.
    DuplicateLine(f64),
    /// Swap two lines.
    SwapLines(f64, f64),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (0.0..1.0, 1usize..20).prop_map(|(a, n)| Mutation::Delete(a, n)),
        (0.0..1.0, "[\\[\\]{}=\",.a-z0-9 \n#-]{1,8}").prop_map(|(a, s)| Mutation::Insert(a, s)),
        (0.0..1.0, 0..VALUES.len()).prop_map(|(a, v)| Mutation::ReplaceValue(a, v)),
        (0.0..1.0).prop_map(Mutation::DuplicateLine),
        (0.0..1.0, 0.0..1.0).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
    ]
}

fn at(text: &str, fraction: f64) -> usize {
    let mut i = ((text.len() as f64) * fraction) as usize;
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn apply(text: &str, m: &Mutation) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let line = |f: f64| ((lines.len() as f64) * f) as usize % lines.len().max(1);
    match m {
        Mutation::Delete(a, n) => {
            let start = at(text, *a);
            let end = at(text, ((start + n) as f64 / text.len() as f64).min(1.0)).max(start);
            format!("{}{}", &text[..start], &text[end..])
        }
        Mutation::Insert(a, s) => {
            let i = at(text, *a);
            format!("{}{s}{}", &text[..i], &text[i..])
        }
        Mutation::ReplaceValue(a, v) => {
            let k = line(*a);
            if let Some(eq) = lines[k].find('=') {
                lines[k] = format!("{}= {}", &lines[k][..eq], VALUES[*v]);
            }
            lines.join("\n")
        }
        Mutation::DuplicateLine(a) => {
            let k = line(*a);
            let copy = lines[k].clone();
            lines.insert(k, copy);
            lines.join("\n")
        }
        Mutation::SwapLines(a, b) => {
            let (i, j) = (line(*a), line(*b));
            lines.swap(i, j);
            lines.join("\n")
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn mutated_examples_never_panic(
        which in 0usize..16,
        mutations in proptest::collection::vec(mutation(), 1..4),
    ) {
        let examples = examples();
        let (path, text) = &examples[which % examples.len()];
        let mut text = text.clone();
        for m in &mutations {
            text = apply(&text, m);
        }
        if let Err(e) = parse_scene(&text, path) {
            // Every message is located in the file.
            let shown = e.to_string();
            prop_assert!(shown.contains(&format!("{}:", path.display())), "{shown}");
        }
    }
}
