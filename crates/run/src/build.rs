//! From a scene to a simulation: the model and settings to the engine, the loads and
//! pressures added and the wall controls set, the run length checked at the time step the
//! engine chose; and the worker threads.

use crate::error::RunError;
use flexdem_integrate::Simulation;
use flexdem_output::OutputSettings;
use flexdem_scene::{check_step_count, RunLength, Scene};
use std::path::PathBuf;

/// The parts of a [`Scene`] that the simulation does not take.
#[derive(Clone, Debug)]
pub struct SceneRest {
    /// How long to run.
    pub run: RunLength,
    /// Worker threads asked for by the scene.
    pub threads: Option<usize>,
    /// What to write.
    pub output: OutputSettings,
    /// The scene file.
    pub source: PathBuf,
}

/// The simulation of `scene` with its loads, pressures and wall controls, and the rest of the
/// scene. Errors name the scene file; they are all bad input.
pub fn build_simulation(scene: Scene) -> Result<(Simulation, SceneRest), RunError> {
    let source = scene.source.clone();
    let refused = |source_error| RunError::Simulation {
        scene: source.clone(),
        source: Box::new(source_error),
    };
    let mut sim = Simulation::new(scene.model, scene.settings).map_err(refused)?;
    for load in scene.loads {
        sim.add_load(load).map_err(refused)?;
    }
    for pressure in scene.pressures {
        sim.add_pressure(pressure).map_err(refused)?;
    }
    for (w, control) in scene.wall_controls.into_iter().enumerate() {
        sim.set_wall_control(w as u32, control).map_err(refused)?;
    }
    // with dt = "auto" the number of steps of a duration is known only now
    check_step_count(scene.run, sim.dt())
        .map_err(|message| RunError::RunLength { scene: source.clone(), message })?;
    let rest = SceneRest {
        run: scene.run,
        threads: scene.threads,
        output: scene.output,
        source: scene.source,
    };
    Ok((sim, rest))
}

/// Sets the number of rayon worker threads of this process (None: rayon's default, one per
/// core) and returns the number in use. Call it once, before building the simulation (which
/// may already use the pool); a second call with a number fails.
pub fn configure_threads(threads: Option<usize>) -> Result<usize, RunError> {
    if let Some(n) = threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
            .map_err(|e| RunError::Threads { threads: n, message: e.to_string() })?;
    }
    Ok(rayon::current_num_threads())
}
