//! Scene files: a TOML description of a simulation (settings, materials, structures from the
//! builders or from mesh files, free spheres, walls, boundary conditions, loads and outputs),
//! read into a [`Scene`] ready for [`flexdem_integrate::Simulation::new`]. The keys, their
//! units and defaults are in `docs/scene-reference.md`.
//!
//! Every error names the file, the line and column, the key and what is expected; unknown
//! keys are errors, with the nearest known key suggested. Relative paths (meshes, the output
//! folder) are relative to the folder of the scene file.

mod build;
mod check;
mod error;
pub mod memory;
mod output;
pub mod packing;
pub mod placement;
mod schema;
mod selection;
mod spheres;
mod structures;

pub use error::SceneError;

use crate::output::OutputSettings;
use error::Ctx;
use flexdem_elements::Model;
use flexdem_geom::Real;
use flexdem_integrate::{Load, Settings};
use std::path::{Path, PathBuf};

/// Largest number of worker threads a scene (`simulation.threads`) or the command line
/// (`--threads`) may ask for.
pub const MAX_THREADS: usize = 4096;

/// Largest number of steps a run may last (`steps`, or `duration` over the time step): 10¹²
/// steps take weeks even at a million steps per second, so more is a typo (`dt = 1e-300`).
pub const MAX_STEPS: u64 = 1_000_000_000_000;

/// `Err(message)` when `run` at time step `dt` lasts more than [`MAX_STEPS`] steps.
pub fn check_step_count(run: RunLength, dt: Real) -> Result<(), String> {
    let steps = match run {
        RunLength::Steps(n) => n as Real,
        RunLength::Duration(d) => d / dt,
    };
    if steps <= MAX_STEPS as Real {
        return Ok(());
    }
    Err(match run {
        RunLength::Steps(n) => format!("is {n} steps: expected at most {MAX_STEPS}"),
        RunLength::Duration(d) => format!(
            "{d} s at dt = {dt:e} s is {steps:.3e} steps: expected at most {:e} \
             (a shorter duration or a larger time step)",
            MAX_STEPS as Real
        ),
    })
}

/// How long a run lasts.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum RunLength {
    /// A number of steps.
    Steps(u64),
    /// A simulated time (s).
    Duration(Real),
}

/// A scene read from a file: everything needed to create and run a simulation.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Materials, particles, structures, walls, with blocked DOFs and imposed velocities.
    pub model: Model,
    /// Time step, gravity, damping, link kinematics.
    pub settings: Settings,
    /// Imposed forces and moments, to add with `Simulation::add_load`.
    pub loads: Vec<Load>,
    /// How long to run.
    pub run: RunLength,
    /// Number of worker threads (None: the machine's default).
    pub threads: Option<usize>,
    /// What to write.
    pub output: OutputSettings,
    /// The scene file.
    pub source: PathBuf,
}

/// Reads and builds the scene file at `path`. Relative paths inside the file are relative to
/// its folder.
pub fn load_scene(path: &Path) -> Result<Scene, SceneError> {
    let bytes =
        std::fs::read(path).map_err(|source| SceneError::Io { path: path.to_owned(), source })?;
    let text = scene_text(bytes, path)?;
    parse_scene(&text, path)
}

/// The text of a scene file, or an error at the first byte that is not UTF-8 (line, column
/// and byte offset).
fn scene_text(bytes: Vec<u8>, path: &Path) -> Result<String, SceneError> {
    String::from_utf8(bytes).map_err(|e| {
        let valid = e.utf8_error().valid_up_to();
        let bytes = e.as_bytes();
        let before = std::str::from_utf8(&bytes[..valid]).unwrap_or_default();
        let file = path.display().to_string();
        let ctx = Ctx { file: &file, text: before };
        let bad: Vec<String> =
            bytes[valid..].iter().take(4).map(|b| format!("0x{b:02x}")).collect();
        ctx.at(
            valid..valid,
            "",
            format!(
                "invalid UTF-8 at byte {valid} ({}): a scene file must be UTF-8 text (save it \
                 as UTF-8)",
                bad.join(" ")
            ),
        )
    })
}

/// Builds a scene from its text. `source` names the file in messages and gives the folder
/// that relative paths (meshes, output) start from; it is not read.
pub fn parse_scene(text: &str, source: &Path) -> Result<Scene, SceneError> {
    let file = source.display().to_string();
    let ctx = Ctx { file: &file, text };
    let parsed: schema::SceneFile = toml::from_str(text).map_err(|e| ctx.toml_error(&e))?;
    build::build(parsed, ctx, source)
}
