//! Integrators: what one sample of a pixel sees.
//!
//! An [`Integrator`] turns (pixel, sample index) into radiance: it draws its own
//! sample values (seeded by the render seed, the pixel and the index, so that
//! nothing depends on threads), asks the camera for the primary ray and follows
//! light along it. It also says how the render loop should schedule its samples
//! ([`Schedule`]). The render loop ([`crate::render()`]) is the same for every
//! integrator: tiles, windows, passes, progress, cancellation, time limit and the
//! per-pixel sums of the [`crate::film::Film`].
//!
//! Integrators are chosen by name from [`INTEGRATORS`]. To add one: a file here
//! with a type that implements [`Integrator`] and a `pub const ENTRY:
//! IntegratorEntry`, and one line in [`INTEGRATORS`] (with the file's `mod` line).

use std::fmt;
use std::ops::Range;

use crate::camera::Camera;
use crate::film::{Filter, PixelSum};
use crate::math::Rgb;
use crate::ray::Ray;
use crate::sampling::Cone;
use crate::scene::Scene;
use crate::Error;

mod path;
mod simple_path;
pub mod trace;
mod whitted;

pub use path::{power_heuristic, unoccluded, PathTracer};
pub use simple_path::SimplePath;
pub use whitted::{Whitted, MAX_DEPTH_LIMIT};

/// Every integrator by name; the first is the default.
pub static INTEGRATORS: &[IntegratorEntry] = &[whitted::ENTRY, path::ENTRY];

/// Counts of rays traced, by kind; summed over threads at the end of a render.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Camera rays.
    pub camera: u64,
    /// Reflected and refracted rays.
    pub secondary: u64,
    /// Shadow rays towards lights.
    pub shadow: u64,
}

impl RayCounts {
    /// All rays.
    pub fn total(&self) -> u64 {
        self.camera + self.secondary + self.shadow
    }

    /// Adds another count.
    pub fn add(&mut self, other: &RayCounts) {
        self.camera += other.camera;
        self.secondary += other.secondary;
        self.shadow += other.shadow;
    }
}

/// The image an integrator renders: the scene, the camera, the full image size
/// (pixel coordinates are the full image's, also when a window is rendered), the
/// samples per pixel and the seed.
#[derive(Clone, Copy, Debug)]
pub struct View<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// The camera making the primary rays.
    pub camera: &'a dyn Camera,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel the render asks for.
    pub spp: u32,
    /// Seed of the per-sample random numbers.
    pub seed: u64,
    /// Whether the camera takes a lens sample (asked once per render, not per ray).
    pub lens: bool,
    /// The shutter, `(open, close)` in frames, when some shape moves
    /// ([`Scene::shutter`]): each camera sample then draws its instant
    /// uniformly in it, after the lens sample, and every ray of its path keeps
    /// it ([`Ray::time`]). `None`: no time is drawn and rays are at time 0.
    pub shutter: Option<(f64, f64)>,
    /// The camera's [`Camera::pixel_offset`] (asked once per render).
    pub pixel_offset: f64,
    /// Largest channel a sample keeps ([`crate::RenderOptions::clamp`]; infinite: no clamp).
    pub clamp: f64,
    /// The film positions samples may take, `[x0, y0, x1, y1]` in pixels: the
    /// whole image, or its crop ([`crate::RenderOptions::crop`]). A filter
    /// wider than a pixel is cut there ([`Filter::sample_in`]).
    pub sample_bounds: [f64; 4],
}

