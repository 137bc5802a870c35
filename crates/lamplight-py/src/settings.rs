//! The render settings of the Python API, stated once: one row per keyword.
//!
//! `render_array`, `resolve_settings` and `Scene.explain` take their settings
//! as keywords and read them here into the request layer's [`Request`], which
//! resolves them as it does the command line's flags (defaults, precedence,
//! limits). The pure-Python wrappers (`lamplight.render`,
//! `lamplight.dask.render`, `render_frames`) build their signatures from
//! [`render_keywords`], and the type stub's signatures are checked against it
//! by the Python tests. A new setting is one row in [`KEYWORDS`] (and the
//! request field it fills).
//!
//! | keyword | Python type | read as |
//! |---|---|---|
//! | `width`, `height` | `int` | whole, 1 to 2^32 - 1 |
//! | `spp`, `max_depth`, `threads`, `min_spp` | `int` | the request layer's ranges ([`limits`]) |
//! | `seed` | `int` | whole, 0 to 2^64 - 1 |
//! | `integrator`, `filter` | `str` | a registry name, checked by the request layer |
//! | `window` | `(x0, y0, w, h)` | four whole numbers |
//! | `time_limit`, `clamp`, `noise_threshold` | `float` | a number |
//! | `environment` | path | an `.exr` or `.hdr` file |
//! | `exr_layers` | list of `str` | `"variance"`, `"samples"`, `"albedo"`, `"normal"`, `"noisy"`, `"emitted"` |
//! | `denoise` | `bool` | Open Image Denoise on the image |
//! | `antialias` | `bool` or `float` | on, off, or a threshold |
//! | `memory_budget` | `int` or `str` | bytes, or a size such as `"4G"` ([`lamplight_scene::memory`]) |
//! | `frame` | `int` | the frame of an animated scene, 0 to 1048574 (default: its first) |
//! | `smooth` | `bool` | a mesh file's meshes without normals smooth (`--smooth`) |
//! | `keep_auto_lights` | `bool` or `str` | `True`, `False` or `"auto"` (`--keep-auto-lights on`, `off`, `auto`) |
//! | `animation` | `str` or `int` | the glTF animation that plays, by name or index (`--animation`) |
//!
//! The last three ([`BUILD_KEYWORDS`]) decide how a mesh file rendered directly
//! is built: `lamplight.load` and `Scene.from_file` take them too, as the
//! scene's own, which a render's keywords override.

use std::path::PathBuf;

use lamplight_scene::request::{limits, AnimationChoice, AutoLights, Layer, MeshOptions, Request};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

use crate::convert::{setting, whole};

/// Which calls take a keyword.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Takes {
    /// Renders and explanations.
    Both,
    /// Whole renders only: a one-pixel explanation has no window, threads, time
    /// limit or extra layers.
    RenderOnly,
}

/// One render keyword.
pub struct Keyword {
    /// Its name, as Python passes it.
    pub name: &'static str,
    /// Its annotation in the type stub and the wrappers' signatures.
    pub annotation: &'static str,
    /// Which calls take it.
    pub takes: Takes,
    /// Reads a value that is not `None` into the request.
    read: for<'py> fn(&mut Request, &Bound<'py, PyAny>) -> PyResult<()>,
}

/// Stores a value read from Python in its request field.
fn set<T>(field: &mut T, value: PyResult<T>) -> PyResult<()> {
    *field = value?;
    Ok(())
}

/// A number keyword (an `int` is a number too, a `bool` is not).
fn number(name: &str, value: &Bound<'_, PyAny>) -> PyResult<f64> {
    if value.is_instance_of::<pyo3::types::PyBool>() {
        return Err(PyTypeError::new_err(format!("{name} must be a number, got bool")));
    }
    value.extract::<f64>().map_err(|_| PyTypeError::new_err(format!("{name} must be a number, got {}", type_name(value))))
}

/// A text keyword.
fn text(name: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    value.extract::<String>().map_err(|_| PyTypeError::new_err(format!("{name} must be a str, got {}", type_name(value))))
}

