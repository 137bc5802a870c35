//! Images between numpy and files: float32 `(H, W, 3)` arrays of linear
//! radiance to PNG/PPM/EXR files (the scene crate's atomic writers), to PNG
//! bytes for Jupyter, and EXR files back to arrays.

use std::path::PathBuf;

use lamplight_core::film::tonemap::{self, ToneMap};
use lamplight_core::film::Image;
use lamplight_scene::exr_layers::ExtraLayer;
use lamplight_scene::image_io::{self, Format, Transfer};
use lamplight_scene::request::Layer;
use numpy::{PyArray1, PyArray3, PyArrayMethods, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

/// A core image from a float32 `(H, W, 3)` array (any strides).
pub(crate) fn to_image(array: &PyReadonlyArray3<'_, f32>) -> PyResult<Image> {
    let shape = array.shape();
    if shape[2] != 3 || shape[0] == 0 || shape[1] == 0 {
        return Err(PyValueError::new_err(format!("an image must have shape (H, W, 3) with H, W >= 1, got {shape:?}")));
    }
    let (height, width) = (u32::try_from(shape[0]), u32::try_from(shape[1]));
    let (Ok(height), Ok(width)) = (height, width) else {
        return Err(PyValueError::new_err(format!("image of shape {shape:?} is too large")));
    };
    let view = array.as_array();
    let pixels = view.outer_iter().flat_map(|row| row.outer_iter().map(|p| [p[0], p[1], p[2]]).collect::<Vec<_>>()).collect();
    Ok(Image { width, height, pixels })
}

fn transfer_of(name: &str) -> PyResult<Transfer> {
    name.parse().map_err(|_| PyValueError::new_err(format!("transfer must be \"srgb\" or \"linear\", got {name:?}")))
}

fn display(image: Image, exposure: f64, tonemap: &str) -> PyResult<Image> {
    let map: ToneMap =
        tonemap.parse().map_err(|_| PyValueError::new_err(format!("tonemap must be \"clamp\" or \"filmic\", got {tonemap:?}")))?;
    if !exposure.is_finite() {
        return Err(PyValueError::new_err("exposure must be a finite number"));
    }
    Ok(if exposure == 0.0 && map == ToneMap::Clamp { image } else { tonemap::apply(&image, exposure, map) })
}

/// Writes `array` to `path` by its extension (`.png`, `.ppm`: 8-bit after
/// `exposure` and `tonemap`, sRGB-encoded or, with `transfer="linear"`, the
/// values as they are; `.exr`: linear float, unchanged, with the extra
/// `layers` of a render, `{"variance": (H, W, 3), "samples": (H, W), "albedo": ...}`, beside
/// the image as `lamplight render --exr-layers` writes them), atomically.
#[pyfunction]
#[pyo3(signature = (path, array, exposure=0.0, tonemap="clamp", layers=None, transfer="srgb"))]
#[allow(clippy::too_many_arguments)]
pub fn write_image(
    py: Python<'_>,
    path: PathBuf,
    array: PyReadonlyArray3<'_, f32>,
    exposure: f64,
    tonemap: &str,
    layers: Option<Bound<'_, pyo3::types::PyDict>>,
    transfer: &str,
) -> PyResult<()> {
    let transfer = transfer_of(transfer)?;
    let format = Format::from_path(&path).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let mut image = to_image(&array)?;
    let mut extra = Vec::new();
    for (name, value) in layers.iter().flat_map(|d| d.iter()) {
        let name: String = name.extract()?;
        let layer = match name.parse::<Layer>().map_err(PyValueError::new_err)? {
            Layer::Samples => {
                let samples: numpy::PyReadonlyArray2<'_, f32> = value.extract()?;
                ExtraLayer::single("samples", samples.as_array().iter().copied().collect())
            }
            layer => layer.to_exr(&to_image(&value.extract::<PyReadonlyArray3<'_, f32>>()?)?),
        };
        if layer.channels.iter().any(|(_, v)| v.len() != image.pixels.len()) {
            return Err(PyValueError::new_err(format!("layer '{name}' does not have the image's {}x{} pixels", image.width, image.height)));
        }
        extra.push(layer);
    }
    if format != Format::Exr {
        if !extra.is_empty() {
            return Err(PyValueError::new_err(format!("{}: only .exr files hold extra layers", path.display())));
        }
        image = display(image, exposure, tonemap)?;
    }
    let written = py.allow_threads(|| {
        if extra.is_empty() {
            image_io::write_image_as(&path, &image, transfer)
        } else {
            lamplight_scene::exr_layers::write_exr_with_layers(&path, &image, &extra)
        }
    });
    written.map_err(|e| PyOSError::new_err(e.to_string()))
}

/// PNG file bytes of `array` (8-bit after `exposure` and `tonemap`, sRGB-encoded
/// or, with `transfer="linear"`, the values as they are).
#[pyfunction]
#[pyo3(signature = (array, exposure=0.0, tonemap="clamp", transfer="srgb"))]
pub fn encode_png<'py>(
    py: Python<'py>,
    array: PyReadonlyArray3<'_, f32>,
    exposure: f64,
    tonemap: &str,
    transfer: &str,
) -> PyResult<Bound<'py, PyBytes>> {
    let transfer = transfer_of(transfer)?;
    let image = display(to_image(&array)?, exposure, tonemap)?;
    let bytes = image_io::png_bytes(&image, transfer).map_err(|e| PyValueError::new_err(format!("cannot encode PNG: {e}")))?;
    Ok(PyBytes::new(py, &bytes))
}

/// Reads an OpenEXR file's R, G, B as a float32 array `(H, W, 3)`.
#[pyfunction]
pub fn read_exr<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let image = image_io::read_exr(&path).map_err(|e| PyOSError::new_err(e.to_string()))?;
    let (w, h) = (image.width as usize, image.height as usize);
    PyArray1::from_vec(py, image.pixels.into_iter().flatten().collect()).reshape([h, w, 3])
}
