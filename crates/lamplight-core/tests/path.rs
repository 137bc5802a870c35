//! The path tracer's proofs: the white furnace (smooth and rough glass included), agreement with the BSDF-only
//! oracle, thread-count independence and progressive continuation.

use std::sync::Arc;

use lamplight_core::integrators::{self, PathTracer, RayCounts, SimplePath};
use lamplight_core::lights::Environment;
use lamplight_core::prelude::*;
use lamplight_core::sampling::PixelSampler;

fn furnace_scene(material: Material) -> Scene {
    let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(30.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let m = b.material(material).unwrap();
    b.object(Sphere::new(Vec3::ZERO, 1.0).unwrap(), m).unwrap();
    b.settings.environment = Some(Arc::new(Environment::Constant(Rgb::ONE)));
    b.settings.max_depth = 64;
    b.build().unwrap()
}

fn white_lambertian() -> Material {
    Material { color: Texture::Constant(Rgb::ONE), ka: Rgb::ZERO, kd: Rgb::ONE, ..Material::default() }
}

fn white_glass() -> Material {
    Material { ks: Rgb::ZERO, ..Material::glass(1.5, 0.0, 1.0) }
}

fn path_options(size: u32, spp: u32) -> RenderOptions {
    RenderOptions { width: size, height: size, spp, integrator: integrators::find("path").unwrap(), ..RenderOptions::default() }
}

#[test]
fn white_furnace_gives_one_everywhere() {
    // A white sphere in a uniform sky of radiance 1 neither adds nor removes light:
    // every pixel, on the sphere or not, sees radiance 1.
    for (name, material) in [("lambertian", white_lambertian()), ("dielectric", white_glass())] {
        let scene = furnace_scene(material);
        let (image, stats) = render_image(&scene, &path_options(8, 8192), &RenderControl::default()).unwrap();
        assert_eq!(stats.nonfinite_samples, 0);
        let mut worst = 0.0f32;
        for (i, p) in image.pixels.iter().enumerate() {
            for c in p {
                worst = worst.max((c - 1.0).abs());
                assert!((c - 1.0).abs() < 0.005, "{name}: pixel {i} is {p:?}");
            }
        }
        eprintln!("{name}: worst pixel error {worst}");
        // The centre pixels do see the sphere.
        assert!(stats.rays.secondary > 0);
    }
}

#[test]
fn rough_glass_furnace_loses_only_the_microfacet_shadowing() {
    // A rough glass sphere in the furnace: the radiance scaling 1 / eta^2 in and eta^2
    // out cancels, so the only loss is the single-scattering microfacet model's
    // (light the microsurface shadows is dropped, as in pbrt and Mitsuba). No pixel
    // may gain energy. The centre 4x4 pixels see the sphere at incidence below 30
    // degrees, where nearly smooth glass keeps 1 within 0.5 %; the silhouette's
    // grazing incidence loses more (G1 -> 0 at grazing for any roughness).
    // The loss is Mitsuba 3's: its `roughdielectric` (GGX, same sphere, camera and
    // box filter, 8192 spp; `bench/mitsuba_furnace.py`) gives the centre and image
    // means below, which lamplight matches within 0.5 % up to alpha 0.1. Mitsuba's
    // masking-shadowing is the separable G1(wo) G1(wi); lamplight's is pbrt-v4's
    // height-correlated 1 / (1 + Lambda(wo) + Lambda(wi)), which is larger, so at alpha
    // 0.4 lamplight keeps about 1 % more (with the separable form swapped in, the
    // image means agreed within 0.1 % at all three roughnesses).
    for (alpha, mitsuba_centre, mitsuba_mean) in [(0.02, 0.9989, 0.9935), (0.1, 0.9799, 0.9529), (0.4, 0.7354, 0.7258)] {
        let scene = furnace_scene(Material { roughness: alpha, ..white_glass() });
        let (image, stats) = render_image(&scene, &path_options(8, 8192), &RenderControl::default()).unwrap();
        assert_eq!(stats.nonfinite_samples, 0);
        let (mut hi, mut centre_lo, mut centre, mut mean) = (f32::MIN, f32::MAX, 0.0, 0.0);
        for (i, p) in image.pixels.iter().enumerate() {
            let (x, y) = (i % 8, i / 8);
            for c in p {
                hi = hi.max(*c);
                mean += *c as f64 / (3.0 * 64.0);
                if (2..6).contains(&x) && (2..6).contains(&y) {
                    centre_lo = centre_lo.min(*c);
                    centre += *c as f64 / (3.0 * 16.0);
                }
            }
        }
        eprintln!("rough glass alpha {alpha}: brightest {hi}, centre 4x4 from {centre_lo} mean {centre:.4} (Mitsuba {mitsuba_centre}), image mean {mean:.4} (Mitsuba {mitsuba_mean})");
        assert!(hi < 1.005, "alpha {alpha}: a pixel gains energy ({hi})");
        if alpha <= 0.02 {
            assert!(centre_lo > 0.995, "alpha {alpha}: darkest centre pixel {centre_lo}");
        }
        let tolerance = if alpha <= 0.1 { (-5e-3, 5e-3) } else { (-5e-3, 1.5e-2) };
        for (what, ours, theirs) in [("centre", centre, mitsuba_centre), ("image", mean, mitsuba_mean)] {
            let d = ours / theirs - 1.0;
            assert!(d > tolerance.0 && d < tolerance.1, "alpha {alpha}: {what} mean {ours} vs Mitsuba {theirs}");
        }
    }
}

#[test]
fn next_event_estimation_agrees_with_bsdf_sampling_alone() {
    // A diffuse floor, a glossy ball, a glass ball, a frosted-glass ball and a rough
    // gold ball lit by a spherical area light and a dim sky: NEE + MIS and the
    // BSDF-only oracle estimate the same integral, so their image means agree within
    // their noise.
    let camera = Perspective::look_at(Vec3::new(0.0, 1.0, 5.0), Vec3::new(0.0, 0.5, 0.0), Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let floor = b.material(Material::plastic(Rgb::new(0.8, 0.6, 0.4), 0.0, 0.9, 0.0, 1.0)).unwrap();
    let glossy = b.material(Material::plastic(Rgb::new(0.2, 0.4, 0.8), 0.0, 0.5, 0.4, 30.0)).unwrap();
    let glass = b.material(Material { ks: Rgb::ZERO, ..Material::glass(1.5, 0.0, 1.0) }).unwrap();
    let frosted = b.material(Material { roughness: 0.3, ..Material::glass(1.5, 0.0, 1.0) }).unwrap();
    let brushed = b.material(Material { roughness: 0.2, ..Material::metal(Metal::Gold, 0.0, 1.0) }).unwrap();
    let lamp = b.material(Material { emission: Rgb::splat(20.0), kd: Rgb::ZERO, ..Material::default() }).unwrap();
    b.object(Rectangle::horizontal(0.0, -3.0, 3.0, -3.0, 3.0).unwrap(), floor).unwrap();
    b.object(Sphere::new(Vec3::new(-0.7, 0.6, 0.0), 0.6).unwrap(), glossy).unwrap();
    b.object(Sphere::new(Vec3::new(0.8, 0.5, 0.5), 0.5).unwrap(), glass).unwrap();
    b.object(Sphere::new(Vec3::new(0.5, 2.5, 1.0), 0.3).unwrap(), lamp).unwrap();
    b.object(Sphere::new(Vec3::new(0.0, 0.35, 1.5), 0.35).unwrap(), frosted).unwrap();
    b.object(Sphere::new(Vec3::new(-1.0, 0.3, 1.2), 0.3).unwrap(), brushed).unwrap();
    b.settings.environment = Some(Arc::new(Environment::Constant(Rgb::splat(0.2))));
    let scene = b.build().unwrap();
    let (w, h, spp) = (12u32, 12u32, 256u32);
    let nee = PathTracer::new(&scene, 6);
    let oracle = SimplePath::new(&scene, 6);
    let mut counts = RayCounts::default();
    let (mut sum_nee, mut sum_oracle, mut sq_nee, mut sq_oracle) = (0.0, 0.0, 0.0, 0.0);
    for y in 0..h {
        for x in 0..w {
            let pixel = (y * w + x) as u64;
            for s in 0..spp {
                let mut a = PixelSampler::new(1, pixel, s);
                let mut o = PixelSampler::new(2, pixel, s);
                let (ax, ay) = a.get_2d();
                let (ox, oy) = o.get_2d();
                let la = nee
                    .li(&scene, &scene.settings.camera.ray(x as f64 + ax, y as f64 + ay, w, h, (0.5, 0.5)), &mut a, &mut counts)
                    .dot(Rgb::ONE);
                let lo =
                    oracle.li(&scene, &scene.settings.camera.ray(x as f64 + ox, y as f64 + oy, w, h, (0.5, 0.5)), &mut o).dot(Rgb::ONE);
                sum_nee += la;
                sum_oracle += lo;
                sq_nee += la * la;
                sq_oracle += lo * lo;
            }
        }
    }
    let n = (w * h * spp) as f64;
    let (mean_nee, mean_oracle) = (sum_nee / n, sum_oracle / n);
    // Standard error of the difference from the sample variances (an upper bound:
    // the Sobol points do better than independent samples).
    let se = ((sq_nee / n - mean_nee * mean_nee) / n + (sq_oracle / n - mean_oracle * mean_oracle) / n).sqrt();
    assert!((mean_nee - mean_oracle).abs() < 4.0 * se, "NEE {mean_nee} vs oracle {mean_oracle} (se {se})");
    assert!(mean_nee > 0.1, "the scene is lit");
}

#[test]
fn point_and_directional_lights_give_the_analytic_radiance() {
    // A white Lambertian floor (albedo 0.5) under a point light of intensity I at
    // height 2 and a directional light at 60 degrees: at the point below the lamp,
    // L = 0.5 (I / 4 + E cos 60), the lecture's value (the lights' radiant
    // intensity and irradiance are pi I and pi E, the BSDF 0.5 / pi).
    let camera = Perspective::look_at(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, Vec3::Z, Fov::VerticalDeg(1.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let grey =
        b.material(Material { color: Texture::Constant(Rgb::ONE), kd: Rgb::splat(0.5), ka: Rgb::ZERO, ..Material::default() }).unwrap();
    b.object(Rectangle::horizontal(0.0, -5.0, 5.0, -5.0, 5.0).unwrap(), grey).unwrap();
    b.light(PointLight::new(Vec3::new(0.0, 2.0, 0.0), Rgb::splat(8.0)).unwrap());
    let dir = Vec3::new(3f64.sqrt() / 2.0, 0.5, 0.0);
    b.light(DirectionalLight::new(-dir, Rgb::splat(2.0)).unwrap());
    let scene = b.build().unwrap();
    let (image, _) =
        render_image(&scene, &RenderOptions { max_depth: Some(2), ..path_options(1, 256) }, &RenderControl::default()).unwrap();
    let expected = 0.5 * (8.0 / 4.0 + 2.0 * 0.5);
    assert!((image.get(0, 0)[0] as f64 - expected).abs() / expected < 1e-3, "{:?} vs {expected}", image.get(0, 0));
}

#[test]
fn images_do_not_depend_on_threads_and_2n_continues_n() {
    let scene = furnace_scene(Material::plastic(Rgb::new(0.9, 0.3, 0.2), 0.0, 0.6, 0.3, 20.0));
    let opts = |threads: usize, spp: u32| RenderOptions { threads, ..path_options(20, spp) };
    let (one, _) = render_image(&scene, &opts(1, 8), &RenderControl::default()).unwrap();
    let (three, _) = render_image(&scene, &opts(3, 8), &RenderControl::default()).unwrap();
    assert_eq!(one, three, "same bytes for 1 and 3 threads");
    // The sums after 2N = 8 samples are those after N = 4 plus samples 4..8, taken
    // one by one with the same sampler: the first N samples are reused exactly.
    let (acc4, _) = render(&scene, &opts(2, 4), &RenderControl::default()).unwrap();
    let (acc8, _) = render(&scene, &opts(2, 8), &RenderControl::default()).unwrap();
    let tracer = PathTracer::new(&scene, scene.settings.max_depth);
    let mut counts = RayCounts::default();
    for y in 0..20u32 {
        for x in 0..20u32 {
            let k = (y * 20 + x) as usize;
            let mut extra = Rgb::ZERO;
            for s in 4..8 {
                let mut sampler = PixelSampler::new(0, k as u64, s);
                let ((dx, dy), _) = lamplight_core::film::Filter::Box.sample(sampler.get_2d());
                let ray = scene.settings.camera.ray(x as f64 + 0.5 + dx, y as f64 + 0.5 + dy, 20, 20, (0.5, 0.5));
                extra += tracer.li(&scene, &ray, &mut sampler, &mut counts);
            }
            assert_eq!(acc8.get(x, y).sum, acc4.get(x, y).sum + extra, "pixel {k}");
        }
    }
}

#[test]
fn time_limit_stops_after_a_complete_pass() {
    let scene = furnace_scene(white_lambertian());
    let options = RenderOptions { time_limit: Some(std::time::Duration::from_millis(150)), ..path_options(32, 1 << 20) };
    let (film, stats) = lamplight_core::render(&scene, &options, &RenderControl::default()).unwrap();
    let spp = stats.samples_per_pixel;
    // The last pass is shortened to what fits, so any count is possible; the
    // film holds one count for every pixel.
    assert!((1..1 << 20).contains(&spp), "{spp} samples");
    assert_eq!(film.samples(), spp);
    assert!(stats.elapsed < std::time::Duration::from_secs(2));
    assert!(film.mean().pixels.iter().all(|p| p.iter().all(|c| c.is_finite())));
}

#[test]
fn a_stop_keeps_the_passes_already_complete() {
    use std::sync::atomic::{AtomicBool, Ordering};
    let scene = furnace_scene(white_lambertian());
    // 4 samples are passes of 1, 1 and 2; one thread makes the tile order fixed.
    let options = RenderOptions { threads: 1, ..path_options(32, 4) };
    let stop = AtomicBool::new(false);
    let progress = |done: u64, total: u64| {
        if done == total / 3 + 1 {
            stop.store(true, Ordering::Relaxed); // one tile into the second pass
        }
    };
    let control = RenderControl { progress: &progress, cancel: None, stop: Some(&stop) };
    let (film, stats) = lamplight_core::render(&scene, &options, &control).unwrap();
    assert_eq!((stats.samples_per_pixel, film.samples()), (1, 1), "the second pass is dropped, the first kept");
    let full = lamplight_core::render(&scene, &RenderOptions { spp: 1, ..options.clone() }, &RenderControl::default()).unwrap().0;
    assert!(film.mean().pixels == full.mean().pixels, "the kept pass is the 1-sample render");
    // Stopped before any pass completes: an error that says so.
    let stopped = AtomicBool::new(true);
    let control = RenderControl { stop: Some(&stopped), ..RenderControl::default() };
    let err = lamplight_core::render(&scene, &options, &control).unwrap_err();
    assert_eq!(err.to_string(), "cannot render: interrupted before the first pass finished");
}

#[test]
fn clamp_scales_bright_samples_down_keeping_their_hue() {
    // The camera sees only a lamp of radiance (8, 4, 2): clamped at 2, each
    // sample becomes (2, 1, 0.5); unclamped it stays.
    let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(10.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let lamp = b.material(Material { emission: Rgb::new(8.0, 4.0, 2.0), kd: Rgb::ZERO, ka: Rgb::ZERO, ..Material::default() }).unwrap();
    b.object(Rectangle::new(Vec3::new(-5.0, -5.0, 0.0), Vec3::new(10.0, 0.0, 0.0), Vec3::new(0.0, 10.0, 0.0)).unwrap(), lamp).unwrap();
    let scene = b.build().unwrap();
    let render = |clamp: Option<f64>| {
        render_image(&scene, &RenderOptions { clamp, ..path_options(4, 4) }, &RenderControl::default()).unwrap().0.get(1, 2)
    };
    assert_eq!(render(None), [8.0, 4.0, 2.0]);
    assert_eq!(render(Some(2.0)), [2.0, 1.0, 0.5]);
    assert_eq!(render(Some(100.0)), [8.0, 4.0, 2.0], "samples below the clamp are untouched");
}
