//! `Scene.explain`: the ray tree (or paths) of one pixel as plain Python data.
//!
//! The request is resolved by the scene crate's request layer, as for a render
//! and for `lamplight explain`; the tree is the core's JSON
//! ([`lamplight_core::explain::PixelExplanation::to_json`]), handed to Python's
//! `json.loads`, so the dicts and lists are those the command line's `--json`
//! prints and `json.dumps` writes them back.

use std::path::PathBuf;

use lamplight_scene::request::{limits, Naming, Request};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::convert::{setting, whole};
use crate::scene::Scene;

/// What `Scene.explain` is asked.
pub struct ExplainArgs<'py> {
    /// Pixel column.
    pub x: Bound<'py, PyAny>,
    /// Pixel row.
    pub y: Bound<'py, PyAny>,
    /// The one sample, or every one.
    pub sample: Option<Bound<'py, PyAny>>,
    /// The render's settings, as `render` takes them.
    pub width: Option<Bound<'py, PyAny>>,
    /// Image height.
    pub height: Option<Bound<'py, PyAny>>,
    /// Samples per pixel.
    pub spp: Option<Bound<'py, PyAny>>,
    /// Integrator name.
    pub integrator: Option<String>,
    /// Seed.
    pub seed: Option<Bound<'py, PyAny>>,
    /// Depth limit.
    pub max_depth: Option<Bound<'py, PyAny>>,
    /// Largest channel a sample keeps.
    pub clamp: Option<f64>,
    /// Pixel filter.
    pub filter: Option<String>,
    /// Environment map.
    pub environment: Option<PathBuf>,
    /// Adaptive anti-aliasing: `True`, `False` or a threshold.
    pub antialias: Option<Bound<'py, PyAny>>,
    /// The path tracer's noise threshold.
    pub noise_threshold: Option<f64>,
    /// Samples before the noise threshold stops a pixel.
    pub min_spp: Option<Bound<'py, PyAny>>,
}

/// Explains the pixel: a dict (see `lamplight.Scene.explain` in the stubs).
pub fn explain(py: Python<'_>, scene: &Scene, a: ExplainArgs<'_>) -> PyResult<PyObject> {
    let coordinate = |name: &str, v: &Bound<'_, PyAny>| -> PyResult<u32> {
        whole::<u32>(name, Some(v), 0, u32::MAX.into(), "")?
            .ok_or_else(|| pyo3::exceptions::PyTypeError::new_err(format!("{name} must be an int, got NoneType")))
    };
    let (x, y) = (coordinate("x", &a.x)?, coordinate("y", &a.y)?);
    let sample = whole::<u32>("sample", a.sample.as_ref(), 0, u32::MAX.into(), "")?;
    let request = Request {
        width: whole("width", a.width.as_ref(), 1, u32::MAX.into(), "")?,
        height: whole("height", a.height.as_ref(), 1, u32::MAX.into(), "")?,
        spp: setting(&limits::SPP, a.spp.as_ref())?,
        antialias: crate::render::antialias_arg(a.antialias.as_ref())?,
        noise_threshold: a.noise_threshold,
        min_spp: whole("min_spp", a.min_spp.as_ref(), 1, limits::MAX_SPP.into(), "")?,
        max_depth: setting(&limits::DEPTH, a.max_depth.as_ref())?,
        seed: whole("seed", a.seed.as_ref(), 0, u64::MAX.into(), "")?,
        integrator: a.integrator,
        clamp: a.clamp,
        filter: a.filter,
        environment: a.environment,
        ..Request::default()
    };
    let job = request.resolve(scene.settings(), Naming::Keywords).map_err(|e| PyValueError::new_err(e.0))?;
    let core = scene.core_for(py, &job)?;
    let text = py.allow_threads(|| {
        lamplight_scene::explain::explain(&core, &job, (x, y), sample, Naming::Keywords).map(|e| e.to_json().to_string())
    });
    let text = text.map_err(|e| PyValueError::new_err(e.0))?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}
