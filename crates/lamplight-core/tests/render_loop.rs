//! The one render loop: every integrator goes through it with the same
//! guarantees (threads do not change bytes, progress, cancellation, the time
//! limit, variance), and one built scene renders at any image size, the camera
//! applying the aspect when rendering.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;

use lamplight_core::camera::Fit;
use lamplight_core::integrators::{IntegratorEntry, INTEGRATORS};
use lamplight_core::lights::Environment;
use lamplight_core::prelude::*;
use lamplight_core::Error;

const EYE: Vec3 = Vec3::new(0.0, 0.0, 5.0);

/// A red ball of radius `radius` at the origin, seen from `EYE`, under a point light and a grey sky.
fn ball_scene(camera: impl Camera + 'static, radius: f64) -> Scene {
    let mut b = SceneBuilder::new(camera);
    let red = b.material(Material::plastic(Rgb::new(0.9, 0.1, 0.1), 0.2, 0.8, 0.3, 20.0)).unwrap();
    b.object(Sphere::new(Vec3::ZERO, radius).unwrap(), red).unwrap();
    b.light(PointLight::new(Vec3::new(3.0, 4.0, 5.0), Rgb::splat(50.0)).unwrap());
    b.settings.environment = Some(Arc::new(Environment::Constant(Rgb::splat(0.3))));
    b.settings.ambient = Rgb::splat(0.3);
    b.build().unwrap()
}

