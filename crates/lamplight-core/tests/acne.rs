//! Shadow acne: a lit surface must never shadow itself, at any scene scale.
//!
//! Each scene is a tilted square and a sphere lit by a directional light, with
//! nothing else to cast shadows, seen so that the sphere does not shadow the
//! square. Every pixel that sees a surface must then hold exactly the analytic
//! Lambert value `ka C La + kd C E max(N.L, 0)`; a self-shadowed pixel (acne)
//! would drop to the ambient term alone.

use lamplight_core::prelude::*;

fn render_scaled(scale: f64) -> (Scene, lamplight_core::film::Image) {
    let s = |v: Vec3| v * scale;
    let camera = Perspective::look_at(s(Vec3::new(0.3, 3.0, 6.0)), s(Vec3::new(0.0, 0.0, 0.0)), Vec3::Y, Fov::VerticalDeg(45.0)).unwrap();
    let mut builder = SceneBuilder::new(camera);
    builder.settings.ambient = Rgb::splat(0.1);
    builder.settings.background = Rgb::ZERO;
    let white = builder.material(Material::plastic(Rgb::ONE, 1.0, 0.8, 0.0, 1.0)).unwrap();
    // A slightly tilted floor: its points have rounding errors in every coordinate.
    let edge_u = Vec3::new(0.0, 0.3, 8.0);
    let edge_v = Vec3::new(8.0, 0.2, 0.0);
    builder.object(Rectangle::new(s(Vec3::new(-4.0, -0.25, -4.0)), s(edge_u), s(edge_v)).unwrap(), white).unwrap();
    builder.object(Sphere::new(s(Vec3::new(2.2, 0.8, 1.0)), 0.7 * scale).unwrap(), white).unwrap();
    // Light from behind the camera, so the sphere's shadow falls behind it, off the floor we see less of.
    builder.light(DirectionalLight::new(Vec3::new(-0.2, -1.0, -0.45), Rgb::ONE).unwrap());
    let scene = builder.build().unwrap();
    let (image, _) =
        render_image(&scene, &RenderOptions { width: 96, height: 96, ..RenderOptions::default() }, &RenderControl::default()).unwrap();
    (scene, image)
}

#[test]
fn no_acne_at_any_scale() {
    let light_dir = -Vec3::new(-0.2, -1.0, -0.45).normalize();
    for scale in [1e-4, 1.0, 1e3, 1e6] {
        let (scene, image) = render_scaled(scale);
        let mut checked = 0;
        for y in 0..96 {
            for x in 0..96 {
                let ray = scene.settings.camera.ray(x as f64 + 0.5, y as f64 + 0.5, 96, 96, (0.5, 0.5));
                let Some(hit) = scene.first_intersect(&ray, f64::INFINITY) else { continue };
                // Skip points that the sphere really shadows (the floor behind it).
                let to_light = lamplight_core::ray::Ray::new(hit.point + hit.geometric_normal * 1e-6 * scale, light_dir);
                if hit.object == 0 && scene.objects[1].shape.intersect(&to_light, 0.0, f64::INFINITY).is_some() {
                    continue;
                }
                let expected = 0.1 + 0.8 * hit.normal.dot(light_dir).max(0.0);
                let got = image.get(x, y)[0] as f64;
                assert!(
                    (got - expected).abs() < 1e-5,
                    "scale {scale}: pixel ({x},{y}) on object {} is {got}, expected {expected}",
                    hit.object
                );
                checked += 1;
            }
        }
        assert!(checked > 5000, "scale {scale}: only {checked} pixels saw a surface");
    }
}
