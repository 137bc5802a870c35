//! `lamplight.denoise`: Open Image Denoise on numpy arrays (the scene crate's
//! [`lamplight_scene::denoise`]), and where this Python keeps the library.

use std::path::PathBuf;

use lamplight_scene::denoise::{pyoidn_library_folder, Denoiser, Guides};
use lamplight_scene::request::{Defaults, Request};
use numpy::{PyArray3, PyReadonlyArray3};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use crate::image::to_image;
use crate::render::{threads_arg, to_array};

/// The library folder of the `pyoidn` package this Python would import, if it
/// has one: the denoiser is looked for there first. `find_spec` locates the
/// package without importing it.
pub fn pyoidn_folders(py: Python<'_>) -> Vec<PathBuf> {
    let found = || -> PyResult<Option<PathBuf>> {
        let spec = py.import("importlib.util")?.call_method1("find_spec", ("pyoidn",))?;
        if spec.is_none() {
            return Ok(None);
        }
        let locations = spec.getattr("submodule_search_locations")?;
        let first: Option<PathBuf> = locations.try_iter()?.next().transpose()?.map(|l| l.extract()).transpose()?;
        Ok(first.map(|p| pyoidn_library_folder(&p)))
    };
    found().ok().flatten().into_iter().collect()
}

/// Tells `request` where this Python's `pyoidn` keeps the library, when it
/// will denoise (asked, or the scene's `[render] denoise`).
pub fn add_library_hints(py: Python<'_>, request: &mut Request, defaults: &Defaults) {
    if request.denoise.unwrap_or(defaults.denoise) {
        request.denoise_library_hints = pyoidn_folders(py);
    }
}

/// `color`, a float32 `(H, W, 3)` array of linear radiance, denoised by Open
/// Image Denoise's HDR `RT` filter, guided by `albedo` and `normal` arrays of
/// the same shape when given (`image.layers["albedo"]`, `["normal"]`); with
/// `emitted` (`["emitted"]`), only `color - emitted` is filtered and `emitted`
/// added back ([`lamplight_scene::denoise`]). The library (device and filter)
/// is kept between calls. `ValueError` when the library is missing (the
/// message says how to get it) or the shapes differ. Releases the GIL.
#[pyfunction]
#[pyo3(signature = (color, albedo=None, normal=None, threads=None, emitted=None))]
pub fn denoise_array<'py>(
    py: Python<'py>,
    color: PyReadonlyArray3<'py, f32>,
    albedo: Option<PyReadonlyArray3<'py, f32>>,
    normal: Option<PyReadonlyArray3<'py, f32>>,
    threads: Option<Bound<'py, PyAny>>,
    emitted: Option<PyReadonlyArray3<'py, f32>>,
) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let threads = threads_arg(threads.as_ref())?;
    let denoiser = Denoiser::load(&pyoidn_folders(py)).map_err(|e| PyValueError::new_err(e.0))?;
    let color = to_image(&color)?;
    let albedo = albedo.as_ref().map(to_image).transpose()?;
    let normal = normal.as_ref().map(to_image).transpose()?;
    let emitted = emitted.as_ref().map(to_image).transpose()?;
    for (name, layer) in [("albedo", &albedo), ("normal", &normal), ("emitted", &emitted)] {
        if let Some(layer) = layer.as_ref().filter(|l| (l.width, l.height) != (color.width, color.height)) {
            let (w, h) = (color.width, color.height);
            return Err(PyValueError::new_err(format!("{name} is {}x{}, the image {w}x{h}", layer.width, layer.height)));
        }
    }
    let guides = Guides { albedo: albedo.as_ref(), normal: normal.as_ref(), emitted: emitted.as_ref() };
    let clean = py.allow_threads(|| denoiser.denoise(&color, guides, threads));
    let clean = clean.map_err(|e| PyRuntimeError::new_err(e.0))?;
    to_array(py, &clean)
}
