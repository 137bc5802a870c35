//! The render loop, one for every integrator: [`render()`] turns a scene into an
//! accumulated [`Film`], [`render_image()`] into its mean image.
//!
//! The image, or a [`PixelWindow`] of it, is cut into [`TILE`] x [`TILE`] tiles
//! rendered in parallel (rayon), in passes as the integrator's [`Schedule`] says.
//! Each sample's random numbers are seeded by (seed, pixel, sample index) and each
//! pixel adds its samples in index order into its own sums, so the bytes of the
//! image depend neither on the number of threads, nor on the order tiles finish
//! in, nor on the pass sizes; and a window renders exactly the pixels of the full
//! render there, so an image can be split across machines and stitched back.
//! With a time limit, a pass that would not finish in time is not started and a
//! pass cut short is dropped: the film is always that of the last complete pass.
//!
//! [`Adaptive`] sampling ([`adaptive`]) spends samples only where a pixel needs
//! them: POV-Ray's anti-aliasing for one-pass integrators, Cycles' noise
//! threshold for the path tracer. Both decide from deterministic sums, so they
//! keep every promise above.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::film::{Film, Filter, Image, PixelSum, PixelWindow, TileBlock, TILE};
use crate::integrators::{self, Integrator, IntegratorEntry, IntegratorSettings, RayCounts, Schedule, View};
use crate::scene::Scene;
use crate::Error;

pub mod adaptive;
pub use adaptive::{Adaptive, Antialias, NoiseThreshold};
mod features;
pub use features::{render_features, Features};

/// What to render and how.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// Depth limit; `None` uses the scene's.
    pub max_depth: Option<u32>,
    /// Worker threads; 0 uses all cores.
    pub threads: usize,
    /// Seed of the per-sample random numbers.
    pub seed: u64,
    /// The integrator, from [`integrators::INTEGRATORS`] (`"path".parse()` finds one by name).
    pub integrator: &'static IntegratorEntry,
    /// Stop after the last complete pass before this much time (an error if the
    /// first pass does not finish in it).
    pub time_limit: Option<Duration>,
    /// The pixel reconstruction filter, for integrators that place samples by it
    /// (the path tracer).
    pub filter: Filter,
    /// Render only this part of the `width x height` image (the result has the
    /// window's size); `None` renders all of it (or the crop).
    pub window: Option<PixelWindow>,
    /// The film's crop (Mitsuba's `hdrfilm` crop window): the part of the
    /// `width x height` image that is rendered, with samples drawn only inside
    /// it, so a filter wider than a pixel is cut at the crop's edges as at the
    /// image's. The image is the crop (or the window, which must lie in it).
    pub crop: Option<PixelWindow>,
    /// Largest channel a sample may have: a brighter sample is scaled down to
    /// it, hue kept (pbrt-v4's film `maxcomponentvalue`). Removes fireflies at the cost
    /// of bias (the image is darker than the true mean wherever it acts); `None`
    /// clamps nothing.
    pub clamp: Option<f64>,
    /// Extra samples only where pixels need them ([`Adaptive`]); `None` gives
    /// every pixel `spp` samples.
    pub adaptive: Option<Adaptive>,
}

impl RenderOptions {
    /// The pixels to render: the window, or the crop, or the whole image.
    pub fn pixel_window(&self) -> PixelWindow {
        self.window.or(self.crop).unwrap_or(PixelWindow { x0: 0, y0: 0, width: self.width, height: self.height })
    }
}

impl Default for RenderOptions {
    fn default() -> RenderOptions {
        RenderOptions {
            width: 640,
            height: 360,
            spp: 1,
            max_depth: None,
            threads: 0,
            seed: 0,
            integrator: integrators::default_integrator(),
            time_limit: None,
            filter: Filter::Box,
            window: None,
            crop: None,
            clamp: None,
            adaptive: None,
        }
    }
}

