//! Why a pixel has its colour: the ray tree of a Whitted sample, or the paths of
//! a path-traced pixel, recorded while the integrator computes them.
//!
//! [`explain`] builds the render's integrator, view and camera exactly as
//! [`crate::render()`] does and calls [`crate::integrators::Integrator::sample_traced`] for the
//! pixel's samples, with the render's seeds (sample `k` of pixel `(x, y)` draws
//! from `(seed, y * width + x, k)`), so sample `k` here is the render's sample
//! `k`. The recorders ([`RayTree`] for Whitted, [`PathRecord`] for the path
//! tracer) keep every term the integrator adds to the pixel in the order it adds
//! them: summed in that order they give the sample's radiance to the last bit,
//! and the pixel is the film's mean of those samples ([`PixelExplanation::pixel`]).
//!
//! Recording costs ordinary renders nothing: they pass
//! [`crate::integrators::trace::NoTrace`] (see [`crate::integrators::trace`]).

use std::fmt;

use crate::film::{self, PixelSum};
use crate::integrators::trace::{PathTrace, WhittedTrace};
use crate::integrators::{RayCounts, Schedule};
use crate::math::{Rgb, Vec3};
use crate::scene::{Hit, Scene};
use crate::{Error, RenderOptions};

mod json;
mod path_record;
mod ray_tree;
mod text;

pub use path_record::{NeeRecord, PathRecord, PathVertex};
pub use ray_tree::{LightOutcome, LightRecord, RayKind, RayNode, RayOutcome, RayTree, ShadingRecord};

/// A ray's hit as the explanation shows it.
#[derive(Clone, Debug, PartialEq)]
pub struct HitInfo {
    /// Distance along the ray.
    pub t: f64,
    /// Hit point.
    pub point: Vec3,
    /// Index of the object hit.
    pub object: usize,
    /// Its name in the scene file, if it has one.
    pub object_name: Option<String>,
    /// Its shape's kind (`Sphere`, `Quadric`, `TriangleMesh (instance)`, ...).
    pub object_kind: String,
    /// Index of its material.
    pub material: usize,
    /// The material's name in the scene file, if it has one.
    pub material_name: Option<String>,
    /// Geometric normal, turned to face the ray.
    pub geometric_normal: Vec3,
    /// Shading normal, turned to face the ray.
    pub shading_normal: Vec3,
    /// The ray arrived on the outward side (it was outside, entering).
    pub front_face: bool,
    /// The normals were flipped to face the ray (the back side was hit).
    pub flipped: bool,
}

impl HitInfo {
    /// What `hit` of `scene` shows.
    pub fn new(scene: &Scene, hit: &Hit) -> HitInfo {
        HitInfo {
            t: hit.t,
            point: hit.point,
            object: hit.object,
            object_name: scene.object_name(hit.object).map(str::to_string),
            object_kind: kind_name(&*scene.objects[hit.object].shape),
            material: hit.material,
            material_name: scene.material_name(hit.material).map(str::to_string),
            geometric_normal: hit.geometric_normal,
            shading_normal: hit.normal,
            front_face: hit.front_face,
            flipped: !hit.front_face,
        }
    }
}

/// What one sample recorded.
#[derive(Clone, Debug, PartialEq)]
pub enum Record {
    /// A Whitted ray tree.
    RayTree(RayNode),
    /// A path.
    Path(PathRecord),
    /// The integrator records nothing.
    Nothing,
}

/// One sample of the pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct SampleExplanation {
    /// Its index.
    pub index: u32,
    /// The radiance the integrator returned: the sum of [`SampleExplanation::contributions`] in order.
    pub radiance: Rgb,
    /// What the film keeps of it ([`film::kept`]; `None`: dropped as non-finite).
    pub film_value: Option<Rgb>,
    /// Every term the integrator added to the radiance, in its order.
    pub contributions: Vec<Rgb>,
    /// The tree or path.
    pub record: Record,
}

impl SampleExplanation {
    /// `sum_i contributions[i]`, added in the integrator's order from 0: equal to
    /// [`SampleExplanation::radiance`] to the last bit.
    pub fn contribution_sum(&self) -> Rgb {
        self.contributions.iter().fold(Rgb::ZERO, |sum, c| sum + *c)
    }
}

