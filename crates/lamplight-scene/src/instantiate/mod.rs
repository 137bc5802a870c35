//! The third stage, instantiate: a [`SceneDescription`] to a core [`Scene`]:
//! settings, the camera, materials and the node tree, every kind found through
//! [`crate::registry`] and every error a [`LoadError`] at the place of the key
//! it concerns. (Named for what it does; `build/` reads as build output.)

use std::path::Path;

use lamplight_core::integrators::{self, IntegratorEntry};
use lamplight_core::math::Rgb;
use lamplight_core::params::{Param, ParamType as T, Params, Table};
use lamplight_core::{Scene, SceneBuilder};

use crate::description::SceneDescription;
use crate::error::LoadError;
use crate::formats::native::{self, Source};

pub mod camera;
pub mod environment;
pub mod implicit;
pub mod imported;
mod materials;
mod mesh_animation;
mod mesh_keys;
mod motion;
mod nodes;
pub mod studio;
pub(crate) mod transform;
pub mod viewer;

pub use mesh_keys::MESH_PARAMS;
pub use nodes::{MAX_NESTING, MAX_OBJECTS};

/// Image and integrator settings with every default resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Width in pixels (default 640).
    pub width: u32,
    /// Height in pixels (default 360).
    pub height: u32,
    /// Samples per pixel; `None` when the file does not say (then the default
    /// render is adaptive: anti-aliased Whitted, or one sample).
    pub spp: Option<u32>,
    /// `antialias` and `antialias_threshold`, when given.
    pub antialias: Option<crate::request::AntialiasRequest>,
    /// `noise_threshold`, when given.
    pub noise_threshold: Option<f64>,
    /// `min_spp`, when given.
    pub min_spp: Option<u32>,
    /// Depth limit (default 5).
    pub max_depth: u32,
    /// Segments before the path tracer's Russian roulette (default 4).
    pub rr_depth: u32,
    /// Weight cut-off (default 0).
    pub min_weight: f64,
    /// Seed (default 0).
    pub seed: u64,
    /// Integrator (default Whitted).
    pub integrator: &'static IntegratorEntry,
    /// How PNG and PPM outputs store the linear values.
    pub transfer: crate::image_io::Transfer,
    /// The path tracer's pixel filter, when given.
    pub filter: Option<lamplight_core::film::Filter>,
    /// The film's crop `[x, y, width, height]`, when given (checked inside the image).
    pub crop: Option<lamplight_core::PixelWindow>,
    /// Camera rays see emitters and the sky as black (default `false`).
    pub hide_emitters: bool,
    /// Which normal decides a hit's side (default the geometry's).
    pub sides: lamplight_core::scene::Sides,
    /// An `.exr` output holds the variance layer too (default `false`).
    pub variance: bool,
    /// The image is denoised (Open Image Denoise, default `false`).
    pub denoise: bool,
    /// The memory budget in bytes (`memory_budget = "4G"`), when given.
    pub memory_budget: Option<u64>,
}

/// Memory the scene's BVH takes per object (nodes and the object's box).
pub const BVH_BYTES_PER_OBJECT: u64 = 256;

/// Deepest `max_depth` a file may ask for: the renderer's limit (as the command line's `--max-depth`).
pub use lamplight_core::integrators::MAX_DEPTH_LIMIT;
/// Most pixels in an image: the renderer's limit.
pub use lamplight_core::MAX_PIXELS;
/// Most samples per pixel.
pub const MAX_SPP: u32 = 1 << 20;

