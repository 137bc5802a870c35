//! Progressive rendering for the path tracer: whole-image passes of 1, 1, 2, 4, ...
//! samples per pixel until the requested count or the time limit.
//!
//! Sample `i` of pixel `p` always uses the Sobol point `i` scrambled for `p`
//! ([`PixelSampler`]), and each pixel adds its samples in index order into its own
//! sum, so the image does not depend on threads or pass sizes: a render of `2N`
//! samples continues one of `N`. Passes double so that each finished pass leaves
//! a power-of-two count, where the Sobol points are best stratified. With a time
//! limit, a pass that would not finish in time is not started, and a pass cut
//! short is dropped: the image is always that of the last complete pass.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Instant;

use rayon::prelude::*;

use crate::film::Image;
use crate::integrators::{PathTracer, RayCounts};
use crate::math::Rgb;
use crate::sampling::PixelSampler;
use crate::scene::Scene;
use crate::{Error, RenderControl, RenderOptions, RenderStats};

const TILE: u32 = 16;

/// One tile of one pass: per pixel (sum, sum of squares), ray counts, non-finite samples.
type TilePass = (Vec<(Rgb, Rgb)>, RayCounts, u64);

/// Per-pixel sums of a progressive render.
#[derive(Clone, Debug)]
pub struct Accumulator {
    /// Sum of sample radiance per pixel.
    pub sum: Vec<Rgb>,
    /// Sum of squared sample radiance per pixel (for the variance).
    pub sum_sq: Vec<Rgb>,
    /// Samples taken per pixel.
    pub samples: u32,
}

impl Accumulator {
    /// The mean image.
    pub fn mean(&self, width: u32, height: u32) -> Image {
        let mut image = Image::new(width, height);
        let n = self.samples.max(1) as f64;
        for (p, s) in image.pixels.iter_mut().zip(&self.sum) {
            let m = *s / n;
            *p = [m.x as f32, m.y as f32, m.z as f32];
        }
        image
    }

    /// Variance of the pixel mean (sample variance / n), per channel.
    pub fn variance(&self, width: u32, height: u32) -> Image {
        let mut image = Image::new(width, height);
        let n = self.samples as f64;
        if n < 2.0 {
            return image;
        }
        for ((p, s), q) in image.pixels.iter_mut().zip(&self.sum).zip(&self.sum_sq) {
            let mean = *s / n;
            let var = ((*q / n - mean * mean) * (n / (n - 1.0))).max(Rgb::ZERO) / n;
            *p = [var.x as f32, var.y as f32, var.z as f32];
        }
        image
    }
}

