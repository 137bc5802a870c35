//! `lamplight._lamplight`: the Python extension module of lamplight.
//!
//! Bindings only: Python values are converted to the scene crate's types
//! ([`convert`]), scenes are built by the same builder as scene files
//! ([`scene`]), and renders, ray queries and image files go to the core and
//! scene crates ([`render`], [`intersect`], [`image`]). Everything a user
//! calls is wrapped by the pure-Python package `lamplight` (`python/lamplight`).
#![deny(missing_docs)]

use pyo3::prelude::*;

pub mod convert;
pub mod denoise;
pub mod explain;
pub mod frames;
pub mod image;
pub mod intersect;
pub mod kinds;
pub mod render;
pub mod scene;
pub mod settings;

pyo3::create_exception!(_lamplight, SceneError, pyo3::exceptions::PyValueError, "A scene that cannot be read or built.");

/// The module: `Scene`, `render_array`, the image helpers and `SceneError`.
#[pymodule]
fn _lamplight(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<scene::Scene>()?;
    m.add_function(wrap_pyfunction!(scene::builtin_names, m)?)?;
    m.add_function(wrap_pyfunction!(scene::scene_from_state, m)?)?;
    m.add_function(wrap_pyfunction!(render::render_array, m)?)?;
    m.add_function(wrap_pyfunction!(kinds::kinds, m)?)?;
    m.add_function(wrap_pyfunction!(render::resolve_settings, m)?)?;
    m.add_function(wrap_pyfunction!(settings::render_keywords, m)?)?;
    m.add_function(wrap_pyfunction!(settings::build_keywords, m)?)?;
    m.add_function(wrap_pyfunction!(image::write_image, m)?)?;
    m.add_function(wrap_pyfunction!(image::encode_png, m)?)?;
    m.add_function(wrap_pyfunction!(image::read_exr, m)?)?;
    m.add_function(wrap_pyfunction!(denoise::denoise_array, m)?)?;
    m.add_function(wrap_pyfunction!(frames::frame_range, m)?)?;
    m.add_function(wrap_pyfunction!(frames::frame_paths, m)?)?;
    m.add_function(wrap_pyfunction!(frames::make_video, m)?)?;
    m.add_function(wrap_pyfunction!(frames::check_video, m)?)?;
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