fn look_at() -> Perspective {
    Perspective::look_at(EYE, Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap()
}

fn options(integrator: &'static IntegratorEntry, width: u32, height: u32, spp: u32) -> RenderOptions {
    RenderOptions { width, height, spp, integrator, threads: 2, ..RenderOptions::default() }
}

fn bits(image: &lamplight_core::film::Image) -> Vec<u32> {
    image.pixels.iter().flat_map(|p| p.map(f32::to_bits)).collect()
}

#[test]
fn one_built_scene_renders_at_any_size_with_its_aspect() {
    let scene = ball_scene(look_at(), 0.5);
    let tan_v = 20f64.to_radians().tan();
    for (width, height) in [(96u32, 48u32), (48, 96), (37, 37)] {
        let (image, _) = render_image(&scene, &options(&INTEGRATORS[0], width, height, 1), &RenderControl::default()).unwrap();
        // The same image as a camera with this aspect written into its window
        // (as cameras were built before the aspect moved to render time).
        let aspect = width as f64 / height as f64;
        let baked = Perspective::window(EYE, EYE - Vec3::Z, Vec3::X * (tan_v * aspect), Vec3::Y * tan_v, Fit::None).unwrap();
        let (expected, _) =
            render_image(&ball_scene(baked, 0.5), &options(&INTEGRATORS[0], width, height, 1), &RenderControl::default()).unwrap();
        assert_eq!(bits(&image), bits(&expected), "{width}x{height}");
        // The ball is round on the film: as many pixels across as down, and its
        // radius the fraction of the half-height that the vertical field gives.
        let red: Vec<(u32, u32)> = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .filter(|&(x, y)| image.get(x, y)[0] > 2.0 * image.get(x, y)[1])
            .collect();
        let across = red.iter().map(|p| p.0).max().unwrap() - red.iter().map(|p| p.0).min().unwrap() + 1;
        let down = red.iter().map(|p| p.1).max().unwrap() - red.iter().map(|p| p.1).min().unwrap() + 1;
        let radius = (0.5f64 / 5.0).asin().tan() / tan_v * height as f64 / 2.0;
        assert!(across.abs_diff(down) <= 1, "{width}x{height}: {across} x {down} pixels");
        assert!((down as f64 - 2.0 * radius).abs() <= 1.5, "{width}x{height}: {down} pixels down, expected {}", 2.0 * radius);
    }
}

#[test]
fn every_integrator_gives_the_same_bytes_on_any_number_of_threads() {
    let scene = ball_scene(look_at(), 1.0);
    for integrator in INTEGRATORS {
        let run =
            |threads| render(&scene, &RenderOptions { threads, ..options(integrator, 29, 19, 6) }, &RenderControl::default()).unwrap();
        let (one, stats) = run(1);
        let (three, _) = run(3);
        assert_eq!(one, three, "{integrator:?}: sums and squares");
        assert_eq!((stats.samples_per_pixel, one.samples()), (6, 6));
        assert_eq!(stats.rays.camera, 29 * 19 * 6, "{integrator:?}");
    }
}

#[test]
fn every_integrator_has_a_variance() {
    // Several samples of a pixel on the ball's silhouette differ, for the
    // stratified Whitted samples as for the path tracer's.
    let scene = ball_scene(look_at(), 1.0);
    for integrator in INTEGRATORS {
        let (film, _) = render(&scene, &options(integrator, 24, 24, 8), &RenderControl::default()).unwrap();
        let variance = film.variance();
        assert!(variance.pixels.iter().any(|p| p[0] > 0.0), "{integrator:?}");
        assert!(variance.pixels.iter().all(|p| p.iter().all(|v| v.is_finite() && *v >= 0.0)));
        let (mean, _) = render_image(&scene, &options(integrator, 24, 24, 8), &RenderControl::default()).unwrap();
        assert_eq!(film.mean(), mean);
    }
}

#[test]
fn every_integrator_reports_progress_and_can_be_cancelled_or_timed_out() {
    let scene = ball_scene(look_at(), 1.0);
    for integrator in INTEGRATORS {
        let (done, total) = (AtomicU64::new(0), AtomicU64::new(0));
        let progress = |d: u64, t: u64| {
            done.fetch_max(d, Ordering::Relaxed);
            total.store(t, Ordering::Relaxed);
        };
        render(&scene, &options(integrator, 40, 20, 4), &RenderControl { progress: &progress, cancel: None, stop: None }).unwrap();
        // 3 x 2 tiles, in one pass for Whitted, in passes of 1, 1, 2 for the path tracer.
        let passes = if integrator.name == "whitted" { 1 } else { 3 };
        assert_eq!((done.into_inner(), total.into_inner()), (6 * passes, 6 * passes), "{integrator:?}");

        let cancel = AtomicBool::new(true);
        let control = RenderControl { cancel: Some(&cancel), ..RenderControl::default() };
        let err = render(&scene, &options(integrator, 40, 20, 4), &control).unwrap_err();
        assert_eq!(err, Error::Render("cancelled".into()), "{integrator:?}");

        let timed = RenderOptions { time_limit: Some(std::time::Duration::from_nanos(1)), ..options(integrator, 40, 20, 4) };
        let err = render(&scene, &timed, &RenderControl::default()).unwrap_err();
        assert_eq!(err, Error::Render("the time limit ended before the first pass finished".into()), "{integrator:?}");
    }
}

#[test]
fn a_closed_aperture_renders_the_pinhole_image_and_an_open_one_blurs() {
    // A lens of radius 0 takes no lens sample, so every integrator draws the same
    // values as through the pinhole; an open lens focused behind the ball blurs it.
    let pinhole = ball_scene(look_at(), 1.0);
    let closed = ball_scene(ThinLens::new(look_at(), 0.0, 5.0).unwrap(), 1.0);
    let open = ball_scene(ThinLens::new(look_at(), 0.3, 20.0).unwrap(), 1.0);
    for integrator in INTEGRATORS {
        let o = options(integrator, 32, 32, 4);
        let image = |scene: &Scene| render_image(scene, &o, &RenderControl::default()).unwrap().0;
        assert_eq!(bits(&image(&pinhole)), bits(&image(&closed)), "{integrator:?}");
        let (sharp, blurred) = (image(&pinhole), image(&open));
        assert_ne!(bits(&sharp), bits(&blurred), "{integrator:?}");
        let one_thread = render_image(&open, &RenderOptions { threads: 1, ..o.clone() }, &RenderControl::default()).unwrap().0;
        assert_eq!(bits(&blurred), bits(&one_thread), "{integrator:?}: lens samples are per pixel sample");
    }
}

#[test]
fn an_orthographic_camera_renders_through_the_same_loop() {
    // A ball of radius 1 in a window of half-height 2: its silhouette is a disk of
    // half the image height, whatever the distance.
    let camera = Orthographic::look_at(EYE * 100.0, Vec3::ZERO, Vec3::Y, 2.0, 2.0).unwrap();
    let scene = ball_scene(camera, 1.0);
    let (image, _) = render_image(&scene, &options(&INTEGRATORS[0], 64, 32, 1), &RenderControl::default()).unwrap();
    let red = |x: u32, y: u32| image.get(x, y)[0] > 2.0 * image.get(x, y)[1];
    let row: Vec<u32> = (0..64).filter(|&x| red(x, 16)).collect();
    assert_eq!(row.len(), 16, "diameter 2 of a 8-unit-wide window (the 2:1 image widens the 4 x 4 one)");
    assert_eq!((row[0], row[15]), (24, 39));
}
