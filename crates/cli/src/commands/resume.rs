//! `flexdem resume CHECKPOINT`: continues a run from a checkpoint, and its output series.

use super::execute::{execute, reached, writes_something, Job};
use super::{absolute, describe_run, set_threads, to_usize};
use crate::cli::ResumeArgs;
use crate::error::{CliError, Outcome};
use flexdem_io::checkpoint::read_checkpoint;
use flexdem_io::output::Output;
use flexdem_io::scene::RunLength;

/// Resumes the run of `args.checkpoint_file`.
pub fn resume(args: &ResumeArgs) -> Result<Outcome, CliError> {
    let path = &args.checkpoint_file;
    let checkpoint = read_checkpoint(path).map_err(|e| CliError::Input(e.to_string()))?;
    // the thread pool first: rebuilding the simulation may already use it
    let threads = to_usize(args.exec.threads)?.or(checkpoint.threads);
    let in_use = set_threads(threads)?;
    let (sim, checkpoint) = checkpoint.into_simulation().map_err(|e| {
        CliError::Input(format!("{}: the checkpoint cannot be resumed: {e}", path.display()))
    })?;
    let target = match args.steps {
        Some(n) => RunLength::Steps(sim.steps().saturating_add(n)),
        None => checkpoint.run,
    };
    if reached(&sim, target) {
        // nothing to run; the output is left as the run wrote it
        println!(
            "nothing to do: the checkpoint is at step {} (t = {:.6e} s), the run length ({}) is \
             reached; use --steps N to run N more steps",
            sim.steps(),
            sim.time(),
            describe_run(checkpoint.run)
        );
        return Ok(Outcome::Done);
    }
    let mut settings = checkpoint.output;
    if args.exec.no_output {
        settings.vtk_every = None;
        settings.series_every = None;
        settings.plot = false;
    }
    let output = if writes_something(&settings) {
        Some(Output::resume(&settings, &sim, &checkpoint.output_progress).map_err(|e| {
            CliError::Input(format!("{}: cannot continue the output: {e}", path.display()))
        })?)
    } else {
        None
    };
    let checkpoint_path = absolute(args.exec.checkpoint.as_deref().unwrap_or(path));
    if !args.exec.quiet {
        eprintln!(
            "resuming {} at step {} (t = {:.6e} s) until {} on {in_use} thread{}",
            checkpoint.scene.display(),
            sim.steps(),
            sim.time(),
            match target {
                RunLength::Steps(n) => format!("step {n}"),
                RunLength::Duration(_) => describe_run(target),
            },
            if in_use == 1 { "" } else { "s" }
        );
    }
    execute(Job {
        sim,
        output,
        output_settings: settings,
        target,
        threads: (threads, in_use),
        scene: checkpoint.scene,
        checkpoint_path,
        checkpoint_every: args.exec.checkpoint_every,
        summary: args.exec.summary.clone(),
        quiet: args.exec.quiet,
    })
}
