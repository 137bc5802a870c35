//! A render request, resolved in one place for the command line and Python.
//!
//! A front end fills a [`Request`] with what the user gave (every field
//! optional) and names the scene ([`SceneRequest::resolve`]: a built-in name, a
//! scene file of any format, a mesh file, or an already parsed file or dict).
//! [`Request::resolve`] then applies the precedence (the request over the
//! scene's own settings over the defaults) and the limits ([`limits`]), and
//! [`Job::run`] renders, with the environment map and the extra layers, so
//! that everything the binary can do reaches Python too. Messages name the
//! option as the front end spells it ([`Naming`]: `--max-depth` or `max_depth`).

use std::path::{Path, PathBuf};
use std::time::Duration;

use lamplight_core::film::Filter;
use lamplight_core::integrators;
use lamplight_core::{PixelWindow, RenderOptions, Scene};

use crate::builtin::{self, Builtin};
use crate::import;
pub use crate::import::gltf_choice::AnimationChoice;
use crate::instantiate::{imported, Built, SceneFile};
pub use imported::{AutoLights, MeshOptions};

mod defaults;
mod layer;
mod output;
mod sampling;
mod scene_arg;
pub use defaults::{program_defaults, Defaults};
pub use layer::Layer;
pub use output::{write, DisplayTransform, Rendered};
pub use sampling::{AntialiasRequest, NOISE_DEFAULT_SPP, NOISE_DEFAULT_THRESHOLD};
pub use scene_arg::{file_kind, names_builtin, FileKind};

pub mod frames;
pub mod limits;
pub mod video;

/// Memory the film takes per pixel: its sums and squares and the image.
pub const FILM_BYTES_PER_PIXEL: u64 = 96;
/// Memory each extra layer (variance, albedo, ...) takes per pixel.
pub const LAYER_BYTES_PER_PIXEL: u64 = 48;

/// How the front end spells its options, for messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Naming {
    /// Command-line flags: `--max-depth`.
    Flags,
    /// Python keywords: `max_depth`.
    Keywords,
}

impl Naming {
    /// `key` (a keyword such as `max_depth`) as this front end spells it.
    pub fn name(self, key: &str) -> String {
        match self {
            Naming::Flags => format!("--{}", key.replace('_', "-")),
            Naming::Keywords => key.to_string(),
        }
    }
}

/// A request that cannot be carried out: bad input, one line (exit code 2).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RequestError(pub String);

impl std::fmt::Display for RequestError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for RequestError {}

fn bad(message: impl Into<String>) -> RequestError {
    RequestError(message.into())
}

/// Where a scene comes from.
#[derive(Clone, Debug)]
pub enum SceneSpec {
    /// A built-in scene.
    Builtin(&'static Builtin),
    /// A scene file or dict, parsed.
    File(Box<SceneFile>),
    /// A mesh file for an importer.
    Mesh(PathBuf),
}

/// A scene named and read, with its own settings.
#[derive(Clone, Debug)]
pub struct SceneRequest {
    /// The scene.
    pub spec: SceneSpec,
    /// Its name in messages and default output names.
    pub name: String,
    /// Its settings.
    pub defaults: Defaults,
    /// How a mesh file rendered directly is built ([`SceneRequest::with_mesh_options`]).
    pub mesh: MeshOptions,
}

impl SceneRequest {
    /// The scene `arg` names: a built-in name (no path separator, no extension),
    /// a `.toml` scene file (read and parsed now, so that a bad file stops before
    /// any work), or a mesh file (read when built).
    pub fn resolve(arg: &str) -> Result<SceneRequest, RequestError> {
        SceneRequest::resolve_with(arg, &[])
    }

    /// [`SceneRequest::resolve`] with `-D name=value` definitions for formats that
    /// take parameters (Mitsuba XML's `$name`).
    pub fn resolve_with(arg: &str, defines: &[(String, String)]) -> Result<SceneRequest, RequestError> {
        if names_builtin(arg) {
            let b = builtin::find(arg).ok_or_else(|| bad(builtin::unknown(arg)))?;
            return Ok(SceneRequest::builtin(b));
        }
        let path = Path::new(arg);
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scene".into());
        match file_kind(path)? {
            FileKind::Scene(format) => {
                let file = SceneFile::read_format(path, format, defines).map_err(|e| bad(e.to_string()))?;
                SceneRequest::file(file, stem)
            }
            FileKind::Mesh => Ok(SceneRequest {
                spec: SceneSpec::Mesh(path.to_path_buf()),
                name: stem,
                defaults: program_defaults(),
                mesh: MeshOptions::default(),
            }),
        }
    }

