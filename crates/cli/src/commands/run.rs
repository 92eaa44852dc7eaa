//! `flexdem run SCENE`: runs a scene file with the command line's overrides.

use super::common::{describe_run, read_scene, set_threads, to_usize};
use super::execute::{execute, interrupt_flag};
use crate::cli::RunArgs;
use crate::error::{CliError, Outcome};
use flexdem_run::{Run, RunOptions};

/// Runs the scene of `args`.
pub fn run(args: &RunArgs) -> Result<Outcome, CliError> {
    let scene = read_scene(&args.scene)?;
    // the thread pool first: building the simulation may already use it
    let threads = to_usize(args.exec.threads)?.or(scene.threads);
    let in_use = set_threads(threads)?;
    let options = RunOptions {
        steps: args.steps,
        threads,
        output_directory: args.output.clone(),
        no_output: args.exec.no_output,
        checkpoint_path: args.exec.checkpoint.clone(),
        checkpoint_every: args.exec.checkpoint_every,
        interrupt: Some(interrupt_flag()?),
    };
    let run = Run::new(scene, options)?;
    if !args.exec.quiet {
        eprintln!(
            "running {} for {} (dt = {:.3e} s, critical {:.3e} s) on {in_use} thread{}",
            args.scene.display(),
            describe_run(run.target()),
            run.sim().dt(),
            run.sim().critical_dt(),
            if in_use == 1 { "" } else { "s" }
        );
    }
    execute(run, &args.exec)
}
