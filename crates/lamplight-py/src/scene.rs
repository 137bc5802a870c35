//! `Scene`: a scene from a built-in name, a scene file, a mesh file or a dict,
//! with the core scene built from it kept after its first use.
//!
//! A scene is the request layer's [`SceneRequest`], as the command line makes
//! it (a built-in, a scene file or dict, or a mesh file, with its settings),
//! so that both front ends build the same scene the same way; Python only
//! keeps the dict a scene came from. It pickles as what it was made from (the
//! name, the file's text and path, the dict, or the mesh path), never as built
//! data: a Dask worker that receives it rebuilds it on first use and then
//! keeps the build.
//! The core camera applies the image's aspect when rendering, so one build serves
//! every image size.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use lamplight_core::camera::Camera;
use lamplight_core::Scene as CoreScene;
use lamplight_scene::builtin;
use lamplight_scene::description::{Node, SceneDescription};
use lamplight_scene::formats::native::Source as FileSource;
use lamplight_scene::instantiate::SceneFile;
use lamplight_scene::request::{self, program_defaults, Defaults, FileKind, MeshOptions, Naming, Request, SceneRequest, SceneSpec};
use lamplight_scene::LoadError;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::convert;
use crate::SceneError;

/// A kept build: the core scene and its mesh files' warnings.
type Kept = (Arc<CoreScene>, Arc<Vec<String>>);

/// A scene: made from a built-in name, a scene or mesh file, or a dict, and
/// built on first use.
#[pyclass(module = "lamplight._lamplight", frozen)]
pub struct Scene {
    /// What the request layer builds: the scene, its settings (`defaults`),
    /// and how a mesh file is built unless a render says otherwise
    /// (`load(path, smooth=True)`).
    request: SceneRequest,
    /// The dict a scene dict was made from, kept plain (its `source`, and what it pickles as).
    dict: Option<PyObject>,
    /// A camera replacing the scene's (`with_camera`): the plain dict and its description.
    camera: Option<(PyObject, Arc<dyn Camera>)>,
    /// The core scene once built for each mesh file options asked for, and the
    /// warnings of the mesh files it read.
    built: Mutex<Vec<(MeshOptions, Kept)>>,
}

/// The names of the built-in scenes, the default first.
#[pyfunction]
pub fn builtin_names() -> Vec<&'static str> {
    builtin::BUILTINS.iter().map(|b| b.name).collect()
}

fn load_error(e: LoadError) -> PyErr {
    SceneError::new_err(e.to_string())
}

/// A parameter error of a dict: `scene dict: key.path: message`.
fn dict_param_error(e: lamplight_core::params::ParamError) -> PyErr {
    load_error(FileSource::without_text("scene dict").param_error(e))
}

impl Scene {
    fn new(request: SceneRequest, dict: Option<PyObject>) -> Scene {
        Scene { request, dict, camera: None, built: Mutex::new(Vec::new()) }
    }

    /// A parsed scene file or dict, its settings checked now.
    fn from_scene_file(file: SceneFile, dict: Option<PyObject>) -> PyResult<Scene> {
        let name = if file.source.is_dict() { "scene dict".to_string() } else { file.source.path.display().to_string() };
        let request = SceneRequest::file(file, name).map_err(|e| SceneError::new_err(e.0))?;
        Ok(Scene::new(request, dict))
    }

    /// The scene file or dict the scene was made from, if it was.
    fn scene_file(&self) -> Option<&SceneFile> {
        match &self.request.spec {
            SceneSpec::File(file) => Some(file),
            _ => None,
        }
    }

    /// The scene built with the mesh file `options` unless a render says
    /// otherwise; refused for a scene that is not a mesh file.
    fn with_mesh(mut self, options: MeshOptions) -> PyResult<Scene> {
        self.check_mesh_options(options)?;
        self.request.mesh = options;
        Ok(self)
    }

    /// The scene playing the glTF animation `choice` names (`animation=`);
    /// a `ValueError` for a name or index the file lacks, or a scene that is not a glTF file.
    fn with_animation(mut self, choice: Option<&request::AnimationChoice>) -> PyResult<Scene> {
        self.request = self.request.with_animation(choice, Naming::Keywords).map_err(|e| PyValueError::new_err(e.0))?;
        Ok(self)
    }

