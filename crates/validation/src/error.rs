//! Why a validation case could not run (a failed check is not an error: see
//! [`crate::CaseReport::passed`]).

use std::path::PathBuf;

/// A case could not be run or its report not be written; each names the place and the cause.
#[derive(Debug, thiserror::Error)]
pub enum ValidationError {
    /// The simulation could not be built or stepped.
    #[error("simulation: {0}")]
    Simulation(#[from] flexdem_integrate::SimulationError),
    /// The model could not be changed (bad particle, material, blocked DOF, ...).
    #[error("model: {0}")]
    Model(#[from] flexdem_elements::ModelError),
    /// A structure could not be built.
    #[error("structure: {0}")]
    Build(#[from] flexdem_elements::BuildError),
    /// A material is invalid.
    #[error("material: {0}")]
    Material(#[from] flexdem_contact::MaterialError),
    /// A scene file could not be read.
    #[error("scene: {0}")]
    Scene(#[from] flexdem_scene::SceneError),
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A plot could not be drawn.
    #[error("cannot draw the plot {path}: {message}")]
    Plot {
        /// The PNG file.
        path: PathBuf,
        /// The cause.
        message: String,
    },
    /// A data file (reference data of YADE, ...) is missing a value or malformed.
    #[error("data file {path}: {message}")]
    Data {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A case did not reach the state it measures (no contact, not at rest, ...).
    #[error("case {case}: {message}")]
    Case {
        /// The case's id.
        case: String,
        /// What went wrong.
        message: String,
    },
}
