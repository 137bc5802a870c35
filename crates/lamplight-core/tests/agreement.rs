//! Whitted and path tracing read a scene the same way: with no ambient term and
//! a black background, direct-only path tracing (depth 2) gives what the Whitted
//! integrator gives, to noise, under point, directional, spot and area lights.
//! Switching integrators then adds only indirect light.

use lamplight_core::film::Image;
use lamplight_core::integrators;
use lamplight_core::lights::{SpotLight, SpotProfile};
use lamplight_core::prelude::*;

const W: u32 = 40;
const H: u32 = 30;

/// A diffuse floor with a sphere on it, lit by `lights` (and a square lamp when
/// `lamp`), seen from above at an angle. Nothing is specular, nothing ambient.
fn scene(lights: &[&str], lamp: bool) -> Scene {
    scene_with(lights, lamp, true)
}

fn scene_with(lights: &[&str], lamp: bool, with_ball: bool) -> Scene {
    let camera = Perspective::look_at(Vec3::new(0.0, 3.0, 4.0), Vec3::new(0.0, 0.0, 0.0), Vec3::Y, Fov::VerticalDeg(50.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let diffuse = |c: Rgb| Material { color: Texture::Constant(c), ka: Rgb::ZERO, kd: Rgb::splat(0.8), ..Material::default() };
    let floor = b.material(diffuse(Rgb::new(0.9, 0.8, 0.7))).unwrap();
    let ball = b.material(diffuse(Rgb::new(0.3, 0.6, 0.9))).unwrap();
    b.object(Rectangle::horizontal(0.0, -4.0, 4.0, -4.0, 4.0).unwrap(), floor).unwrap();
    if with_ball {
        b.object(Sphere::new(Vec3::new(0.3, 0.6, 0.0), 0.6).unwrap(), ball).unwrap();
    }
    for light in lights {
        match *light {
            "point" => {
                b.light(PointLight::new(Vec3::new(-1.5, 3.0, 1.0), Rgb::splat(4.0)).unwrap());
            }
            "directional" => {
                b.light(DirectionalLight::new(Vec3::new(1.0, -2.0, -0.5), Rgb::splat(0.6)).unwrap());
            }
            "spot" => {
                let spot = SpotLight::new(
                    Vec3::new(1.5, 2.5, 1.5),
                    Vec3::new(-1.0, -2.0, -1.0),
                    Rgb::splat(6.0),
                    15.0,
                    30.0,
                    SpotProfile::Smoothstep,
                );
                b.light(spot.unwrap());
            }
            other => panic!("{other}"),
        }
    }
    if lamp {
        // A downward-facing 1 x 1 square at height 2.5, out of view.
        let emitter = b.material(Material { emission: Rgb::splat(3.0), kd: Rgb::ZERO, ka: Rgb::ZERO, ..Material::default() }).unwrap();
        let square = Rectangle::new(Vec3::new(-1.0, 2.5, -1.5), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0)).unwrap();
        b.object(square, emitter).unwrap();
    }
    b.settings.ambient = Rgb::ZERO;
    b.settings.background = Rgb::ZERO;
    b.build().unwrap()
}

fn render(scene: &Scene, integrator: &str, spp: u32) -> Image {
    let options = RenderOptions {
        width: W,
        height: H,
        spp,
        max_depth: Some(2),
        integrator: integrators::find(integrator).unwrap(),
        ..RenderOptions::default()
    };
    render_image(scene, &options, &RenderControl::default()).unwrap().0
}

/// Means of 10 x 10 pixel blocks, per channel.
fn blocks(image: &Image) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for by in 0..H / 10 {
        for bx in 0..W / 10 {
            let mut sum = [0.0; 3];
            for y in by * 10..by * 10 + 10 {
                for x in bx * 10..bx * 10 + 10 {
                    let p = image.get(x, y);
                    (0..3).for_each(|c| sum[c] += f64::from(p[c]) / 100.0);
                }
            }
            out.push(sum);
        }
    }
    out
}

fn assert_agree(lights: &[&str], lamp: bool, tolerance: f64) {
    let scene = scene(lights, lamp);
    let whitted = blocks(&render(&scene, "whitted", 64));
    let path = blocks(&render(&scene, "path", 256));
    let brightest = whitted.iter().flatten().fold(0.0f64, |a, &b| a.max(b));
    assert!(brightest > 0.05, "{lights:?}: the scene is lit ({brightest})");
    for (k, (a, b)) in whitted.iter().zip(&path).enumerate() {
        for c in 0..3 {
            // Relative to the block, with a floor of 1 % of the brightest block for the dark ones.
            let scale = a[c].max(0.01 * brightest);
            assert!(
                (a[c] - b[c]).abs() <= tolerance * scale,
                "{lights:?} lamp {lamp}: block {k} channel {c}: Whitted {} path {}",
                a[c],
                b[c]
            );
        }
    }
}

#[test]
fn point_light_direct_light_is_the_same_under_both() {
    assert_agree(&["point"], false, 0.02);
}

#[test]
fn directional_light_direct_light_is_the_same_under_both() {
    assert_agree(&["directional"], false, 0.02);
}

