//! Adaptive sampling: samples only where a pixel needs them.
//!
//! - [`Antialias`], POV-Ray's `+A` (its "method 1") for one-pass integrators
//!   (Whitted): one sample at each pixel's centre; then every pixel whose colour
//!   differs from one of its four neighbours' by more than the threshold,
//!   measured as POV-Ray does by the sum over channels of the absolute
//!   differences (of colours clipped to [0, 1], as the display shows them), is
//!   rendered again with `samples` stratified, jittered samples. A refined pixel is
//!   exactly the pixel of a `spp = samples` render, any other exactly that of a
//!   one-sample render.
//! - [`NoiseThreshold`], Cycles' adaptive sampling for progressive integrators
//!   (the path tracer): after every pass from `min_samples` on, a pixel whose
//!   noise ([`pixel_error`]: the standard error of its mean relative to the
//!   square root of its brightness, Cycles' measure) is below the threshold
//!   takes no more samples.
//!
//! Both decide from sums that depend only on (seed, pixel, sample index), and a
//! pixel's fate only on its own samples and (anti-aliasing) its neighbours', which
//! a window renders in a one-pixel border: the image is the same for any number
//! of threads and when rendered in windows on several machines.

use std::time::{Duration, Instant};

use rayon::prelude::*;

use super::{passes, RenderControl, RenderOptions, RenderStats, Sampled};
use crate::film::{variance_of_mean, Film, Image, PixelSum, PixelWindow};
use crate::integrators::Integrator;
use crate::scene::Scene;
use crate::Error;

/// How a render spends samples adaptively.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Adaptive {
    /// Anti-aliasing where neighbours differ (one-pass integrators).
    Antialias(Antialias),
    /// Stop converged pixels (progressive integrators).
    NoiseThreshold(NoiseThreshold),
}

/// POV-Ray's adaptive anti-aliasing (`+A0.3`), see the module doc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Antialias {
    /// Largest difference from a neighbour, summed over channels, that leaves a
    /// pixel with one sample (POV-Ray's `Antialias_Threshold`, 0.3 by default).
    pub threshold: f64,
    /// Samples of a refined pixel (stratified on a grid when a square).
    pub samples: u32,
}

impl Default for Antialias {
    /// POV-Ray's threshold 0.3, and 16 samples (a 4 x 4 grid) where it acts.
    fn default() -> Antialias {
        Antialias { threshold: 0.3, samples: 16 }
    }
}

/// Cycles' noise threshold, see the module doc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NoiseThreshold {
    /// Noise ([`pixel_error`]) below which a pixel stops.
    pub threshold: f64,
    /// Samples every pixel takes before any stops.
    pub min_samples: u32,
}

/// Brightness below which the error is measured against this instead, so that
/// a black pixel's error is finite (Cycles adds 1e-4).
pub const ERROR_FLOOR: f64 = 1e-4;

/// Default of [`NoiseThreshold::min_samples`]: enough that a pixel whose first
/// samples all missed a small light is rarely taken for converged.
pub const DEFAULT_MIN_SAMPLES: u32 = 16;

/// A pixel's noise after `n` samples with sums `sum`:
/// `sqrt(mean_c Var[mean]_c) / sqrt(max(B, ERROR_FLOOR))`, `B = mean_c mean_c`:
/// the RMS over channels of the standard error of the pixel's mean, relative to
/// the square root of its brightness, as Cycles measures it. The square root is
/// close to what a display's encoding does to radiance, so this is about the
/// noise the display shows: relative to `B` itself, dark pixels, whose noise is
/// invisible, would take most samples (measured on cornell-box: at a threshold
/// of 0.1 the darkest pixels took all 1024 samples and the image had three
/// times the error of a fixed count with the same total). Infinite with fewer
/// than two samples.
pub fn pixel_error(sum: PixelSum, n: u32) -> f64 {
    if n < 2 {
        return f64::INFINITY;
    }
    let n = n as f64;
    let var = variance_of_mean(sum.sum, sum.sum_sq, n);
    let mean = sum.sum / n;
    let brightness = ((mean.x + mean.y + mean.z) / 3.0).max(ERROR_FLOOR);
    ((var.x + var.y + var.z) / 3.0 / brightness).sqrt()
}

/// Checks in a row a pixel's error must be below the threshold before it
/// stops. One check is not enough: at a few samples the error estimate is itself
/// noisy, and the pixels that stop first are those whose samples happened to
/// agree (on cornell-box, bright wall pixels stopped at 16 samples with 14
/// times the error they had at 428). A second check, after twice the samples,
/// catches most of them. Checks start at half of `min_samples`, so a pixel can
/// stop at `min_samples`.
pub const CHECKS_IN_A_ROW: u8 = 2;

impl NoiseThreshold {
    /// Whether the render checks the pixels after `done` of `spp` samples
    /// (from half of `min_samples` on, before the last pass) and, if so, whether
    /// a pixel may stop then (from `min_samples` on).
    pub(crate) fn check_after(&self, done: u32, spp: u32) -> Option<bool> {
        (done >= (self.min_samples / 2).max(2) && done < spp).then_some(done >= self.min_samples)
    }
}

