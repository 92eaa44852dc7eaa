//! Why a run could not be set up or went wrong; each error says whether the input was at fault
//! ([`RunError::is_bad_input`]).

use flexdem_integrate::SimulationError;
use flexdem_io::checkpoint::CheckpointError;
use flexdem_output::OutputError;
use flexdem_scene::SceneError;
use std::path::PathBuf;

/// Why a run could not be set up, or stopped on an error.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The scene file cannot be read (its error names the file, line, column and key).
    #[error(transparent)]
    Scene(Box<SceneError>),
    /// The engine refuses the scene's model, settings or loads.
    #[error("{}: the scene cannot be simulated: {source}", scene.display())]
    Simulation {
        /// The scene file.
        scene: PathBuf,
        /// The engine's error.
        source: Box<SimulationError>,
    },
    /// The scene's duration is too many steps at the time step the engine chose.
    #[error("{}: `simulation.duration`: {message}", scene.display())]
    RunLength {
        /// The scene file.
        scene: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The checkpoint file cannot be read.
    #[error(transparent)]
    ReadCheckpoint(Box<CheckpointError>),
    /// The checkpoint was read but its state cannot be resumed.
    #[error("{}: the checkpoint cannot be resumed: {source}", path.display())]
    Resume {
        /// The checkpoint file.
        path: PathBuf,
        /// Why.
        source: Box<CheckpointError>,
    },
    /// The output cannot be set up (a bad setting or series, a folder that cannot be made).
    #[error(transparent)]
    OutputSetup(OutputError),
    /// The output of the checkpointed run cannot be continued.
    #[error("{}: cannot continue the output: {source}", path.display())]
    OutputResume {
        /// The checkpoint file.
        path: PathBuf,
        /// Why.
        source: OutputError,
    },
    /// The worker threads cannot be started.
    #[error("cannot start {threads} worker threads: {message}")]
    Threads {
        /// The number asked for.
        threads: usize,
        /// Why.
        message: String,
    },
    /// A step failed (an unstable run, energy created beyond the tolerance, ...).
    #[error(transparent)]
    Step(Box<SimulationError>),
    /// Writing the output failed during the run.
    #[error(transparent)]
    Output(OutputError),
    /// The folder of the checkpoint file cannot be created.
    #[error("cannot create the checkpoint folder {}: {source}", path.display())]
    CheckpointFolder {
        /// The folder.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A checkpoint cannot be written.
    #[error(transparent)]
    WriteCheckpoint(Box<CheckpointError>),
    /// The JSON summary cannot be written.
    #[error("{0}")]
    Summary(String),
}

impl From<SceneError> for RunError {
    fn from(e: SceneError) -> RunError {
        RunError::Scene(Box::new(e))
    }
}

impl RunError {
    /// Whether the input (scene, checkpoint, options) is at fault rather than the run: the
    /// command line exits with code 2 for these, 1 for the others.
    pub fn is_bad_input(&self) -> bool {
        matches!(
            self,
            RunError::Scene(_)
                | RunError::Simulation { .. }
                | RunError::RunLength { .. }
                | RunError::ReadCheckpoint(_)
                | RunError::Resume { .. }
                | RunError::OutputSetup(_)
                | RunError::OutputResume { .. }
        )
    }
}
