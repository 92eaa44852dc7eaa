//! `flexdem resume CHECKPOINT`: continues a run from a checkpoint, and its output series.

use super::common::{describe_run, set_threads, to_usize};
use super::execute::{execute, interrupt_flag};
use crate::cli::ResumeArgs;
use crate::error::{CliError, Outcome};
use flexdem_io::checkpoint::read_checkpoint;
use flexdem_io::scene::RunLength;
use flexdem_run::{Run, RunOptions};

/// Resumes the run of `args.checkpoint_file`.
pub fn resume(args: &ResumeArgs) -> Result<Outcome, CliError> {
    let path = &args.checkpoint_file;
    let checkpoint = read_checkpoint(path).map_err(|e| CliError::Input(e.to_string()))?;
    // the thread pool first: rebuilding the simulation may already use it
    let threads = to_usize(args.exec.threads)?.or(checkpoint.threads);
    let in_use = set_threads(threads)?;
    let options = RunOptions {
        steps: args.steps,
        threads,
        output_directory: None,
        no_output: args.exec.no_output,
        checkpoint_path: args.exec.checkpoint.clone(),
        checkpoint_every: args.exec.checkpoint_every,
        interrupt: Some(interrupt_flag()?),
    };
    let run = Run::from_checkpoint(checkpoint, path, options)?;
    let sim = run.sim();
    if run.is_done() {
        // nothing to run; the output is left as the run wrote it
        println!(
            "nothing to do: the checkpoint is at step {} (t = {:.6e} s), the run length ({}) is \
             reached; use --steps N to run N more steps",
            sim.steps(),
            sim.time(),
            describe_run(run.target())
        );
        return Ok(Outcome::Done);
    }
    if !args.exec.quiet {
        eprintln!(
            "resuming {} at step {} (t = {:.6e} s) until {} on {in_use} thread{}",
            run.scene_file().display(),
            sim.steps(),
            sim.time(),
            match run.target() {
                RunLength::Steps(n) => format!("step {n}"),
                RunLength::Duration(_) => describe_run(run.target()),
            },
            if in_use == 1 { "" } else { "s" }
        );
    }
    execute(run, &args.exec)
}