#[test]
fn spot_light_direct_light_is_the_same_under_both() {
    assert_agree(&["spot"], false, 0.02);
}

#[test]
fn area_light_direct_light_and_soft_shadows_are_the_same_under_both() {
    // Both estimate the lamp's integral by sampling: 16 points per hit under
    // Whitted, 256 NEE + BSDF samples per pixel under path tracing.
    assert_agree(&[], true, 0.04);
}

#[test]
fn all_lights_together() {
    assert_agree(&["point", "directional", "spot"], true, 0.03);
}

#[test]
fn whitted_lights_an_area_lit_scene_with_soft_shadows() {
    // Along a line of floor points through the ball's shadow, the fraction of
    // the lamp's light that arrives (with the ball over without it) falls from 1
    // to 0 through a penumbra; a point light at the lamp's centre casts a hard
    // edge. Rays come straight down from just above each floor point.
    let visibility = |lights: &[&str], lamp: bool, moved: Option<Vec3>| -> Vec<f64> {
        let (with, without) = (scene_with(lights, lamp, true), scene_with(lights, lamp, false));
        let (a, b) = (integrators::Whitted::new(&with, 2, 0.0), integrators::Whitted::new(&without, 2, 0.0));
        (0..200)
            .map(|i| {
                let p = Vec3::new(-1.5 + 4.0 * i as f64 / 200.0, 0.01, 0.316) + moved.unwrap_or(Vec3::ZERO);
                let ray = lamplight_core::ray::Ray::unit(p, -Vec3::Y);
                let mut counts = integrators::RayCounts::default();
                a.trace(&with, &ray, &mut counts).x / b.trace(&without, &ray, &mut counts).x
            })
            .collect()
    };
    let between = |v: &[f64]| v.iter().filter(|&&f| f > 0.1 && f < 0.9).count();
    let soft = visibility(&[], true, None);
    assert!(soft.iter().any(|&f| f < 0.1) && soft.iter().any(|&f| f > 0.99), "shadowed and lit points: {soft:?}");
    assert!(between(&soft) >= 10, "a penumbra of {} points: {soft:?}", between(&soft));
    let hard = visibility(&["point"], false, None);
    assert!(hard.contains(&0.0), "the point light's umbra: {hard:?}");
    assert!(between(&hard) <= 1, "a hard edge under a point light: {hard:?}");
}

#[test]
fn the_background_is_a_sky_for_every_ray_under_path_tracing() {
    // A mirror ball and a white diffuse floor under a blue background, no lights.
    let camera = Perspective::look_at(Vec3::new(0.0, 1.0, 4.0), Vec3::new(0.0, 0.5, 0.0), Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let mirror =
        b.material(Material { kd: Rgb::ZERO, ka: Rgb::ZERO, reflection: Reflection::Constant(Rgb::ONE), ..Material::default() }).unwrap();
    let white = b.material(Material { color: Texture::Constant(Rgb::ONE), kd: Rgb::ONE, ka: Rgb::ZERO, ..Material::default() }).unwrap();
    b.object(Sphere::new(Vec3::new(0.0, 1.0, 0.0), 0.5).unwrap(), mirror).unwrap();
    b.object(Rectangle::horizontal(0.0, -50.0, 50.0, -50.0, 50.0).unwrap(), white).unwrap();
    let sky = Rgb::new(0.2, 0.4, 0.8);
    b.settings.background = sky;
    b.settings.ambient = Rgb::ZERO;
    let scene = b.build().unwrap();
    let (w, h) = (W, H);
    let options = |integrator: &str, spp: u32| RenderOptions {
        width: w,
        height: h,
        spp,
        max_depth: Some(2),
        integrator: integrators::find(integrator).unwrap(),
        ..RenderOptions::default()
    };
    let whitted = render_image(&scene, &options("whitted", 1), &RenderControl::default()).unwrap().0;
    let path = render_image(&scene, &options("path", 64), &RenderControl::default()).unwrap().0;
    // The ball's centre pixel looks at its mirror, which reflects the sky (the
    // ray back to the camera leaves upward past the ball): the sky's colour under both.
    let centre = |image: &Image| image.get(w / 2, h / 2 - 8).map(f64::from);
    for (c, want) in sky.to_array().iter().enumerate() {
        assert!((centre(&whitted)[c] - want).abs() < 1e-6, "Whitted mirror: {:?}", centre(&whitted));
        assert!((centre(&path)[c] - want).abs() < 1e-6, "path mirror: {:?}", centre(&path));
    }
    // The floor near the bottom of the image sees (almost) the whole sky: a white
    // Lambertian surface under a uniform sky L reflects L. The ball covers a
    // little of it; the far floor's horizon none from up here.
    let floor = path.get(2, h - 2).map(f64::from);
    for (c, want) in sky.to_array().iter().enumerate() {
        assert!((floor[c] - want).abs() < 0.03 * want, "path floor: {floor:?} vs {sky:?}");
    }
    // Under Whitted the floor has no light at all: only the ambient term would light it.
    assert_eq!(whitted.get(2, h - 2), [0.0; 3]);
}