fn type_name(value: &Bound<'_, PyAny>) -> String {
    value.get_type().name().map(|n| n.to_string()).unwrap_or_default()
}

/// The four whole numbers of `window = (x0, y0, w, h)`.
fn window(value: &Bound<'_, PyAny>) -> PyResult<(u32, u32, u32, u32)> {
    let parts: Vec<Bound<'_, PyAny>> = value
        .extract()
        .ok()
        .filter(|p: &Vec<Bound<'_, PyAny>>| p.len() == 4 && !value.is_instance_of::<PyString>())
        .ok_or_else(|| PyTypeError::new_err(format!("window must be (x0, y0, width, height), got {}", type_name(value))))?;
    let side = |name: &str, v: &Bound<'_, PyAny>| whole::<u32>(name, Some(v), 0, u32::MAX.into(), "").map(Option::unwrap_or_default);
    Ok((side("window x0", &parts[0])?, side("window y0", &parts[1])?, side("window width", &parts[2])?, side("window height", &parts[3])?))
}

/// A `True` or `False` keyword.
fn flag(name: &str, value: &Bound<'_, PyAny>) -> PyResult<bool> {
    value
        .downcast::<pyo3::types::PyBool>()
        .map(|b| b.is_true())
        .map_err(|_| PyTypeError::new_err(format!("{name} must be True or False, got {}", type_name(value))))
}

/// `animation`: a name (`str`) or an index (`int`, not a `bool`).
fn animation(value: &Bound<'_, PyAny>) -> PyResult<AnimationChoice> {
    let wrong = || PyTypeError::new_err(format!("animation must be an animation's name (str) or index (int), got {}", type_name(value)));
    if value.is_instance_of::<pyo3::types::PyBool>() {
        return Err(wrong());
    }
    if let Ok(name) = value.downcast::<PyString>() {
        let name = name.to_str()?;
        if name.is_empty() {
            return Err(PyValueError::new_err("animation must be an animation's name or index, got an empty string"));
        }
        return Ok(AnimationChoice::Name(name.to_string()));
    }
    let index: i128 = value.extract().map_err(|_| wrong())?;
    usize::try_from(index)
        .map(AnimationChoice::Index)
        .map_err(|_| PyValueError::new_err(format!("animation must be a name or an index from 0, got {index}")))
}

/// `keep_auto_lights`: `True` (on), `False` (off) or `"auto"` (also `"on"`, `"off"`).
fn auto_lights(value: &Bound<'_, PyAny>) -> PyResult<AutoLights> {
    if let Ok(on) = value.downcast::<pyo3::types::PyBool>() {
        return Ok(if on.is_true() { AutoLights::On } else { AutoLights::Off });
    }
    let text = value
        .extract::<String>()
        .map_err(|_| PyTypeError::new_err(format!("keep_auto_lights must be True, False or \"auto\", got {}", type_name(value))))?;
    text.parse().map_err(|_| PyValueError::new_err(format!("keep_auto_lights must be True, False or \"auto\", got {text:?}")))
}

/// The layers of `exr_layers`.
fn layers(value: &Bound<'_, PyAny>) -> PyResult<Vec<Layer>> {
    if value.is_instance_of::<PyString>() {
        return Err(PyTypeError::new_err("exr_layers must be a list of layer names, got str"));
    }
    let names: Vec<String> =
        value.extract().map_err(|_| PyTypeError::new_err(format!("exr_layers must be a list of layer names, got {}", type_name(value))))?;
    names.iter().map(|l| l.parse::<Layer>().map_err(PyValueError::new_err)).collect()
}

/// Every render keyword, in the order of the wrappers' signatures.
pub const KEYWORDS: &[Keyword] = &[
    Keyword {
        name: "width",
        annotation: "Optional[int]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.width, whole("width", Some(v), 1, u32::MAX.into(), "")),
    },
    Keyword {
        name: "height",
        annotation: "Optional[int]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.height, whole("height", Some(v), 1, u32::MAX.into(), "")),
    },
    Keyword { name: "spp", annotation: "Optional[int]", takes: Takes::Both, read: |r, v| set(&mut r.spp, setting(&limits::SPP, Some(v))) },
    Keyword {
        name: "integrator",
        annotation: "Optional[str]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.integrator, text("integrator", v).map(Some)),
    },
    Keyword {
        name: "threads",
        annotation: "Optional[int]",
        takes: Takes::RenderOnly,
        read: |r, v| set(&mut r.threads, setting(&limits::THREADS, Some(v))),
    },
    Keyword {
        name: "seed",
        annotation: "Optional[int]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.seed, whole("seed", Some(v), 0, u64::MAX.into(), "")),
    },
    Keyword {
        name: "max_depth",
        annotation: "Optional[int]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.max_depth, setting(&limits::DEPTH, Some(v))),
    },
    Keyword {
        name: "window",
        annotation: "Optional[Tuple[int, int, int, int]]",
        takes: Takes::RenderOnly,
        read: |r, v| set(&mut r.window, window(v).map(Some)),
    },
    Keyword {
        name: "time_limit",
        annotation: "Optional[float]",
        takes: Takes::RenderOnly,
        read: |r, v| set(&mut r.time_limit, number("time_limit", v).map(Some)),
    },
    Keyword {
        name: "filter",
        annotation: "Optional[str]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.filter, text("filter", v).map(Some)),
    },
    Keyword {
        name: "environment",
        annotation: "Optional[Union[str, os.PathLike[str]]]",
        takes: Takes::Both,
        read: |r, v| {
            let path: PathBuf =
                v.extract().map_err(|_| PyTypeError::new_err(format!("environment must be a path, got {}", type_name(v))))?;
            set(&mut r.environment, Ok(Some(path)))
        },
    },
    Keyword {
        name: "exr_layers",
        annotation: "Optional[Sequence[str]]",
        takes: Takes::RenderOnly,
        read: |r, v| set(&mut r.layers, layers(v)),
    },
    Keyword {
        name: "denoise",
        annotation: "Optional[bool]",
        takes: Takes::RenderOnly,
        read: |r, v| {
            let on = v
                .downcast::<pyo3::types::PyBool>()
                .map_err(|_| PyTypeError::new_err(format!("denoise must be True or False, got {}", type_name(v))))?;
            set(&mut r.denoise, Ok(Some(on.is_true())))
        },
    },
    Keyword {
        name: "clamp",
        annotation: "Optional[float]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.clamp, number("clamp", v).map(Some)),
    },
    Keyword {
        name: "antialias",
        annotation: "Optional[Union[bool, float]]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.antialias, crate::render::antialias_arg(Some(v))),
    },
    Keyword {
        name: "noise_threshold",
        annotation: "Optional[float]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.noise_threshold, number("noise_threshold", v).map(Some)),
    },
    Keyword {
        name: "min_spp",
        annotation: "Optional[int]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.min_spp, whole("min_spp", Some(v), 1, limits::MAX_SPP.into(), "")),
    },
    Keyword {
        name: "memory_budget",
        annotation: "Optional[Union[int, str]]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.memory_budget, memory_budget(v).map(Some)),
    },
    Keyword {
        name: "smooth",
        annotation: "Optional[bool]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.smooth, flag("smooth", v).map(Some)),
    },
    Keyword {
        name: "keep_auto_lights",
        annotation: "Optional[Union[bool, str]]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.keep_auto_lights, auto_lights(v).map(Some)),
    },
    Keyword {
        name: "frame",
        annotation: "Optional[int]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.frame, whole("frame", Some(v), 0, lamplight_scene::request::frames::MAX_FRAME as i128, "")),
    },
    Keyword {
        name: "animation",
        annotation: "Optional[Union[str, int]]",
        takes: Takes::Both,
        read: |r, v| set(&mut r.animation, animation(v).map(Some)),
    },
];

/// The keywords that decide how a mesh file is built ([`MeshOptions`]), which
/// `lamplight.load` and `Scene.from_file` take as well as the renders.
pub const BUILD_KEYWORDS: &[&str] = &["smooth", "keep_auto_lights", "animation"];

/// The mesh file options the keywords `settings` give for `call` (`load`,
/// `Scene.from_file`): only [`BUILD_KEYWORDS`], read by their rows of [`KEYWORDS`].
pub fn mesh_options(settings: Option<&Bound<'_, PyDict>>, call: &str) -> PyResult<MeshOptions> {
    let Some(settings) = settings else { return Ok(MeshOptions::default()) };
    for key in settings.keys() {
        let key: String = key.extract()?;
        if !BUILD_KEYWORDS.contains(&key.as_str()) {
            let hint = lamplight_core::params::suggestion(&key, BUILD_KEYWORDS.iter().copied())
                .map(|s| format!(" (did you mean '{s}'?)"))
                .unwrap_or_default();
            return Err(PyTypeError::new_err(format!("{call}() got an unexpected keyword argument '{key}'{hint}")));
        }
    }
    Ok(request(Some(settings), call, false)?.mesh_options(MeshOptions::default()))
}

/// The glTF animation the keywords `settings` choose for `call` (`animation=`), if any.
pub fn animation_choice(settings: Option<&Bound<'_, PyDict>>, call: &str) -> PyResult<Option<AnimationChoice>> {
    match settings {
        Some(settings) => Ok(request(Some(settings), call, false)?.animation),
        None => Ok(None),
    }
}

/// The names of [`BUILD_KEYWORDS`], for the Python wrapper of `load`.
#[pyfunction]
pub fn build_keywords() -> Vec<&'static str> {
    BUILD_KEYWORDS.to_vec()
}