/// Figures about a finished render.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    /// Rays traced, by kind.
    pub rays: RayCounts,
    /// Samples whose radiance was NaN, infinite or beyond
    /// [`crate::film::MAX_RADIANCE`] and was replaced by black.
    pub nonfinite_samples: u64,
    /// Wall-clock time of the render (not of scene building or file writing).
    pub elapsed: Duration,
    /// Threads used.
    pub threads: usize,
    /// Samples per pixel actually taken (fewer than asked when a time limit
    /// stopped the render; after adaptive sampling, the most any pixel took).
    pub samples_per_pixel: u32,
    /// Samples taken over all pixels of the image (`pixel_samples / pixels` is
    /// the mean per pixel; adaptive sampling takes fewer than `spp` per pixel).
    pub pixel_samples: u64,
}

/// Progress reports and cancellation for a running render.
pub struct RenderControl<'a> {
    /// Called after each tile of each pass with (tiles done, tiles of all passes); from worker threads.
    pub progress: &'a (dyn Fn(u64, u64) + Sync),
    /// When set, remaining tiles are skipped and `render` returns [`Error::Render`].
    pub cancel: Option<&'a AtomicBool>,
    /// When set, the pass in progress is dropped and `render` returns the passes
    /// already complete, every pixel with the same sample count (a first Ctrl-C);
    /// [`Error::Render`] when none is.
    pub stop: Option<&'a AtomicBool>,
}

impl Default for RenderControl<'_> {
    fn default() -> Self {
        RenderControl { progress: &|_, _| {}, cancel: None, stop: None }
    }
}

impl RenderControl<'_> {
    fn cancelled(&self) -> bool {
        self.cancel.is_some_and(|c| c.load(Ordering::Relaxed))
    }

    fn stopped(&self) -> bool {
        self.stop.is_some_and(|s| s.load(Ordering::Relaxed))
    }
}

/// Most of the time left that a pass shortened to fit a time limit may take by
/// the previous pass's time per sample: the rest is the margin for its spread.
const BUDGET_SHARE: f64 = 0.85;

/// A pool of `threads` workers (0: one per core).
fn thread_pool(threads: usize) -> Result<rayon::ThreadPool, Error> {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().map_err(|e| Error::Render(format!("cannot start worker threads: {e}")))
}

/// Most pixels in an image (`2^28`, e.g. 16384x16384): the film's buffers of a
/// larger image would not fit in memory. The one statement of the limit; the
/// front ends' checks (`lamplight_scene::request::limits`) read it.
pub const MAX_PIXELS: u64 = 1 << 28;

/// Checks the image size and samples, and returns the depth limit in force.
fn checked_depth(scene: &Scene, options: &RenderOptions) -> Result<u32, Error> {
    let RenderOptions { width, height, spp, .. } = *options;
    if width == 0 || height == 0 || spp == 0 {
        return Err(Error::invalid("image", "width, height and samples per pixel must be at least 1"));
    }
    if width as u64 * height as u64 > MAX_PIXELS {
        return Err(Error::invalid("image", format!("{width}x{height} is too large (at most {MAX_PIXELS} pixels)")));
    }
    let full = PixelWindow { x0: 0, y0: 0, width, height };
    let crop = options.crop.unwrap_or(full);
    if !crop.is_inside(full) {
        return Err(Error::invalid("crop", format!("{crop:?} must be non-empty and inside the {width}x{height} image")));
    }
    let w = options.pixel_window();
    if !w.is_inside(crop) {
        let of =
            if options.crop.is_some() { format!("crop {crop:?} of the {width}x{height} image") } else { format!("{width}x{height} image") };
        return Err(Error::invalid("window", format!("{w:?} must be non-empty and inside the {of}")));
    }
    let max_depth = options.max_depth.unwrap_or(scene.settings.max_depth);
    if max_depth == 0 {
        return Err(Error::invalid("max_depth", "must be at least 1"));
    }
    Ok(max_depth)
}