    /// A built-in scene.
    pub fn builtin(b: &'static Builtin) -> SceneRequest {
        SceneRequest {
            spec: SceneSpec::Builtin(b),
            name: b.name.to_string(),
            // The registry's names are tested to be integrators (tests/native.rs).
            defaults: Defaults {
                size: b.default_size,
                integrator: integrators::find(b.integrator).unwrap_or(integrators::default_integrator()),
                transfer: b.transfer,
                spp: b.spp,
                ..program_defaults()
            },
            mesh: MeshOptions::default(),
        }
    }

    /// A parsed scene file or dict; its `[render]` settings are checked now.
    pub fn file(file: SceneFile, name: String) -> Result<SceneRequest, RequestError> {
        let s = file.settings().map_err(|e| bad(e.to_string()))?;
        let defaults = Defaults::from_settings(&s);
        Ok(SceneRequest { spec: SceneSpec::File(Box::new(file)), name, defaults, mesh: MeshOptions::default() })
    }

    /// The scene built with `options` when it is a mesh file rendered
    /// directly ([`MeshOptions`]: `--smooth`, `--keep-auto-lights`). A scene
    /// file says these itself (a mesh's `shading = "smooth"`, its own lights),
    /// so a choice other than the default is refused there rather than ignored.
    /// The animation chosen by [`SceneRequest::with_animation`] is kept unless `options` chooses one.
    pub fn with_mesh_options(mut self, options: MeshOptions, naming: Naming) -> Result<SceneRequest, RequestError> {
        check_mesh_options(matches!(self.spec, SceneSpec::Mesh(_)), &self.name, options, naming)?;
        self.mesh = MeshOptions { animation: options.animation.or(self.mesh.animation), ..options };
        Ok(self)
    }

    /// The scene playing the glTF animation `choice` names (`--animation
    /// Walk`, `animation=2`; `None`: the file's first): the frames, the
    /// render and `lamplight info` follow it. Only a glTF file rendered
    /// directly takes a choice (a scene file names its mesh's animation in
    /// `[meshes.NAME]`); a name or index the file lacks is one error listing
    /// the file's animations.
    pub fn with_animation(mut self, choice: Option<&AnimationChoice>, naming: Naming) -> Result<SceneRequest, RequestError> {
        let Some(choice) = choice else { return Ok(self) };
        let key = naming.name("animation");
        let path = match &self.spec {
            SceneSpec::Mesh(path) if import::gltf_choice::is_gltf(path) => path,
            SceneSpec::Mesh(path) => {
                return Err(bad(format!("{}: {key} applies to a glTF file (.gltf, .glb); this file has no animations", path.display())))
            }
            SceneSpec::File(_) => {
                return Err(bad(format!(
                    "{key} applies to a glTF file rendered directly (.gltf, .glb); '{}' is a scene file: give its glTF mesh `animation = {choice}` in [meshes.NAME]",
                    self.name
                )))
            }
            SceneSpec::Builtin(_) => {
                return Err(bad(format!("{key} applies to a glTF file rendered directly (.gltf, .glb); '{}' is a built-in scene", self.name)))
            }
        };
        let index = import::gltf_choice::resolve(path, choice, &key).map_err(|e| bad(e.to_string()))?;
        self.mesh.animation = Some(index);
        Ok(self)
    }

    /// Builds the scene (for any image size: the camera applies the aspect when rendering).
    pub fn build(&self) -> Result<Scene, RequestError> {
        self.build_with_warnings().map(|built| built.scene)
    }

    /// The scene `job` renders: built ([`SceneRequest::build_with_warnings`])
    /// and lit by the job's environment map ([`Job::prepare`]). The one way every
    /// front end (the command line's render and explain, the viewer) goes from a
    /// request to a scene that renders.
    pub fn instantiate(&self, job: &Job) -> Result<Built, RequestError> {
        crate::memory::set_limit(job.memory_budget);
        let mut built = self.build_frame(job.frame)?;
        job.reserve_film()?;
        job.prepare(&mut built.scene)?;
        Ok(built)
    }

    /// Builds the scene and keeps the warnings of the mesh files it read
    /// (`FILE: what`, each once), for the front end to show.
    pub fn build_with_warnings(&self) -> Result<Built, RequestError> {
        self.build_frame(None)
    }