/// The keys of `[render]`.
pub const RENDER_PARAMS: &[Param] = &[
    Param::new("width", T::Integer, "640", "pixels, >= 1", "image width (`--width`)"),
    Param::new("height", T::Integer, "360", "pixels, >= 1; width x height <= 2^28", "image height (`--height`)"),
    Param::new(
        "spp",
        T::Integer,
        "none",
        "1 to 2^20",
        "samples per pixel, stratified and jittered (`--spp`); without it Whitted anti-aliases adaptively and path samples each pixel to noise 0.05 (16 to 1024 samples)",
    ),
    Param::new(
        "antialias",
        T::Bool,
        "true",
        "",
        "adaptive anti-aliasing of one-pass (Whitted) renders without `spp`: 16 samples where a neighbour differs (POV-Ray's `+A`) (`--antialias`)",
    ),
    Param::new(
        "antialias_threshold",
        T::Number,
        "0.3",
        ">= 0",
        "difference from a neighbour, summed over channels, that refines a pixel (POV-Ray's `Antialias_Threshold`)",
    ),
    Param::new(
        "noise_threshold",
        T::Number,
        "none",
        "> 0",
        "path tracer: a pixel stops once its noise (standard error of its mean over the square root of its brightness) is below this, twice in a row (Cycles' noise threshold) (`--noise-threshold`); without it and without `spp`, 0.05",
    ),
    Param::new("min_spp", T::Integer, "16", "1 to spp", "path tracer with `noise_threshold` (or without `spp`): samples before any pixel stops (`--min-spp`)"),
    Param::new("max_depth", T::Integer, "5", "1 to 64, camera ray = 1", "ray depth limit (`--max-depth`)"),
    Param::new(
        "rr_depth",
        T::Integer,
        "4",
        "1 to 64, camera ray = 1",
        "path tracer: segments before Russian roulette starts (Mitsuba's `rr_depth`, counted the same); changes only the noise",
    ),
    Param::new("min_weight", T::Number, "0", ">= 0", "secondary rays of weight <= this are not traced"),
    Param::new("seed", T::Integer, "0", ">= 0", "seed of the per-sample random numbers (`--seed`)"),
    Param::new(
        "integrator",
        T::String,
        "\"whitted\"",
        "",
        "`\"whitted\"` (the lecture's recursive ray tracer) or `\"path\"` (path tracing with NEE and MIS) (`--integrator`)",
    ),
    Param::new(
        "transfer",
        T::String,
        "\"srgb\"",
        "",
        "how PNG and PPM store the values: `\"srgb\"`-encoded, or `\"linear\"` for display-referred numbers (POV-Ray's `File_Gamma 1`) (`--transfer`)",
    ),
    Param::new(
        "filter",
        T::String,
        "\"box\"",
        "",
        "path tracer: pixel filter, `\"box\"`, `\"tent\"` (radius 1 pixel), `\"gaussian\"` (sigma 0.5 pixel, cut at 2), `\"mitchell\"` (Mitchell-Netravali, B = C = 1/3, radius 2; `\"mitchell(B=0.5, C=0.25)\"`), `\"catmullrom\"` (radius 2) or `\"lanczos\"` (3 lobes; `\"lanczos(lobes=2)\"`, radius the lobes), as Mitsuba's: cut at the image's (or crop's) edge and renormalised; the last three have negative lobes (`--filter`)",
    ),
    Param::new(
        "crop",
        T::Array,
        "none",
        "[x, y, width, height] in pixels, inside the image",
        "render only this part of the `width x height` image, seen by the same camera (Mitsuba's `hdrfilm` crop window); samples stay inside it, so a wide filter is cut at its edges; `--window` then picks pixels inside it",
    ),
    Param::new(
        "variance",
        T::Bool,
        "false",
        "",
        "an `.exr` output (and Python's `image.layers`) also holds the variance of each pixel's mean, as `--exr-layers variance` (Mitsuba's `moment` integrator)",
    ),
    Param::new(
        "denoise",
        T::Bool,
        "false",
        "",
        "denoise the image with Intel Open Image Denoise, guided by albedo and normal layers (`--denoise`; `pip install pyoidn`, see docs/denoise.md)",
    ),
    Param::new(
        "memory_budget",
        T::String,
        "half the available memory",
        "a size such as \"4G\" or \"512M\" (powers of 1024), at least 16M",
        "the memory the meshes, textures, acceleration structures and film of this render may take together (`--memory-budget`; see Limits); the scene file's own meshes and textures are counted against it, what a Mitsuba XML reader reads while parsing against `--memory-budget` or the default",
    ),
    Param::new(
        "hide_emitters",
        T::Bool,
        "false",
        "",
        "camera rays go through emitting surfaces and see black where they leave the scene (no sky, no background); the light of both still reaches the scene (Mitsuba's `hide_emitters`)",
    ),
    Param::new(
        "sides",
        T::String,
        "\"geometric\"",
        "\"geometric\" or \"shading\"",
        "which normal decides a hit's side where a mesh's interpolated shading normal faces away from the ray the geometry faces: the geometry's (lamplight's, no light leaks), or the shading normal's, as Mitsuba 3 renders (a one-sided material is black there); the Mitsuba XML reader sets `\"shading\"`",
    ),
];

/// The top-level values.
pub const SCENE_PARAMS: &[Param] = &[
    Param::new("ambient", T::Color, "0", "radiance", "ambient radiance `La`; each surface reflects `ka * C * La` (Whitted only)"),
    Param::new(
        "background",
        T::Color,
        "0",
        "radiance",
        "radiance of rays that hit nothing; under path tracing a uniform sky that lights the scene",
    ),
    Param::new("environment", T::Table, "none", "", "an environment light in place of `background` (see below)"),
];

