//! Python values to scene descriptions.
//!
//! A scene dict is first made plain ([`plain`]: numpy arrays and scalars become
//! lists and numbers, tuples become lists, and the result is a copy the caller
//! cannot change behind our back), then deserialized by serde straight into the
//! scene crate's description types, so a dict and a TOML file share one schema
//! and one builder. Errors name the key path, such as `objects[2].radius`.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};
use serde::de::DeserializeOwned;

use crate::SceneError;

/// Nesting depth beyond which a dict is rejected (scene files allow 64 levels of nodes,
/// each a dict in a list).
const MAX_NESTING: usize = 256;

/// A deep copy of `obj` with only dicts (string keys), lists, strings, numbers,
/// booleans and `None`: tuples become lists, objects with `tolist` (numpy arrays
/// and scalars) become what `tolist` returns.
pub fn plain(obj: &Bound<'_, PyAny>) -> PyResult<PyObject> {
    plain_at(obj, 0)
}

fn plain_at(obj: &Bound<'_, PyAny>, depth: usize) -> PyResult<PyObject> {
    let py = obj.py();
    if depth > MAX_NESTING {
        return Err(SceneError::new_err(format!("scene dict is nested more than {MAX_NESTING} levels deep")));
    }
    if let Ok(dict) = obj.downcast::<PyDict>() {
        let out = PyDict::new(py);
        for (k, v) in dict.iter() {
            if !k.is_instance_of::<PyString>() {
                return Err(PyTypeError::new_err(format!("scene dict keys must be strings, got {}", k.repr()?)));
            }
            out.set_item(k, plain_at(&v, depth + 1)?)?;
        }
        return Ok(out.into_any().unbind());
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let items = obj.try_iter()?.map(|item| plain_at(&item?, depth + 1)).collect::<PyResult<Vec<_>>>()?;
        return Ok(PyList::new(py, items)?.into_any().unbind());
    }
    if !obj.is_instance_of::<PyString>() && obj.hasattr("tolist")? {
        let listed = obj.call_method0("tolist")?;
        return plain_at(&listed, depth + 1);
    }
    Ok(obj.clone().unbind())
}

/// Deserializes the plain Python value `obj` into `T`; an error names the key path.
pub fn from_python<T: DeserializeOwned>(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<T> {
    let mut de = pythonize::Depythonizer::from_object(obj);
    serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let path = e.path().to_string();
        let message = e
            .inner()
            .to_string()
            .replace("invalid type: floating point", "invalid type: number")
            .replace("expected f64", "expected a number");
        if path == "." || path.is_empty() {
            SceneError::new_err(format!("{what}: {message}"))
        } else {
            SceneError::new_err(format!("{what}: {path}: {message}"))
        }
    })
}