    /// [`SceneRequest::build_with_warnings`] at frame `frame` of an animated
    /// scene file (`None`: its first frame); any other scene is the same at every frame.
    pub fn build_frame(&self, frame: Option<i64>) -> Result<Built, RequestError> {
        crate::memory::restart();
        match &self.spec {
            SceneSpec::Builtin(b) => (b.build)()
                .map(|scene| Built { scene, warnings: Vec::new() })
                .map_err(|e| bad(format!("cannot build scene '{}': {e}", b.name))),
            SceneSpec::File(file) => file.build_frame(frame).map_err(|e| bad(e.to_string())),
            SceneSpec::Mesh(path) => imported::load_frame(path, self.mesh, frame).map_err(|e| bad(e.to_string())),
        }
    }
}

impl SceneRequest {
    /// The scene's `[animation]`, when it is an animated scene file, or the
    /// frames of the animation of a glTF file that plays ([`MeshOptions::animation`],
    /// [`crate::import::gltf_choice::file_clip_frames`]).
    pub fn animation(&self) -> Option<crate::description::Animation> {
        match &self.spec {
            SceneSpec::File(file) => file.description.animation.clone(),
            SceneSpec::Mesh(path) => import::gltf_choice::file_clip_frames(path, self.mesh.animation.unwrap_or(0)),
            SceneSpec::Builtin(_) => None,
        }
    }
}

/// Refuses mesh file `options` other than the default for a scene `name`
/// that is not a mesh file rendered directly (`is_mesh`), naming the option as
/// the front end spells it ([`SceneRequest::with_mesh_options`]).
pub fn check_mesh_options(is_mesh: bool, name: &str, options: MeshOptions, naming: Naming) -> Result<(), RequestError> {
    let (key, instead) = if is_mesh {
        return Ok(());
    } else if options.smooth {
        ("smooth", "in a scene file, give the mesh `shading = \"smooth\"`")
    } else if options.auto_lights != AutoLights::Auto {
        ("keep_auto_lights", "a scene file is lit by the lights it states")
    } else {
        return Ok(());
    };
    let mesh_files = import::EXTENSIONS.iter().map(|e| format!(".{e}")).collect::<Vec<_>>().join(", ");
    Err(bad(format!("{} applies to a mesh file rendered directly ({mesh_files}); '{name}' is not one: {instead}", naming.name(key))))
}

/// What the user asked for; `None` leaves a setting to the scene or the default.
#[derive(Clone, Debug, Default)]
pub struct Request {
    /// Image width; with only one side given the other keeps the scene's aspect.
    pub width: Option<u32>,
    /// Image height.
    pub height: Option<u32>,
    /// Samples per pixel (fixed supersampling; the most a noise threshold takes).
    pub spp: Option<u32>,
    /// Adaptive anti-aliasing (one-pass integrators).
    pub antialias: Option<AntialiasRequest>,
    /// Relative standard error at which the path tracer stops a pixel.
    pub noise_threshold: Option<f64>,
    /// Samples before a noise threshold stops any pixel.
    pub min_spp: Option<u32>,
    /// Depth limit.
    pub max_depth: Option<u32>,
    /// Worker threads (0: every core).
    pub threads: Option<usize>,
    /// Seed.
    pub seed: Option<u64>,
    /// Integrator name.
    pub integrator: Option<String>,
    /// Stop after the last complete pass before this many seconds.
    pub time_limit: Option<f64>,
    /// Largest channel a sample keeps (fireflies; biased), see [`RenderOptions::clamp`].
    pub clamp: Option<f64>,
    /// Pixel filter name (`box`, `gaussian`, `lanczos(lobes=2)`: [`Filter`]'s `from_str`).
    pub filter: Option<String>,
    /// Render only `(x0, y0, width, height)` of the image.
    pub window: Option<(u32, u32, u32, u32)>,
    /// An environment map (`.exr`, `.hdr`) lighting the scene.
    pub environment: Option<PathBuf>,
    /// Extra layers (variance, samples, albedo, normal, noisy, emitted).
    pub layers: Vec<Layer>,
    /// Denoise the image with Open Image Denoise ([`crate::denoise`]); `None`: as the scene says.
    pub denoise: Option<bool>,
    /// Folders the front end knows to hold the denoiser's library (Python's `pyoidn`), looked in
    /// before the others ([`crate::denoise::Denoiser::load`]).
    pub denoise_library_hints: Vec<PathBuf>,
    /// The memory budget in bytes ([`crate::memory`]); `None`: the scene's, else
    /// the default share of the machine's memory.
    pub memory_budget: Option<u64>,
    /// Smooth a mesh file's meshes that have no normals ([`MeshOptions::smooth`]);
    /// `None`: as the scene was made (not smoothed).
    pub smooth: Option<bool>,
    /// Whether a mesh file with lights keeps the automatic ones ([`AutoLights`]); `None`: as the scene was made (auto).
    pub keep_auto_lights: Option<AutoLights>,
    /// The frame of an animated scene (`None`: its first); see [`frames`].
    pub frame: Option<i64>,
    /// The animation of a glTF file rendered directly that plays (`None`: its
    /// first); applied by [`SceneRequest::with_animation`].
    pub animation: Option<AnimationChoice>,
}

/// A request checked and with every default resolved.
#[derive(Clone, Debug)]
pub struct Job {
    /// What the renderer is told.
    pub options: RenderOptions,
    /// The environment map to light the scene with.
    pub environment: Option<PathBuf>,
    /// Extra layers, each at most once, in the order asked.
    pub layers: Vec<Layer>,
    /// The denoiser, loaded when the request asks to denoise (so that a
    /// machine without it fails before rendering).
    pub denoiser: Option<std::sync::Arc<crate::denoise::Denoiser>>,
    /// The memory budget in bytes that building and rendering draw on.
    pub memory_budget: u64,
    /// The frame of an animated scene this job renders (`None`: its first).
    pub frame: Option<i64>,
}

impl Request {
    /// The mesh file options of this request over those a scene was made with (`base`).
    pub fn mesh_options(&self, base: MeshOptions) -> MeshOptions {
        MeshOptions {
            smooth: self.smooth.unwrap_or(base.smooth),
            auto_lights: self.keep_auto_lights.unwrap_or(base.auto_lights),
            animation: base.animation,
        }
    }