/// A built core scene and what its importers warned about: the parts of its
/// mesh files that were not used, one line each, `FILE: what`, each once.
#[derive(Debug)]
pub struct Built {
    /// The scene, for any image size.
    pub scene: Scene,
    /// Warnings in the order they were found.
    pub warnings: Vec<String>,
}

/// A scene file read and parsed, ready to build at any image size.
#[derive(Clone, Debug)]
pub struct SceneFile {
    /// The description.
    pub description: SceneDescription,
    /// Where it came from.
    pub source: Source,
}

impl SceneFile {
    /// Reads and parses the native scene file at `path`.
    pub fn read(path: &Path) -> Result<SceneFile, LoadError> {
        let (description, source) = native::read(path)?;
        Ok(SceneFile { description, source })
    }

    /// Reads the scene file at `path` in the format `format` (see
    /// [`crate::formats::FORMATS`]), with `-D name=value` definitions.
    pub fn read_format(path: &Path, format: &crate::formats::Format, defines: &[(String, String)]) -> Result<SceneFile, LoadError> {
        let (description, source) = (format.read)(path, defines)?;
        Ok(SceneFile { description, source })
    }

    /// Parses native scene text, reporting errors against `path`.
    pub fn parse(path: &Path, text: &str) -> Result<SceneFile, LoadError> {
        let (description, source) = native::parse(path, text.to_string())?;
        Ok(SceneFile { description, source })
    }

    /// The file's `[render]` settings with defaults filled in.
    pub fn settings(&self) -> Result<Settings, LoadError> {
        settings(&self.description, &self.source)
    }

    /// Builds the core scene (for any image size: the camera applies the aspect when rendering).
    pub fn build(&self) -> Result<Scene, LoadError> {
        build(&self.description, &self.source)
    }

    /// Builds the core scene and keeps the warnings of the mesh files it read.
    pub fn build_with_warnings(&self) -> Result<Built, LoadError> {
        build_with_warnings(&self.description, &self.source)
    }

    /// Builds frame `frame` of an animated scene ([`build_frame`]).
    pub fn build_frame(&self, frame: Option<i64>) -> Result<Built, LoadError> {
        build_frame(&self.description, &self.source, frame)
    }
}