/// `memory_budget`: bytes as an `int`, or a size such as `"4G"`.
fn memory_budget(v: &Bound<'_, PyAny>) -> PyResult<u64> {
    let text = match v.extract::<u64>() {
        Ok(n) => n.to_string(),
        Err(_) => v.extract::<String>().map_err(|_| {
            PyTypeError::new_err(format!("memory_budget must be a size such as \"4G\" or a number of bytes, got {}", type_name(v)))
        })?,
    };
    lamplight_scene::memory::parse(&text).map_err(|e| PyValueError::new_err(format!("memory_budget {e}")))
}

/// The request `settings` (keyword arguments; `None` values are "not given")
/// make for `call`, which names the function in errors. `explain` leaves out the
/// keywords only whole renders take. An unknown keyword is a `TypeError`, as
/// Python's own, with the nearest known name.
pub fn request(settings: Option<&Bound<'_, PyDict>>, call: &str, explain: bool) -> PyResult<Request> {
    let mut request = Request::default();
    let Some(settings) = settings else { return Ok(request) };
    let known = || KEYWORDS.iter().filter(|k| !explain || k.takes == Takes::Both);
    for (key, value) in settings.iter() {
        let key: String = key.extract()?;
        let Some(keyword) = known().find(|k| k.name == key) else {
            let hint = lamplight_core::params::suggestion(&key, known().map(|k| k.name))
                .map(|s| format!(" (did you mean '{s}'?)"))
                .unwrap_or_default();
            return Err(PyTypeError::new_err(format!("{call}() got an unexpected keyword argument '{key}'{hint}")));
        };
        if !value.is_none() {
            (keyword.read)(&mut request, &value)?;
        }
    }
    Ok(request)
}

/// `(name, annotation, explain)` of every render keyword, in order: whether
/// `Scene.explain` takes it too. The Python wrappers build their signatures from it.
#[pyfunction]
pub fn render_keywords() -> Vec<(&'static str, &'static str, bool)> {
    KEYWORDS.iter().map(|k| (k.name, k.annotation, k.takes == Takes::Both)).collect()
}
