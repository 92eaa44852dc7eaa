//! Loads given from Python between the stages of a run: dicts with the keys of a scene
//! file's `[[loads]]` tables, written as TOML and read by the scene reader
//! ([`flexdem_scene::parse_loads`]) with the same checks and messages; and the simulation's
//! loads back as dicts of the same keys.

use crate::arrays::column;
use crate::convert::dict_to_toml;
use crate::errors::SceneError;
use flexdem_integrate::{Load, Ramp, Simulation};
use flexdem_scene::{parse_loads, SceneNames};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::Path;

/// The name messages give the text of a script's loads.
const SOURCE: &str = "<loads>";

/// `loads` (an iterable of dicts, each a `[[loads]]` table) as the TOML text of a scene's
/// `[[loads]]` tables (`flexdem.to_toml({"loads": [...]})`). This runs the script's code (a
/// generator, a mapping's methods), so it is called before the simulation is locked: code
/// that reads the simulation, as `(... sim.masses[i] ...) for i in top` does, would else wait
/// for its own lock for ever.
pub(crate) fn to_text(loads: &Bound<'_, PyAny>) -> PyResult<String> {
    let py = loads.py();
    let list = PyList::empty(py);
    for load in loads.try_iter()? {
        list.append(load?)?;
    }
    let file = PyDict::new(py);
    file.set_item("loads", list)?;
    dict_to_toml(file.as_any())
}

/// The loads of [`to_text`]'s `text` as engine loads over the simulation's current model;
/// errors as [`SceneError`] with the scene reader's message, located in that text.
pub(crate) fn parse(text: &str, sim: &Simulation, names: &SceneNames) -> PyResult<Vec<Load>> {
    parse_loads(text, Path::new(SOURCE), sim.model(), names)
        .map_err(|e| SceneError::new_err(e.to_string()))
}

/// The engine's loads as dicts with the keys of a `[[loads]]` table, which `set_loads`
/// takes back: `select = {"ids": array}`, `force` and `moment` (on each particle, arrays of
/// 3), and `ramp = {"start", "duration"}` for a ramped load.
pub(crate) fn to_python<'py>(py: Python<'py>, loads: &[Load]) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for load in loads {
        let d = PyDict::new(py);
        let select = PyDict::new(py);
        let ids: Vec<i64> = load.particles.iter().map(|&i| i64::from(i)).collect();
        select.set_item("ids", column(py, ids))?;
        d.set_item("select", select)?;
        let (f, m) = (load.force, load.torque);
        d.set_item("force", column(py, vec![f.x, f.y, f.z]))?;
        d.set_item("moment", column(py, vec![m.x, m.y, m.z]))?;
        if let Ramp::Linear { start, duration } = load.ramp {
            let ramp = PyDict::new(py);
            ramp.set_item("start", start)?;
            ramp.set_item("duration", duration)?;
            d.set_item("ramp", ramp)?;
        }
        list.append(d)?;
    }
    Ok(list)
}