    /// Refuses mesh file `options` other than the default for a scene that is not a mesh file.
    fn check_mesh_options(&self, options: MeshOptions) -> PyResult<()> {
        let is_mesh = matches!(self.request.spec, SceneSpec::Mesh(_));
        request::check_mesh_options(is_mesh, &self.request.name, options, Naming::Keywords).map_err(|e| PyValueError::new_err(e.0))
    }

    /// The core scene (for any image size), built once and kept.
    pub fn core(&self, py: Python<'_>) -> PyResult<Arc<CoreScene>> {
        self.core_and_warnings(py, self.request.mesh).map(|(scene, _)| scene)
    }

    /// The core scene built with `options` and its mesh files' warnings, built
    /// once and kept. The build that is kept gives each warning to Python's
    /// `warnings.warn` once.
    fn core_and_warnings(&self, py: Python<'_>, options: MeshOptions) -> PyResult<Kept> {
        let found = |kept: &[(MeshOptions, Kept)]| kept.iter().find(|(o, _)| *o == options).map(|(_, k)| k.clone());
        if let Some(built) = found(&self.built.lock().map_err(|_| SceneError::new_err("scene cache poisoned"))?) {
            return Ok(built);
        }
        // Building reads mesh files and builds BVHs: let other Python threads run.
        // Two threads may both build; the first to finish is kept.
        let (scene, warnings) = py.allow_threads(|| self.build_core(options, None))?;
        let built = (Arc::new(scene), Arc::new(warnings));
        let (kept, first) = {
            let mut kept = self.built.lock().map_err(|_| SceneError::new_err("scene cache poisoned"))?;
            match found(&kept) {
                Some(earlier) => (earlier, false),
                None => {
                    kept.push((options, built.clone()));
                    (built, true)
                }
            }
        };
        if first {
            warn_each(py, &kept.1)?;
        }
        Ok(kept)
    }

    /// Builds the scene with the mesh file `options`, at `frame` of its
    /// animation (`None`: the first frame).
    fn build_core(&self, options: MeshOptions, frame: Option<i64>) -> PyResult<(CoreScene, Vec<String>)> {
        // The request layer builds what a job renders, as for the command line
        // (a dict's errors read `scene dict: key.path: message`).
        let request = SceneRequest { mesh: options, ..self.request.clone() };
        let built = request.build_frame(frame).map_err(|e| SceneError::new_err(e.0))?;
        Ok(self.with_own_camera(built.scene, built.warnings))
    }

    /// `scene` seen by the camera given with `with_camera`, if one was.
    fn with_own_camera(&self, mut scene: CoreScene, warnings: Vec<String>) -> (CoreScene, Vec<String>) {
        if let Some((_, camera)) = &self.camera {
            scene.settings.camera = camera.clone();
        }
        (scene, warnings)
    }

    /// A scene file (read now) or a mesh file (read when built), by extension.
    fn read_file(path: PathBuf) -> PyResult<Scene> {
        match request::file_kind(&path).map_err(|e| PyValueError::new_err(e.0))? {
            FileKind::Scene(format) => Scene::from_scene_file(SceneFile::read_format(&path, format, &[]).map_err(load_error)?, None),
            FileKind::Mesh => {
                if !path.is_file() {
                    return Err(pyo3::exceptions::PyFileNotFoundError::new_err(format!("{}: no such file", path.display())));
                }
                Ok(Scene::mesh(std::path::absolute(&path).unwrap_or(path)))
            }
        }
    }

    fn from_dict_with(py: Python<'_>, dict: &Bound<'_, PyAny>, base_dir: Option<PathBuf>) -> PyResult<Scene> {
        if !dict.is_instance_of::<PyDict>() {
            return Err(pyo3::exceptions::PyTypeError::new_err(format!("a scene dict must be a dict, got {}", dict.get_type().name()?)));
        }
        let plain = convert::plain(dict)?;
        let description = SceneDescription::from_table(convert::table(plain.bind(py), "")?).map_err(dict_param_error)?;
        let base_dir = match base_dir {
            Some(dir) => dir,
            None => std::env::current_dir().map_err(|e| SceneError::new_err(format!("cannot read the current directory: {e}")))?,
        };
        let file = SceneFile { description, source: FileSource::for_dict(base_dir) };
        Scene::from_scene_file(file, Some(plain))
    }

