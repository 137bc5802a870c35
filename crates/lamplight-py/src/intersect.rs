//! `Scene.intersect`: nearest hits of a batch of rays given as numpy arrays,
//! through the batch API of `lamplight_core::batch` (the one `lamplight raycast`
//! uses, with the same meaning of every number).
//!
//! Origins and directions are `(N, 3)` arrays of float32 or float64 (the same
//! for both), read in place (no copy, any strides); a list or tuple of
//! `[x, y, z]` rows is copied into an array first (of the other argument's
//! float type when that one is an array, else float64). The rays are traced on a
//! rayon pool with the GIL released. Answers, for ray `o + s d` (`d` of any
//! non-zero length): `t`, the distance `s |d|` from the origin to the nearest hit
//! (the input's float type, `+inf` on a miss); the id of the object hit (int64,
//! objects in scene order, `-1` on a miss); the index of the triangle hit within
//! a mesh object (int64, the mesh's face order; `-1` on a miss and for other
//! shapes); and the unit outward geometric normal (`(N, 3)`, zero on a miss).
//! With `errors=True` a fifth answer bounds the rounding in each `t` (the
//! input's float type, `+inf` on a miss; `lamplight_core::batch::scene`), which
//! says where precision was lost far from the origin. A ray with a zero or
//! non-finite direction or a non-finite origin misses.

use lamplight_core::batch::{self, Float, Hits, Rays};
use lamplight_core::Scene as CoreScene;
use lamplight_scene::request::{limits, Naming};
use numpy::ndarray::ArrayView2;
use numpy::{Element, PyArray1, PyArray2, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

/// Two `(N, 3)` numpy arrays read in place as rays.
struct ArrayRays<'a, T> {
    origins: ArrayView2<'a, T>,
    directions: ArrayView2<'a, T>,
}

impl<T: Float> Rays for ArrayRays<'_, T> {
    type Scalar = T;

    fn len(&self) -> usize {
        self.origins.nrows()
    }

    #[inline]
    fn get(&self, i: usize) -> ([T; 3], [T; 3]) {
        let (o, d) = (&self.origins, &self.directions);
        (std::array::from_fn(|k| o[[i, k]]), std::array::from_fn(|k| d[[i, k]]))
    }
}

/// `obj` as a numpy array: an array as it is; a list or tuple copied into one of
/// `other`'s float type when `other` is a float32 array, else float64. Any
/// other type is left for [`rows`] to name.
fn as_array<'py>(obj: &Bound<'py, PyAny>, other: &Bound<'py, PyAny>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    if !(obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>()) {
        return Ok(obj.clone());
    }
    let dtype = if other.downcast::<PyArray2<f32>>().is_ok() { "float32" } else { "float64" };
    let numpy = obj.py().import("numpy")?;
    numpy
        .call_method1("asarray", (obj, dtype))
        .map_err(|e| PyValueError::new_err(format!("{name} must be rows of three numbers, shape (N, 3): {}", e.value(obj.py()))))
}

/// Checks that `obj` is an `(N, 3)` numpy array and returns N.
fn rows(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<usize> {
    let array = obj.downcast::<PyUntypedArray>().map_err(|_| {
        let type_name = obj.get_type().name().map(|n| n.to_string()).unwrap_or_default();
        PyTypeError::new_err(format!("{name} must be a numpy array (or a list of rows) of shape (N, 3), got {type_name}"))
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

/// Traces every ray in a pool of `threads` (0: one per core); returns
/// `(t, ids, prims, normals)`, and `t_error` after them when `errors`.
pub fn intersect<'py>(
    py: Python<'py>,
    scene: &CoreScene,
    origins: &Bound<'py, PyAny>,
    directions: &Bound<'py, PyAny>,
    threads: usize,
    errors: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let (origins, directions) = (&as_array(origins, directions, "origins")?, &as_array(directions, origins, "directions")?);
    let n = rows(origins, "origins")?;
    let m = rows(directions, "directions")?;
    if n != m {
        return Err(PyValueError::new_err(format!("origins and directions must have the same number of rows, got {n} and {m}")));
    }
    limits::THREADS.check(threads as u64, Naming::Keywords).map_err(PyValueError::new_err)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start worker threads: {e}")))?;
    if let (Ok(o), Ok(d)) = (origins.downcast::<PyArray2<f64>>(), directions.downcast::<PyArray2<f64>>()) {
        let (o, d) = (o.readonly(), d.readonly());
        let rays = ArrayRays { origins: o.as_array(), directions: d.as_array() };
        return answer(py, &pool, scene, &rays, errors);
    }
    if let (Ok(o), Ok(d)) = (origins.downcast::<PyArray2<f32>>(), directions.downcast::<PyArray2<f32>>()) {
        let (o, d) = (o.readonly(), d.readonly());
        let rays = ArrayRays { origins: o.as_array(), directions: d.as_array() };
        return answer(py, &pool, scene, &rays, errors);
    }
    Err(PyTypeError::new_err(format!(
        "origins and directions must both be float32 or both float64 arrays, got {} and {}",
        dtype_name(origins),
        dtype_name(directions)
    )))
}

/// Casts `rays` with the GIL released and wraps the answers as numpy arrays.
fn answer<'py, T: Float + Element>(
    py: Python<'py>,
    pool: &rayon::ThreadPool,
    scene: &CoreScene,
    rays: &ArrayRays<'_, T>,
    errors: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let n = rays.len();
    let (mut t, mut ids, mut prims) = (vec![T::from_f64(0.0); n], vec![0i64; n], vec![0i64; n]);
    let mut normals = vec![[T::from_f64(0.0); 3]; n];
    let mut t_error = if errors { vec![T::from_f64(0.0); n] } else { Vec::new() };
    py.allow_threads(|| {
        let error = errors.then_some(&mut t_error[..]);
        let out = Hits { t: &mut t, object: Some(&mut ids), primitive: Some(&mut prims), normal: Some(&mut normals), error };
        pool.install(|| batch::cast(scene, rays, out, 0))
    })
    .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let t = PyArray1::from_vec(py, t);
    let ids = PyArray1::from_vec(py, ids);
    let prims = PyArray1::from_vec(py, prims);
    let normals = PyArray1::from_vec(py, normals.into_flattened()).reshape([n, 3])?;
    let mut answers = vec![t.into_any(), ids.into_any(), prims.into_any(), normals.into_any()];
    if errors {
        answers.push(PyArray1::from_vec(py, t_error).into_any());
    }
    PyTuple::new(py, answers)
}
