//! `flexdem run SCENE`: runs a scene file with the command line's overrides.

use super::execute::{default_checkpoint_path, execute, writes_something, Job};
use super::{absolute, build_simulation, read_scene, set_threads, to_usize};
use crate::cli::RunArgs;
use crate::error::{CliError, Outcome};
use flexdem_io::output::Output;
use flexdem_io::scene::RunLength;

/// Runs the scene of `args`.
pub fn run(args: &RunArgs) -> Result<Outcome, CliError> {
    let scene = read_scene(&args.scene)?;
    let threads = to_usize(args.exec.threads)?.or(scene.threads);
    let in_use = set_threads(threads)?;
    let (sim, mut rest) = build_simulation(scene)?;
    if let Some(dir) = &args.output {
        rest.output.directory = dir.clone();
    }
    rest.output.directory = absolute(&rest.output.directory);
    if args.exec.no_output {
        rest.output.vtk_every = None;
        rest.output.series_every = None;
        rest.output.plot = false;
    }
    let target = match args.steps {
        Some(n) => RunLength::Steps(n),
        None => rest.run,
    };
    let output = if writes_something(&rest.output) {
        Some(Output::new(&rest.output, &sim).map_err(|e| CliError::Input(e.to_string()))?)
    } else {
        None
    };
    let checkpoint_path = match &args.exec.checkpoint {
        Some(path) => absolute(path),
        None => default_checkpoint_path(&rest.output.directory),
    };
    if !args.exec.quiet {
        eprintln!(
            "running {} for {} (dt = {:.3e} s, critical {:.3e} s) on {in_use} thread{}",
            rest.source.display(),
            super::describe_run(target),
            sim.dt(),
            sim.critical_dt(),
            if in_use == 1 { "" } else { "s" }
        );
    }
    execute(Job {
        sim,
        output,
        output_settings: rest.output,
        target,
        threads: (threads, in_use),
        scene: absolute(&rest.source),
        checkpoint_path,
        checkpoint_every: args.exec.checkpoint_every,
        summary: args.exec.summary.clone(),
        quiet: args.exec.quiet,
    })
}