/// The description's settings with defaults filled in, checked.
pub fn settings(desc: &SceneDescription, source: &Source) -> Result<Settings, LoadError> {
    let empty = Table::default();
    let table = desc.render.as_ref().unwrap_or(&empty);
    let mut p = Params::new("render", table);
    let read = |p: &mut Params<'_>| -> lamplight_core::params::ParamResult<Settings> {
        p.check_keys(RENDER_PARAMS, &[])?;
        let whole = |p: &mut Params<'_>, key: &str, max: u64, default: u64| -> lamplight_core::params::ParamResult<u64> {
            Ok(p.integer(key, 0..=max as i64)?.map_or(default, |v| v as u64))
        };
        let width = whole(p, "width", u32::MAX as u64, 640)? as u32;
        let height = whole(p, "height", u32::MAX as u64, 360)? as u32;
        if width == 0 || height == 0 || width as u64 * height as u64 > MAX_PIXELS {
            return Err(p.error(format!("image size {width}x{height} must be at least 1x1 and at most {MAX_PIXELS} pixels")));
        }
        let spp = p.integer("spp", 1..=MAX_SPP as i64)?.map(|v| v as u32);
        let threshold = p.number("antialias_threshold")?;
        if threshold.is_some_and(|t| !(t >= 0.0)) {
            return Err(p.key_error("antialias_threshold", format!("must be a non-negative number, got {}", threshold.unwrap_or_default())));
        }
        let antialias = match (p.boolean("antialias")?, threshold) {
            (Some(false), _) => Some(crate::request::AntialiasRequest::Off),
            (None, None) => None,
            (_, t) => Some(crate::request::AntialiasRequest::On { threshold: t.unwrap_or(lamplight_core::Antialias::default().threshold) }),
        };
        let noise_threshold = p.number("noise_threshold")?;
        if noise_threshold.is_some_and(|t| !(t > 0.0)) {
            return Err(p.key_error("noise_threshold", format!("must be a positive number, got {}", noise_threshold.unwrap_or_default())));
        }
        let min_spp = p.integer("min_spp", 1..=MAX_SPP as i64)?.map(|v| v as u32);
        let max_depth = p.integer("max_depth", 1..=MAX_DEPTH_LIMIT as i64)?.unwrap_or(5) as u32;
        let rr_depth = p.integer("rr_depth", 1..=MAX_DEPTH_LIMIT as i64)?.unwrap_or(4) as u32;
        let min_weight = p.number_or("min_weight", 0.0)?;
        if min_weight < 0.0 {
            return Err(p.key_error("min_weight", format!("must be a non-negative number, got {min_weight}")));
        }
        let seed = whole(p, "seed", i64::MAX as u64, 0)?;
        let integrator = match p.string("integrator")? {
            None => integrators::default_integrator(),
            Some(name) => name.parse::<&integrators::IntegratorEntry>().map_err(|message| p.key_error("integrator", message))?,
        };
        let transfer = match p.choice("transfer", &["srgb", "linear"])? {
            "linear" => crate::image_io::Transfer::Linear,
            _ => crate::image_io::Transfer::Srgb,
        };
        let filter = match p.string("filter")? {
            None => None,
            Some(name) => Some(name.parse::<lamplight_core::film::Filter>().map_err(|e| {
                // A known name with a bad parameter says which; any other, the names.
                if e.starts_with("unknown filter") {
                    p.key_error("filter", format!("expected {}, got \"{name}\"", lamplight_core::film::FILTER_NAMES))
                } else {
                    p.key_error("filter", e)
                }
            })?),
        };
        let crop = crop(p, width, height)?;
        let hide_emitters = p.boolean("hide_emitters")?.unwrap_or(false);
        let sides = match p.string("sides")? {
            None | Some("geometric") => lamplight_core::scene::Sides::Geometric,
            Some("shading") => lamplight_core::scene::Sides::Shading,
            Some(other) => return Err(p.key_error("sides", format!("expected \"geometric\" or \"shading\", got \"{other}\""))),
        };
        let variance = p.boolean("variance")?.unwrap_or(false);
        let denoise = p.boolean("denoise")?.unwrap_or(false);
        let memory_budget = match p.string("memory_budget")? {
            None => None,
            Some(text) => Some(crate::memory::parse(text).map_err(|e| p.key_error("memory_budget", e))?),
        };
        Ok(Settings {
            width,
            height,
            spp,
            antialias,
            noise_threshold,
            min_spp,
            max_depth,
            rr_depth,
            min_weight,
            seed,
            integrator,
            transfer,
            filter,
            crop,
            hide_emitters,
            sides,
            variance,
            denoise,
            memory_budget,
        })
    };
    let settings = read(&mut p).map_err(|e| source.param_error(e))?;
    p.finish().map_err(|e| source.param_error(e))?;
    Ok(settings)
}

/// `[render] crop = [x, y, width, height]`: four whole numbers, a non-empty
/// rectangle inside the `width x height` image.
fn crop(p: &mut Params<'_>, width: u32, height: u32) -> lamplight_core::params::ParamResult<Option<lamplight_core::PixelWindow>> {
    use lamplight_core::params::Value;
    let Some(item) = p.item("crop") else { return Ok(None) };
    let whole: Option<Vec<i64>> = match &item.value {
        Value::Array(items) if items.len() == 4 => items
            .iter()
            .map(|i| match i.value {
                Value::Integer(v) => Some(v),
                _ => None,
            })
            .collect(),
        _ => None,
    };
    let Some(v) = whole else {
        return Err(p.key_error("crop", format!("expected [x, y, width, height] (four whole numbers), got {}", item.value.describe())));
    };
    let (x, y, w, h) = (v[0], v[1], v[2], v[3]);
    if x < 0 || y < 0 || w < 1 || h < 1 || x + w > width as i64 || y + h > height as i64 {
        return Err(p.key_error(
            "crop",
            format!("[{x}, {y}, {w}, {h}] must have x, y >= 0, width, height >= 1 and lie inside the {width}x{height} image"),
        ));
    }
    Ok(Some(lamplight_core::PixelWindow { x0: x as u32, y0: y as u32, width: w as u32, height: h as u32 }))
}

/// Builds the core scene (for any image size: the camera applies the aspect when rendering).
pub fn build(desc: &SceneDescription, source: &Source) -> Result<Scene, LoadError> {
    build_with_warnings(desc, source).map(|built| built.scene)
}

/// [`build`], keeping the warnings of the mesh files the scene reads. An
/// animated scene is built at its first frame.
pub fn build_with_warnings(desc: &SceneDescription, source: &Source) -> Result<Built, LoadError> {
    build_frame(desc, source, None)
}

