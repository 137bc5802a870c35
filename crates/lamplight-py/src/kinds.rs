//! `kinds()`: the registry of kinds as plain data, so that the Python package
//! makes a constructor for every node kind without a list of its own.

use lamplight_core::params::Param;
use lamplight_scene::registry;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

fn entry<'py>(py: Python<'py>, role: &str, name: &str, summary: &str, params: &[Param]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("role", role)?;
    d.set_item("name", name)?;
    d.set_item("summary", summary)?;
    let list = PyList::empty(py);
    for p in params {
        let row = PyDict::new(py);
        row.set_item("name", p.name)?;
        row.set_item("type", p.ty.to_string())?;
        row.set_item("default", if p.default.is_empty() { None } else { Some(p.default) })?;
        row.set_item("unit", p.unit)?;
        row.set_item("doc", p.doc)?;
        list.append(row)?;
    }
    d.set_item("params", list)?;
    Ok(d)
}

/// Every registered kind: dicts with `role` (`"shape"`, `"light"`, `"node"`,
/// `"material"`, `"texture"`, `"camera"`), `name`, `summary` and `params` (each
/// `name`, `type`, `default` (`None` when required), `unit`, `doc`).
#[pyfunction]
pub fn kinds(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let out = PyList::empty(py);
    for k in registry::SHAPES {
        let params: Vec<Param> = k.params.iter().chain(registry::SHAPE_COMMON).copied().collect();
        out.append(entry(py, "shape", k.name, k.summary, &params)?)?;
    }
    for k in registry::LIGHTS {
        out.append(entry(py, "light", k.name, k.summary, k.params)?)?;
    }
    for s in registry::STRUCTURAL {
        out.append(entry(py, "node", s.name, s.summary, s.params)?)?;
    }
    for k in registry::MATERIALS {
        out.append(entry(py, "material", k.name, k.summary, k.params)?)?;
    }
    for k in registry::TEXTURES {
        out.append(entry(py, "texture", k.name, k.summary, k.params)?)?;
    }
    for k in registry::CAMERAS {
        out.append(entry(py, "camera", k.name, k.summary, k.params)?)?;
    }
    Ok(out)
}