/// Renders `scene` with `options` into a film of the window's size: per pixel the
/// sum and sum of squares of its samples, so the mean and its variance follow for
/// any integrator. Errors on bad sizes, an integrator that cannot be built for the
/// scene, a thread pool that cannot start, cancellation, and a time limit (or a
/// stop) that ends before the first pass.
///
/// With a time limit, a pass that would not fit in the time left (judged by the
/// previous pass's time per sample) is shortened to the samples that do, so the
/// budget is used and every pixel still has the same sample count.
pub fn render(scene: &Scene, options: &RenderOptions, control: &RenderControl) -> Result<(Film, RenderStats), Error> {
    let pool = thread_pool(options.threads)?;
    render_in(&pool, scene, options, control, false)
}

/// [`render()`], developed into the mean image.
pub fn render_image(scene: &Scene, options: &RenderOptions, control: &RenderControl) -> Result<(Image, RenderStats), Error> {
    let pool = thread_pool(options.threads)?;
    let (film, stats) = render_in(&pool, scene, options, control, true)?;
    Ok((pool.install(|| film.into_mean()), stats))
}

fn render_in(
    pool: &rayon::ThreadPool,
    scene: &Scene,
    options: &RenderOptions,
    control: &RenderControl,
    image_only: bool,
) -> Result<(Film, RenderStats), Error> {
    let integrator = integrator_for(scene, options)?;
    let schedule = integrator.schedule();
    match options.adaptive {
        Some(Adaptive::Antialias(aa)) => {
            if schedule != Schedule::OnePass {
                return Err(Error::invalid(
                    "antialias",
                    format!(
                        "is for one-pass integrators (whitted); the {} integrator takes spp samples per pixel",
                        options.integrator.name
                    ),
                ));
            }
            adaptive::antialias(pool, scene, options, control, integrator.as_ref(), aa)
        }
        Some(Adaptive::NoiseThreshold(noise)) => {
            if schedule != Schedule::Doubling {
                return Err(Error::invalid(
                    "noise_threshold",
                    format!("needs a progressive integrator (path); {} takes all its samples in one pass", options.integrator.name),
                ));
            }
            passes(pool, scene, options, control, integrator.as_ref(), Sampled { image_only, only: None, noise: Some(noise) })
        }
        None => passes(pool, scene, options, control, integrator.as_ref(), Sampled { image_only, only: None, noise: None }),
    }
}

/// What [`passes`] samples besides `options`.
#[derive(Clone, Copy)]
struct Sampled<'a> {
    /// Keep only the mean image (the film need not hold sums).
    image_only: bool,
    /// Sample only the pixels marked (row-major over the window).
    only: Option<&'a [bool]>,
    /// Stop sampling pixels that have converged.
    noise: Option<NoiseThreshold>,
}