/// One pixel's check after `n` samples with sums `sum`: `below` (the checks in
/// a row its error was below `threshold`) counts up or starts again; whether
/// the pixel goes on sampling (it stops after [`CHECKS_IN_A_ROW`], if `may_stop`).
pub(crate) fn keeps_sampling(below: &mut u8, sum: PixelSum, n: u32, threshold: f64, may_stop: bool) -> bool {
    let converged = pixel_error(sum, n) < threshold;
    *below = if converged { *below + 1 } else { 0 };
    *below < CHECKS_IN_A_ROW || !may_stop
}

/// Which pixels a noise threshold still samples, check after check.
pub(super) struct Convergence {
    /// Per pixel (row-major), the checks in a row its error was below the threshold.
    below: Vec<u8>,
}

impl Convergence {
    pub(super) fn new(pixels: usize) -> Convergence {
        Convergence { below: vec![0; pixels] }
    }

    /// Checks the pixels of `film` still sampled (of `active`, or all) against
    /// `threshold` ([`pixel_error`]) and returns those to go on sampling: all
    /// but those below it [`CHECKS_IN_A_ROW`] checks in a row (none before
    /// `may_stop`).
    pub(super) fn check(
        &mut self,
        pool: &rayon::ThreadPool,
        film: &Film,
        active: Option<&[bool]>,
        threshold: f64,
        may_stop: bool,
    ) -> Vec<bool> {
        let width = film.width() as usize;
        let mut still = vec![false; self.below.len()];
        pool.install(|| {
            still.par_chunks_mut(width).zip(self.below.par_chunks_mut(width)).enumerate().for_each(|(y, (row, below))| {
                for (x, (out, below)) in row.iter_mut().zip(below).enumerate() {
                    if active.is_some_and(|a| !a[y * width + x]) {
                        continue;
                    }
                    let (x, y) = (x as u32, y as u32);
                    *out = keeps_sampling(below, film.get(x, y), film.samples_at(x, y), threshold, may_stop);
                }
            });
        });
        still
    }
}

/// Sum over channels of `|a - b|`, each clipped to [0, 1] first.
fn colour_distance(a: [f32; 3], b: [f32; 3]) -> f64 {
    a.iter().zip(b).map(|(a, b)| (a.clamp(0.0, 1.0) - b.clamp(0.0, 1.0)).abs() as f64).sum()
}

/// Which pixels of `window` to refine (row-major): those whose colour in
/// `probe` (an image of `around`, the window grown by up to a pixel on each
/// side) differs from a neighbour's by more than `threshold`.
pub fn refine_mask(probe: &Image, around: PixelWindow, window: PixelWindow, threshold: f64) -> Vec<bool> {
    let at = |x: u32, y: u32| probe.pixels[((y - around.y0) * around.width + (x - around.x0)) as usize];
    let mut mask = Vec::with_capacity(window.width as usize * window.height as usize);
    for y in window.y0..window.y0 + window.height {
        for x in window.x0..window.x0 + window.width {
            let here = at(x, y);
            let mut neighbours = [(x.wrapping_sub(1), y), (x + 1, y), (x, y.wrapping_sub(1)), (x, y + 1)].into_iter();
            let differs = neighbours.any(|(nx, ny)| {
                let inside = nx >= around.x0 && nx < around.x0 + around.width && ny >= around.y0 && ny < around.y0 + around.height;
                inside && colour_distance(here, at(nx, ny)) > threshold
            });
            mask.push(differs);
        }
    }
    mask
}

/// The window grown by one pixel on each side, inside the `width x height` image.
pub(crate) fn grown(w: PixelWindow, width: u32, height: u32) -> PixelWindow {
    let (x0, y0) = (w.x0.saturating_sub(1), w.y0.saturating_sub(1));
    let x1 = (w.x0 + w.width + 1).min(width);
    let y1 = (w.y0 + w.height + 1).min(height);
    PixelWindow { x0, y0, width: x1 - x0, height: y1 - y0 }
}

