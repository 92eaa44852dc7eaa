//! A Python dict (nested dicts, lists, tuples, str, int, float, bool, numpy arrays and
//! scalars, paths) to a TOML table, so that a script builds a scene with the keys of a scene
//! file and the scene reader checks it as it checks a file; and a scene file to such a dict
//! (a script's starting point, changed then read back).

use crate::errors::SceneError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use std::path::Path;

/// Nesting deeper than this is refused: a scene is a few levels deep, and a dict that
/// contains itself would otherwise recurse until the stack overflows.
const MAX_DEPTH: usize = 64;

/// `obj` (a dict) as a TOML table; errors name the key (`structures[0].radius`).
pub(crate) fn dict_to_table(obj: &Bound<'_, PyAny>) -> PyResult<toml::Table> {
    match to_value(obj, "", 0)? {
        toml::Value::Table(table) => Ok(table),
        _ => Err(SceneError::new_err(format!(
            "a scene is a dict of tables (`simulation`, `materials`, ...), not a {}",
            type_name(obj)
        ))),
    }
}

/// `obj` as the text of a TOML file.
pub(crate) fn dict_to_toml(obj: &Bound<'_, PyAny>) -> PyResult<String> {
    let table = dict_to_table(obj)?;
    toml::to_string(&table).map_err(|e| SceneError::new_err(format!("cannot write TOML: {e}")))
}

/// The Python type name of `obj`.
fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type().name().map(|n| n.to_string()).unwrap_or_else(|_| "?".to_string())
}

/// `path` then `key`, dotted.
fn child(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// `obj` (at `path` in the dict) as a TOML value.
fn to_value(obj: &Bound<'_, PyAny>, path: &str, depth: usize) -> PyResult<toml::Value> {
    let at = |message: String| {
        let key = if path.is_empty() { "the scene" } else { path };
        SceneError::new_err(format!("`{key}`: {message}"))
    };
    if depth > MAX_DEPTH {
        return Err(at(format!(
            "nested more than {MAX_DEPTH} levels deep (a dict or list that contains itself?)"
        )));
    }
    // bool before int: Python's bool is an int
    if let Ok(b) = obj.cast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if obj.cast::<PyInt>().is_ok() {
        let i: i64 = obj.extract().map_err(|_| at("integer out of the 64-bit range".into()))?;
        return Ok(toml::Value::Integer(i));
    }
    if let Ok(f) = obj.cast::<PyFloat>() {
        return Ok(toml::Value::Float(f.value()));
    }
    if let Ok(s) = obj.cast::<PyString>() {
        return Ok(toml::Value::String(s.extract::<String>()?));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in d.iter() {
            let key = match k.cast::<PyString>() {
                Ok(s) => s.extract::<String>()?,
                Err(_) => return Err(at(format!("keys must be strings, not {}", type_name(&k)))),
            };
            let value = to_value(&v, &child(path, &key), depth + 1)?;
            table.insert(key, value);
        }
        return Ok(toml::Value::Table(table));
    }
    if obj.cast::<PyList>().is_ok() || obj.cast::<PyTuple>().is_ok() {
        let mut items = Vec::new();
        for (i, item) in obj.try_iter()?.enumerate() {
            items.push(to_value(&item?, &format!("{path}[{i}]"), depth + 1)?);
        }
        return Ok(toml::Value::Array(items));
    }
    if obj.is_none() {
        return Err(at("None has no TOML value: leave the key out for its default".into()));
    }
    // numpy arrays and scalars: their Python values
    if obj.hasattr("tolist")? {
        return to_value(&obj.call_method0("tolist")?, path, depth + 1);
    }
    // paths (pathlib.Path, os.PathLike)
    if obj.hasattr("__fspath__")? {
        return to_value(&obj.call_method0("__fspath__")?, path, depth + 1);
    }
    Err(at(format!(
        "a {} has no TOML value (use str, int, float, bool, list or dict)",
        type_name(obj)
    )))
}

/// The TOML file at `path` as a dict of its keys (tables as dicts, arrays as lists); errors
/// (a file that cannot be read, bad TOML syntax) as [`SceneError`] naming the file.
pub(crate) fn read_toml_dict<'py>(py: Python<'py>, path: &Path) -> PyResult<Bound<'py, PyAny>> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        SceneError::new_err(format!("{}: cannot read the scene file: {e}", path.display()))
    })?;
    let table: toml::Table = toml::from_str(&text).map_err(|e| {
        SceneError::new_err(format!("{}: {}", path.display(), e.to_string().trim_end()))
    })?;
    to_python(py, &toml::Value::Table(table))
}

/// A TOML value as the Python value `to_value` turns back into it.
fn to_python<'py>(py: Python<'py>, value: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        toml::Value::String(s) => s.into_pyobject(py)?.into_any(),
        toml::Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        toml::Value::Float(f) => f.into_pyobject(py)?.into_any(),
        toml::Value::Boolean(b) => b.into_pyobject(py)?.to_owned().into_any(),
        // scene files have no dates: their text, for the scene reader to refuse
        toml::Value::Datetime(d) => d.to_string().into_pyobject(py)?.into_any(),
        toml::Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(to_python(py, item)?)?;
            }
            list.into_any()
        }
        toml::Value::Table(table) => {
            let d = PyDict::new(py);
            for (k, v) in table {
                d.set_item(k, to_python(py, v)?)?;
            }
            d.into_any()
        }
    })
}
