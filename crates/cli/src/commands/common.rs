//! What the subcommands share: reading a scene, building its simulation, the worker
//! threads, the run length in words.

use crate::error::CliError;
use flexdem_integrate::Simulation;
use flexdem_io::scene::{load_scene, RunLength, Scene};
use flexdem_run::SceneRest;
use std::path::Path;

/// Reads the scene file at `path`; its errors (file, line, column, key) are bad input.
pub fn read_scene(path: &Path) -> Result<Scene, CliError> {
    load_scene(path).map_err(|e| CliError::Input(e.to_string()))
}

/// The simulation of `scene` with its loads, and the rest of the scene
/// ([`flexdem_run::build_simulation`]); its errors are bad input.
pub fn build_simulation(scene: Scene) -> Result<(Simulation, SceneRest), CliError> {
    Ok(flexdem_run::build_simulation(scene)?)
}

/// Sets the number of worker threads for this process (None: one per core); returns the
/// number in use.
pub fn set_threads(threads: Option<usize>) -> Result<usize, CliError> {
    Ok(flexdem_run::configure_threads(threads)?)
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
