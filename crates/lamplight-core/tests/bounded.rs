//! Issue 12: no NaN or infinity reaches a pixel. A light bright enough (and
//! near enough) that its radiance leaves `f32`'s range is dropped by the film,
//! counted, and the image stays finite for every integrator.
//! See: issue 12 ("Inf pixels").

use lamplight_core::integrators::INTEGRATORS;
use lamplight_core::prelude::*;
use lamplight_core::{render, render_image, RenderControl, RenderOptions};

#[test]
fn radiance_beyond_the_films_bound_never_reaches_a_pixel() {
    let camera = Perspective::look_at(Vec3::new(0.0, 5.0, 0.0), Vec3::ZERO, Vec3::Z, Fov::VerticalDeg(1e-4)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let m = b.material(Material::plastic(Rgb::ONE, 0.0, 1.0, 0.0, 1.0)).unwrap();
    b.object(Rectangle::horizontal(0.0, -10.0, 10.0, -10.0, 10.0).unwrap(), m).unwrap();
    // 1e12 (the largest a scene file may give) from 1e-4 above the floor: 1e20 at
    // the points below it (the camera sees 1e-5 of the floor), beyond the film's
    // 1e18 and, squared, beyond f32.
    b.light(PointLight::new(Vec3::new(0.0, 1e-4, 0.0), Rgb::splat(1e12)).unwrap());
    let scene = b.build().unwrap();
    let control = RenderControl { progress: &|_, _| {}, cancel: None, stop: None };
    for integrator in INTEGRATORS {
        let options = RenderOptions { width: 9, height: 9, spp: 4, integrator, ..RenderOptions::default() };
        let (image, stats) = render_image(&scene, &options, &control).unwrap();
        assert!(image.pixels.iter().flatten().all(|c| c.is_finite()), "{}", integrator.name);
        assert!(stats.nonfinite_samples > 0, "{}: the samples exceed the bound", integrator.name);
        let (film, _) = render(&scene, &options, &control).unwrap();
        assert!(film.variance().pixels.iter().flatten().all(|c| c.is_finite()), "{}: variance too", integrator.name);
    }
    assert!(!lamplight_core::film::accepts(Rgb::new(0.0, f64::NAN, 0.0)));
    assert!(!lamplight_core::film::accepts(Rgb::new(0.0, 0.0, -2e18)));
    assert!(lamplight_core::film::accepts(Rgb::splat(lamplight_core::film::MAX_RADIANCE)));
}

/// Issue 26: the inputs are bounded only by what an `f32` holds
/// (`params::MAX_COLOR`), so products of them overflow even `f64`. Lights,
/// colours, emission and ambient at that bound, through mirrors and glass
/// and every integrator: each product that overflows is infinite or NaN at
/// the film, which drops it; no pixel, mean or variance is infinite, and
/// nothing panics.
#[test]
fn inputs_at_the_f32_bound_never_reach_a_pixel() {
    let max = lamplight_core::params::MAX_COLOR;
    assert!(lamplight_core::params::fits_f32(max) && !lamplight_core::params::fits_f32(1e39));
    let camera = Perspective::look_at(Vec3::new(0.0, 2.0, 5.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(50.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    b.settings.ambient = Rgb::splat(max);
    b.settings.background = Rgb::splat(max);
    let bright = b.material(Material { emission: Rgb::splat(max), ..Material::plastic(Rgb::splat(max), 1.0, max, max, 10.0) }).unwrap();
    let glass = b.material(Material::glass(1.5, max, 300.0)).unwrap();
    b.object(Rectangle::horizontal(0.0, -10.0, 10.0, -10.0, 10.0).unwrap(), bright).unwrap();
    b.object(Sphere::new(Vec3::new(0.0, 0.6, 0.0), 0.5).unwrap(), glass).unwrap();
    b.object(Sphere::new(Vec3::new(1.2, 0.6, 0.0), 0.5).unwrap(), bright).unwrap();
    b.light(PointLight::new(Vec3::new(0.0, 3.0, 0.0), Rgb::splat(max)).unwrap());
    b.light(DirectionalLight::new(Vec3::new(0.3, -1.0, 0.2), Rgb::splat(max)).unwrap());
    let scene = b.build().unwrap();
    let control = RenderControl { progress: &|_, _| {}, cancel: None, stop: None };
    for integrator in INTEGRATORS {
        let options = RenderOptions { width: 8, height: 8, spp: 2, integrator, ..RenderOptions::default() };
        let (film, stats) = render(&scene, &options, &control).unwrap();
        assert!(film.mean().pixels.iter().flatten().all(|c| c.is_finite()), "{}", integrator.name);
        assert!(film.variance().pixels.iter().flatten().all(|c| c.is_finite()), "{}: variance too", integrator.name);
        assert!(stats.nonfinite_samples > 0, "{}: the products exceed the film's bound", integrator.name);
    }
}