    /// A mesh file, read when built.
    fn mesh(path: PathBuf) -> Scene {
        let name = path.display().to_string();
        Scene::new(SceneRequest { spec: SceneSpec::Mesh(path), name, defaults: program_defaults(), mesh: MeshOptions::default() }, None)
    }
}

#[pymethods]
impl Scene {
    /// A scene from a built-in name (`lamplight.builtin_names()`), a scene file
    /// (`.toml`) or a mesh file (`.obj`, `.ply`, `.gltf`, `.glb`): a string with no
    /// path separator and no extension is a built-in name, as on the command line.
    #[new]
    fn py_new(scene: &Bound<'_, PyAny>) -> PyResult<Scene> {
        if scene.is_instance_of::<PyDict>() {
            return Scene::from_dict_with(scene.py(), scene, None);
        }
        let text: PathBuf = scene.extract().map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err(format!(
                "a scene is a built-in name, a file path, a dict or a lamplight.Scene, got {}",
                scene.get_type().name().map(|n| n.to_string()).unwrap_or_default()
            ))
        })?;
        let arg = text.to_string_lossy().into_owned();
        if request::names_builtin(&arg) {
            return Scene::builtin(&arg);
        }
        Scene::read_file(text)
    }

    /// The built-in scene `name`.
    #[staticmethod]
    fn builtin(name: &str) -> PyResult<Scene> {
        let b = builtin::find(name).ok_or_else(|| PyValueError::new_err(builtin::unknown(name)))?;
        Ok(Scene::new(SceneRequest::builtin(b), None))
    }

    /// A scene file (`.toml` or Mitsuba `.xml`, read now) or a mesh file (`.obj`,
    /// `.ply`, `.gltf`, `.glb`, read when the scene is built), by extension. A
    /// mesh file takes the keywords that decide how it is built (`smooth`,
    /// `keep_auto_lights`: the settings table's build keywords), which a
    /// render's own override.
    #[staticmethod]
    #[pyo3(signature = (path, **settings))]
    fn from_file(path: PathBuf, settings: Option<&Bound<'_, PyDict>>) -> PyResult<Scene> {
        let options = crate::settings::mesh_options(settings, "from_file")?;
        let animation = crate::settings::animation_choice(settings, "from_file")?;
        Scene::read_file(path)?.with_mesh(options)?.with_animation(animation.as_ref())
    }

    /// Scene text in the native TOML format; relative mesh paths resolve against
    /// `base_dir` (default: the current directory).
    #[staticmethod]
    #[pyo3(signature = (text, base_dir=None))]
    fn from_toml(text: &str, base_dir: Option<PathBuf>) -> PyResult<Scene> {
        let dir = match base_dir {
            Some(dir) => dir,
            None => std::env::current_dir().map_err(|e| SceneError::new_err(format!("cannot read the current directory: {e}")))?,
        };
        Scene::from_scene_file(SceneFile::parse(&dir.join("<text>.toml"), text).map_err(load_error)?, None)
    }

    /// A scene from a dict with the structure of a scene file (see
    /// `docs/scene-format.md`); relative mesh paths resolve against `base_dir`
    /// (default: the current directory).
    #[staticmethod]
    #[pyo3(signature = (scene, base_dir=None))]
    fn from_dict(py: Python<'_>, scene: &Bound<'_, PyAny>, base_dir: Option<PathBuf>) -> PyResult<Scene> {
        Scene::from_dict_with(py, scene, base_dir)
    }

    /// The same scene seen by another camera: `camera` is a dict with the keys
    /// of a scene file's `[camera]` table.
    fn with_camera(&self, py: Python<'_>, camera: &Bound<'_, PyAny>) -> PyResult<Scene> {
        let plain = convert::plain(camera)?;
        let table = convert::table(plain.bind(py), "camera")?;
        let desc = Node::from_table(table, "camera", Some("perspective"), false).map_err(dict_param_error)?;
        // Built now, so that a bad camera fails here rather than at the first render.
        let camera = lamplight_scene::instantiate::camera::camera(&desc).map_err(dict_param_error)?;
        let dict = self.dict.as_ref().map(|d| d.clone_ref(py));
        Ok(Scene { camera: Some((plain, camera)), ..Scene::new(self.request.clone(), dict) })
    }

    /// What the scene was made from: `"builtin"`, `"file"`, `"dict"` or `"mesh"`.
    #[getter]
    fn kind(&self) -> &'static str {
        match &self.request.spec {
            SceneSpec::Builtin(_) => "builtin",
            SceneSpec::File(_) if self.dict.is_some() => "dict",
            SceneSpec::File(_) => "file",
            SceneSpec::Mesh(_) => "mesh",
        }
    }

    /// The built-in name, the file's path, or a copy of the dict.
    #[getter]
    fn source(&self, py: Python<'_>) -> PyResult<PyObject> {
        if let Some(dict) = &self.dict {
            return convert::plain(dict.bind(py));
        }
        Ok(match &self.request.spec {
            SceneSpec::Builtin(b) => b.name.into_pyobject(py)?.into_any().unbind(),
            SceneSpec::File(file) => file.source.path.clone().into_pyobject(py)?.into_any().unbind(),
            SceneSpec::Mesh(path) => path.clone().into_pyobject(py)?.into_any().unbind(),
        })
    }

    /// The folder relative mesh paths resolve against (`None` for built-in scenes).
    #[getter]
    fn base_dir(&self) -> Option<PathBuf> {
        match &self.request.spec {
            SceneSpec::Builtin(_) => None,
            SceneSpec::File(file) => Some(file.source.dir()),
            SceneSpec::Mesh(path) => Some(path.parent().map(Path::to_path_buf).unwrap_or_default()),
        }
    }

    /// Mesh files the scene reads, as written (relative to `base_dir` unless absolute).
    fn mesh_files(&self) -> Vec<String> {
        match &self.request.spec {
            SceneSpec::Builtin(_) => Vec::new(),
            SceneSpec::File(file) => {
                let mut files: Vec<String> = file
                    .description
                    .meshes
                    .iter()
                    .filter_map(|m| match m.value.get("file").map(|e| &e.item.value) {
                        Some(lamplight_core::params::Value::String(f)) => Some(f.clone()),
                        _ => None,
                    })
                    .collect();
                files.dedup();
                files
            }
            SceneSpec::Mesh(path) => vec![path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default()],
        }
    }

    /// The scene file's text (`None` unless the scene came from a `.toml` file or text).
    #[getter]
    fn text(&self) -> Option<String> {
        self.scene_file().and_then(|file| file.source.text.clone())
    }

    /// The replacement camera given to `with_camera`, or `None`.
    #[getter]
    fn camera(&self, py: Python<'_>) -> PyResult<Option<PyObject>> {
        self.camera.as_ref().map(|(dict, _)| convert::plain(dict.bind(py))).transpose()
    }

    /// The scene's `[animation]` as `{"frames": (start, end), "fps": fps}`,
    /// `None` for a scene that does not move.
    #[getter(animation)]
    fn animation_dict<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(a) = self.animation() else { return Ok(None) };
        let d = PyDict::new(py);
        d.set_item("frames", (a.start, a.end))?;
        d.set_item("fps", a.fps)?;
        Ok(Some(d))
    }

    /// The settings a render uses when it does not say: `width`, `height`,
    /// `spp`, `seed` and `integrator`, `transfer`, how the scene's PNGs
    /// store values (`"srgb"` or `"linear"`), and `crop`, the part
    /// `(x0, y0, width, height)` of the image the scene renders (`None`: all).
    fn defaults<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let Defaults { size: (width, height), spp, seed, integrator, transfer, crop, denoise, .. } = self.request.defaults;
        d.set_item("width", width)?;
        d.set_item("height", height)?;
        d.set_item("spp", spp)?;
        d.set_item("seed", seed)?;
        d.set_item("integrator", integrator.name)?;
        d.set_item("transfer", if transfer == lamplight_scene::image_io::Transfer::Linear { "linear" } else { "srgb" })?;
        d.set_item("crop", crop.map(|c| (c.x0, c.y0, c.width, c.height)))?;
        d.set_item("denoise", denoise)?;
        Ok(d)
    }

    /// Builds the scene now (one build serves every image size; `width` and
    /// `height` are accepted for compatibility), so that errors show here and the
    /// first render starts at once.
    #[pyo3(signature = (width=None, height=None))]
    fn build(&self, py: Python<'_>, width: Option<u32>, height: Option<u32>) -> PyResult<()> {
        let _ = (width, height);
        self.core(py).map(|_| ())
    }

    /// What the importers skipped in the scene's mesh files (texture
    /// coordinates, unsupported glTF parts, ...), one line each, `FILE: what`.
    /// Building the scene (here, or at its first render) also gives each to
    /// `warnings.warn` once.
    #[getter]
    fn warnings(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        Ok(self.core_and_warnings(py, self.request.mesh)?.1.as_ref().clone())
    }

    /// Number of objects (placed shapes) in the scene; primitive ids run below it.
    fn object_count(&self, py: Python<'_>) -> PyResult<usize> {
        Ok(self.core(py)?.objects.len())
    }

    /// Nearest hits of rays `origins[i] + s * directions[i]`, `t = s |directions[i]|`
    /// the distance: see `lamplight.Scene.intersect` in the type stubs.
    #[pyo3(signature = (origins, directions, threads=None, errors=false))]
    fn intersect<'py>(
        &self,
        py: Python<'py>,
        origins: &Bound<'py, PyAny>,
        directions: &Bound<'py, PyAny>,
        threads: Option<Bound<'py, PyAny>>,
        errors: bool,
    ) -> PyResult<Bound<'py, PyTuple>> {
        let threads = crate::render::threads_arg(threads.as_ref())?;
        let scene = self.core(py)?;
        crate::intersect::intersect(py, &scene, origins, directions, threads, errors)
    }

    /// Why pixel `(x, y)` has its colour: the ray tree of each sample (Whitted)
    /// or its paths (path tracer), as dicts and lists; see the type stubs.
    #[pyo3(signature = (x, y, sample=None, **settings))]
    fn explain<'py>(
        &self,
        py: Python<'py>,
        x: Bound<'py, PyAny>,
        y: Bound<'py, PyAny>,
        sample: Option<Bound<'py, PyAny>>,
        settings: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<PyObject> {
        crate::explain::explain(py, self, (x, y), sample, settings)
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(PyObject, Bound<'py, PyTuple>)> {
        let from_state = py.import("lamplight._lamplight")?.getattr("scene_from_state")?.unbind();
        let camera = self.camera(py)?;
        let mesh = (self.request.mesh.smooth, self.request.mesh.auto_lights.name(), self.request.mesh.animation);
        let state = match (&self.request.spec, &self.dict) {
            (SceneSpec::Builtin(b), _) => ("builtin", b.name.into_pyobject(py)?.into_any().unbind(), None, camera, mesh),
            (SceneSpec::File(file), Some(dict)) => ("dict", dict.clone_ref(py), Some(file.source.dir()), camera, mesh),
            (SceneSpec::File(file), None) => {
                let text = file.source.text.clone().unwrap_or_default();
                ("file", text.into_pyobject(py)?.into_any().unbind(), Some(file.source.path.clone()), camera, mesh)
            }
            (SceneSpec::Mesh(path), _) => ("mesh", path.clone().into_pyobject(py)?.into_any().unbind(), None, camera, mesh),
        };
        Ok((from_state, (state,).into_pyobject(py)?))
    }

    fn __repr__(&self) -> String {
        let camera = if self.camera.is_some() { ", camera replaced" } else { "" };
        match &self.request.spec {
            SceneSpec::Builtin(b) => format!("lamplight.Scene(builtin {:?}{camera})", b.name),
            SceneSpec::File(file) if self.dict.is_some() => {
                format!("lamplight.Scene(dict with {} top-level objects{camera})", file.description.objects.len())
            }
            SceneSpec::File(file) => format!("lamplight.Scene(file {:?}{camera})", file.source.path.display().to_string()),
            SceneSpec::Mesh(path) => format!("lamplight.Scene(mesh {:?}{camera})", path.display().to_string()),
        }
    }
}

