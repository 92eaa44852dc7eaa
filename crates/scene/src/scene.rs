//! [`Scene`]: what a scene file describes, ready for a simulation.

use crate::built::SceneNames;
use crate::run_length::RunLength;
use flexdem_elements::Model;
use flexdem_integrate::{Load, Pressure, Settings, WallControl};
use flexdem_output::OutputSettings;
use std::path::PathBuf;

/// Largest number of worker threads a scene (`simulation.threads`) or the command line
/// (`--threads`) may ask for.
pub const MAX_THREADS: usize = 4096;

/// A scene read from a file: everything needed to create and run a simulation.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Materials, particles, structures, walls, with blocked DOFs and imposed velocities.
    pub model: Model,
    /// Time step, gravity, damping, link kinematics.
    pub settings: Settings,
    /// Imposed forces and moments, to add with `Simulation::add_load`.
    pub loads: Vec<Load>,
    /// Pressures on PFacets, to add with `Simulation::add_pressure`.
    pub pressures: Vec<Pressure>,
    /// The structures and sphere groups by name, for selections after the build
    /// ([`crate::parse_loads`]).
    pub names: SceneNames,
    /// How each wall moves (one per wall of the model), to set with
    /// `Simulation::set_wall_control`.
    pub wall_controls: Vec<WallControl>,
    /// How long to run.
    pub run: RunLength,
    /// Number of worker threads (None: the machine's default).
    pub threads: Option<usize>,
    /// What to write.
    pub output: OutputSettings,
    /// The scene file.
    pub source: PathBuf,
}
