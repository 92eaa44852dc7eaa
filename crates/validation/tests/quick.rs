//! The quick subset of the validation cases, run by `cargo test`: each case runs with
//! `quick: true` into a temporary folder and every check must pass.

use flexdem_validation::{cases, run_case, write_report, CaseReport, Context};

/// Runs the registered case `id` in quick mode and fails with its report table unless every
/// check passes; returns the report.
fn run_quick(id: &str) -> CaseReport {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let ctx = Context { out_dir: dir.path().to_path_buf(), quick: true };
    let case = cases().into_iter().find(|c| c.id == id).unwrap_or_else(|| panic!("no case {id}"));
    assert!(case.in_quick_subset, "{id} is not in the quick subset");
    let report = match run_case(&ctx, &case) {
        Ok(report) => report,
        Err(e) => panic!("{id} did not run: {e}"),
    };
    for figure in &report.figures {
        assert!(dir.path().join(&figure.file).is_file(), "{id}: figure {} missing", figure.file);
        assert!(figure.file.starts_with(id.split('_').next().unwrap_or(id)), "{}", figure.file);
    }
    assert!(!report.checks.is_empty(), "{id} checks nothing");
    assert!(report.passed(), "{id} failed:\n{}\n{:?}", report.checks_table(), report.informative);
    write_report(dir.path(), true, &[(case, Ok(report.clone()))]).expect("the report is written");
    report
}

#[test]
fn chung_ooi_1() {
    run_quick("chung_ooi_1");
}

#[test]
fn chung_ooi_2() {
    run_quick("chung_ooi_2");
}

#[test]
fn chung_ooi_4() {
    run_quick("chung_ooi_4");
}

#[test]
fn catenary() {
    run_quick("catenary");
}

#[test]
fn yade_cantilever() {
    run_quick("yade_cantilever");
}

#[test]
fn yade_force_splits() {
    run_quick("yade_force_splits");
}

/// The tension test and the linear part of the bending: two checks.
#[test]
fn brazier() {
    let report = run_quick("brazier");
    assert_eq!(report.checks.len(), 2, "{}", report.checks_table());
}

/// The impactor touches the tube, slows down, the energy balance closes: three checks each.
#[test]
fn impact_solid() {
    let report = run_quick("impact_solid");
    assert_eq!(report.checks.len(), 3, "{}", report.checks_table());
}

#[test]
fn impact_hollow() {
    let report = run_quick("impact_hollow");
    assert_eq!(report.checks.len(), 3, "{}", report.checks_table());
}
