//! `render_array`: a render of a [`Scene`] as a float32 numpy array `(H, W, 3)`
//! of linear radiance, the numbers the command line writes to EXR. The request
//! (defaults, precedence, limits, environment map, extra layers) is resolved by
//! the scene crate's request layer, as for the command line.
//!
//! The render runs on its own thread with the GIL released. The calling thread
//! wakes every 100 ms to pass progress to a Python callback and to let Python
//! handle signals: on Ctrl-C (or any exception from the callback) it sets the
//! core's cancel flag, waits for the render to stop, and raises.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::Arc;
use std::time::Duration;

use lamplight_core::film::Image;
use lamplight_core::RenderControl;
use lamplight_scene::request::{self, limits, Layer, Naming};
use numpy::{PyArray1, PyArray3, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::setting;
use crate::scene::Scene;

/// How often the waiting thread looks at signals and progress.
const POLL: Duration = Duration::from_millis(100);

type Rendered = Result<request::Rendered, lamplight_core::Error>;

/// The image array, the statistics and the extra layers.
type RenderArrays<'py> = (Bound<'py, PyArray3<f32>>, Bound<'py, PyDict>, Bound<'py, PyDict>);

/// Renders `scene` and returns a float32 array `(h, w, 3)` of linear radiance
/// (of the pixel `window = (x0, y0, w, h)` when given), a dict of statistics and
/// a dict of the extra layers asked for (`exr_layers`: `"variance"` `(h, w, 3)`,
/// `"samples"` `(h, w)`). The settings are the keywords of
/// [`crate::settings::KEYWORDS`]; every one left out or `None` comes from the
/// scene, then the defaults, through the same request layer as the command line.
/// `progress(done, total)` is called from this thread.
#[pyfunction]
#[pyo3(signature = (scene, progress=None, **settings))]
pub fn render_array<'py>(
    py: Python<'py>,
    scene: &Scene,
    progress: Option<Bound<'py, PyAny>>,
    settings: Option<&Bound<'py, PyDict>>,
) -> PyResult<RenderArrays<'py>> {
    let mut request = crate::settings::request(settings, "render_array", false)?;
    crate::denoise::add_library_hints(py, &mut request, scene.settings());
    let mut job = request.resolve(scene.settings(), Naming::Keywords).map_err(|e| PyValueError::new_err(e.0))?;
    job.add_scene_layers(scene.settings(), true);
    let core = scene.core_for(py, &job, &request)?;
    job.reserve_film().map_err(|e| PyValueError::new_err(e.0))?;

    let warnings: Vec<String> = job.light_warnings(&core);
    let cancel = Arc::new(AtomicBool::new(false));
    let done = Arc::new(AtomicU64::new(0));
    let total = Arc::new(AtomicU64::new(0));
    let (tx, rx) = mpsc::channel::<Rendered>();
    {
        let (cancel, done, total, core) = (cancel.clone(), done.clone(), total.clone(), core.clone());
        std::thread::Builder::new()
            .name("lamplight-render".into())
            .spawn(move || {
                let report = |d: u64, t: u64| {
                    total.store(t, Ordering::Relaxed);
                    done.fetch_max(d, Ordering::Relaxed);
                };
                let control = RenderControl { progress: &report, cancel: Some(&cancel), stop: None };
                // The receiver may be gone (an error already raised): nothing to tell then.
                let _ = tx.send(job.run(&core, &control));
            })
            .map_err(|e| PyRuntimeError::new_err(format!("cannot start the render thread: {e}")))?;
    }

    let mut rx = Some(rx);
    let mut reported = (u64::MAX, u64::MAX);
    let result = loop {
        let receiver = rx.take().expect("the receiver is put back after each wait");
        let (receiver, got) = py.allow_threads(move || {
            let got = receiver.recv_timeout(POLL);
            (receiver, got)
        });
        rx = Some(receiver);
        let finished = match got {
            Ok(result) => Some(result),
            Err(RecvTimeoutError::Timeout) => None,
            Err(RecvTimeoutError::Disconnected) => return Err(PyRuntimeError::new_err("the render thread stopped without a result")),
        };
        let now = (done.load(Ordering::Relaxed), total.load(Ordering::Relaxed));
        let step = match (&progress, finished.is_some()) {
            (Some(callback), _) if now != reported && now.1 > 0 => callback.call1(now).map(|_| ()),
            _ => Ok(()),
        };
        reported = now;
        let step = step.and_then(|()| if finished.is_none() { py.check_signals() } else { Ok(()) });
        if let Err(e) = step {
            cancel.store(true, Ordering::Relaxed);
            if finished.is_none() {
                let receiver = rx.take().expect("the receiver is there");
                // Tiles already started finish; the rest are skipped.
                py.allow_threads(move || {
                    let _ = receiver.recv();
                });
            }
            return Err(e);
        }
        if let Some(result) = finished {
            break result;
        }
    };
    let rendered = result.map_err(|e| match e {
        lamplight_core::Error::Render(m) => PyRuntimeError::new_err(m),
        other => PyValueError::new_err(other.to_string()),
    })?;
    let mut warnings = warnings;
    warnings.extend(core.shape_warnings());
    let stats = rendered.stats;
    let array = to_array(py, &rendered.image)?;
    let info = PyDict::new(py);
    info.set_item("seconds", stats.elapsed.as_secs_f64())?;
    info.set_item("threads", stats.threads)?;
    info.set_item("samples_per_pixel", stats.samples_per_pixel)?;
    info.set_item("pixel_samples", stats.pixel_samples)?;
    let pixels = (rendered.image.width as f64 * rendered.image.height as f64).max(1.0);
    info.set_item("mean_samples_per_pixel", stats.pixel_samples as f64 / pixels)?;
    info.set_item("camera_rays", stats.rays.camera)?;
    info.set_item("secondary_rays", stats.rays.secondary)?;
    info.set_item("shadow_rays", stats.rays.shadow)?;
    info.set_item("nonfinite_samples", stats.nonfinite_samples)?;
    info.set_item("warnings", warnings)?;
    // How the scene's PNGs store values, for `Image.save` and `to_png`.
    let transfer = if scene.settings().transfer == lamplight_scene::image_io::Transfer::Linear { "linear" } else { "srgb" };
    info.set_item("transfer", transfer)?;
    let layers = PyDict::new(py);
    for (layer, image) in &rendered.layers {
        match layer {
            Layer::Samples => {
                let (w, h) = (image.width as usize, image.height as usize);
                let flat: Vec<f32> = image.pixels.iter().map(|p| p[0]).collect();
                layers.set_item("samples", PyArray1::from_vec(py, flat).reshape([h, w])?)?
            }
            _ => layers.set_item(layer.name(), to_array(py, image)?)?,
        }
    }
    if let Some(t) = rendered.denoise_time {
        info.set_item("denoise_seconds", t.as_secs_f64())?;
    }
    Ok((array, info, layers))
}