impl Scene {
    /// The `[animation]` of an animated scene file or dict, or the frames of
    /// the animation of a glTF file that plays (its first unless `animation=` chose one).
    pub fn animation(&self) -> Option<lamplight_scene::description::Animation> {
        self.request.animation()
    }

    /// The settings a render uses when it does not say.
    pub fn settings(&self) -> &Defaults {
        &self.request.defaults
    }

    /// A fresh core scene, not cached (a render that changes it, such as one with
    /// its own environment map, takes this).
    /// Its warnings go to `warnings.warn` unless a kept build gave them already.
    pub fn fresh_core(&self, py: Python<'_>, options: MeshOptions) -> PyResult<CoreScene> {
        self.fresh_core_at(py, options, None)
    }

    /// [`Scene::fresh_core`] at `frame` of an animated scene.
    fn fresh_core_at(&self, py: Python<'_>, options: MeshOptions, frame: Option<i64>) -> PyResult<CoreScene> {
        let (scene, warnings) = py.allow_threads(|| self.build_core(options, frame))?;
        if !self.built.lock().map_err(|_| SceneError::new_err("scene cache poisoned"))?.iter().any(|(o, _)| *o == options) {
            warn_each(py, &warnings)?;
        }
        Ok(scene)
    }

    /// The core scene `job` renders, built with the mesh file options of
    /// `request` over the scene's own: the kept build (the first frame of an
    /// animated scene), or a fresh one of the job's frame, or lit by its
    /// environment map.
    pub fn core_for(&self, py: Python<'_>, job: &lamplight_scene::request::Job, request: &Request) -> PyResult<Arc<CoreScene>> {
        let mut options = request.mesh_options(self.request.mesh);
        self.check_mesh_options(options)?;
        if let Some(choice) = &request.animation {
            let chosen = self.request.clone().with_animation(Some(choice), Naming::Keywords);
            options.animation = chosen.map_err(|e| PyValueError::new_err(e.0))?.mesh.animation;
        }
        let other_frame = match (self.animation(), job.frame) {
            (Some(a), Some(frame)) => frame != a.start,
            _ => false,
        };
        if job.environment.is_none() && !other_frame {
            return self.core_and_warnings(py, options).map(|(scene, _)| scene);
        }
        let mut fresh = self.fresh_core_at(py, options, job.frame)?;
        job.prepare(&mut fresh).map_err(|e| PyValueError::new_err(e.0))?;
        Ok(Arc::new(fresh))
    }
}

