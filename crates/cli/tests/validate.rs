//! `flexdem validate`: one line per case, the report written, exit code 2 for an unknown case.

use std::process::{Command, Output};

/// Runs `flexdem` with `args`.
fn flexdem(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexdem")).args(args).output().expect("flexdem starts")
}

#[test]
fn validate_one_case_writes_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("report");
    let out_str = out_dir.to_str().unwrap();
    let out = flexdem(&["validate", "--quick", "--case", "chung_ooi_1", "--output", out_str]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    let line = stdout.lines().next().unwrap_or_default();
    assert!(line.starts_with("chung_ooi_1") && line.contains("pass"), "{stdout}");
    assert!(line.contains(" s "), "no wall time: {line}");
    let report = std::fs::read_to_string(out_dir.join("report.md")).unwrap();
    assert!(report.contains("| [`chung_ooi_1`](#chung_ooi_1) |"), "{report}");
    assert!(report.contains("## Coverage of validation.md"), "{report}");
    assert!(!report.contains("<a id=\"chung_ooi_2\">"), "only the asked case runs: {report}");
}

#[test]
fn validate_an_unknown_case_is_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let out =
        flexdem(&["validate", "--case", "no_such_case", "--output", dir.path().to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("no_such_case") && stderr.contains("catenary"), "{stderr}");
}

/// `flexdem validate` used to write over the committed `validation/report/` by default: it
/// now writes under `target/` of the current folder.
#[test]
fn validate_writes_under_target_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_flexdem"))
        .args(["validate", "--quick", "--case", "chung_ooi_1"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    assert!(dir.path().join("target/flexdem/validation/report.md").is_file(), "{stdout}");
    assert!(stdout.contains("report: target/flexdem/validation/report.md"), "{stdout}");
    assert!(!dir.path().join("validation").exists());
    let both = flexdem(&["validate", "--update-committed", "--output", "x", "--case", "none"]);
    assert_eq!(both.status.code(), Some(2), "--output and --update-committed conflict");
}
