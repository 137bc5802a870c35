//! A [`SceneDescription`] to a core [`Scene`]: defaults, the camera, materials,
//! and the node tree (the private `nodes` and `shapes` modules), with every error a [`LoadError`] at the place
//! of the entry it concerns.

use std::collections::BTreeMap;
use std::path::Path;

use lamplight_core::camera::{Fit, Fov, Perspective};
use lamplight_core::integrators::{self, IntegratorEntry};
use lamplight_core::materials::{Material, Metal, Reflection, Refraction, Texture};
use lamplight_core::math::{Rgb, Vec3};
use lamplight_core::{Scene, SceneBuilder};

use crate::description::{CameraDesc, Located, MaterialDesc, ReflectionDesc, RefractionDesc, SceneDescription, Triple};
use crate::error::LoadError;
use crate::formats::native::{self, Source};

pub mod imported;
mod nodes;
mod shapes;
mod transform;

/// Image and integrator settings with every default resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Width in pixels (default 640).
    pub width: u32,
    /// Height in pixels (default 360).
    pub height: u32,
    /// Samples per pixel (default 1).
    pub spp: u32,
    /// Depth limit (default 5).
    pub max_depth: u32,
    /// Weight cut-off (default 0).
    pub min_weight: f64,
    /// Seed (default 0).
    pub seed: u64,
    /// Integrator (default Whitted).
    pub integrator: &'static IntegratorEntry,
}

/// Deepest `max_depth` a file may ask for (as the command line's `--max-depth`).
pub const MAX_DEPTH_LIMIT: u32 = 64;
/// Most pixels in an image (the renderer's limit).
pub const MAX_PIXELS: u64 = 1 << 28;

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

    /// Parses native scene text, reporting errors against `path`.
    pub fn parse(path: &Path, text: &str) -> Result<SceneFile, LoadError> {
        let (description, source) = native::parse(path, text.to_string())?;
        Ok(SceneFile { description, source })
    }

    /// The file's `[render]` settings with defaults filled in.
    pub fn settings(&self) -> Result<Settings, LoadError> {
        settings(&self.description, &self.source)
    }

    /// Builds the core scene (for any image size).
    pub fn build(&self) -> Result<Scene, LoadError> {
        build(&self.description, &self.source)
    }
}

/// The description's settings with defaults filled in, checked.
pub fn settings(desc: &SceneDescription, source: &Source) -> Result<Settings, LoadError> {
    let default = Located::new(Default::default());
    let render = desc.render.as_ref().unwrap_or(&default);
    let err = |m: String| source.error(render.span.as_ref(), m);
    let r = &render.value;
    let s = Settings {
        width: r.width.unwrap_or(640),
        height: r.height.unwrap_or(360),
        spp: r.spp.unwrap_or(1),
        max_depth: r.max_depth.unwrap_or(5),
        min_weight: r.min_weight.unwrap_or(0.0),
        seed: r.seed.unwrap_or(0),
        integrator: {
            let name = r.integrator.as_deref().unwrap_or("whitted");
            integrators::find(name)
                .ok_or_else(|| err(format!("unknown integrator \"{name}\", expected {}", integrators::quoted_names())))?
        },
    };
    if s.width == 0 || s.height == 0 || s.width as u64 * s.height as u64 > MAX_PIXELS {
        return Err(err(format!("image size {}x{} must be at least 1x1 and at most {MAX_PIXELS} pixels", s.width, s.height)));
    }
    if s.spp == 0 || s.spp > 1 << 20 {
        return Err(err(format!("spp must be between 1 and {}, got {}", 1 << 20, s.spp)));
    }
    if !(1..=MAX_DEPTH_LIMIT).contains(&s.max_depth) {
        return Err(err(format!("max_depth must be between 1 and {MAX_DEPTH_LIMIT}, got {}", s.max_depth)));
    }
    if !(s.min_weight.is_finite() && s.min_weight >= 0.0) {
        return Err(err(format!("min_weight must be a non-negative number, got {}", s.min_weight)));
    }
    Ok(s)
}

/// Builds the core scene (for any image size: the camera applies the aspect when rendering).
pub fn build(desc: &SceneDescription, source: &Source) -> Result<Scene, LoadError> {
    let settings = settings(desc, source)?;
    let camera_desc = desc.camera.as_ref().ok_or_else(|| LoadError::file(&source.path, "has no [camera] table, expected one"))?;
    let camera = camera(&camera_desc.value).map_err(|m| source.error(camera_desc.span.as_ref(), format!("camera: {m}")))?;
    let mut builder = SceneBuilder::new(camera);
    builder.ambient = color(desc.ambient, 0.0);
    builder.background = color(desc.background, 0.0);
    builder.max_depth = settings.max_depth;
    builder.min_weight = settings.min_weight;
    for (key, c) in [("ambient", builder.ambient), ("background", builder.background)] {
        if !(c.is_finite() && c.min_element() >= 0.0) {
            return Err(LoadError::file(&source.path, format!("{key} must be finite and non-negative, got {c}")));
        }
    }
    let mut materials = BTreeMap::new();
    for (name, m) in &desc.materials {
        let material = material(&m.value).map_err(|e| source.error(m.span.as_ref(), format!("material \"{name}\": {e}")))?;
        let index = builder.material(material).map_err(|e| source.error(m.span.as_ref(), format!("material \"{name}\": {e}")))?;
        materials.insert(name.clone(), index);
    }
    nodes::add_all(desc, source, &mut builder, materials)?;
    builder.build().map_err(|e| LoadError::file(&source.path, e.to_string()))
}