/// The passes of a render with a built integrator: every pixel of the window
/// (or those `sampled.only` marks) gets `options.spp` samples, fewer where a
/// noise threshold finds it converged or a time limit or stop ends the render.
fn passes(
    pool: &rayon::ThreadPool,
    scene: &Scene,
    options: &RenderOptions,
    control: &RenderControl,
    integrator: &dyn Integrator,
    sampled: Sampled,
) -> Result<(Film, RenderStats), Error> {
    let window = options.pixel_window();
    // The camera's window for this image size, worked out once rather than per ray.
    let sized = scene.settings.camera.for_image(options.width, options.height);
    let camera = sized.as_deref().unwrap_or(scene.settings.camera.as_ref());
    let view = view_of(scene, camera, options);
    let schedule = integrator.schedule();
    let spp = options.spp;
    let mut stats = RenderStats { threads: pool.current_num_threads(), ..RenderStats::default() };
    let start = Instant::now();
    let deadline = options.time_limit.map(|limit| start + limit);
    let tiles_done = AtomicU64::new(0);
    let tiles_per_pass = window.width.div_ceil(TILE) as u64 * window.height.div_ceil(TILE) as u64;
    let total_tiles = tiles_per_pass * schedule.pass_count(spp) as u64;
    // Pixels still sampled, row-major over the window; `None`: all of them.
    let mut active: Option<Vec<bool>> = sampled.only.map(<[bool]>::to_vec);
    // Made at the first check: a render without a noise threshold needs none.
    let mut convergence: Option<adaptive::Convergence> = None;
    // The first complete pass becomes the film; later ones are rendered into a
    // spare film and added, so a pass cut short leaves the film untouched.
    let (mut film, mut spare): (Option<Film>, Option<Film>) = (None, None);
    let mut done = 0;
    // Samples the time left allows the next pass (None: no limit in force).
    let mut fits: Option<u32> = None;
    while done < spp {
        let count = schedule.next_pass(done, spp).min(fits.unwrap_or(u32::MAX));
        let pass_start = Instant::now();
        // Only the image of one pass is wanted: keep its means, not its sums.
        let new_film = || match (sampled.image_only && active.is_none(), schedule) {
            (true, Schedule::OnePass) => Film::means_only(window.width, window.height),
            _ => Film::new(window.width, window.height),
        };
        let mut pass = spare.take().unwrap_or_else(new_film);
        pass.prepare_pass(count);
        let tiles_x = pass.tiles_x();
        let expired = AtomicBool::new(false);
        let mask = active.as_deref();
        let results: Vec<Option<TileOutcome>> = pool.install(|| {
            pass.tiles_mut(count)
                .enumerate()
                .map(|(tile, block)| {
                    if control.cancelled() || control.stopped() {
                        return None;
                    }
                    if deadline.is_some_and(|d| Instant::now() > d) {
                        expired.store(true, Ordering::Relaxed);
                        return None;
                    }
                    let (tx, ty) = (tile as u32 % tiles_x, tile as u32 / tiles_x);
                    let (x0, y0) = (window.x0 + tx * TILE, window.y0 + ty * TILE);
                    let x1 = (x0 + TILE).min(window.x0 + window.width);
                    let y1 = (y0 + TILE).min(window.y0 + window.height);
                    let out = render_tile(integrator, &view, block, (x0, y0, x1, y1), done, count, mask.map(|m| (m, window)));
                    (control.progress)(tiles_done.fetch_add(1, Ordering::Relaxed) + 1, total_tiles);
                    Some(out)
                })
                .collect()
        });
        if control.cancelled() {
            return Err(Error::Render("cancelled".into()));
        }
        let stopped = control.stopped();
        if (expired.load(Ordering::Relaxed) || stopped) && results.iter().any(Option::is_none) {
            if done == 0 {
                let why = if stopped { "interrupted" } else { "the time limit ended" };
                return Err(Error::Render(format!("{why} before the first pass finished")));
            }
            break; // drop the incomplete pass
        }
        for outcome in results.into_iter().flatten() {
            stats.rays.add(&outcome.counts);
            stats.nonfinite_samples += outcome.nonfinite;
            stats.pixel_samples += outcome.samples;
        }
        done += count;
        match (film.as_mut(), active.as_deref()) {
            (None, None) => {
                pass.set_samples(count);
                film = Some(pass);
            }
            (None, Some(mask)) => {
                pass.set_samples(0);
                pass.add_counts(mask, count);
                film = Some(pass);
            }
            (Some(film), mask) => {
                if let Some(mask) = mask {
                    film.add_counts(mask, count);
                }
                pass.set_samples(count);
                pool.install(|| film.add(&pass));
                spare = Some(pass);
            }
        }
        if stopped {
            break;
        }
        if let (Some(noise), Some(film)) = (sampled.noise, film.as_ref()) {
            if let Some(may_stop) = noise.check_after(done, spp) {
                let pixels = window.width as usize * window.height as usize;
                let convergence = convergence.get_or_insert_with(|| adaptive::Convergence::new(pixels));
                let still = convergence.check(pool, film, active.as_deref(), noise.threshold, may_stop);
                let any = still.iter().any(|a| *a);
                active = Some(still);
                if !any {
                    break;
                }
            }
        }
        if let Some(d) = deadline {
            // Do not start a pass that cannot finish: shorten it to the samples
            // this one's time per sample says fit in what is left.
            let now = Instant::now();
            let per_sample = pass_start.elapsed().as_secs_f64() / count as f64;
            let left = d.saturating_duration_since(now).as_secs_f64();
            let n = (BUDGET_SHARE * left / per_sample.max(1e-9)).floor().min(u32::MAX as f64) as u32;
            if n == 0 {
                break;
            }
            fits = Some(n);
        }
    }
    stats.elapsed = start.elapsed();
    // `spp >= 1`, and a render without a complete pass returned above.
    let film = film.ok_or_else(|| Error::Render("no pass finished".into()))?;
    stats.samples_per_pixel = film.samples();
    Ok((film, stats))
}

