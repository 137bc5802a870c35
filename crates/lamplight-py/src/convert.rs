//! Python values to scene descriptions.
//!
//! A scene dict is first made plain ([`plain`]: numpy arrays and scalars become
//! lists and numbers, tuples become lists, and the result is a copy the caller
//! cannot change behind our back), then converted to the located [`Table`] that
//! the TOML reader also produces ([`table`]), so a dict and a TOML file share one
//! description, one registry and one builder, and their errors the same text.
//! Errors name the key path, such as `objects[2].radius`.

use lamplight_core::params::{Entry, Item, Loc, Table, Value};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use lamplight_scene::request::{limits, Naming};

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

/// The plain dict `obj` as a located [`Table`]: every key and value carries its
/// key path (`objects[2].radius`), which errors print in place of a file's
/// line and column. `path` is the dict's own path (empty for the top level).
pub fn table(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<Table> {
    match value(obj, path)? {
        Value::Table(t) => Ok(t),
        other => Err(PyTypeError::new_err(format!("expected a dict, got {}", other.describe()))),
    }
}

fn loc(path: &str) -> Loc {
    if path.is_empty() {
        Loc::Unknown
    } else {
        Loc::Path(path.to_string())
    }
}

fn value(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<Value> {
    if let Ok(dict) = obj.downcast::<PyDict>() {
        let mut entries = Vec::with_capacity(dict.len());
        for (k, v) in dict.iter() {
            let key: String = k.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "scene dict keys must be strings, got {}",
                    k.repr().map(|r| r.to_string()).unwrap_or_default()
                ))
            })?;
            let at = if path.is_empty() { key.clone() } else { format!("{path}.{key}") };
            entries.push(Entry { key_loc: loc(&at), item: Item { value: value(&v, &at)?, loc: loc(&at) }, key });
        }
        return Ok(Value::Table(Table { entries, loc: loc(path) }));
    }
    if let Ok(list) = obj.downcast::<PyList>() {
        let mut items = Vec::with_capacity(list.len());
        for (i, v) in list.iter().enumerate() {
            let at = format!("{path}[{i}]");
            items.push(Item { value: value(&v, &at)?, loc: loc(&at) });
        }
        return Ok(Value::Array(items));
    }
    if let Ok(b) = obj.downcast::<PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if obj.is_instance_of::<PyInt>() {
        return obj.extract::<i64>().map(Value::Integer).map_err(|_| {
            SceneError::new_err(format!(
                "scene dict: {path}: the integer {} does not fit in 64 bits",
                obj.repr().map(|r| r.to_string()).unwrap_or_default()
            ))
        });
    }
    if let Ok(f) = obj.downcast::<PyFloat>() {
        return Ok(Value::Number(f.value()));
    }
    if let Ok(s) = obj.downcast::<PyString>() {
        return Ok(Value::String(s.to_str()?.to_string()));
    }
    let type_name = obj.get_type().name().map(|n| n.to_string()).unwrap_or_default();
    Err(SceneError::new_err(format!("scene dict: {path}: expected a number, string, boolean, list or dict, got {type_name}")))
}

/// A whole-number keyword argument: a Python int of any size, checked here
/// against `T`'s range so that the error is a `ValueError` naming the argument
/// and its bound (`seed must be at most 18446744073709551615, got ...`) rather
/// than PyO3's bare `OverflowError`. `min` and `max` are the argument's real
/// limits as the messages quote them; `note` follows the bound. Settings with a
/// range of the request layer use [`setting`] instead, so that their message is
/// that layer's whatever the value.
pub fn whole<T: TryFrom<i128>>(name: &str, value: Option<&Bound<'_, PyAny>>, min: i128, max: i128, note: &str) -> PyResult<Option<T>> {
    whole_with(name, value, |shown, below| {
        if below {
            format!("{name} must be at least {min}{note}, got {shown}")
        } else {
            format!("{name} must be at most {max}{note}, got {shown}")
        }
    })
}

/// The setting of `range` (`spp`, `max_depth`, `threads`) as [`whole`] reads it,
/// passed on unchecked when it fits `T`: the request layer checks the range. A
/// value too large (or negative) for `T` gets the request layer's own message
/// ([`limits::Range::message`]), so that every value outside the range reads alike.
pub fn setting<T: TryFrom<i128>>(range: &limits::Range, value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<T>> {
    whole_with(range.key, value, |shown, below| range.message(shown, below, Naming::Keywords))
}

/// [`whole`] with the message for a value below `T`'s range (`true`) or above it.
fn whole_with<T: TryFrom<i128>>(
    name: &str,
    value: Option<&Bound<'_, PyAny>>,
    message: impl Fn(&str, bool) -> String,
) -> PyResult<Option<T>> {
    let Some(value) = value.filter(|v| !v.is_none()) else { return Ok(None) };
    if value.is_instance_of::<PyBool>() || !value.is_instance_of::<PyInt>() {
        return Err(PyTypeError::new_err(format!("{name} must be an int, got {}", value.get_type().name()?)));
    }
    let shown = || value.str().map(|s| s.to_string()).unwrap_or_default();
    // Beyond i128 the extraction fails: too large (or too small) either way.
    let v: Option<i128> = value.extract().ok();
    let negative = || value.lt(0).unwrap_or(false);
    match v.and_then(|v| T::try_from(v).ok()) {
        Some(t) => Ok(Some(t)),
        None => Err(PyValueError::new_err(message(&shown(), negative()))),
    }
}