fn color(t: Option<Triple>, default: f64) -> Rgb {
    t.map_or(Rgb::splat(default), |t| Rgb::from_array(t.0))
}

fn vec3(a: [f64; 3]) -> Vec3 {
    Vec3::from_array(a)
}

fn camera(c: &CameraDesc) -> Result<Perspective, String> {
    let eye = vec3(c.eye.ok_or("needs eye = [x, y, z]")?);
    if let Some(center) = c.window_center {
        if c.look_at.is_some() || c.vfov.is_some() || c.hfov.is_some() {
            return Err("the window form (window_center, right, up) takes no look_at, vfov or hfov".into());
        }
        let right = vec3(c.right.ok_or("the window form needs right = [x, y, z]")?);
        let up = vec3(c.up.ok_or("the window form needs up = [x, y, z]")?);
        // The aspect is applied when rendering, as `fit` says.
        let fit = match c.fit.as_deref().unwrap_or("none") {
            "none" => Fit::None,
            "width" => Fit::Width,
            "height" => Fit::Height,
            other => return Err(format!("unknown fit \"{other}\", expected \"none\", \"width\" or \"height\"")),
        };
        let pixel_offset = c.pixel_offset.unwrap_or(0.5);
        let finite = [eye, vec3(center), right, up].iter().all(|v| v.is_finite());
        if !finite || !(0.0..=1.0).contains(&pixel_offset) {
            return Err("vectors must be finite and pixel_offset between 0 and 1".into());
        }
        if right.cross(up).length_squared() == 0.0 {
            return Err("right and up must be non-zero and not parallel".into());
        }
        let camera = Perspective::window(eye, vec3(center), right, up, fit).and_then(|c| c.with_pixel_offset(pixel_offset));
        return camera.map_err(|e| e.to_string());
    }
    if c.right.is_some() || c.fit.is_some() {
        return Err("right and fit belong to the window form (with window_center)".into());
    }
    let target = vec3(c.look_at.ok_or("needs look_at = [x, y, z] (or the window form with window_center)")?);
    let sky = vec3(c.up.unwrap_or([0.0, 1.0, 0.0]));
    let fov = match (c.vfov, c.hfov) {
        (Some(v), None) => Fov::VerticalDeg(v),
        (None, Some(h)) => Fov::HorizontalDeg(h),
        (None, None) => return Err("needs vfov or hfov (degrees)".into()),
        (Some(_), Some(_)) => return Err("takes vfov or hfov, not both".into()),
    };
    let mut camera = Perspective::look_at(eye, target, sky, fov).map_err(|e| e.to_string())?;
    if let Some(offset) = c.pixel_offset {
        if !(0.0..=1.0).contains(&offset) {
            return Err(format!("pixel_offset must be between 0 and 1, got {offset}"));
        }
        camera = camera.with_pixel_offset(offset).map_err(|e| e.to_string())?;
    }
    Ok(camera)
}

fn material(m: &MaterialDesc) -> Result<Material, String> {
    let d = Material::default();
    let rgb = |t: Option<Triple>, default: Rgb| t.map_or(default, |t| Rgb::from_array(t.0));
    let color = match (&m.color, &m.checker) {
        (Some(_), Some(_)) => return Err("takes color or checker, not both".into()),
        (_, Some(c)) => Texture::Checker {
            size: c.size,
            even: Rgb::from_array(c.even.0),
            odd: Rgb::from_array(c.odd.0),
            offset: vec3(c.offset.unwrap_or([0.0; 3])),
        },
        (c, None) => match c {
            Some(c) => Texture::Constant(Rgb::from_array(c.0)),
            None => d.color.clone(),
        },
    };
    let reflection = match &m.reflection {
        None => Reflection::None,
        Some(ReflectionDesc::Constant { weight }) => Reflection::Constant(Rgb::from_array(weight.0)),
        Some(ReflectionDesc::Dielectric { ior, min, max }) => {
            Reflection::Dielectric { ior: *ior, min: min.unwrap_or(0.0), max: max.unwrap_or(1.0) }
        }
        Some(ReflectionDesc::Conductor { metal, eta, k }) => match (metal, eta, k) {
            (Some(name), None, None) => {
                let metal = Metal::from_name(name)
                    .ok_or_else(|| format!("unknown metal \"{name}\", expected \"gold\", \"silver\", \"copper\" or \"aluminium\""))?;
                let (eta, k) = metal.eta_k();
                Reflection::Conductor { eta, k }
            }
            (None, Some(eta), Some(k)) => Reflection::Conductor { eta: Rgb::from_array(eta.0), k: Rgb::from_array(k.0) },
            _ => return Err("conductor reflection takes either metal or both eta and k".into()),
        },
    };
    let refraction = match &m.refraction {
        None => Refraction::None,
        Some(RefractionDesc::Fresnel { ior }) => Refraction::Fresnel { ior: *ior },
        Some(RefractionDesc::Constant { ior, weight }) => Refraction::Constant { ior: *ior, weight: Rgb::from_array(weight.0) },
    };
    let material = Material {
        color,
        ka: rgb(m.ka, d.ka),
        kd: rgb(m.kd, d.kd),
        ks: rgb(m.ks, d.ks),
        shininess: m.shininess.unwrap_or(d.shininess),
        emission: rgb(m.emission, d.emission),
        reflection,
        refraction,
        shadow_transmittance: rgb(m.shadow_transmittance, d.shadow_transmittance),
        roughness: m.roughness.unwrap_or(d.roughness),
    };
    material.validate().map_err(|e| e.to_string())?;
    Ok(material)
}