/// The integrator `options` ask for, built for `scene` (sizes and depth checked).
pub(crate) fn integrator_for(scene: &Scene, options: &RenderOptions) -> Result<Box<dyn Integrator>, Error> {
    let max_depth = checked_depth(scene, options)?;
    (options.integrator.build)(scene, &IntegratorSettings { max_depth, filter: options.filter })
}

/// The view of the render of `scene` with `options` through `camera` (the
/// scene's camera sized for the image, [`crate::camera::Camera::for_image`]).
pub(crate) fn view_of<'a>(scene: &'a Scene, camera: &'a dyn crate::camera::Camera, options: &RenderOptions) -> View<'a> {
    View::new(scene, camera, options.width, options.height, options.spp, options.seed).with_clamp(options.clamp).with_crop(options.crop)
}

/// What one tile of one pass did.
struct TileOutcome {
    counts: RayCounts,
    /// Samples dropped as NaN, infinite or too bright.
    nonfinite: u64,
    /// Samples taken.
    samples: u64,
}

/// Samples `first..first + count` of every pixel of the tile covering columns
/// `x0..x1` and rows `y0..y1` of the full image (only those `mask` marks, row-major
/// over its window, when given; the others stay zero), each pixel's summed in
/// sample order into `block`.
fn render_tile(
    integrator: &dyn Integrator,
    view: &View,
    mut block: TileBlock,
    (x0, y0, x1, y1): (u32, u32, u32, u32),
    first: u32,
    count: u32,
    mask: Option<(&[bool], PixelWindow)>,
) -> TileOutcome {
    let mut outcome = TileOutcome { counts: RayCounts::default(), nonfinite: 0, samples: 0 };
    let mut row = [PixelSum::default(); TILE as usize];
    let width = (x1 - x0) as usize;
    let samples = first..first + count;
    for y in y0..y1 {
        let sums = &mut row[..width];
        sums.fill(PixelSum::default());
        match mask {
            None => {
                outcome.nonfinite += integrator.sample_row(view, (x0, y), samples.clone(), &mut outcome.counts, sums);
                outcome.samples += width as u64 * count as u64;
            }
            Some((mask, window)) => {
                let start = (y - window.y0) as usize * window.width as usize + (x0 - window.x0) as usize;
                let marked = &mask[start..start + width];
                // Each run of marked pixels in one call, as an unmasked row is.
                let mut i = 0;
                while i < width {
                    if !marked[i] {
                        i += 1;
                        continue;
                    }
                    let run = marked[i..].iter().take_while(|m| **m).count();
                    let at = (x0 + i as u32, y);
                    outcome.nonfinite += integrator.sample_row(view, at, samples.clone(), &mut outcome.counts, &mut sums[i..i + run]);
                    outcome.samples += run as u64 * count as u64;
                    i += run;
                }
            }
        }
        for (x, sum) in (x0..x1).zip(sums.iter()) {
            block.set(x - x0, y - y0, *sum);
        }
    }
    outcome
}
