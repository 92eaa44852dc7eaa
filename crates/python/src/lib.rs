//! The Python module of flexdem, `import flexdem`: a thin binding over the run driver
//! ([`flexdem_run`]) and the scene reader ([`flexdem_scene`]), built with maturin
//! (`pip install ./crates/python`).
//!
//! ```python
//! import flexdem
//! sim = flexdem.Simulation.from_scene("examples/tube_impact_solid.toml")
//! sim.run(steps=1000, callback=lambda s: print(s.time, s.energy()["balance"]), every=100)
//! print(sim.positions.shape, sim.contacts()["normal_force"].max())
//! ```
//!
//! What Python sees: `Simulation` ([`simulation`]), the exceptions `SceneError` (a
//! `ValueError`: bad input, with the command line's message) and `SimulationError` (a
//! `RuntimeError`: a run that went wrong), `set_threads`, `threads`, `to_toml` and
//! `scene_dict`. Every read of the engine's state goes through the `access` module; loads
//! from Python are read by the scene reader (`loads`), the tracked series recorded as a run
//! goes (`series`).

mod access;
mod arrays;
mod convert;
mod errors;
mod loads;
mod series;
pub mod simulation;
mod threads;

pub use errors::{SceneError, SimulationError};
use pyo3::prelude::*;

/// Sets the number of worker threads of the process (like the command line's `--threads`):
/// once, before the first simulation is built. Returns the number in use.
#[pyfunction]
fn set_threads(n: usize) -> PyResult<usize> {
    threads::set(n)
}

/// The number of worker threads in use (the machine's cores unless set).
#[pyfunction(name = "threads")]
fn thread_count() -> usize {
    rayon::current_num_threads()
}

/// A scene dict written as the TOML text `Simulation.from_dict` reads (where the line
/// numbers of its errors point).
#[pyfunction]
fn to_toml(scene: &Bound<'_, PyAny>) -> PyResult<String> {
    convert::dict_to_toml(scene)
}

/// The scene file at `path` as a dict with the keys of the file, to change and give to
/// `Simulation.from_dict(scene, base_dir=path.parent)` (relative paths in it start from the
/// file's folder). Raises `flexdem.SceneError` when the file cannot be read or is not TOML.
#[pyfunction]
fn scene_dict(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Bound<'_, PyAny>> {
    convert::read_toml_dict(py, &path)
}

/// The module `flexdem`.
#[pymodule]
#[pyo3(name = "flexdem")]
fn flexdem_python(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // before any code compiled for this CPU's extensions runs (see `flexdem_run::cpu`)
    let missing = flexdem_run::cpu::unsupported_features();
    if let Some(message) = flexdem_run::cpu::unsupported_message(&missing) {
        return Err(pyo3::exceptions::PyImportError::new_err(message));
    }
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<simulation::PySimulation>()?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("SimulationError", py.get_type::<SimulationError>())?;
    m.add_function(wrap_pyfunction!(set_threads, m)?)?;
    m.add_function(wrap_pyfunction!(thread_count, m)?)?;
    m.add_function(wrap_pyfunction!(to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(scene_dict, m)?)?;
    Ok(())
}