/// An anti-aliased render (see the module doc): a one-sample probe of the window
/// and its border, then `aa.samples` samples of the pixels that differ from a
/// neighbour. With a time limit or a stop that ends the second pass, the probe
/// alone is the image (every pixel one sample).
pub(super) fn antialias(
    pool: &rayon::ThreadPool,
    scene: &Scene,
    options: &RenderOptions,
    control: &RenderControl,
    integrator: &dyn Integrator,
    aa: Antialias,
) -> Result<(Film, RenderStats), Error> {
    let start = Instant::now();
    let window = options.pixel_window();
    let around = grown(window, options.width, options.height);
    let probe_options = RenderOptions { spp: 1, window: Some(around), adaptive: None, ..options.clone() };
    let (probe, mut stats) =
        passes(pool, scene, &probe_options, control, integrator, Sampled { image_only: true, only: None, noise: None })?;
    let probe = pool.install(|| probe.into_mean());
    let mask = refine_mask(&probe, around, window, aa.threshold);
    let left = options.time_limit.map(|limit| limit.saturating_sub(start.elapsed()));
    let refined = if mask.iter().any(|m| *m) && left.is_none_or(|l| l > Duration::ZERO) && !control.stopped() {
        let refine_options = RenderOptions { spp: aa.samples, window: Some(window), adaptive: None, time_limit: left, ..options.clone() };
        let only = Sampled { image_only: false, only: Some(&mask), noise: None };
        match passes(pool, scene, &refine_options, control, integrator, only) {
            Ok(refined) => Some(refined),
            Err(_) if control.cancelled() => return Err(Error::Render("cancelled".into())),
            // The time limit or a stop ended the refinement: the probe stands.
            Err(_) => None,
        }
    } else {
        None
    };
    let mut film = match refined {
        Some((film, refined_stats)) => {
            stats.rays.add(&refined_stats.rays);
            stats.nonfinite_samples += refined_stats.nonfinite_samples;
            stats.pixel_samples += refined_stats.pixel_samples;
            film
        }
        None => Film::new(window.width, window.height),
    };
    // The probe's border pixels are not part of the image.
    stats.pixel_samples -= around.width as u64 * around.height as u64 - window.width as u64 * window.height as u64;
    let refined_any = film.samples() > 0;
    for y in 0..window.height {
        for x in 0..window.width {
            if refined_any && mask[(y * window.width + x) as usize] {
                continue;
            }
            let p = probe.pixels[((y + window.y0 - around.y0) * around.width + x + window.x0 - around.x0) as usize];
            let sum = crate::math::Rgb::new(p[0] as f64, p[1] as f64, p[2] as f64);
            film.set_pixel(x, y, PixelSum { sum, sum_sq: sum * sum }, 1);
        }
    }
    stats.samples_per_pixel = film.samples();
    stats.elapsed = start.elapsed();
    Ok((film, stats))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rgb;

    #[test]
    fn pixel_error_is_the_standard_error_over_the_root_of_the_mean() {
        // Samples 1 and 3 in every channel: mean 2, sample variance 2, variance of the mean 1.
        let sum = PixelSum { sum: Rgb::splat(4.0), sum_sq: Rgb::splat(10.0) };
        assert!((pixel_error(sum, 2) - 0.5f64.sqrt()).abs() < 1e-15);
        // Samples 6 and 10: four times brighter, four times the variance of the
        // mean: the same error (the noise a square-root display shows).
        let bright = PixelSum { sum: Rgb::splat(16.0), sum_sq: Rgb::splat(136.0) };
        assert!((pixel_error(bright, 2) - 0.5f64.sqrt()).abs() < 1e-15);
        // Equal samples: no error; one sample: unknown.
        assert_eq!(pixel_error(PixelSum { sum: Rgb::splat(6.0), sum_sq: Rgb::splat(12.0) }, 3), 0.0);
        assert_eq!(pixel_error(sum, 1), f64::INFINITY);
        // A black pixel is measured against the floor: samples 0 and 0.00001.
        let dark = PixelSum { sum: Rgb::splat(1e-5), sum_sq: Rgb::splat(1e-10) };
        assert!((pixel_error(dark, 2) - (0.25e-10 / ERROR_FLOOR).sqrt()).abs() < 1e-15);
    }

    #[test]
    fn pixels_are_refined_where_a_neighbour_differs_by_more_than_the_threshold() {
        // A 4 x 3 image, black but for a grey pixel at (1, 1) that differs from
        // its neighbours by 3 x 0.2 = 0.6, and a bright one at (3, 0) clipped to
        // 1 so its difference from (2, 0)'s 0.95 is 3 x 0.05.
        let mut probe = Image::new(4, 3);
        probe.pixels[5] = [0.2; 3];
        probe.pixels[3] = [7.0; 3];
        probe.pixels[2] = [0.95; 3];
        let all = PixelWindow { x0: 0, y0: 0, width: 4, height: 3 };
        let mask = refine_mask(&probe, all, all, 0.3);
        #[rustfmt::skip]
        let expected = [
            false, true, true, true,
            true, true, true, true,
            false, true, false, false,
        ];
        assert_eq!(mask, expected);
        // (2, 0) against (3, 0) alone stays below a threshold of 0.3 ...
        assert!(colour_distance([0.95; 3], [7.0; 3]) < 0.3);
        // ... and a window sees neighbours in the border around it.
        let window = PixelWindow { x0: 2, y0: 1, width: 1, height: 1 };
        assert_eq!(grown(window, 4, 3), PixelWindow { x0: 1, y0: 0, width: 3, height: 3 });
        assert_eq!(refine_mask(&probe, all, window, 0.3), [true]);
        assert_eq!(grown(all, 4, 3), all);
    }
}
