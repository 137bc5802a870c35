//! `render_array`: a render of a [`Scene`] as a float32 numpy array `(H, W, 3)`
//! of linear radiance, the numbers the command line writes to EXR.
//!
//! The render runs on its own thread with the GIL released. The calling thread
//! wakes every 100 ms to pass progress to a Python callback and to let Python
//! handle signals: on Ctrl-C (or any exception from the callback) it sets the
//! core's cancel flag, waits for the render to stop, and raises.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::Arc;
use std::time::Duration;

use lamplight_core::film::{Filter, Image};
use lamplight_core::integrators::{self, IntegratorEntry};
use lamplight_core::{PixelWindow, RenderControl, RenderOptions, RenderStats};
use numpy::{PyArray1, PyArray3, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use crate::scene::Scene;

/// How often the waiting thread looks at signals and progress.
const POLL: Duration = Duration::from_millis(100);
/// Most samples per pixel (as in scene files).
const MAX_SPP: u32 = 1 << 20;
/// Deepest recursion (as on the command line).
const MAX_DEPTH: u32 = 64;
/// Most worker threads (as on the command line).
const MAX_THREADS: usize = 1024;

type Rendered = Result<(Image, RenderStats), lamplight_core::Error>;

/// Renders `scene` at `width x height` (or only the pixel `window = (x0, y0, w, h)`
/// of that image) and returns a float32 array `(h, w, 3)` of linear radiance and
/// a dict of statistics. `progress(done, total)` is called from this thread.
#[pyfunction]
#[pyo3(signature = (scene, width, height, spp=1, integrator="whitted", threads=0, seed=0, max_depth=None, window=None, progress=None, time_limit=None, filter="box"))]
#[allow(clippy::too_many_arguments)]
pub fn render_array<'py>(
    py: Python<'py>,
    scene: &Scene,
    width: u32,
    height: u32,
    spp: u32,
    integrator: &str,
    threads: usize,
    seed: u64,
    max_depth: Option<u32>,
    window: Option<(u32, u32, u32, u32)>,
    progress: Option<Bound<'py, PyAny>>,
    time_limit: Option<f64>,
    filter: &str,
) -> PyResult<(Bound<'py, PyArray3<f32>>, Bound<'py, pyo3::types::PyDict>)> {
    if width == 0 || height == 0 || width as u64 * height as u64 > 1 << 28 {
        return Err(PyValueError::new_err(format!("image size {width}x{height} must be at least 1x1 and at most 2^28 pixels")));
    }
    if !(1..=MAX_SPP).contains(&spp) {
        return Err(PyValueError::new_err(format!("spp must be between 1 and {MAX_SPP}, got {spp}")));
    }
    if let Some(depth) = max_depth {
        if !(1..=MAX_DEPTH).contains(&depth) {
            return Err(PyValueError::new_err(format!("max_depth must be between 1 and {MAX_DEPTH}, got {depth}")));
        }
    }
    if threads > MAX_THREADS {
        return Err(PyValueError::new_err(format!("threads must be at most {MAX_THREADS} (0 uses all cores), got {threads}")));
    }
    let integrator: &'static IntegratorEntry = integrator
        .parse()
        .map_err(|_| PyValueError::new_err(format!("integrator must be {}, got {integrator:?}", integrators::quoted_names())))?;
    let filter: Filter =
        filter.parse().map_err(|_| PyValueError::new_err(format!("filter must be \"box\" or \"gaussian\", got {filter:?}")))?;
    let time_limit = match time_limit {
        None => None,
        Some(t) if t.is_finite() && t > 0.0 && t < 1e9 => Some(Duration::from_secs_f64(t)),
        Some(t) => return Err(PyValueError::new_err(format!("time_limit must be a positive number of seconds, got {t}"))),
    };
    let window = window.map(|(x0, y0, w, h)| PixelWindow { x0, y0, width: w, height: h });
    if let Some(w) = window {
        if w.width == 0 || w.height == 0 || w.x0 as u64 + w.width as u64 > width as u64 || w.y0 as u64 + w.height as u64 > height as u64 {
            return Err(PyValueError::new_err(format!(
                "window (x0={}, y0={}, width={}, height={}) must be non-empty and inside the {width}x{height} image",
                w.x0, w.y0, w.width, w.height
            )));
        }
    }
    let options = RenderOptions { width, height, spp, max_depth, threads, seed, integrator, time_limit, filter, window };
    let core = scene.core(py)?;

    let cancel = Arc::new(AtomicBool::new(false));
    let done = Arc::new(AtomicU64::new(0));
    let total = Arc::new(AtomicU64::new(0));
    let (tx, rx) = mpsc::channel::<Rendered>();
    {
        let (cancel, done, total) = (cancel.clone(), done.clone(), total.clone());
        std::thread::Builder::new()
            .name("lamplight-render".into())
            .spawn(move || {
                let report = |d: u64, t: u64| {
                    total.store(t, Ordering::Relaxed);
                    done.fetch_max(d, Ordering::Relaxed);
                };
                let control = RenderControl { progress: &report, cancel: Some(&cancel) };
                // The receiver may be gone (an error already raised): nothing to tell then.
                let _ = tx.send(lamplight_core::render_image(&core, &options, &control));
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
    let (image, stats) = result.map_err(|e| match e {
        lamplight_core::Error::Render(m) => PyRuntimeError::new_err(m),
        other => PyValueError::new_err(other.to_string()),
    })?;
    let (w, h) = (image.width as usize, image.height as usize);
    let flat: Vec<f32> = image.pixels.into_iter().flatten().collect();
    let array = PyArray1::from_vec(py, flat).reshape([h, w, 3])?;
    let info = pyo3::types::PyDict::new(py);
    info.set_item("seconds", stats.elapsed.as_secs_f64())?;
    info.set_item("threads", stats.threads)?;
    info.set_item("samples_per_pixel", stats.samples_per_pixel)?;
    info.set_item("camera_rays", stats.rays.camera)?;
    info.set_item("secondary_rays", stats.rays.secondary)?;
    info.set_item("shadow_rays", stats.rays.shadow)?;
    info.set_item("nonfinite_samples", stats.nonfinite_samples)?;
    Ok((array, info))
}
