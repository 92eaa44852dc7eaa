//! The subcommands, and what they share: reading a scene, building its simulation, the
//! worker threads.

pub mod bench;
pub mod check;
pub mod execute;
pub mod info;
pub mod resume;
pub mod run;
pub mod validate;

use crate::error::CliError;
use flexdem_integrate::Simulation;
use flexdem_io::scene::{check_step_count, load_scene, RunLength, Scene};
use std::path::{Path, PathBuf};

/// Reads the scene file at `path`; its errors (file, line, column, key) are bad input.
pub fn read_scene(path: &Path) -> Result<Scene, CliError> {
    load_scene(path).map_err(|e| CliError::Input(e.to_string()))
}

/// The simulation of `scene` with its loads. The scene is consumed but for what is returned
/// alongside: its run length, threads, output settings and source.
pub fn build_simulation(scene: Scene) -> Result<(Simulation, SceneRest), CliError> {
    let source = scene.source.clone();
    let bad = |e: &dyn std::fmt::Display| {
        CliError::Input(format!("{}: the scene cannot be simulated: {e}", source.display()))
    };
    let mut sim = Simulation::new(scene.model, scene.settings).map_err(|e| bad(&e))?;
    for load in scene.loads {
        sim.add_load(load).map_err(|e| bad(&e))?;
    }
    // with dt = "auto" the number of steps of a duration is known only now
    check_step_count(scene.run, sim.dt()).map_err(|e| {
        CliError::Input(format!("{}: `simulation.duration`: {e}", source.display()))
    })?;
    let rest = SceneRest {
        run: scene.run,
        threads: scene.threads,
        output: scene.output,
        source: scene.source,
    };
    Ok((sim, rest))
}

/// The parts of a [`Scene`] that the simulation does not take.
#[derive(Clone, Debug)]
pub struct SceneRest {
    /// How long to run.
    pub run: RunLength,
    /// Worker threads asked for by the scene.
    pub threads: Option<usize>,
    /// What to write.
    pub output: flexdem_io::output::OutputSettings,
    /// The scene file.
    pub source: PathBuf,
}

/// Sets the number of rayon worker threads for this process (None: rayon's default, one per
/// core); returns the number in use.
pub fn set_threads(threads: Option<usize>) -> Result<usize, CliError> {
    if let Some(n) = threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
            .map_err(|e| CliError::Run(format!("cannot start {n} worker threads: {e}")))?;
    }
    Ok(rayon::current_num_threads())
}

/// `path` made absolute against the current folder (so that a checkpoint can be resumed
/// from anywhere); unchanged if that fails.
pub fn absolute(path: &Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf())
}

/// The run length in words: `2000 steps`, `0.15 s`.
pub fn describe_run(run: RunLength) -> String {
    match run {
        RunLength::Steps(n) => format!("{n} steps"),
        RunLength::Duration(d) => format!("{d} s of simulated time"),
    }
}

/// A `u64` from the command line as a `usize` (thread counts).
pub fn to_usize(n: Option<u64>) -> Result<Option<usize>, CliError> {
    n.map(|n| usize::try_from(n).map_err(|_| CliError::Input(format!("{n} is too large a number"))))
        .transpose()
}
