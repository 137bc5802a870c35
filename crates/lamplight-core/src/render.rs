//! `render()`: the one entry point that turns a scene into an image.
//!
//! The image is cut into 16x16 tiles rendered in parallel (rayon). Each pixel's
//! samples use their own generators seeded by (seed, pixel, sample), and each
//! pixel is averaged in a fixed order, so the bytes of the image do not depend on
//! the number of threads or the order tiles finish in. For the same reason a
//! [`PixelWindow`] of the image renders to exactly the pixels of the full render
//! there, so an image can be split across machines and stitched back.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::film::{Filter, Image};
use crate::integrators::{Integrator, IntegratorKind, RayCounts, Whitted};
use crate::progressive::Accumulator;
use crate::sampling::{stratified_2d, Rng};
use crate::scene::Scene;
use crate::Error;

const TILE: u32 = 16;

/// One finished tile: its pixels (row-major), ray counts and non-finite samples.
type TileResult = (Vec<[f32; 3]>, RayCounts, u64);

/// What to render and how.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel, stratified and jittered when more than one.
    pub spp: u32,
    /// Depth limit; `None` uses the scene's.
    pub max_depth: Option<u32>,
    /// Worker threads; 0 uses all cores.
    pub threads: usize,
    /// Seed of the per-sample generators.
    pub seed: u64,
    /// The integrator.
    pub integrator: IntegratorKind,
    /// Path tracer only: stop after the last complete pass before this much time.
    pub time_limit: Option<Duration>,
    /// Path tracer only: the pixel reconstruction filter.
    pub filter: Filter,
    /// Render only this part of the `width x height` image (the result has the
    /// window's size); `None` renders all of it.
    pub window: Option<PixelWindow>,
}

/// A rectangle of pixels of the full image: columns `x0..x0 + width`, rows `y0..y0 + height`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelWindow {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
}

impl RenderOptions {
    /// The pixels to render: the window, or the whole image.
    pub fn pixel_window(&self) -> PixelWindow {
        self.window.unwrap_or(PixelWindow { x0: 0, y0: 0, width: self.width, height: self.height })
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
            integrator: IntegratorKind::Whitted,
            time_limit: None,
            filter: Filter::Box,
            window: None,
        }
    }
}

/// Figures about a finished render.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    /// Rays traced, by kind.
    pub rays: RayCounts,
    /// Samples whose radiance was NaN or infinite and was replaced by black.
    pub nonfinite_samples: u64,
    /// Wall-clock time of the render (not of scene building or file writing).
    pub elapsed: Duration,
    /// Threads used.
    pub threads: usize,
    /// Samples per pixel actually taken (fewer than asked when a time limit stopped the render).
    pub samples_per_pixel: u32,
}

/// Progress reports and cancellation for a running render.
pub struct RenderControl<'a> {
    /// Called after each tile with (tiles done, tiles in all); from worker threads.
    pub progress: &'a (dyn Fn(u64, u64) + Sync),
    /// When set, remaining tiles are skipped and `render` returns [`Error::Render`].
    pub cancel: Option<&'a AtomicBool>,
}

impl Default for RenderControl<'_> {
    fn default() -> Self {
        RenderControl { progress: &|_, _| {}, cancel: None }
    }
}

/// A pool of `threads` workers (0: one per core), shared by every renderer.
pub(crate) fn thread_pool(threads: usize) -> Result<rayon::ThreadPool, Error> {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().map_err(|e| Error::Render(format!("cannot start worker threads: {e}")))
}

/// Checks the image size and samples, and returns the depth limit in force.
fn checked_depth(scene: &Scene, options: &RenderOptions) -> Result<u32, Error> {
    let RenderOptions { width, height, spp, .. } = *options;
    if width == 0 || height == 0 || spp == 0 {
        return Err(Error::invalid("image", "width, height and samples per pixel must be at least 1"));
    }
    if width as u64 * height as u64 > 1 << 28 {
        return Err(Error::invalid("image", format!("{width}x{height} is too large (at most 2^28 pixels)")));
    }
    let w = options.pixel_window();
    if w.width == 0 || w.height == 0 || w.x0 as u64 + w.width as u64 > width as u64 || w.y0 as u64 + w.height as u64 > height as u64 {
        return Err(Error::invalid("window", format!("{w:?} must be non-empty and inside the {width}x{height} image")));
    }
    let max_depth = options.max_depth.unwrap_or(scene.max_depth);
    if max_depth == 0 {
        return Err(Error::invalid("max_depth", "must be at least 1"));
    }
    Ok(max_depth)
}