/// A pixel explained.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelExplanation {
    /// The integrator's name.
    pub integrator: &'static str,
    /// Pixel column.
    pub x: u32,
    /// Pixel row (from the top).
    pub y: u32,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Samples per pixel of the render.
    pub spp: u32,
    /// Seed.
    pub seed: u64,
    /// Depth limit in force.
    pub max_depth: u32,
    /// The samples explained: all of them, or the one asked for.
    pub samples: Vec<SampleExplanation>,
    /// The film's value of the pixel, `sum / spp` of all its samples summed as
    /// the render sums them (in sample order within a pass, passes added in
    /// order), before any tone map; as `f32`, it is the rendered image's pixel.
    pub pixel: Rgb,
}

impl PixelExplanation {
    /// The pixel as the rendered image stores it (`f32`).
    pub fn pixel_f32(&self) -> [f32; 3] {
        [self.pixel.x as f32, self.pixel.y as f32, self.pixel.z as f32]
    }

    /// The explanation as JSON (the same tree as the text).
    pub fn to_json(&self) -> serde_json::Value {
        json::pixel(self)
    }
}

impl fmt::Display for PixelExplanation {
    /// The tree as indented text for a reader.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        text::write_pixel(f, self)
    }
}

/// Explains pixel `(x, y)` of the render of `scene` with `options`: every
/// sample, or only sample `sample`. Errors as [`crate::render()`] does on bad
/// options, and on a pixel outside the image or a sample index `>= spp`.
pub fn explain(scene: &Scene, options: &RenderOptions, x: u32, y: u32, sample: Option<u32>) -> Result<PixelExplanation, Error> {
    let integrator = crate::render::integrator_for(scene, options)?;
    let (width, height, spp) = (options.width, options.height, options.spp);
    if x >= width || y >= height {
        return Err(Error::invalid("pixel", format!("({x}, {y}) is outside the {width}x{height} image")));
    }
    if let Some(k) = sample {
        if k >= spp {
            return Err(Error::invalid("sample", format!("{k} does not exist: the pixel has {spp} samples (0 to {})", spp - 1)));
        }
    }
    let sized = scene.camera.for_image(width, height);
    let camera = sized.as_deref().unwrap_or(scene.camera.as_ref());
    let view = crate::render::view_of(scene, camera, options);
    let mut counts = RayCounts::default();
    let mut samples = Vec::new();
    // The film's sums, pass by pass as the render loop makes them.
    let mut film_sum = PixelSum::default();
    let schedule = integrator.schedule();
    let mut done = 0;
    while done < spp {
        let count = schedule.next_pass(done, spp);
        let mut pass = PixelSum::default();
        for k in done..done + count {
            let wanted = sample.is_none_or(|s| s == k);
            let radiance = if wanted {
                let mut recorder = Recorder::default();
                let radiance = integrator.sample_traced(&view, x, y, k, &mut counts, &mut recorder);
                let (contributions, mut record) = recorder.finish();
                if let Record::RayTree(root) = &mut record {
                    root.name_lights(scene);
                }
                samples.push(SampleExplanation { index: k, radiance, film_value: film::kept(radiance, view.clamp), contributions, record });
                radiance
            } else {
                integrator.sample(&view, x, y, k, &mut counts)
            };
            if let Some(l) = film::kept(radiance, view.clamp) {
                pass.add(l);
            }
        }
        if done == 0 {
            film_sum = pass;
        } else {
            film_sum.sum += pass.sum;
        }
        done += count;
    }
    debug_assert!(matches!(schedule, Schedule::OnePass | Schedule::Doubling));
    let max_depth = options.max_depth.unwrap_or(scene.max_depth);
    let pixel = film_sum.sum / spp as f64;
    Ok(PixelExplanation { integrator: options.integrator.name, x, y, width, height, spp, seed: options.seed, max_depth, samples, pixel })
}

/// Records whichever integrator calls it.
#[derive(Default)]
struct Recorder {
    tree: RayTree,
    path: PathRecord,
}

impl Recorder {
    fn finish(self) -> (Vec<Rgb>, Record) {
        if let Some((root, contributions)) = self.tree.finish() {
            return (contributions, Record::RayTree(root));
        }
        if !self.path.vertices.is_empty() {
            let contributions = self.path.contributions.clone();
            return (contributions, Record::Path(self.path));
        }
        (Vec::new(), Record::Nothing)
    }
}