impl<'a> View<'a> {
    /// The view of `scene` through `camera` (the scene's, or one made from it by
    /// [`Camera::for_image`] for this size).
    pub fn new(scene: &'a Scene, camera: &'a dyn Camera, width: u32, height: u32, spp: u32, seed: u64) -> View<'a> {
        View {
            scene,
            camera,
            width,
            height,
            spp,
            seed,
            lens: camera.uses_lens_sample(),
            shutter: scene.shutter(),
            pixel_offset: camera.pixel_offset(),
            clamp: f64::INFINITY,
            sample_bounds: [0.0, 0.0, width as f64, height as f64],
        }
    }

    /// The ray cone ([`Cone`]) of the camera ray `ray` through film position
    /// `(fx, fy)` with lens sample `lens`, from the camera's rays one pixel over
    /// in x and in y.
    #[inline]
    pub fn pixel_cone(&self, ray: &Ray, fx: f64, fy: f64, lens: (f64, f64)) -> Cone {
        let x = self.camera.ray(fx + 1.0, fy, self.width, self.height, lens);
        let y = self.camera.ray(fx, fy + 1.0, self.width, self.height, lens);
        Cone::of_neighbours(ray, &x, &y, self.spp)
    }

    /// The instant of shutter position `u` in `[0, 1)`.
    #[inline]
    pub fn instant(shutter: (f64, f64), u: f64) -> f64 {
        shutter.0 + (shutter.1 - shutter.0) * u
    }

    /// The same view with samples drawn only inside `crop` (`None`: the whole image).
    pub fn with_crop(self, crop: Option<crate::film::PixelWindow>) -> View<'a> {
        match crop {
            None => self,
            Some(c) => View { sample_bounds: [c.x0 as f64, c.y0 as f64, (c.x0 + c.width) as f64, (c.y0 + c.height) as f64], ..self },
        }
    }

    /// The filter offsets whose positions lie in [`View::sample_bounds`], for
    /// the pixel `(x, y)` centred at `(x + 1/2, y + 1/2)`: `(lo, hi)` per axis.
    #[inline]
    pub fn offset_bounds(&self, x: u32, y: u32) -> ((f64, f64), (f64, f64)) {
        let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
        let [x0, y0, x1, y1] = self.sample_bounds;
        ((x0 - cx, y0 - cy), (x1 - cx, y1 - cy))
    }

    /// The same view with samples clamped to `clamp` in their largest channel
    /// (`None`: unclamped; see [`crate::RenderOptions::clamp`]).
    pub fn with_clamp(self, clamp: Option<f64>) -> View<'a> {
        View { clamp: clamp.unwrap_or(f64::INFINITY), ..self }
    }

    /// Index of pixel `(x, y)` in the full image, row-major: the seed of its samples.
    #[inline]
    pub fn pixel_index(&self, x: u32, y: u32) -> u64 {
        y as u64 * self.width as u64 + x as u64
    }
}

/// A pixel sample's camera ray ([`Integrator::camera_sample`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSample {
    /// The primary ray.
    pub ray: Ray,
    /// Its pixel footprint, for texture filtering (zero: point lookups).
    pub cone: Cone,
    /// The filter weight its radiance is multiplied by (1 but for filters with negative lobes).
    pub weight: f64,
}

/// How the render loop splits a pixel's samples into passes over the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Schedule {
    /// Every sample in one pass (the stratified Whitted sampler needs the count).
    OnePass,
    /// Passes of 1, 1, 2, 4, ... samples: each finished pass leaves a power-of-two
    /// count (where Sobol points are best stratified) and a time limit can stop
    /// after any of them.
    Doubling,
}

impl Schedule {
    /// Samples of the pass after `done` samples of `spp`: `spp - done`, or
    /// `max(done, 1)` capped by it for [`Schedule::Doubling`].
    pub fn next_pass(self, done: u32, spp: u32) -> u32 {
        let left = spp.saturating_sub(done);
        match self {
            Schedule::OnePass => left,
            Schedule::Doubling => done.max(1).min(left),
        }
    }

    /// Number of passes for `spp` samples.
    pub fn pass_count(self, spp: u32) -> u32 {
        let (mut done, mut passes) = (0, 0);
        while done < spp {
            done += self.next_pass(done, spp);
            passes += 1;
        }
        passes
    }
}

/// Computes the radiance of pixel samples.
pub trait Integrator: Send + Sync {
    /// Radiance of sample `index` of pixel `(x, y)` of `view`'s image. Ray counts
    /// go to `counts`. The same arguments give the same value on any thread.
    fn sample(&self, view: &View, x: u32, y: u32, index: u32, counts: &mut RayCounts) -> Rgb;

    /// [`Integrator::sample`] telling `trace` what it does ([`trace`]): the same
    /// code, so the same value. The default records nothing.
    fn sample_traced(&self, view: &View, x: u32, y: u32, index: u32, counts: &mut RayCounts, trace: &mut dyn trace::Trace) -> Rgb {
        let _ = trace;
        self.sample(view, x, y, index, counts)
    }

    /// The camera ray of sample `index` of pixel `(x, y)`: the ray
    /// [`Integrator::sample`] traces for the same arguments, with its footprint
    /// and the filter weight its radiance gets. The feature pass
    /// ([`crate::render_features`]) follows these rays, so its layers have the
    /// beauty image's sample positions and anti-aliasing.
    fn camera_sample(&self, view: &View, x: u32, y: u32, index: u32) -> CameraSample;

    /// How the render loop schedules the samples.
    fn schedule(&self) -> Schedule;

