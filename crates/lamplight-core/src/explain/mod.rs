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
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use crate::film::{self, PixelSum};
use crate::integrators::RayCounts;
use crate::math::{Rgb, Vec3};
use crate::scene::{Hit, Scene};
use crate::{Error, RenderOptions};

mod json;
mod path_record;
mod ray_tree;
mod recorder;
mod summary;
mod text;

use recorder::Recorder;

pub use summary::{SampleSummary, Unrecorded, MAX_RECORDED_SAMPLES, RECORD_BYTES, RECORD_OUTPUT_FACTOR};

pub use path_record::{NeeRecord, PathRecord, PathVertex};
pub use ray_tree::{LightOutcome, LightRecord, ObjectRef, RayKind, RayNode, RayOutcome, RayTree, ShadingRecord};

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
    /// Samples the render takes at this pixel.
    pub spp: u32,
    /// How they were chosen (fixed, or adaptive sampling's decision).
    pub sampling: Sampling,
    /// Seed.
    pub seed: u64,
    /// Depth limit in force.
    pub max_depth: u32,
    /// The samples recorded in full: the first [`MAX_RECORDED_SAMPLES`] of
    /// them, or the one asked for.
    pub samples: Vec<SampleExplanation>,
    /// The samples not recorded in full, summarised: those past the first
    /// [`MAX_RECORDED_SAMPLES`], or from where the memory allowance ran out
    /// (`None`: every sample is recorded).
    pub unrecorded: Option<SampleSummary>,
    /// The film's value of the pixel, `sum / n` of its `n` samples summed as
    /// the render sums them (in sample order within a pass, passes added in
    /// order), before any tone map, as the rendered image stores it (`f32`).
    pub pixel: [f32; 3],
}

