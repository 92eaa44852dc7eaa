//! The malformed-scene corpus (tests/data/scenes/bad, written by its generate.py): each
//! NAME.toml fails with a message containing every fragment of NAME.expected, the first of
//! which is "NAME.toml:LINE:" (file and line of the error).

use flexdem_scene::{load_scene, parse_scene, SceneError};
use std::path::{Path, PathBuf};

fn corpus() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/scenes/bad")
}

#[test]
fn every_bad_scene_gives_its_error() {
    let mut cases: Vec<PathBuf> = std::fs::read_dir(corpus())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    cases.sort();
    assert!(cases.len() >= 20, "only {} bad scenes", cases.len());
    let mut failures = Vec::new();
    for path in &cases {
        let expected = std::fs::read_to_string(path.with_extension("expected"))
            .unwrap_or_else(|e| panic!("{}: no .expected file: {e}", path.display()));
        let message = match load_scene(path) {
            Ok(_) => {
                failures.push(format!("{}: loaded without error", path.display()));
                continue;
            }
            Err(e) => e.to_string(),
        };
        println!("{message}");
        for fragment in expected.lines().filter(|l| !l.is_empty()) {
            if !message.contains(fragment) {
                failures.push(format!(
                    "{}:\n  message: {message}\n  missing: {fragment}",
                    path.display()
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn errors_carry_line_column_and_key() {
    let text = "[simulation]\nsteps = 10\ndamping = -0.5\n";
    let err = parse_scene(text, Path::new("s.toml")).unwrap_err();
    match &err {
        SceneError::At { file, line, column, key, .. } => {
            assert_eq!(
                (file.as_str(), *line, *column, key.as_str()),
                ("s.toml", 3, 11, "simulation.damping")
            );
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        err.to_string(),
        "s.toml:3:11: `simulation.damping`: is -0.5: expected a number in [0, 1)"
    );
}

#[test]
fn a_missing_scene_file_is_an_io_error() {
    let err = load_scene(Path::new("/no/such/scene.toml")).unwrap_err();
    assert!(matches!(err, SceneError::Io { .. }));
    assert!(err.to_string().contains("/no/such/scene.toml"), "{err}");
}

/// A scene that is not UTF-8 used to fail with "stream did not contain valid UTF-8" and no
/// place: the error now gives the line, column and byte of the first bad byte.
#[test]
fn invalid_utf8_is_located() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("latin1.toml");
    std::fs::write(&path, b"[simulation]\nsteps = 10\n# caf\xe9\ndt = 1e-6\n").unwrap();
    let message = load_scene(&path).unwrap_err().to_string();
    let expected =
        format!("{}:3:6: invalid UTF-8 at byte 29 (0xe9 0x0a 0x64 0x74)", path.display());
    assert!(message.starts_with(&expected), "{message}");
}

/// The unterminated string with a non-ASCII character of the mutation fuzzer (`dt = "a·b = 1`)
/// used to panic in the error formatter ("byte index is not a char boundary").
#[test]
fn non_ascii_in_a_broken_line_does_not_panic() {
    for text in ["[simulation]\nsteps = 10\ndt = \"a·b = 1\n", "[simulation]\nsté·ps = 10\n", "·=·"]
    {
        let message = parse_scene(text, Path::new("s.toml")).unwrap_err().to_string();
        assert!(message.starts_with("s.toml:"), "{message}");
    }
}
