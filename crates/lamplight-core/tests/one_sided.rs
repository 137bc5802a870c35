//! One-sided surfaces (`Material::one_sided`, Mitsuba's one-sided BSDFs): black
//! from the back and lit only from the front, for the path tracer and Whitted
//! alike; two-sided surfaces stay as they were.

use std::sync::Arc;

use lamplight_core::integrators;
use lamplight_core::lights::Environment;
use lamplight_core::prelude::*;

/// A white disk of radius 10 facing +z at the origin, seen by a camera on the
/// `side` (+1: in front, -1: behind) of it, in a sky of radiance 1 (an
/// ambient of 1 for Whitted), with an optional point light at `light_z`.
fn disk_scene(one_sided: bool, side: f64, light_z: Option<f64>) -> Scene {
    let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 3.0 * side), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(20.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let white = Material { color: Texture::Constant(Rgb::ONE), ka: Rgb::ONE, kd: Rgb::ONE, one_sided, ..Material::default() };
    let m = b.material(white).unwrap();
    b.object(Disk::new(Vec3::ZERO, Vec3::Z, 10.0).unwrap(), m).unwrap();
    if let Some(z) = light_z {
        b.light(PointLight::new(Vec3::new(0.0, 0.0, z), Rgb::splat(4.0)).unwrap().with_falloff(Falloff::None));
        b.settings.background = Rgb::ZERO;
    } else {
        b.settings.environment = Some(Arc::new(Environment::Constant(Rgb::ONE)));
        b.settings.ambient = Rgb::ONE;
    }
    b.settings.max_depth = 8;
    b.build().unwrap()
}

fn mean(scene: &Scene, integrator: &str, spp: u32) -> f32 {
    let options =
        RenderOptions { width: 4, height: 4, spp, integrator: integrators::find(integrator).unwrap(), ..RenderOptions::default() };
    let (image, _) = render_image(scene, &options, &RenderControl::default()).unwrap();
    image.pixels.iter().map(|p| p[0]).sum::<f32>() / image.pixels.len() as f32
}

#[test]
fn a_one_sided_surface_is_black_from_the_back_in_both_integrators() {
    for integrator in ["path", "whitted"] {
        // From the front both reflect the sky (path: the white furnace's 1; Whitted: ka C La = 1).
        for one_sided in [false, true] {
            let front = mean(&disk_scene(one_sided, 1.0, None), integrator, 64);
            assert!((front - 1.0).abs() < 0.01, "{integrator}, one-sided {one_sided}: front {front}");
        }
        // From the back the two-sided disk reflects the sky too; the one-sided one is exactly black.
        let two = mean(&disk_scene(false, -1.0, None), integrator, 64);
        assert!((two - 1.0).abs() < 0.01, "{integrator}: two-sided back {two}");
        assert_eq!(mean(&disk_scene(true, -1.0, None), integrator, 64), 0.0, "{integrator}: one-sided back");
    }
}

#[test]
fn a_one_sided_surface_reflects_no_light_arriving_at_its_back() {
    for integrator in ["path", "whitted"] {
        // A point light 1 behind the disk, the camera behind it too: the two-sided
        // disk's back is lit (E = 4 / 1^2 at the centre, so radiance 4 / pi there),
        // the one-sided one's is not.
        let lit = mean(&disk_scene(false, -1.0, Some(-1.0)), integrator, 16);
        assert!(lit > 0.5, "{integrator}: two-sided back lit by {lit}");
        assert_eq!(mean(&disk_scene(true, -1.0, Some(-1.0)), integrator, 16), 0.0, "{integrator}: one-sided back");
        // The light in front lights the one-sided front as it lights the two-sided one.
        let front = |one_sided| mean(&disk_scene(one_sided, 1.0, Some(1.0)), integrator, 16);
        assert_eq!(front(true), front(false), "{integrator}: front");
    }
}