/// Forwards the Whitted events to the ray tree.
impl WhittedTrace for Recorder {
    fn ray(&mut self, ray: &crate::ray::Ray, weight: Rgb, depth: u32) {
        self.tree.ray(ray, weight, depth)
    }
    fn miss(&mut self, radiance: Rgb, contribution: Rgb) {
        self.tree.miss(radiance, contribution)
    }
    fn hit(&mut self, scene: &Scene, hit: &Hit) {
        WhittedTrace::hit(&mut self.tree, scene, hit)
    }
    fn surface(&mut self, color: Rgb, emission: Rgb, ambient: Rgb) {
        self.tree.surface(color, emission, ambient)
    }
    fn light(&mut self, light: crate::integrators::trace::LightRef) {
        self.tree.light(light)
    }
    fn unlit(&mut self, why: crate::integrators::trace::Unlit) {
        self.tree.unlit(why)
    }
    fn lit(&mut self, scene: &Scene, term: &crate::integrators::trace::LightTerm) {
        self.tree.lit(scene, term)
    }
    fn direct(&mut self, direct: Rgb, contribution: Rgb) {
        self.tree.direct(direct, contribution)
    }
    fn depth_cutoff(&mut self) {
        self.tree.depth_cutoff()
    }
    fn reflection(&mut self, how: crate::integrators::trace::ReflectionWeight, weight: Rgb) {
        self.tree.reflection(how, weight)
    }
    fn refraction(&mut self, fresnel: Option<f64>, weight: Option<Rgb>) {
        self.tree.refraction(fresnel, weight)
    }
    fn branch(&mut self, ray: &crate::ray::Ray, weight: Rgb, depth: u32, traced: bool) {
        self.tree.branch(ray, weight, depth, traced)
    }
}

/// Forwards the path events to the path record.
impl PathTrace for Recorder {
    fn segment(&mut self, depth: u32, ray: &crate::ray::Ray, beta: Rgb) {
        self.path.segment(depth, ray, beta)
    }
    fn path_hit(&mut self, scene: &Scene, hit: &Hit) {
        self.path.path_hit(scene, hit)
    }
    fn emitted(&mut self, le: Rgb, weight: f64, contribution: Rgb) {
        self.path.emitted(le, weight, contribution)
    }
    fn nee_miss(&mut self, why: crate::integrators::trace::NeeMiss) {
        self.path.nee_miss(why)
    }
    fn nee(&mut self, sample: &crate::integrators::trace::NeeSample) {
        self.path.nee(sample)
    }
    fn nee_contribution(&mut self, contribution: Rgb) {
        self.path.nee_contribution(contribution)
    }
    fn bsdf_sample(&mut self, sample: &crate::bsdfs::BsdfSample, wi: Vec3, beta: Rgb) {
        self.path.bsdf_sample(sample, wi, beta)
    }
    fn survived(&mut self, survive: f64, beta: Rgb) {
        self.path.survived(survive, beta)
    }
    fn end(&mut self, why: crate::integrators::trace::PathEnd) {
        self.path.end(why)
    }
}

/// The type name at the front of `value`'s `Debug` text (`Sphere`; an instance
/// as `Sphere (instance)`). Shapes and lights carry no kind name of their own,
/// and their `Debug` text can be a whole mesh: the writer stops after 96 bytes.
pub fn kind_name(value: &dyn fmt::Debug) -> String {
    struct Head(String);
    impl fmt::Write for Head {
        fn write_str(&mut self, s: &str) -> fmt::Result {
            self.0.push_str(s);
            if self.0.len() > 96 {
                Err(fmt::Error)
            } else {
                Ok(())
            }
        }
    }
    let mut head = Head(String::new());
    let _ = fmt::write(&mut head, format_args!("{value:?}"));
    let ident = |s: &str| s.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect::<String>();
    let name = ident(&head.0);
    match head.0.strip_prefix("Instance { shape: ") {
        Some(rest) => format!("{} (instance)", ident(rest)),
        None => name,
    }
}

#[cfg(test)]
mod tests;