    /// Applies the precedence and the limits; messages spell options by `naming`.
    pub fn resolve(&self, defaults: &Defaults, naming: Naming) -> Result<Job, RequestError> {
        let n = |k: &str| naming.name(k);
        let d = defaults;
        let (width, height) = image_size(self.width, self.height, d.size, naming)?;
        if let Some(spp) = self.spp {
            limits::SPP.check(spp.into(), naming).map_err(bad)?;
        }
        if let Some(depth) = self.max_depth {
            limits::DEPTH.check(depth.into(), naming).map_err(bad)?;
        }
        let threads = self.threads.unwrap_or(0);
        limits::THREADS.check(threads as u64, naming).map_err(bad)?;
        let time_limit = match self.time_limit {
            None => None,
            Some(t) if t.is_finite() && t > 0.0 && t < limits::MAX_TIME_LIMIT => Some(Duration::from_secs_f64(t)),
            Some(t) => return Err(bad(format!("{} must be a positive number of seconds, got {t}", n("time_limit")))),
        };
        if let Some(c) = self.clamp {
            if !(c.is_finite() && c > 0.0) {
                return Err(bad(format!("{} must be a positive number (a radiance), got {c}", n("clamp"))));
            }
        }
        let integrator = match &self.integrator {
            None => d.integrator,
            Some(name) => integrators::find(name)
                .ok_or_else(|| bad(format!("{} must be {}, got {name:?}", n("integrator"), integrators::quoted_names())))?,
        };
        let filter: Filter = match &self.filter {
            None => d.filter.unwrap_or(Filter::Box),
            Some(name) => name.parse().map_err(|e: String| {
                // A known name with a bad parameter says which; any other, the names.
                if e.starts_with("unknown filter") {
                    bad(format!("{} must be {}, got {name:?}", n("filter"), lamplight_core::film::FILTER_NAMES))
                } else {
                    bad(format!("{}: {e}", n("filter")))
                }
            })?,
        };
        if self.filter.is_some() && filter != Filter::Box && !integrator.filters {
            return Err(bad(format!(
                "{} is for the path tracer ({} path); {} averages its samples over the pixel square (a box)",
                n("filter"),
                n("integrator"),
                integrator.name
            )));
        }
        let crop = d.crop;
        if let Some(c) = crop {
            // The crop is in pixels of the scene's film: at another size it would name other pixels.
            if (width, height) != d.size {
                return Err(bad(format!(
                    "the scene crops its {}x{} image to (x0={}, y0={}, width={}, height={}); {} and {} must keep that size \
                     (or remove [render] crop)",
                    d.size.0,
                    d.size.1,
                    c.x0,
                    c.y0,
                    c.width,
                    c.height,
                    n("width"),
                    n("height")
                )));
            }
        }
        let window = self.window.map(|(x0, y0, w, h)| PixelWindow { x0, y0, width: w, height: h });
        if let Some(w) = window {
            let inside = crop.unwrap_or(PixelWindow { x0: 0, y0: 0, width, height });
            if !w.is_inside(inside) {
                let of = match crop {
                    None => format!("the {width}x{height} image"),
                    Some(c) => format!("the scene's crop (x0={}, y0={}, width={}, height={})", c.x0, c.y0, c.width, c.height),
                };
                return Err(bad(format!(
                    "{} (x0={}, y0={}, width={}, height={}) must be non-empty and inside {of}",
                    n("window"),
                    w.x0,
                    w.y0,
                    w.width,
                    w.height
                )));
            }
        }
        let mut layers = Vec::new();
        for layer in &self.layers {
            if !layers.contains(layer) {
                layers.push(*layer);
            }
        }
        let denoise = self.denoise.unwrap_or(d.denoise);
        if layers.contains(&Layer::Noisy) && !denoise {
            return Err(bad(format!("the noisy layer is the image before denoising: it needs {}", n("denoise"))));
        }
        let denoiser = match denoise {
            false => None,
            true => Some(std::sync::Arc::new(crate::denoise::Denoiser::load(&self.denoise_library_hints).map_err(|e| bad(e.0))?)),
        };
        let (spp, adaptive) = sampling::resolve(self, d, integrator, naming)?;
        let seed = self.seed.unwrap_or(d.seed);
        if let Some(frame) = self.frame {
            frames::check_frame(frame).map_err(|e| bad(format!("{} {e}", n("frame"))))?;
        }
        let options = RenderOptions {
            width,
            height,
            spp,
            max_depth: self.max_depth,
            threads,
            seed,
            integrator,
            time_limit,
            filter,
            window,
            crop,
            clamp: self.clamp,
            adaptive,
        };
        let memory_budget = self.memory_budget.or(d.memory_budget).unwrap_or_else(crate::memory::default_limit);
        Ok(Job { options, environment: self.environment.clone(), layers, denoiser, memory_budget, frame: self.frame })
    }
}

impl Job {
    /// Applies the job's memory budget and takes the film's share of it
    /// ([`FILM_BYTES_PER_PIXEL`], [`LAYER_BYTES_PER_PIXEL`] for each extra
    /// layer), before the film is allocated.
    pub fn reserve_film(&self) -> Result<(), RequestError> {
        crate::memory::set_limit(self.memory_budget);
        let (w, h) = match self.options.window {
            Some(win) => (win.width, win.height),
            None => (self.options.width, self.options.height),
        };
        let pixels = w as u64 * h as u64;
        let per_pixel = FILM_BYTES_PER_PIXEL + LAYER_BYTES_PER_PIXEL * self.layers.len() as u64;
        crate::memory::reserve(pixels * per_pixel, || format!("the film of {w}x{h} pixels")).map_err(|e| bad(e.to_string()))
    }