    /// Adds samples `samples` of pixels `x0..x0 + sums.len()` of row `y` to `sums`, each pixel's in sample order, dropping samples the film does not accept
    /// ([`crate::film::accepts`]: NaN, infinite or beyond [`crate::film::MAX_RADIANCE`])
    /// and scaling those above [`View::clamp`] down to it; returns how many were dropped. The render loop calls this once per tile
    /// row: the default body is compiled for each integrator, so its loop calls
    /// [`Integrator::sample`] directly rather than through the trait object
    /// (1.5 % of a Whitted render's instructions went to those calls).
    ///
    /// On CPUs with [`crate::cpu::RENDER_FEATURES`] (or else
    /// [`crate::cpu::AVX2_FEATURES`]) the loop, with the integrator's sample
    /// inlined into it, runs compiled for them (the same values, see [`crate::cpu`]).
    fn sample_row(&self, view: &View, row: (u32, u32), samples: Range<u32>, counts: &mut RayCounts, sums: &mut [PixelSum]) -> u64 {
        sample_row_one_by_one(self, view, row, samples, counts, sums)
    }
}

/// [`Integrator::sample_row`]'s default: each sample on its own, through the
/// compilation for this CPU.
#[inline(always)]
pub(crate) fn sample_row_one_by_one<I: Integrator + ?Sized>(
    integrator: &I,
    view: &View,
    row: (u32, u32),
    samples: Range<u32>,
    counts: &mut RayCounts,
    sums: &mut [PixelSum],
) -> u64 {
    #[cfg(target_arch = "x86_64")]
    if crate::cpu::render_features() {
        // SAFETY: the CPU has every feature `sample_row_features` is compiled for.
        return unsafe { sample_row_features(integrator, view, row, samples, counts, sums) };
    }
    #[cfg(target_arch = "x86_64")]
    if crate::cpu::avx2_features() {
        // SAFETY: the CPU has every feature `sample_row_avx2` is compiled for.
        return unsafe { sample_row_avx2(integrator, view, row, samples, counts, sums) };
    }
    sample_row_loop(integrator, view, row, samples, counts, sums)
}

/// [`Integrator::sample_row`]'s loop, inlined into each compilation of it.
#[inline(always)]
fn sample_row_loop<I: Integrator + ?Sized>(
    integrator: &I,
    view: &View,
    (x0, y): (u32, u32),
    samples: Range<u32>,
    counts: &mut RayCounts,
    sums: &mut [PixelSum],
) -> u64 {
    let mut nonfinite = 0;
    for (x, sum) in (x0..).zip(sums.iter_mut()) {
        for s in samples.clone() {
            nonfinite += add_sample(sum, integrator.sample(view, x, y, s, counts), view.clamp);
        }
    }
    nonfinite
}

/// Adds sample value `l` to `sum` as the film takes it ([`crate::film::kept`]:
/// clamped to `clamp`, dropped where not finite); 1 where dropped, else 0.
/// Every row loop adds its samples through here, in sample order.
#[inline(always)]
pub(crate) fn add_sample(sum: &mut PixelSum, l: Rgb, clamp: f64) -> u64 {
    match crate::film::kept(l, clamp) {
        Some(l) => {
            sum.add(l);
            0
        }
        None => 1,
    }
}

/// [`sample_row_loop`] compiled for [`crate::cpu::RENDER_FEATURES`] (the list is
/// written out here because the attribute takes a literal; a test keeps the two equal).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt,gfni")]
unsafe fn sample_row_features<I: Integrator + ?Sized>(
    integrator: &I,
    view: &View,
    row: (u32, u32),
    samples: Range<u32>,
    counts: &mut RayCounts,
    sums: &mut [PixelSum],
) -> u64 {
    sample_row_loop(integrator, view, row, samples, counts, sums)
}

/// [`sample_row_loop`] compiled for [`crate::cpu::AVX2_FEATURES`] (AVX2
/// processors without GFNI).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
unsafe fn sample_row_avx2<I: Integrator + ?Sized>(
    integrator: &I,
    view: &View,
    row: (u32, u32),
    samples: Range<u32>,
    counts: &mut RayCounts,
    sums: &mut [PixelSum],
) -> u64 {
    sample_row_loop(integrator, view, row, samples, counts, sums)
}