impl PixelExplanation {
    /// The pixel as the rendered image stores it (`f32`).
    pub fn pixel_f32(&self) -> [f32; 3] {
        self.pixel
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

/// What [`PixelPlan::film_value`] records: the samples asked for in full, and
/// a summary of the others when every sample was asked for.
#[derive(Default)]
struct Recorded {
    samples: Vec<SampleExplanation>,
    unrecorded: Option<SampleSummary>,
    /// Bytes the full records may still take.
    allowance_left: usize,
    /// The allowance the explanation started with (for the summary).
    allowance: usize,
}

impl Recorded {
    fn within(allowance: usize) -> Recorded {
        Recorded { allowance_left: allowance, allowance, ..Recorded::default() }
    }

    /// Sample `k`, not recorded in full for `why` (the first such sample
    /// decides the summary's reason).
    fn summarise(&mut self, k: u32, why: Unrecorded, film_value: Option<Rgb>) {
        self.unrecorded.get_or_insert(SampleSummary::new(k, why)).add(k, film_value);
    }
}

/// How the render chose the pixel's samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sampling {
    /// `spp` samples, as every pixel.
    Fixed,
    /// Adaptive anti-aliasing ([`crate::Antialias`]): a one-sample probe of the
    /// pixel and its neighbours decided whether it takes `samples` samples.
    Antialias {
        /// Largest colour difference from a neighbour that leaves one sample.
        threshold: f64,
        /// A neighbour differs by more: the pixel was refined.
        refined: bool,
        /// Samples of a refined pixel.
        samples: u32,
    },
    /// Cycles' noise threshold ([`crate::NoiseThreshold`]): the pixel stopped
    /// where the render's checks of its error against `threshold` stopped it.
    NoiseThreshold {
        /// Relative standard error at which a pixel stops.
        threshold: f64,
        /// Samples before any pixel stops.
        min_samples: u32,
        /// The most a pixel takes (`spp`).
        max_samples: u32,
    },
}

/// A pixel of a render, with the samples the render gives it worked out
/// ([`plan`]); [`PixelPlan::explain`] records them.
pub struct PixelPlan {
    integrator: Box<dyn crate::integrators::Integrator>,
    /// Raised: the work stops within [`CANCEL_CHECK`] samples and errs.
    cancel: Option<Arc<AtomicBool>>,
    camera: Option<Box<dyn crate::camera::Camera>>,
    /// The options the pixel's samples are taken with (adaptive sampling resolved).
    options: RenderOptions,
    x: u32,
    y: u32,
    /// How the samples were chosen.
    pub sampling: Sampling,
    /// Samples the render takes at the pixel.
    pub samples: u32,
    /// The pixel's film value, as [`PixelExplanation::pixel`].
    pub pixel: [f32; 3],
}

/// How many samples a cancelled plan or explanation may still take.
pub const CANCEL_CHECK: u32 = 256;

/// Works out the samples the render of `scene` with `options` takes at pixel
/// `(x, y)`, as its render loop does (adaptive sampling included). Errors as
/// [`crate::render()`] does on bad options, and on a pixel outside the image.
pub fn plan(scene: &Scene, options: &RenderOptions, x: u32, y: u32) -> Result<PixelPlan, Error> {
    plan_cancellable(scene, options, x, y, None)
}

/// [`plan`], stopping with an error within [`CANCEL_CHECK`] samples once
/// `cancel` is raised, and so does [`PixelPlan::explain`] of the plan (a
/// pixel of a million samples takes seconds; the viewer drops a stale one).
pub fn plan_cancellable(
    scene: &Scene,
    options: &RenderOptions,
    x: u32,
    y: u32,
    cancel: Option<Arc<AtomicBool>>,
) -> Result<PixelPlan, Error> {
    let integrator = crate::render::integrator_for(scene, options)?;
    let (width, height) = (options.width, options.height);
    if x >= width || y >= height {
        return Err(Error::invalid("pixel", format!("({x}, {y}) is outside the {width}x{height} image")));
    }
    let camera = scene.settings.camera.for_image(width, height);
    let fixed = RenderOptions { adaptive: None, time_limit: None, window: None, ..options.clone() };
    let mut plan = PixelPlan { integrator, cancel, camera, options: fixed, x, y, sampling: Sampling::Fixed, samples: 0, pixel: [0.0; 3] };
    match options.adaptive {
        None => {}
        Some(crate::Adaptive::Antialias(aa)) => {
            // The render's probe: one sample at the pixel and at its neighbours.
            let probe_options = RenderOptions { spp: 1, ..plan.options.clone() };
            let here = crate::PixelWindow { x0: x, y0: y, width: 1, height: 1 };
            let around = crate::render::adaptive::grown(here, width, height);
            let mut probe = film::Image::new(around.width, around.height);
            for (i, p) in probe.pixels.iter_mut().enumerate() {
                let (px, py) = (around.x0 + i as u32 % around.width, around.y0 + i as u32 / around.width);
                *p = plan.film_value(scene, &probe_options, px, py, None, &mut Recorded::within(0))?.0;
            }
            let refined = crate::render::adaptive::refine_mask(&probe, around, here, aa.threshold)[0];
            plan.options.spp = if refined { aa.samples } else { 1 };
            plan.sampling = Sampling::Antialias { threshold: aa.threshold, refined, samples: aa.samples };
        }
        Some(crate::Adaptive::NoiseThreshold(noise)) => {
            plan.sampling =
                Sampling::NoiseThreshold { threshold: noise.threshold, min_samples: noise.min_samples, max_samples: options.spp };
        }
    }
    let (pixel, samples) = plan.film_value(scene, &plan.options.clone(), x, y, None, &mut Recorded::within(0))?;
    plan.samples = samples;
    plan.pixel = pixel;
    Ok(plan)
}

impl PixelPlan {
    /// The film's value of pixel `(px, py)` rendered with `options` (`sum / n`
    /// of its samples summed as the render loop sums them: in sample order within
    /// a pass, passes added in order, stopping where the noise threshold stops)
    /// and its sample count `n`. The samples `record` names (`Some(None)`:
    /// all, of which the first [`MAX_RECORDED_SAMPLES`] in full and the others
    /// summarised) are traced into `recorded`. Errs once the plan is cancelled.
    fn film_value(
        &self,
        scene: &Scene,
        options: &RenderOptions,
        px: u32,
        py: u32,
        record: Option<Option<u32>>,
        recorded: &mut Recorded,
    ) -> Result<([f32; 3], u32), Error> {
        let camera = self.camera.as_deref().unwrap_or(scene.settings.camera.as_ref());
        let view = crate::render::view_of(scene, camera, options);
        let integrator = self.integrator.as_ref();
        let mut counts = RayCounts::default();
        let schedule = integrator.schedule();
        let mut film_sum = PixelSum::default();
        // The noise threshold's checks in a row below it.
        let mut below = 0;
        let spp = options.spp;
        let mut done = 0;
        while done < spp {
            let count = schedule.next_pass(done, spp);
            let mut pass = PixelSum::default();
            for k in done..done + count {
                if k % CANCEL_CHECK == 0 && self.cancel.as_ref().is_some_and(|c| c.load(Ordering::Relaxed)) {
                    return Err(Error::Render("cancelled".into()));
                }
                // Once the allowance ran out, every later sample is summarised.
                let out_of_memory = matches!(recorded.unrecorded, Some(SampleSummary { why: Unrecorded::Memory { .. }, .. }));
                let wanted = match record {
                    None => false,
                    Some(None) => k < MAX_RECORDED_SAMPLES && !out_of_memory,
                    Some(Some(only)) => only == k,
                };
                let radiance = if wanted {
                    let mut recorder = Recorder::within(recorded.allowance_left);
                    let radiance = integrator.sample_traced(&view, px, py, k, &mut counts, &mut recorder);
                    let film_value = film::kept(radiance, view.clamp);
                    if recorder.overflowed() {
                        // Dropped whole: a partial tree would not add up to the sample.
                        recorded.summarise(k, Unrecorded::Memory { allowance: recorded.allowance }, film_value);
                    } else {
                        recorded.allowance_left -= recorder.bytes();
                        let (contributions, mut record) = recorder.finish();
                        if let Record::RayTree(root) = &mut record {
                            root.name_lights(scene);
                        }
                        recorded.samples.push(SampleExplanation { index: k, radiance, film_value, contributions, record });
                    }
                    radiance
                } else {
                    let radiance = integrator.sample(&view, px, py, k, &mut counts);
                    if record == Some(None) {
                        let why = if out_of_memory { Unrecorded::Memory { allowance: recorded.allowance } } else { Unrecorded::PastCount };
                        recorded.summarise(k, why, film::kept(radiance, view.clamp));
                    }
                    radiance
                };
                if let Some(l) = film::kept(radiance, view.clamp) {
                    pass.add(l);
                }
            }
            if done == 0 {
                film_sum = pass;
            } else {
                film_sum.sum += pass.sum;
                film_sum.sum_sq += pass.sum_sq;
            }
            done += count;
            if let Sampling::NoiseThreshold { threshold, min_samples, .. } = self.sampling {
                // The render's rule, check for check.
                let noise = crate::NoiseThreshold { threshold, min_samples };
                if let Some(may_stop) = noise.check_after(done, spp) {
                    if !crate::render::adaptive::keeps_sampling(&mut below, film_sum, done, threshold, may_stop) {
                        break;
                    }
                }
            }
        }
        let m = film_sum.sum / done.max(1) as f64;
        Ok(([m.x as f32, m.y as f32, m.z as f32], done))
    }

