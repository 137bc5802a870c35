//! `Scene.explain`: the ray tree (or paths) of one pixel as plain Python data.
//!
//! The request is resolved by the scene crate's request layer, as for a render
//! and for `lamplight explain`; the tree is the core's JSON
//! ([`lamplight_core::explain::PixelExplanation::to_json`]), handed to Python's
//! `json.loads`, so the dicts and lists are those the command line's `--json`
//! prints and `json.dumps` writes them back.

use lamplight_scene::request::Naming;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::whole;
use crate::scene::Scene;

/// Explains pixel `(x, y)` (every sample, or only `sample`) of the render that
/// `settings` (the keywords of [`crate::settings::KEYWORDS`] that explanations
/// take) ask for: a dict (see `lamplight.Scene.explain` in the stubs).
pub fn explain(
    py: Python<'_>,
    scene: &Scene,
    (x, y): (Bound<'_, PyAny>, Bound<'_, PyAny>),
    sample: Option<Bound<'_, PyAny>>,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyObject> {
    let coordinate = |name: &str, v: &Bound<'_, PyAny>| -> PyResult<u32> {
        whole::<u32>(name, Some(v), 0, u32::MAX.into(), "")?
            .ok_or_else(|| pyo3::exceptions::PyTypeError::new_err(format!("{name} must be an int, got NoneType")))
    };
    let (x, y) = (coordinate("x", &x)?, coordinate("y", &y)?);
    let sample = whole::<u32>("sample", sample.as_ref(), 0, u32::MAX.into(), "")?;
    let request = crate::settings::request(settings, "explain", true)?;
    let job = request.resolve(scene.settings(), Naming::Keywords).map_err(|e| PyValueError::new_err(e.0))?;
    let core = scene.core_for(py, &job, &request)?;
    let text = py.allow_threads(|| {
        lamplight_scene::explain::explain(&core, &job, (x, y), sample, Naming::Keywords).map(|e| e.to_json().to_string())
    });
    let text = text.map_err(|e| PyValueError::new_err(e.0))?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}
