//! Adaptive sampling through the render loop: POV-Ray's anti-aliasing for the
//! Whitted tracer and Cycles' noise threshold for the path tracer. Each pixel of
//! an adaptive render is exactly the pixel of a fixed-count render with its own
//! count, the counts follow the stated rules, and the bytes do not depend on
//! threads or windows.

use std::sync::Arc;

use lamplight_core::adaptive::{pixel_error, refine_mask};
use lamplight_core::film::{Film, Image};
use lamplight_core::integrators::IntegratorEntry;
use lamplight_core::lights::Environment;
use lamplight_core::prelude::*;
use lamplight_core::{Adaptive, Antialias, NoiseThreshold, PixelWindow};

/// A red ball on a grey floor under a point light, a sky around: hard edges for
/// anti-aliasing and, under the path tracer, noise that converges at different
/// rates (the sky in a few samples, the penumbra and the floor slowly).
fn scene() -> Scene {
    let camera = Perspective::look_at(Vec3::new(0.0, 1.0, 5.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let red = b.material(Material::plastic(Rgb::new(0.9, 0.1, 0.1), 0.2, 0.8, 0.3, 20.0)).unwrap();
    let grey = b.material(Material::plastic(Rgb::splat(0.6), 0.2, 0.0, 0.0, 1.0)).unwrap();
    b.object(Sphere::new(Vec3::ZERO, 1.0).unwrap(), red).unwrap();
    b.object(Sphere::new(Vec3::new(0.0, -1001.0, 0.0), 1000.0).unwrap(), grey).unwrap();
    b.light(PointLight::new(Vec3::new(3.0, 4.0, 5.0), Rgb::splat(40.0)).unwrap());
    b.settings.environment = Some(Arc::new(Environment::Constant(Rgb::splat(0.4))));
    b.settings.ambient = Rgb::splat(0.1);
    b.build().unwrap()
}

fn integrator(name: &str) -> &'static IntegratorEntry {
    name.parse().unwrap()
}

const W: u32 = 40;
const H: u32 = 30;

fn options(name: &str, spp: u32, adaptive: Option<Adaptive>) -> RenderOptions {
    RenderOptions { width: W, height: H, spp, integrator: integrator(name), threads: 2, adaptive, ..RenderOptions::default() }
}

fn film(options: &RenderOptions) -> (Film, RenderStats) {
    render(&scene(), options, &RenderControl::default()).unwrap()
}

fn image(options: &RenderOptions) -> Image {
    render_image(&scene(), options, &RenderControl::default()).unwrap().0
}

fn bits(p: [f32; 3]) -> [u32; 3] {
    p.map(f32::to_bits)
}

#[test]
fn antialiasing_refines_exactly_the_pixels_whose_neighbours_differ() {
    let aa = Antialias::default();
    let (film, stats) = film(&options("whitted", 1, Some(Adaptive::Antialias(aa))));
    let adaptive = film.mean();
    let one = image(&options("whitted", 1, None));
    let sixteen = image(&options("whitted", 16, None));
    let all = PixelWindow { x0: 0, y0: 0, width: W, height: H };
    let mask = refine_mask(&one, all, all, aa.threshold);
    let refined = mask.iter().filter(|m| **m).count();
    // The ball's outline and the horizon: some pixels, far from all.
    assert!(refined > 40 && refined < (W * H / 2) as usize, "{refined} of {} pixels refined", W * H);
    for y in 0..H {
        for x in 0..W {
            let i = (y * W + x) as usize;
            let (expected, count) = if mask[i] { (sixteen.get(x, y), 16) } else { (one.get(x, y), 1) };
            assert_eq!(bits(adaptive.get(x, y)), bits(expected), "pixel ({x}, {y})");
            assert_eq!(film.samples_at(x, y), count, "pixel ({x}, {y})");
        }
    }
    // Taken: the probe's sample of every pixel, then 16 more where refined.
    assert_eq!(stats.pixel_samples, (W * H) as u64 + 16 * refined as u64);
    assert_eq!(stats.samples_per_pixel, 16);
    // Flat regions stay as they were: the render is one-sample Whitted there.
    assert!(refined < (W * H) as usize);
}

#[test]
fn antialiasing_gives_the_same_bytes_on_any_threads_and_in_windows() {
    let aa = Some(Adaptive::Antialias(Antialias::default()));
    let full = image(&RenderOptions { threads: 1, ..options("whitted", 1, aa) });
    assert_eq!(full.pixels, image(&RenderOptions { threads: 3, ..options("whitted", 1, aa) }).pixels);
    // A window whose edges cut through the ball's outline: the border pixels
    // outside it decide as they do in the full image.
    let window = PixelWindow { x0: 13, y0: 7, width: 11, height: 9 };
    let part = image(&RenderOptions { window: Some(window), ..options("whitted", 1, aa) });
    for y in 0..window.height {
        for x in 0..window.width {
            assert_eq!(bits(part.get(x, y)), bits(full.get(x + window.x0, y + window.y0)), "window pixel ({x}, {y})");
        }
    }
}

#[test]
fn antialiasing_is_refused_for_the_path_tracer_and_noise_threshold_for_whitted() {
    let scene = scene();
    let aa = options("path", 4, Some(Adaptive::Antialias(Antialias::default())));
    let err = render(&scene, &aa, &RenderControl::default()).unwrap_err().to_string();
    assert_eq!(err, "invalid antialias: is for one-pass integrators (whitted); the path integrator takes spp samples per pixel");
    let noise = options("whitted", 4, Some(Adaptive::NoiseThreshold(NoiseThreshold { threshold: 0.1, min_samples: 2 })));
    let err = render(&scene, &noise, &RenderControl::default()).unwrap_err().to_string();
    assert_eq!(err, "invalid noise_threshold: needs a progressive integrator (path); whitted takes all its samples in one pass");
}

#[test]
fn a_noise_threshold_stops_each_pixel_once_its_error_is_below_it() {
    let noise = NoiseThreshold { threshold: 0.05, min_samples: 8 };
    let spp = 128;
    let film_of = film;
    let (film, stats) = film_of(&options("path", spp, Some(Adaptive::NoiseThreshold(noise))));
    let mut counts = std::collections::BTreeMap::new();
    for y in 0..H {
        for x in 0..W {
            let n = film.samples_at(x, y);
            *counts.entry(n).or_insert(0u32) += 1;
            // Checked after the passes of 1, 1, 2, 4, ... samples: a power of two.
            assert!(n.is_power_of_two() && (noise.min_samples..=spp).contains(&n), "pixel ({x}, {y}): {n} samples");
            let error = pixel_error(film.get(x, y), n);
            if n < spp {
                assert!(error < noise.threshold, "pixel ({x}, {y}) stopped at {n} samples with error {error}");
            }
        }
    }
    // The sky converges at once, the penumbra takes all the samples.
    assert!(counts.len() >= 3, "sample counts {counts:?}");
    assert!(counts.get(&spp).copied().unwrap_or(0) > 0 && counts.get(&noise.min_samples).copied().unwrap_or(0) > 0, "{counts:?}");
    let total: u64 = counts.iter().map(|(n, k)| *n as u64 * *k as u64).sum();
    assert_eq!(stats.pixel_samples, total);
    assert!(total < (W * H * spp) as u64 / 2, "{total} samples, of {} without a threshold", W * H * spp);
    // A pixel that stopped at n samples is exactly the pixel of an n-sample render.
    let sixteen = image(&options("path", 16, None));
    let adaptive = film.mean();
    let mut compared = 0;
    for y in 0..H {
        for x in 0..W {
            if film.samples_at(x, y) == 16 {
                assert_eq!(bits(adaptive.get(x, y)), bits(sixteen.get(x, y)), "pixel ({x}, {y})");
                compared += 1;
            }
        }
    }
    assert!(compared > 0, "no pixel stopped at 16 samples: {counts:?}");
    // A pixel stops after two checks in a row below the threshold: one that
    // stopped at 32 samples was below it at 16 too.
    let (at16, _) = film_of(&options("path", 16, None));
    let mut checked = 0;
    for y in 0..H {
        for x in 0..W {
            if film.samples_at(x, y) == 32 {
                assert!(pixel_error(at16.get(x, y), 16) < noise.threshold, "pixel ({x}, {y}) stopped at 32 without a first check at 16");
                checked += 1;
            }
        }
    }
    assert!(checked > 0, "no pixel stopped at 32 samples: {counts:?}");
    // Threads and windows do not change a byte.
    let with = |threads, window| {
        render(
            &scene(),
            &RenderOptions { threads, window, ..options("path", spp, Some(Adaptive::NoiseThreshold(noise))) },
            &RenderControl::default(),
        )
        .unwrap()
        .0
    };
    assert_eq!(with(1, None), with(3, None));
    let window = PixelWindow { x0: 5, y0: 9, width: 17, height: 6 };
    let part = with(2, Some(window));
    for y in 0..window.height {
        for x in 0..window.width {
            assert_eq!(part.get(x, y), film.get(x + window.x0, y + window.y0), "window pixel ({x}, {y})");
            assert_eq!(part.samples_at(x, y), film.samples_at(x + window.x0, y + window.y0));
        }
    }
}

#[test]
fn variance_and_sample_counts_are_per_pixel() {
    let noise = NoiseThreshold { threshold: 0.05, min_samples: 4 };
    let (film, _) = film(&options("path", 32, Some(Adaptive::NoiseThreshold(noise))));
    let variance = film.variance();
    let counts = film.sample_counts();
    for y in 0..H {
        for x in 0..W {
            let n = film.samples_at(x, y) as f64;
            assert_eq!(counts[(y * W + x) as usize], n as f32);
            let s = film.get(x, y);
            let mean = s.sum.x / n;
            let expected = ((s.sum_sq.x / n - mean * mean) * n / (n - 1.0)).max(0.0) / n;
            assert_eq!(variance.get(x, y)[0], expected as f32, "pixel ({x}, {y}) with {n} samples");
        }
    }
}
