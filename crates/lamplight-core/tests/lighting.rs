//! The rough model and the lights against values worked out by hand.

use lamplight_core::integrators::{RayCounts, Whitted};
use lamplight_core::lights::Light;
use lamplight_core::prelude::*;
use lamplight_core::ray::Ray;

/// A camera looking straight down at the origin from height 5.
fn top_camera() -> Perspective {
    Perspective::look_at(Vec3::new(0.0, 5.0, 0.0), Vec3::ZERO, Vec3::Z, Fov::VerticalDeg(30.0)).unwrap()
}

/// Radiance seen along the ray from (0, 5, 0) straight down at the floor's origin.
fn centre_radiance(scene: &Scene, max_depth: u32) -> (Rgb, RayCounts) {
    let mut counts = RayCounts::default();
    let ray = Ray::new(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y);
    let value = Whitted::new(scene, max_depth, 0.0).trace(scene, &ray, &mut counts);
    (value, counts)
}

fn floor_scene(light: impl Light + 'static, occluder: Option<(Vec3, f64)>) -> Scene {
    let mut b = SceneBuilder::new(top_camera());
    b.settings.ambient = Rgb::splat(0.5);
    let m = b.material(Material::plastic(Rgb::new(0.5, 0.25, 1.0), 0.2, 0.8, 0.0, 1.0)).unwrap();
    b.object(Rectangle::horizontal(0.0, -10.0, 10.0, -10.0, 10.0).unwrap(), m).unwrap();
    if let Some((c, r)) = occluder {
        b.object(Sphere::new(c, r).unwrap(), m).unwrap();
    }
    b.light(light);
    b.build().unwrap()
}

#[test]
fn lambert_with_inverse_square_point_light() {
    // Light at (3, 4, 0): d = 5, cos = 4/5. L = ka C La + kd C I/d^2 cos.
    let scene = floor_scene(PointLight::new(Vec3::new(3.0, 4.0, 0.0), Rgb::splat(50.0)).unwrap(), None);
    let (value, counts) = centre_radiance(&scene, 5);
    let c = Rgb::new(0.5, 0.25, 1.0);
    let expected = c * 0.2 * 0.5 + c * 0.8 * (50.0 / 25.0) * 0.8;
    assert!((value - expected).abs().max_element() < 1e-12, "{value} vs {expected}");
    assert_eq!((counts.camera, counts.shadow), (1, 1));
}

#[test]
fn constant_falloff_and_directional_light() {
    let flat = PointLight::new(Vec3::new(3.0, 4.0, 0.0), Rgb::splat(2.0)).unwrap().with_falloff(Falloff::None);
    let (value, _) = centre_radiance(&floor_scene(flat, None), 5);
    let c = Rgb::new(0.5, 0.25, 1.0);
    assert!((value - (c * 0.1 + c * 0.8 * 2.0 * 0.8)).abs().max_element() < 1e-12);
    let sun = DirectionalLight::new(Vec3::new(-3.0, -4.0, 0.0), Rgb::splat(2.0)).unwrap();
    let (value, _) = centre_radiance(&floor_scene(sun, None), 5);
    assert!((value - (c * 0.1 + c * 0.8 * 2.0 * 0.8)).abs().max_element() < 1e-12);
}

#[test]
fn occluder_counts_only_between_the_point_and_the_light() {
    // Light at (1, 2, 0), seen from the floor's origin along (1, 2, 0)/sqrt(5); a small
    // ball on that line shadows the point only when it is nearer than the light.
    let light = || PointLight::new(Vec3::new(1.0, 2.0, 0.0), Rgb::splat(4.0)).unwrap();
    let ball_at = |y: f64| Some((Vec3::new(0.5 * y, y, 0.0), 0.1));
    let c = Rgb::new(0.5, 0.25, 1.0);
    let ambient_only = c * 0.1;
    let (shadowed, _) = centre_radiance(&floor_scene(light(), ball_at(1.0)), 5);
    assert!((shadowed - ambient_only).abs().max_element() < 1e-12, "ball between: {shadowed}");
    let (lit, _) = centre_radiance(&floor_scene(light(), ball_at(3.0)), 5);
    let d2: f64 = 5.0;
    let expected = ambient_only + c * 0.8 * (4.0 / d2) * (2.0 / d2.sqrt());
    assert!((lit - expected).abs().max_element() < 1e-12, "ball beyond the light: {lit} vs {expected}");
}

#[test]
fn blinn_highlight_peaks_at_the_mirror_direction() {
    // Light straight above the viewpoint: H = N, highlight = ks * 1^n * E, no diffuse.
    let mut b = SceneBuilder::new(top_camera());
    let m = b.material(Material { ka: Rgb::ZERO, kd: Rgb::ZERO, ks: Rgb::splat(0.7), shininess: 50.0, ..Material::default() }).unwrap();
    b.object(Rectangle::horizontal(0.0, -10.0, 10.0, -10.0, 10.0).unwrap(), m).unwrap();
    b.light(PointLight::new(Vec3::new(0.0, 2.0, 0.0), Rgb::splat(8.0)).unwrap());
    let (value, _) = centre_radiance(&b.build().unwrap(), 5);
    assert!((value - Rgb::splat(0.7 * 8.0 / 4.0)).abs().max_element() < 1e-12, "{value}");
}

#[test]
fn depth_limit_bounds_the_work_between_parallel_mirrors() {
    // Two facing mirrors: every reflection spawns exactly one more ray, so with depth
    // limit D the camera ray causes D - 1 secondary rays and the sum of the geometric
    // series of weights 0.5^k.
    let mut b = SceneBuilder::new(top_camera());
    b.settings.background = Rgb::ONE;
    let mirror = b
        .material(Material {
            ka: Rgb::ZERO,
            kd: Rgb::ZERO,
            emission: Rgb::splat(1.0),
            reflection: Reflection::Constant(Rgb::splat(0.5)),
            ..Material::default()
        })
        .unwrap();
    b.object(Rectangle::horizontal(0.0, -10.0, 10.0, -10.0, 10.0).unwrap(), mirror).unwrap();
    b.object(Rectangle::new(Vec3::new(-10.0, 6.0, 10.0), Vec3::new(0.0, 0.0, -20.0), Vec3::new(20.0, 0.0, 0.0)).unwrap(), mirror).unwrap();
    let scene = b.build().unwrap();
    for depth in [1u32, 5, 40] {
        let (value, counts) = centre_radiance(&scene, depth);
        assert_eq!(counts.secondary, depth as u64 - 1);
        let expected: f64 = (0..depth).map(|k| 0.5f64.powi(k as i32)).sum();
        assert!((value.x - expected).abs() < 1e-12, "depth {depth}: {value} vs {expected}");
    }
}
