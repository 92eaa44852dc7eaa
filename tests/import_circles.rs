//! No import circle between the files of any crate (issue 13): a module that uses another
//! (`crate::…`, `super::…`, or a child it declares) may not be used back, directly or through
//! others. Parsed from the sources (comments and `#[cfg(test)]` parts left out), so a new
//! circle fails here with the modules named.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let path = entry.path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The module path of a source file under `src` (`lib.rs` is ``, `a/mod.rs` is `a`).
fn module_of(file: &Path, src: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib" | "main")) {
        parts.pop();
    }
    parts.join("::")
}

/// The code of a file without comment lines and without what follows `#[cfg(test)]`.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]").next().unwrap_or("");
    text.lines().filter(|l| !l.trim_start().starts_with("//")).collect::<Vec<_>>().join("\n")
}

/// The paths that start right after `prefix` at each of its occurrences, as identifiers; a
/// group `prefix a::{B, c::D}` gives `a::B` and `a::c::D`.
fn paths_after(text: &str, prefix: &str) -> Vec<Vec<String>> {
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == ':';
    let split = |path: &str| -> Vec<String> {
        path.split("::").filter(|s| !s.is_empty()).map(String::from).collect()
    };
    let mut out = Vec::new();
    for (at, _) in text.match_indices(prefix) {
        let rest = &text[at + prefix.len()..];
        let end = rest.find(|c: char| !ident(c)).unwrap_or(rest.len());
        let base = split(&rest[..end]);
        match rest[end..].strip_prefix('{') {
            Some(group) => {
                let group = &group[..group.find('}').unwrap_or(group.len())];
                for entry in group.split(',') {
                    let entry = entry.trim();
                    let name = &entry[..entry.find(|c: char| !ident(c)).unwrap_or(entry.len())];
                    if name.is_empty() {
                        continue; // after a trailing comma
                    }
                    let mut path = base.clone();
                    path.extend(split(name));
                    out.push(path);
                }
            }
            None => out.push(base),
        }
    }
    out
}

/// The items each module defines (`pub`, `pub(crate)`, `pub(super)` or private functions,
/// types, traits, constants and statics at the start of a line).
type Definitions = BTreeMap<String, BTreeSet<String>>;

fn definitions(text: &str) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    for line in text.lines() {
        let mut rest = line.trim_start();
        for visibility in ["pub(crate) ", "pub(super) ", "pub "] {
            rest = rest.strip_prefix(visibility).unwrap_or(rest);
        }
        for kind in ["fn ", "struct ", "enum ", "trait ", "type ", "const ", "static "] {
            if let Some(after) = rest.strip_prefix(kind) {
                let name: String =
                    after.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
                if !name.is_empty() {
                    names.insert(name);
                }
            }
        }
    }
    names
}

/// The module `parts` (a path inside the crate) depends on: the longest module prefix, or,
/// when the item after it is not defined there but re-exported, the one module (preferably
/// below it) that defines the item. A use through a re-export depends on the item's module,
/// not on the module that re-exports it.
fn resolve(parts: &[&str], modules: &BTreeSet<String>, defined: &Definitions) -> Option<String> {
    let k = (0..=parts.len()).rev().find(|&k| modules.contains(&parts[..k].join("::")))?;
    let module = parts[..k].join("::");
    let Some(item) = parts.get(k) else { return Some(module) };
    let own = defined.get(&module).is_some_and(|names| names.contains(*item));
    if own {
        return Some(module);
    }
    let owners: Vec<&String> =
        defined.iter().filter(|(_, names)| names.contains(*item)).map(|(m, _)| m).collect();
    let below: Vec<&String> = owners
        .iter()
        .copied()
        .filter(|m| module.is_empty() || m.starts_with(&format!("{module}::")))
        .collect();
    match below.as_slice() {
        [one] => Some((*one).clone()),
        _ => match owners.as_slice() {
            [one] => Some((*one).clone()),
            _ => Some(module),
        },
    }
}