/// Gives each importer warning to Python's `warnings.warn` (a `UserWarning`).
fn warn_each(py: Python<'_>, warnings: &[String]) -> PyResult<()> {
    let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
    for warning in warnings {
        let message = std::ffi::CString::new(warning.replace('\0', " ")).expect("no NUL left");
        PyErr::warn(py, category.as_any(), &message, 1)?;
    }
    Ok(())
}

/// The pickled state of a [`Scene`]: kind, payload, path, camera and mesh file options.
type State<'py> = (String, Bound<'py, PyAny>, Option<PathBuf>, Option<Bound<'py, PyAny>>, (bool, String, Option<usize>));

/// Rebuilds a pickled [`Scene`] from `(kind, payload, path, camera, (smooth, keep_auto_lights, animation))`.
#[pyfunction]
pub fn scene_from_state(py: Python<'_>, state: &Bound<'_, PyTuple>) -> PyResult<Scene> {
    let (kind, payload, path, camera, (smooth, auto_lights, animation)): State<'_> = state.extract()?;
    let auto_lights = auto_lights.parse().map_err(PyValueError::new_err)?;
    let mesh = MeshOptions { smooth, auto_lights, animation };
    let scene = match kind.as_str() {
        "builtin" => Scene::builtin(&payload.extract::<String>()?)?,
        "file" => {
            let path = path.ok_or_else(|| PyValueError::new_err("a pickled scene file needs its path"))?;
            Scene::from_scene_file(SceneFile::parse(&path, &payload.extract::<String>()?).map_err(load_error)?, None)?
        }
        "dict" => Scene::from_dict_with(py, &payload, path)?,
        "mesh" => Scene::mesh(payload.extract()?),
        other => return Err(PyValueError::new_err(format!("unknown pickled scene kind {other:?}"))),
    };
    let scene = scene.with_mesh(mesh)?;
    match camera {
        Some(camera) => scene.with_camera(py, &camera),
        None => Ok(scene),
    }
}
