//! What one benchmark runs: a built-in scene at a size, or a scene file (the twins of other
//! codes' inputs under `bench/`, or any user scene).

use crate::{BenchError, SceneKind};
use flexdem_geom::Real;
use flexdem_integrate::Simulation;
use std::path::PathBuf;

/// Warm-up steps of a scene file when none are asked for.
pub const FILE_WARMUP_STEPS: u64 = 20;

/// A benchmark case.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Case {
    /// A built-in scene at a size (see [`SceneKind::size_meaning`]).
    Scene(SceneKind, usize),
    /// A scene file (TOML, `flexdem run`'s format), run as it is: its settings, its time step.
    File(PathBuf),
}

impl Case {
    /// The name in tables: the scene's, or the file's stem.
    pub fn name(&self) -> String {
        match self {
            Case::Scene(kind, _) => kind.name().to_string(),
            Case::File(path) => path
                .file_stem()
                .map_or_else(|| path.display().to_string(), |s| s.to_string_lossy().into_owned()),
        }
    }

    /// The size parameter: the scene's, or 0 for a file (its counts are in the element
    /// columns).
    pub fn size(&self) -> usize {
        match self {
            Case::Scene(_, size) => *size,
            Case::File(_) => 0,
        }
    }

    /// Builds the simulation: the scene's model and settings, and for a file its loads,
    /// pressures and wall controls as `flexdem run` sets them.
    pub fn simulation(&self, threads: usize) -> Result<Simulation, BenchError> {
        match self {
            Case::Scene(kind, size) => {
                let (model, settings) = kind.build(*size)?;
                Simulation::new(model, settings).map_err(|source| BenchError::Simulation {
                    scene: self.name(),
                    size: *size,
                    threads,
                    source,
                })
            }
            Case::File(path) => {
                let failed =
                    |message: String| BenchError::SceneFile { path: path.clone(), message };
                let text = std::fs::read_to_string(path).map_err(|e| failed(e.to_string()))?;
                let scene =
                    flexdem_scene::parse_scene(&text, path).map_err(|e| failed(e.to_string()))?;
                let (sim, _) =
                    flexdem_run::build_simulation(scene).map_err(|e| failed(e.to_string()))?;
                Ok(sim)
            }
        }
    }

    /// Untimed steps before timing.
    pub fn warmup_steps(&self) -> u64 {
        match self {
            Case::Scene(kind, _) => kind.warmup_steps(),
            Case::File(_) => FILE_WARMUP_STEPS,
        }
    }

    /// Timed steps when none are asked for (None: adaptive).
    pub fn fixed_steps(&self) -> Option<u64> {
        match self {
            Case::Scene(kind, _) => kind.fixed_steps(),
            Case::File(_) => None,
        }
    }

    /// A named final value to compare with other codes (built-in scenes only).
    pub fn probe(&self, sim: &Simulation) -> Option<(&'static str, Real)> {
        match self {
            Case::Scene(kind, _) => kind.probe(sim),
            Case::File(_) => None,
        }
    }
}