#[cfg(all(test, target_arch = "x86_64"))]
mod feature_tests {
    /// The attribute of `sample_row_features` names [`crate::cpu::RENDER_FEATURES`].
    #[test]
    fn the_render_loop_is_compiled_for_the_detected_features() {
        let source = include_str!("mod.rs");
        let attribute = format!("#[target_feature(enable = \"{}\")]\nunsafe fn sample_row_features", crate::cpu::RENDER_FEATURES);
        assert!(source.contains(&attribute), "sample_row_features must be compiled for RENDER_FEATURES");
        let attribute = format!("#[target_feature(enable = \"{}\")]\nunsafe fn sample_row_avx2", crate::cpu::AVX2_FEATURES);
        assert!(source.contains(&attribute), "sample_row_avx2 must be compiled for AVX2_FEATURES");
    }
}

/// What an integrator is built from besides the scene, resolved by the render loop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntegratorSettings {
    /// Depth limit in segments (camera ray = 1), at least 1.
    pub max_depth: u32,
    /// Pixel reconstruction filter (for integrators that sample film positions).
    pub filter: Filter,
}

/// How a registry entry makes its integrator for a scene.
pub type BuildIntegrator = fn(&Scene, &IntegratorSettings) -> Result<Box<dyn Integrator>, Error>;

/// An integrator the program offers by name.
pub struct IntegratorEntry {
    /// Name on the command line, in scene files and in Python.
    pub name: &'static str,
    /// One line for help texts.
    pub summary: &'static str,
    /// Builds the integrator for a scene.
    pub build: BuildIntegrator,
    /// How its integrators schedule their samples ([`Integrator::schedule`]),
    /// known before one is built: which adaptive sampling fits it.
    pub schedule: Schedule,
    /// Whether it places its samples by [`IntegratorSettings::filter`]; one
    /// that does not averages them over the pixel square (a box), so asking it
    /// for another filter is an error, not a silent box.
    pub filters: bool,
}

impl fmt::Debug for IntegratorEntry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name)
    }
}

/// Entries are the same integrator when their names are.
impl PartialEq for IntegratorEntry {
    fn eq(&self, other: &IntegratorEntry) -> bool {
        self.name == other.name
    }
}

impl Eq for IntegratorEntry {}

/// The default integrator, the first of [`INTEGRATORS`].
pub fn default_integrator() -> &'static IntegratorEntry {
    &INTEGRATORS[0]
}

/// The integrator called `name`.
pub fn find(name: &str) -> Option<&'static IntegratorEntry> {
    INTEGRATORS.iter().find(|e| e.name == name)
}

/// The names, comma separated: `whitted, path`.
pub fn names() -> String {
    INTEGRATORS.iter().map(|e| e.name).collect::<Vec<_>>().join(", ")
}

/// The names quoted as alternatives: `"whitted" or "path"`.
pub fn quoted_names() -> String {
    let quoted: Vec<String> = INTEGRATORS.iter().map(|e| format!("\"{}\"", e.name)).collect();
    match quoted.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => quoted.join(""),
    }
}

impl std::str::FromStr for &'static IntegratorEntry {
    type Err = String;

    fn from_str(s: &str) -> Result<&'static IntegratorEntry, String> {
        find(s).ok_or_else(|| crate::params::unknown("integrator", s, &INTEGRATORS.iter().map(|e| e.name).collect::<Vec<_>>()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn doubling_passes_leave_powers_of_two() {
        let passes = |schedule: Schedule, spp: u32| {
            let mut done = 0;
            let mut sizes = Vec::new();
            while done < spp {
                let n = schedule.next_pass(done, spp);
                sizes.push(n);
                done += n;
            }
            assert_eq!(sizes.len() as u32, schedule.pass_count(spp));
            sizes
        };
        assert_eq!(passes(Schedule::Doubling, 16), [1, 1, 2, 4, 8]);
        assert_eq!(passes(Schedule::Doubling, 6), [1, 1, 2, 2]);
        assert_eq!(passes(Schedule::Doubling, 1), [1]);
        assert_eq!(passes(Schedule::OnePass, 6), [6]);
    }

    #[test]
    fn integrators_are_found_by_name() {
        assert_eq!(default_integrator().name, "whitted");
        assert_eq!("path".parse::<&IntegratorEntry>().unwrap().name, "path");
        assert_eq!("photon".parse::<&IntegratorEntry>().unwrap_err(), "unknown integrator \"photon\" (integrators: whitted, path)");
        assert_eq!(quoted_names(), "\"whitted\" or \"path\"");
        let names: std::collections::HashSet<_> = INTEGRATORS.iter().map(|e| e.name).collect();
        assert_eq!(names.len(), INTEGRATORS.len(), "names are unique");
    }
}