/// Edges module → modules it uses, for the crate whose sources are in `src`.
fn uses(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut files = Vec::new();
    sources(src, &mut files);
    let modules: BTreeSet<String> = files.iter().map(|f| module_of(f, src)).collect();
    let texts: Vec<String> =
        files.iter().map(|f| code(&std::fs::read_to_string(f).unwrap())).collect();
    let defined: Definitions =
        files.iter().zip(&texts).map(|(f, t)| (module_of(f, src), definitions(t))).collect();
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (file, text) in files.iter().zip(&texts) {
        let me = module_of(file, src);
        let mut used = BTreeSet::new();
        for parts in paths_after(text, "crate::") {
            let parts: Vec<&str> = parts.iter().map(String::as_str).collect();
            used.extend(resolve(&parts, &modules, &defined));
        }
        let parent: Vec<&str> = me.split("::").filter(|s| !s.is_empty()).collect();
        let parent = &parent[..parent.len().saturating_sub(1)];
        for parts in paths_after(text, "super::") {
            let full: Vec<&str> =
                parent.iter().copied().chain(parts.iter().map(String::as_str)).collect();
            used.extend(resolve(&full, &modules, &defined));
        }
        // children it declares and refers to (`pub use child::…`, `child::f()`)
        for line in text.lines() {
            let line = line.trim_start();
            let decl = line.trim_start_matches("pub(crate) ").trim_start_matches("pub ");
            if let Some(name) = decl.strip_prefix("mod ").and_then(|r| r.strip_suffix(';')) {
                let child = if me.is_empty() { name.to_string() } else { format!("{me}::{name}") };
                if modules.contains(&child) && text.contains(&format!("{name}::")) {
                    used.insert(child);
                }
            }
        }
        used.remove(&me);
        edges.insert(me, used);
    }
    edges
}

/// The strongly connected components of more than one module (Tarjan).
fn circles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct Walk<'a> {
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        found: Vec<Vec<String>>,
    }
    fn visit<'a>(w: &mut Walk<'a>, v: &'a str) {
        let n = w.index.len();
        w.index.insert(v, n);
        w.low.insert(v, n);
        w.stack.push(v);
        for u in w.edges.get(v).into_iter().flatten() {
            let u = u.as_str();
            if !w.edges.contains_key(u) {
                continue;
            }
            if !w.index.contains_key(u) {
                visit(w, u);
                let low = w.low[v].min(w.low[u]);
                w.low.insert(v, low);
            } else if w.stack.contains(&u) {
                let low = w.low[v].min(w.index[u]);
                w.low.insert(v, low);
            }
        }
        if w.low[v] == w.index[v] {
            let at = w.stack.iter().rposition(|&x| x == v).unwrap();
            let component: Vec<String> = w.stack.drain(at..).map(String::from).collect();
            if component.len() > 1 {
                w.found.push(component);
            }
        }
    }
    let mut w = Walk {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        found: Vec::new(),
    };
    for v in edges.keys() {
        if !w.index.contains_key(v.as_str()) {
            visit(&mut w, v);
        }
    }
    w.found
}

#[test]
fn no_crate_has_an_import_circle_between_its_files() {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates");
    let mut found = Vec::new();
    for entry in std::fs::read_dir(&crates).unwrap().flatten() {
        let src = entry.path().join("src");
        if src.is_dir() {
            let edges = uses(&src);
            if std::env::var("IMPORT_EDGES").is_ok_and(|c| entry.file_name().to_string_lossy() == c)
            {
                eprintln!("{edges:#?}");
            }
            for circle in circles(&edges) {
                found.push(format!(
                    "{}: {}",
                    entry.file_name().to_string_lossy(),
                    circle.join(" ↔ ")
                ));
            }
        }
    }
    found.sort();
    assert!(found.is_empty(), "import circles:\n{}", found.join("\n"));
}

#[test]
fn a_circle_is_found() {
    let edges: BTreeMap<String, BTreeSet<String>> =
        [("a", vec!["b"]), ("b", vec!["c"]), ("c", vec!["a"]), ("d", vec!["a"])]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v.into_iter().map(String::from).collect()))
            .collect();
    let found = circles(&edges);
    assert_eq!(found.len(), 1);
    let mut circle = found[0].clone();
    circle.sort();
    assert_eq!(circle, ["a", "b", "c"]);
}