/// Renders `scene` with `options`. Errors on zero sizes, on a thread pool that cannot
/// start, and on cancellation.
pub fn render(scene: &Scene, options: &RenderOptions, control: &RenderControl) -> Result<(Image, RenderStats), Error> {
    let max_depth = checked_depth(scene, options)?;
    let PixelWindow { x0: wx, y0: wy, width, height } = options.pixel_window();
    let spp = options.spp;
    let integrator: Box<dyn Integrator> = match options.integrator {
        IntegratorKind::Whitted => Box::new(Whitted { max_depth, min_weight: scene.min_weight }),
        IntegratorKind::Path => {
            let (acc, stats) = crate::progressive::render_path(scene, options, max_depth, control)?;
            return Ok((acc.mean(width, height), stats));
        }
    };
    let pool = thread_pool(options.threads)?;
    let threads = pool.current_num_threads();

    let tiles_x = width.div_ceil(TILE);
    let tiles_y = height.div_ceil(TILE);
    let tile_count = tiles_x as u64 * tiles_y as u64;
    let done = AtomicU64::new(0);
    let start = Instant::now();
    let results: Vec<Option<TileResult>> = pool.install(|| {
        (0..tile_count)
            .into_par_iter()
            .map(|tile| {
                if control.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                    return None;
                }
                let x0 = wx + (tile % tiles_x as u64) as u32 * TILE;
                let y0 = wy + (tile / tiles_x as u64) as u32 * TILE;
                let out = render_tile(scene, integrator.as_ref(), options, x0, y0);
                let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
                (control.progress)(finished, tile_count);
                Some(out)
            })
            .collect()
    });
    let elapsed = start.elapsed();
    let mut image = Image::new(width, height);
    let mut stats = RenderStats { elapsed, threads, samples_per_pixel: spp, ..RenderStats::default() };
    for (tile, result) in results.into_iter().enumerate() {
        let Some((pixels, counts, nonfinite)) = result else {
            return Err(Error::Render("cancelled".into()));
        };
        stats.rays.add(&counts);
        stats.nonfinite_samples += nonfinite;
        let x0 = (tile as u64 % tiles_x as u64) as u32 * TILE;
        let y0 = (tile as u64 / tiles_x as u64) as u32 * TILE;
        // Row by row: a division per pixel to find its place cost ~10 ms of serial
        // time at 1280x720.
        let tile_w = TILE.min(width - x0) as usize;
        for (row, line) in pixels.chunks_exact(tile_w).enumerate() {
            let start = (y0 as usize + row) * width as usize + x0 as usize;
            image.pixels[start..start + tile_w].copy_from_slice(line);
        }
    }
    Ok((image, stats))
}

/// Renders `scene` with the path tracer (whatever `options.integrator` says) and
/// returns the per-pixel sums, from which the mean and its variance follow (of the
/// window's pixels, row-major, when `options.window` is set).
pub fn render_path(scene: &Scene, options: &RenderOptions, control: &RenderControl) -> Result<(Accumulator, RenderStats), Error> {
    let max_depth = checked_depth(scene, options)?;
    crate::progressive::render_path(scene, options, max_depth, control)
}

fn render_tile(scene: &Scene, integrator: &dyn Integrator, options: &RenderOptions, x0: u32, y0: u32) -> TileResult {
    let (width, height, spp) = (options.width, options.height, options.spp);
    let w = options.pixel_window();
    let x1 = (x0 + TILE).min(w.x0 + w.width);
    let y1 = (y0 + TILE).min(w.y0 + w.height);
    let mut pixels = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
    let mut counts = RayCounts::default();
    let mut nonfinite = 0;
    let camera = &scene.camera;
    let shift = camera.pixel_offset - 0.5;
    for y in y0..y1 {
        for x in x0..x1 {
            let pixel = y as u64 * width as u64 + x as u64;
            let mut sum = crate::math::Rgb::ZERO;
            for s in 0..spp {
                let mut rng = Rng::for_sample(options.seed, pixel, s as u64);
                let (dx, dy) = if spp == 1 {
                    (camera.pixel_offset, camera.pixel_offset)
                } else {
                    let jitter = (rng.uniform(), rng.uniform());
                    let (sx, sy) = stratified_2d(s, spp, jitter);
                    (sx + shift, sy + shift)
                };
                let ray = camera.ray(x as f64 + dx, y as f64 + dy, width, height);
                let radiance = integrator.radiance(scene, &ray, &mut rng, &mut counts);
                if radiance.is_finite() {
                    sum += radiance;
                } else {
                    nonfinite += 1;
                }
            }
            let mean = sum / spp as f64;
            pixels.push([mean.x as f32, mean.y as f32, mean.z as f32]);
        }
    }
    (pixels, counts, nonfinite)
}