    /// Adds the layers the scene itself asks for (`[render] variance`) when the
    /// output can hold them (`holds_layers`: an `.exr` file, or Python's dict of
    /// layers; PNG and PPM cannot), after those asked for.
    pub fn add_scene_layers(&mut self, defaults: &Defaults, holds_layers: bool) {
        if defaults.variance && holds_layers && !self.layers.contains(&Layer::Variance) {
            self.layers.push(Layer::Variance);
        }
    }
}

/// The image size: both sides given, one given (the other follows the default
/// aspect, rounded, at least 1), or the default.
pub fn image_size(width: Option<u32>, height: Option<u32>, default: (u32, u32), naming: Naming) -> Result<(u32, u32), RequestError> {
    for (key, value) in [("width", width), ("height", height)] {
        if value == Some(0) {
            return Err(bad(format!("{} must be at least 1", naming.name(key))));
        }
    }
    let (dw, dh) = (default.0 as f64, default.1 as f64);
    let scaled = |v: u32, ratio: f64| ((v as f64 * ratio).round().max(1.0)).min(u32::MAX as f64) as u32;
    let (w, h) = match (width, height) {
        (Some(w), Some(h)) => (w, h),
        (Some(w), None) => (w, scaled(w, dh / dw)),
        (None, Some(h)) => (scaled(h, dw / dh), h),
        (None, None) => default,
    };
    if w as u64 * h as u64 > limits::MAX_PIXELS {
        return Err(bad(format!("image {w}x{h} is too large (at most {} pixels)", limits::MAX_PIXELS)));
    }
    Ok((w, h))
}

#[cfg(test)]
mod tests;
