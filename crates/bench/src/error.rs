//! What can go wrong while building or running a benchmark scene.

use flexdem_elements::{BuildError, ModelError};
use flexdem_integrate::SimulationError;
use flexdem_scene::SceneError;

/// A benchmark that could not be built or run; the message names the scene and size.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// A size outside what the scene supports.
    #[error("{scene}: size {size} is out of range: {expected}")]
    BadSize {
        /// Scene name.
        scene: &'static str,
        /// The size asked for.
        size: usize,
        /// What is accepted.
        expected: &'static str,
    },
    /// A scene name that is not one of `tube_impact`, `membrane`, `packing`.
    #[error("unknown scene {0:?}: expected tube_impact, membrane, packing or all")]
    UnknownScene(String),
    /// Zero threads or zero timed steps.
    #[error("{what} must be at least 1")]
    Zero {
        /// `threads` or `steps`.
        what: &'static str,
    },
    /// The embedded tube impact scene file did not load.
    #[error("tube_impact: the scene file does not load: {0}")]
    Scene(#[from] SceneError),
    /// A builder rejected the scene's geometry.
    #[error("{scene}: cannot build the structure: {source}")]
    Build {
        /// Scene name.
        scene: &'static str,
        /// The builder's error.
        source: BuildError,
    },
    /// The model rejected a material, sphere, wall or boundary condition.
    #[error("{scene}: cannot build the model: {source}")]
    Model {
        /// Scene name.
        scene: &'static str,
        /// The model's error.
        source: ModelError,
    },
    /// A scene file that cannot be read, parsed or built.
    #[error("{}: {message}", path.display())]
    SceneFile {
        /// The file.
        path: std::path::PathBuf,
        /// What is wrong (the scene parser's message names the line).
        message: String,
    },
    /// The engine refused the model or failed during the run.
    #[error("{scene} (size {size}, {threads} threads): the simulation failed: {source}")]
    Simulation {
        /// Scene name (a built-in scene's, or a scene file's stem).
        scene: String,
        /// Scene size.
        size: usize,
        /// Worker threads.
        threads: usize,
        /// The engine's error.
        source: SimulationError,
    },
    /// The rayon thread pool could not be started.
    #[error("cannot start a pool of {threads} worker threads: {message}")]
    ThreadPool {
        /// Threads asked for.
        threads: usize,
        /// rayon's message.
        message: String,
    },
}
