//! The worker threads of the process (rayon's global pool): set once, before the first
//! simulation, like the command line's `--threads`.

use crate::errors::SceneError;
use flexdem_scene::MAX_THREADS;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use std::sync::Mutex;

/// The thread count this module set up, if it did.
static CONFIGURED: Mutex<Option<usize>> = Mutex::new(None);

/// Sets the pool to `n` threads, or checks that it has them already. Fails when the pool
/// runs with another count (set before, or started with the default by a simulation).
pub(crate) fn set(n: usize) -> PyResult<usize> {
    if n == 0 || n > MAX_THREADS {
        return Err(SceneError::new_err(format!(
            "threads = {n}: give a number from 1 to {MAX_THREADS}"
        )));
    }
    let mut configured = CONFIGURED.lock().unwrap_or_else(|p| p.into_inner());
    match *configured {
        Some(m) if m == n => Ok(n),
        Some(m) => Err(PyRuntimeError::new_err(format!(
            "the worker threads are already set to {m}: set them once, before the first \
             simulation"
        ))),
        None => {
            let count = flexdem_run::configure_threads(Some(n)).map_err(|e| {
                PyRuntimeError::new_err(format!(
                    "{e} (the pool has already started: call flexdem.set_threads before the \
                     first simulation)"
                ))
            })?;
            *configured = Some(count);
            Ok(count)
        }
    }
}

/// For a simulation about to be built: the `threads` argument must be honoured
/// ([`set`]); a scene's `threads` key is honoured when the pool is not set up yet, and
/// otherwise ignored with a Python warning.
pub(crate) fn prepare(
    py: Python<'_>,
    argument: Option<usize>,
    scene: Option<usize>,
) -> PyResult<()> {
    if let Some(n) = argument {
        set(n)?;
        return Ok(());
    }
    let Some(n) = scene else { return Ok(()) };
    let configured = *CONFIGURED.lock().unwrap_or_else(|p| p.into_inner());
    let result = match configured {
        Some(m) if m == n => Ok(n),
        Some(_) => Err(()),
        None => set(n).map_err(|_| ()),
    };
    if result.is_err() {
        let message = std::ffi::CString::new(format!(
            "the scene asks for {n} worker threads; the pool already runs with {}",
            rayon::current_num_threads()
        ))
        .unwrap_or_default();
        PyErr::warn(py, &py.get_type::<pyo3::exceptions::PyRuntimeWarning>(), &message, 1)?;
    }
    Ok(())
}
