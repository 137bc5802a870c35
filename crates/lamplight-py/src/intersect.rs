//! `Scene.intersect`: nearest hits of a batch of rays given as numpy arrays.
//!
//! Origins and directions are `(N, 3)` arrays of float32 or float64 (the same
//! for both), read in place (no copy, any strides). The rays are traced on a
//! rayon pool with the GIL released. Directions are normalized, so `t` is the
//! distance from the origin to the hit. Answers: `t` (the input's float type,
//! `+inf` on a miss), the id of the object hit (int64, `-1` on a miss; objects
//! are numbered in scene order) and its unit outward geometric normal (`(N, 3)`,
//! zero on a miss). A ray with a zero or non-finite direction or a non-finite
//! origin misses.

use lamplight_core::math::Vec3;
use lamplight_core::ray::Ray;
use lamplight_core::Scene as CoreScene;
use numpy::ndarray::ArrayView2;
use numpy::{Element, PyArray1, PyArray2, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use rayon::prelude::*;

/// Rays per rayon work item.
const CHUNK: usize = 1024;

/// One ray's answer: distance, object id, outward normal.
type Answer = (f64, i64, [f64; 3]);

/// Checks that `obj` is an `(N, 3)` numpy array and returns N.
fn rows(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<usize> {
    let array = obj.downcast::<PyUntypedArray>().map_err(|_| {
        let type_name = obj.get_type().name().map(|n| n.to_string()).unwrap_or_default();
        PyTypeError::new_err(format!("{name} must be a numpy array of shape (N, 3), got {type_name}"))
    })?;
    let shape = array.shape();
    if shape.len() != 2 || shape[1] != 3 {
        return Err(PyValueError::new_err(format!("{name} must have shape (N, 3), got {shape:?}")));
    }
    Ok(shape[0])
}

fn dtype_name(obj: &Bound<'_, PyAny>) -> String {
    obj.downcast::<PyUntypedArray>().ok().and_then(|a| a.dtype().str().ok().map(|s| s.to_string())).unwrap_or_default()
}

/// Traces every ray in a pool of `threads` (0: one per core).
pub fn intersect<'py>(
    py: Python<'py>,
    scene: &CoreScene,
    origins: &Bound<'py, PyAny>,
    directions: &Bound<'py, PyAny>,
    threads: usize,
) -> PyResult<Bound<'py, PyTuple>> {
    let n = rows(origins, "origins")?;
    let m = rows(directions, "directions")?;
    if n != m {
        return Err(PyValueError::new_err(format!("origins and directions must have the same number of rows, got {n} and {m}")));
    }
    if threads > 1024 {
        return Err(PyValueError::new_err(format!("threads must be at most 1024 (0 uses all cores), got {threads}")));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start worker threads: {e}")))?;
    if let (Ok(o), Ok(d)) = (origins.downcast::<PyArray2<f64>>(), directions.downcast::<PyArray2<f64>>()) {
        let (o, d) = (o.readonly(), d.readonly());
        let (o, d) = (o.as_array(), d.as_array());
        let answers = py.allow_threads(|| pool.install(|| trace(scene, o, d, |v| v)));
        return answer(py, answers, |t| t);
    }
    if let (Ok(o), Ok(d)) = (origins.downcast::<PyArray2<f32>>(), directions.downcast::<PyArray2<f32>>()) {
        let (o, d) = (o.readonly(), d.readonly());
        let (o, d) = (o.as_array(), d.as_array());
        let answers = py.allow_threads(|| pool.install(|| trace(scene, o, d, f64::from)));
        return answer(py, answers, |t| t as f32);
    }
    Err(PyTypeError::new_err(format!(
        "origins and directions must both be float32 or both float64 arrays, got {} and {}",
        dtype_name(origins),
        dtype_name(directions)
    )))
}

fn trace<T: Copy + Send + Sync>(scene: &CoreScene, o: ArrayView2<'_, T>, d: ArrayView2<'_, T>, to_f64: fn(T) -> f64) -> Vec<Answer> {
    (0..o.nrows())
        .into_par_iter()
        .with_min_len(CHUNK)
        .map(|i| {
            let origin = Vec3::new(to_f64(o[[i, 0]]), to_f64(o[[i, 1]]), to_f64(o[[i, 2]]));
            let dir = Vec3::new(to_f64(d[[i, 0]]), to_f64(d[[i, 1]]), to_f64(d[[i, 2]]));
            let length = dir.length();
            if !(origin.is_finite() && length.is_finite() && length > 0.0) {
                return (f64::INFINITY, -1, [0.0; 3]);
            }
            let ray = Ray { origin, dir: dir / length };
            match scene.first_intersect(&ray, f64::INFINITY) {
                Some(hit) => {
                    // The scene turns normals to face the ray; give the shape's outward one.
                    let outward = if hit.front_face { hit.geometric_normal } else { -hit.geometric_normal };
                    (hit.t, hit.object as i64, outward.to_array())
                }
                None => (f64::INFINITY, -1, [0.0; 3]),
            }
        })
        .collect()
}

fn answer<'py, T: Element>(py: Python<'py>, answers: Vec<Answer>, from_f64: fn(f64) -> T) -> PyResult<Bound<'py, PyTuple>> {
    let n = answers.len();
    let mut t = Vec::with_capacity(n);
    let mut ids = Vec::with_capacity(n);
    let mut normals = Vec::with_capacity(n * 3);
    for (distance, id, normal) in answers {
        t.push(from_f64(distance));
        ids.push(id);
        normals.extend(normal.map(from_f64));
    }
    let t = PyArray1::from_vec(py, t);
    let ids = PyArray1::from_vec(py, ids);
    let normals = PyArray1::from_vec(py, normals).reshape([n, 3])?;
    PyTuple::new(py, [t.into_any(), ids.into_any(), normals.into_any()])
}
