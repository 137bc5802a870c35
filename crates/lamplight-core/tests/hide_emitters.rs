//! `SceneSettings::hide_emitters` (Mitsuba's `hide_emitters`): camera rays go through
//! emitting surfaces and see black sky; the light of both stays in the scene.

use std::sync::Arc;

use lamplight_core::integrators;
use lamplight_core::lights::Environment;
use lamplight_core::prelude::*;

/// A white wall at z = -1 lit by a point light off to the side, a sky of 0.5,
/// and (`glow`) an emitting disk at the origin facing the camera on +z.
fn scene(glow: bool, hide: bool) -> Scene {
    let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let white =
        b.material(Material { color: Texture::Constant(Rgb::ONE), ka: Rgb::ZERO, kd: Rgb::splat(0.8), ..Material::default() }).unwrap();
    b.object(Rectangle::new(Vec3::new(-1.0, -1.0, -1.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)).unwrap(), white).unwrap();
    if glow {
        let lamp = Material { kd: Rgb::ZERO, ka: Rgb::ZERO, emission: Rgb::splat(5.0), ..Material::default() };
        let lamp = b.material(lamp).unwrap();
        b.object(Disk::new(Vec3::ZERO, Vec3::Z, 0.3).unwrap(), lamp).unwrap();
    }
    b.light(PointLight::new(Vec3::new(2.0, 0.0, 2.0), Rgb::splat(4.0)).unwrap().with_falloff(Falloff::None));
    b.settings.environment = Some(Arc::new(Environment::Constant(Rgb::splat(0.5))));
    b.settings.background = Rgb::splat(0.5);
    b.settings.hide_emitters = hide;
    b.settings.max_depth = 2;
    b.build().unwrap()
}

fn image(scene: &Scene, integrator: &str, spp: u32) -> Vec<[f32; 3]> {
    let options =
        RenderOptions { width: 9, height: 9, spp, integrator: integrators::find(integrator).unwrap(), ..RenderOptions::default() };
    render_image(scene, &options, &RenderControl::default()).unwrap().0.pixels.iter().map(|p| [p[0], p[1], p[2]]).collect()
}

#[test]
fn hidden_emitters_are_seen_through_and_the_sky_is_black() {
    // Whitted's wall sees only the point light: exact. The path tracer's also
    // sees the sky, of which the disk (still there for the wall) hides about
    // pi 0.3^2 / pi of the cosine-weighted hemisphere: 0.8 0.5 0.09 = 0.036 less.
    for (integrator, spp, tolerance) in [("whitted", 1, 1e-6), ("path", 1024, 0.06)] {
        let shown = image(&scene(true, false), integrator, spp);
        let hidden = image(&scene(true, true), integrator, spp);
        let bare = image(&scene(false, false), integrator, spp);
        let centre = 4 * 9 + 4;
        // Shown, the centre sees the emitter (5); hidden, the wall behind it, as if the disk were not there.
        assert!(shown[centre][0] > 4.0, "{integrator}: shown {:?}", shown[centre]);
        assert!((hidden[centre][0] - bare[centre][0]).abs() < tolerance, "{integrator}: {:?} vs {:?}", hidden[centre], bare[centre]);
        assert!(bare[centre][0] > 0.05, "{integrator}: the wall is lit");
        // The corner sees the sky: 0.5 shown, black hidden.
        assert!((shown[0][0] - 0.5).abs() < 1e-6, "{integrator}: sky {:?}", shown[0]);
        assert_eq!(hidden[0], [0.0; 3], "{integrator}: hidden sky");
    }
}
