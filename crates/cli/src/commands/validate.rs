//! `flexdem validate [--quick] [--case ID] [--output DIR]`: runs the validation cases of
//! `flexdem-validation` and writes their report (`report.md` and PNG plots).

use crate::error::{CliError, Outcome};
use clap::Args;
use flexdem_validation::{cases, run_cases_with, selected_cases, write_report, Context};
use std::path::PathBuf;

/// `flexdem validate`.
#[derive(Debug, Args)]
pub struct ValidateArgs {
    /// Run only the quick subset (the cases `cargo test` runs, with shorter runs).
    #[arg(long)]
    pub quick: bool,
    /// Run only the case with this id (see the report's summary for the ids).
    #[arg(long, value_name = "ID")]
    pub case: Option<String>,
    /// Write the report and its plots into this folder.
    #[arg(long, value_name = "DIR", default_value = "validation/report")]
    pub output: PathBuf,
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
    std::fs::create_dir_all(&args.output).map_err(|e| {
        CliError::Run(format!("cannot create the output folder {}: {e}", args.output.display()))
    })?;
    let ctx = Context { out_dir: args.output.clone(), quick: args.quick };
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
    let path = write_report(&args.output, args.quick, &results)
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