    /// Records the pixel's samples (the first [`MAX_RECORDED_SAMPLES`] in
    /// full, the rest summarised), or only `sample` (which must be below
    /// [`PixelPlan::samples`]), within [`RECORD_BYTES`] of memory.
    pub fn explain(&self, scene: &Scene, sample: Option<u32>) -> Result<PixelExplanation, Error> {
        self.explain_within(scene, sample, RECORD_BYTES)
    }

    /// [`PixelPlan::explain`] with full records taking at most about
    /// `allowance` bytes: recording stops at the sample that would pass it,
    /// and that sample and the later ones are summarised, with
    /// [`Unrecorded::Memory`] as the reason (for `sample` asked alone: no
    /// sample recorded, and a summary of that one).
    pub fn explain_within(&self, scene: &Scene, sample: Option<u32>, allowance: usize) -> Result<PixelExplanation, Error> {
        if let Some(k) = sample {
            if k >= self.samples {
                let n = self.samples;
                return Err(Error::invalid("sample", format!("{k} does not exist: the pixel takes {n} samples (0 to {})", n - 1)));
            }
        }
        let mut recorded = Recorded::within(allowance);
        let (_, n) = self.film_value(scene, &self.options, self.x, self.y, Some(sample), &mut recorded)?;
        debug_assert_eq!(n, self.samples);
        let o = &self.options;
        Ok(PixelExplanation {
            integrator: o.integrator.name,
            x: self.x,
            y: self.y,
            width: o.width,
            height: o.height,
            spp: self.samples,
            sampling: self.sampling,
            seed: o.seed,
            max_depth: o.max_depth.unwrap_or(scene.settings.max_depth),
            samples: recorded.samples,
            unrecorded: recorded.unrecorded,
            pixel: self.pixel,
        })
    }
}

/// Explains pixel `(x, y)` of the render of `scene` with `options`: the
/// samples the render takes there (the first [`MAX_RECORDED_SAMPLES`] in
/// full, the rest summarised), or only sample `sample` ([`plan`], then
/// [`PixelPlan::explain`]).
pub fn explain(scene: &Scene, options: &RenderOptions, x: u32, y: u32, sample: Option<u32>) -> Result<PixelExplanation, Error> {
    plan(scene, options, x, y)?.explain(scene, sample)
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
