//! Flat Rust vectors to numpy arrays (the vector moves into the array: no copy, no loop in
//! Python).

use numpy::{Element, PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `values` as a 1-D array.
pub(crate) fn column<'py, T: Element>(py: Python<'py>, values: Vec<T>) -> Bound<'py, PyAny> {
    PyArray1::from_vec(py, values).into_any()
}

/// `flat` (`width` values per row) as an n×`width` array.
pub(crate) fn rows<'py, T: Element>(
    py: Python<'py>,
    flat: Vec<T>,
    width: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let n = flat.len() / width;
    Ok(PyArray1::from_vec(py, flat).reshape([n, width])?.into_any())
}

/// A dict of named arrays.
pub(crate) fn dict<'py>(
    py: Python<'py>,
    items: Vec<(&str, Bound<'py, PyAny>)>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in items {
        d.set_item(k, v)?;
    }
    Ok(d)
}