/// The settings a render of `scene` with these keywords would use: `(width,
/// height, spp, integrator, seed)`, each the argument, else the scene's, else the
/// default, through the request layer (so Dask splits exactly the image a local
/// render makes).
#[pyfunction]
#[pyo3(signature = (scene, **settings))]
pub fn resolve_settings(
    py: Python<'_>,
    scene: &Scene,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<(u32, u32, u32, &'static str, u64)> {
    let mut request = crate::settings::request(settings, "resolve_settings", false)?;
    crate::denoise::add_library_hints(py, &mut request, scene.settings());
    let o = request.resolve(scene.settings(), Naming::Keywords).map_err(|e| PyValueError::new_err(e.0))?.options;
    Ok((o.width, o.height, o.spp, o.integrator.name, o.seed))
}

/// `antialias` as Python gave it: `True`, `False` or a threshold `>= 0`.
pub fn antialias_arg(value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<request::AntialiasRequest>> {
    let Some(value) = value else { return Ok(None) };
    if let Ok(on) = value.downcast::<pyo3::types::PyBool>() {
        let on = on.is_true();
        return Ok(Some(if on {
            request::AntialiasRequest::On { threshold: lamplight_core::Antialias::default().threshold }
        } else {
            request::AntialiasRequest::Off
        }));
    }
    match value.extract::<f64>() {
        Ok(t) if t.is_finite() && t >= 0.0 => Ok(Some(request::AntialiasRequest::On { threshold: t })),
        _ => Err(PyValueError::new_err(format!("antialias must be True, False or a threshold >= 0 (POV-Ray's 0.3), got {value}"))),
    }
}

/// `threads` as Python gave it (`None` or 0: every core), read by [`setting`].
pub fn threads_arg(threads: Option<&Bound<'_, PyAny>>) -> PyResult<usize> {
    Ok(setting(&limits::THREADS, threads)?.unwrap_or(0))
}

pub(crate) fn to_array<'py>(py: Python<'py>, image: &Image) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let (w, h) = (image.width as usize, image.height as usize);
    let flat: Vec<f32> = image.pixels.iter().flatten().copied().collect();
    PyArray1::from_vec(py, flat).reshape([h, w, 3])
}
