//! The module's exceptions and how the run driver's errors become them.

use flexdem_run::RunError;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    flexdem,
    SceneError,
    PyValueError,
    "Bad input: a scene (file, TOML text or dict), a checkpoint or an argument that cannot be \
     simulated. The message is the command line's, with the file, line, column and key."
);

pyo3::create_exception!(
    flexdem,
    SimulationError,
    PyRuntimeError,
    "A run that went wrong: an unstable step, energy created beyond the tolerance, output or \
     checkpoint files that cannot be written."
);

/// `e` as a Python exception: [`SceneError`] when the input is at fault (the command line's
/// exit code 2), [`SimulationError`] otherwise; the message is what the command line prints
/// after `error: `.
pub(crate) fn run_error(e: RunError) -> PyErr {
    if e.is_bad_input() {
        SceneError::new_err(e.to_string())
    } else {
        SimulationError::new_err(e.to_string())
    }
}