/// Renders with the path tracer; returns the accumulator and the statistics.
pub(crate) fn render_path(
    scene: &Scene,
    options: &RenderOptions,
    max_depth: u32,
    control: &RenderControl,
) -> Result<(Accumulator, RenderStats), Error> {
    let crate::render::PixelWindow { x0: wx, y0: wy, width, height } = options.pixel_window();
    let tracer = PathTracer::new(scene, max_depth);
    let pool = crate::render::thread_pool(options.threads)?;
    let threads = pool.current_num_threads();
    let tiles_x = width.div_ceil(TILE);
    let tile_count = tiles_x as u64 * height.div_ceil(TILE) as u64;
    let pixels = width as usize * height as usize;
    let mut acc = Accumulator { sum: vec![Rgb::ZERO; pixels], sum_sq: vec![Rgb::ZERO; pixels], samples: 0 };
    let mut stats = RenderStats { threads, ..RenderStats::default() };
    let start = Instant::now();
    let deadline = options.time_limit.map(|limit| start + limit);
    let done = AtomicU64::new(0);
    let total_tiles = tile_count * pass_count(options.spp) as u64;
    let mut pass_size = 1u32;
    while acc.samples < options.spp {
        let first = acc.samples;
        let count = pass_size.min(options.spp - first);
        let pass_start = Instant::now();
        let expired = AtomicBool::new(false);
        let results: Vec<Option<TilePass>> = pool.install(|| {
            (0..tile_count)
                .into_par_iter()
                .map(|tile| {
                    if control.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                        return None;
                    }
                    if deadline.is_some_and(|d| Instant::now() > d) {
                        expired.store(true, Ordering::Relaxed);
                        return None;
                    }
                    let x0 = wx + (tile % tiles_x as u64) as u32 * TILE;
                    let y0 = wy + (tile / tiles_x as u64) as u32 * TILE;
                    let out = render_tile(scene, &tracer, options, x0, y0, first, count);
                    let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
                    (control.progress)(finished, total_tiles);
                    Some(out)
                })
                .collect()
        });
        if control.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            return Err(Error::Render("cancelled".into()));
        }
        if expired.load(Ordering::Relaxed) && results.iter().any(|r| r.is_none()) {
            if acc.samples == 0 {
                return Err(Error::Render("the time limit ended before the first pass finished".into()));
            }
            break; // drop the incomplete pass
        }
        for (tile, result) in results.into_iter().enumerate() {
            let (values, counts, nonfinite) = result.expect("every tile of a complete pass");
            stats.rays.add(&counts);
            stats.nonfinite_samples += nonfinite;
            let x0 = (tile as u64 % tiles_x as u64) as u32 * TILE;
            let y0 = (tile as u64 / tiles_x as u64) as u32 * TILE;
            let tile_w = TILE.min(width - x0);
            for (i, (s, q)) in values.into_iter().enumerate() {
                let (x, y) = (x0 + i as u32 % tile_w, y0 + i as u32 / tile_w);
                let k = (y * width + x) as usize;
                acc.sum[k] += s;
                acc.sum_sq[k] += q;
            }
        }
        acc.samples += count;
        if first > 0 {
            pass_size = pass_size.saturating_mul(2);
        }
        if let Some(d) = deadline {
            // Do not start a pass that cannot finish: the next one takes about
            // twice as long as this one (it has twice the samples).
            let now = Instant::now();
            let next = pass_start.elapsed().mul_f64(pass_size.min(options.spp - acc.samples.min(options.spp)) as f64 / count as f64);
            if now >= d || now + next > d {
                break;
            }
        }
    }
    stats.elapsed = start.elapsed();
    stats.samples_per_pixel = acc.samples;
    Ok((acc, stats))
}

fn pass_count(spp: u32) -> u32 {
    let (mut n, mut taken, mut size) = (0, 0u32, 1u32);
    while taken < spp {
        taken = taken.saturating_add(size.min(spp - taken));
        if n > 0 {
            size = size.saturating_mul(2);
        }
        n += 1;
    }
    n
}

/// Samples `first..first + count` of every pixel of a tile: per pixel the sum of
/// the values and of their squares, added in sample order.
fn render_tile(scene: &Scene, tracer: &PathTracer, options: &RenderOptions, x0: u32, y0: u32, first: u32, count: u32) -> TilePass {
    let (width, height) = (options.width, options.height);
    let w = options.pixel_window();
    let x1 = (x0 + TILE).min(w.x0 + w.width);
    let y1 = (y0 + TILE).min(w.y0 + w.height);
    let mut out = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
    let mut counts = RayCounts::default();
    let mut nonfinite = 0;
    for y in y0..y1 {
        for x in x0..x1 {
            let pixel = y as u64 * width as u64 + x as u64;
            let (mut sum, mut sum_sq) = (Rgb::ZERO, Rgb::ZERO);
            for s in first..first + count {
                let mut sampler = PixelSampler::new(options.seed, pixel, s);
                let (dx, dy) = options.filter.sample(sampler.get_2d());
                let ray = scene.camera.ray(x as f64 + 0.5 + dx, y as f64 + 0.5 + dy, width, height);
                let l = tracer.li(scene, &ray, &mut sampler, &mut counts);
                if l.is_finite() {
                    sum += l;
                    sum_sq += l * l;
                } else {
                    nonfinite += 1;
                }
            }
            out.push((sum, sum_sq));
        }
    }
    (out, counts, nonfinite)
}
