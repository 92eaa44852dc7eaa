//! `flexdem validate [--quick] [--case ID] [--output DIR | --update-committed]`: runs the
//! validation cases of `flexdem-validation` and writes their report (`report.md` and PNG
//! plots): into `target/flexdem/validation/` by default, never over the committed report
//! (`validation/report/`) unless asked to.

use crate::error::{CliError, Outcome};
use clap::Args;
use flexdem_validation::{cases, run_cases_with, selected_cases, write_report, Context};
use std::path::{Path, PathBuf};

/// `flexdem validate`.
#[derive(Debug, Args)]
pub struct ValidateArgs {
    /// Run only the quick subset (the cases `cargo test` runs, with shorter runs).
    #[arg(long)]
    pub quick: bool,
    /// Run only the case with this id (see the report's summary for the ids).
    #[arg(long, value_name = "ID")]
    pub case: Option<String>,
    /// Write the report and its plots into this folder (default:
    /// target/flexdem/validation in the current folder).
    #[arg(long, value_name = "DIR", conflicts_with = "update_committed")]
    pub output: Option<PathBuf>,
    /// Write into the committed report of the source tree (validation/report/), to update it.
    #[arg(long)]
    pub update_committed: bool,
}

/// Default folder of the report: under `target/` of the current folder.
pub const DEFAULT_OUTPUT: &str = "target/flexdem/validation";

/// The committed report of the source tree this binary was built from.
pub fn committed_report() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../validation/report")
}

impl ValidateArgs {
    /// Where the report goes.
    pub fn output_dir(&self) -> PathBuf {
        match (&self.output, self.update_committed) {
            (Some(dir), _) => dir.clone(),
            (None, true) => committed_report(),
            (None, false) => PathBuf::from(DEFAULT_OUTPUT),
        }
    }
}

/// Runs the selected cases, printing one line per case (id, verdict, checks, wall time),
/// writes the report and fails (exit code 1) when a case fails or cannot run.
pub fn validate(args: &ValidateArgs) -> Result<Outcome, CliError> {
    if let Some(id) = &args.case {
        if selected_cases(args.quick, Some(id)).is_empty() {
            let ids: Vec<&str> = cases().iter().map(|c| c.id).collect();
            return Err(CliError::Input(format!(
                "--case {id}: no such validation case (cases: {})",
                ids.join(", ")
            )));
        }
    }
    let output = args.output_dir();
    std::fs::create_dir_all(&output).map_err(|e| {
        CliError::Run(format!("cannot create the output folder {}: {e}", output.display()))
    })?;
    let ctx = Context { out_dir: output.clone(), quick: args.quick };
    let results = run_cases_with(&ctx, args.case.as_deref(), |case, result, elapsed| {
        let (verdict, checks) = match result {
            Ok(r) => (
                if r.passed() { "pass" } else { "FAIL" },
                format!("{}/{} checks", r.checks_passed(), r.checks.len()),
            ),
            Err(e) => ("ERROR", e.to_string()),
        };
        println!("{:<24} {verdict:<5} {:>8.1} s  {checks}", case.id, elapsed.as_secs_f64());
    });
    let path = write_report(&output, args.quick, &results)
        .map_err(|e| CliError::Run(format!("cannot write the report: {e}")))?;
    println!("report: {}", path.display());
    let failed: Vec<&str> = results
        .iter()
        .filter(|(_, r)| !r.as_ref().is_ok_and(|r| r.passed()))
        .map(|(c, _)| c.id)
        .collect();
    if failed.is_empty() {
        Ok(Outcome::Done)
    } else {
        Err(CliError::Run(format!("validation failed: {}", failed.join(", "))))
    }
}