/// Builds frame `frame` (`None`: the first of `[animation] frames`): the
/// static description of that frame ([`SceneDescription::at_frame`]), built as
/// any other. Errors found in it say the frame: `s.toml:9:20: frame 12: ...`.
/// A scene without `[animation]` is the same at every frame.
pub fn build_frame(desc: &SceneDescription, source: &Source, frame: Option<i64>) -> Result<Built, LoadError> {
    let Some(animation) = &desc.animation else { return build_static(desc, source, None) };
    let frame = frame.unwrap_or(animation.start);
    let in_frame = |e: LoadError| LoadError { message: format!("frame {frame}: {}", e.message), ..e };
    let at = desc.at_frame(frame as f64).map_err(|e| in_frame(source.param_error(e)))?;
    let seconds = animation.time(frame as f64, crate::description::animation::TimeUnit::Seconds);
    let shutter = motion::instants(desc, frame).map_err(|e| in_frame(source.param_error(e)))?;
    build_at(&at, source, &shutter, animation.shutter, Some(seconds)).map_err(in_frame)
}

fn build_static(desc: &SceneDescription, source: &Source, seconds: Option<f64>) -> Result<Built, LoadError> {
    build_at(desc, source, &motion::Instants::NONE, (0.0, 0.0), seconds)
}

/// Builds `desc` with no animation left in it, at the scene's time `seconds`
/// (its glTF meshes' animations; `None`: the scene has no `[animation]`), its
/// shapes moving as the descriptions of the shutter's instants place them
/// ([`motion`]).
fn build_at(
    desc: &SceneDescription,
    source: &Source,
    instants: &motion::Instants,
    shutter: (f64, f64),
    seconds: Option<f64>,
) -> Result<Built, LoadError> {
    let settings = settings(desc, source)?;
    // Each build counts afresh (a reload, another Python `Scene`); the limit
    // is the job's ([`crate::request::SceneRequest::instantiate`]).
    crate::memory::restart();
    let camera_node = desc.camera.as_ref().ok_or_else(|| LoadError::file(&source.path, "has no [camera] table, expected one"))?;
    let camera = camera::camera(camera_node).map_err(|e| source.param_error(e))?;
    let mut builder = SceneBuilder::with_camera(camera);
    let dir = source.dir();
    let (ambient, background, environment) = globals(&desc.globals, &dir).map_err(|e| source.param_error(e))?;
    builder.settings.ambient = ambient;
    builder.settings.background = background;
    builder.settings.environment = environment;
    builder.settings.max_depth = settings.max_depth;
    builder.settings.hide_emitters = settings.hide_emitters;
    builder.settings.sides = settings.sides;
    builder.settings.rr_depth = settings.rr_depth;
    builder.settings.min_weight = settings.min_weight;
    builder.settings.shutter = shutter;
    // Texture files are found beside the scene file, and decoded once each,
    // whether a material or a light reads them.
    let images = crate::texture_files::ImageFiles::new(&dir);
    let materials = materials::add_all(desc, source, &mut builder, &images)?;
    let textures = lamplight_core::materials::Textures { kinds: crate::registry::TEXTURES, images: Some(&images), materials: None };
    for (name, &index) in &materials {
        builder.name_material(index, name);
    }
    let mut warnings = source.warnings.clone();
    warnings.extend(nodes::add_all(desc, source, &mut builder, materials, &textures, seconds, instants)?);
    let objects = builder.object_count() as u64;
    crate::memory::reserve(objects * BVH_BYTES_PER_OBJECT, || format!("the scene's BVH over {objects} objects"))
        .map_err(|e| LoadError::file(&source.path, e.to_string()))?;
    let scene = builder.build().map_err(|e| LoadError::file(&source.path, e.to_string()))?;
    Ok(Built { scene, warnings })
}

type Globals = (Rgb, Rgb, Option<std::sync::Arc<lamplight_core::lights::Environment>>);

fn globals(table: &Table, dir: &Path) -> lamplight_core::params::ParamResult<Globals> {
    let mut p = Params::new("scene", table);
    p.check_keys(SCENE_PARAMS, &[])?;
    let mut colour = |key: &str| -> lamplight_core::params::ParamResult<Rgb> {
        let c = p.color_or(key, Rgb::ZERO)?;
        if c.min_element() < 0.0 {
            return Err(p.key_error(key, format!("must be non-negative, got {c}")));
        }
        Ok(c)
    };
    let ambient = colour("ambient")?;
    let background = colour("background")?;
    let environment = match p.table("environment")? {
        Some(env) => Some(environment::read(env, dir)?),
        None => None,
    };
    p.finish()?;
    Ok((ambient, background, environment))
}
