//! A pixel window renders exactly the pixels of the full image there, for both
//! integrators: tiles rendered apart (as on the machines of a cluster) stitch back
//! into the same bytes as one render.

use std::sync::Arc;

use lamplight_core::integrators::INTEGRATORS;
use lamplight_core::lights::Environment;
use lamplight_core::prelude::*;
use lamplight_core::PixelWindow;

fn scene() -> Scene {
    let camera = Perspective::look_at(Vec3::new(0.0, 1.0, 5.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
    let mut b = SceneBuilder::new(camera);
    let red = b.material(Material::plastic(Rgb::new(0.9, 0.2, 0.1), 0.1, 0.8, 0.3, 30.0)).unwrap();
    let glass = b.material(Material::glass(1.5, 0.5, 50.0)).unwrap();
    b.object(Sphere::new(Vec3::new(-0.8, 0.0, 0.0), 0.7).unwrap(), red).unwrap();
    b.object(Sphere::new(Vec3::new(0.8, 0.0, 0.5), 0.6).unwrap(), glass).unwrap();
    b.object(Plane::new(Vec3::new(0.0, -0.7, 0.0), Vec3::Y).unwrap(), red).unwrap();
    b.light(PointLight::new(Vec3::new(3.0, 4.0, 3.0), Rgb::splat(40.0)).unwrap());
    b.settings.environment = Some(Arc::new(Environment::Constant(Rgb::splat(0.5))));
    b.settings.ambient = Rgb::splat(0.2);
    b.build().unwrap()
}

#[test]
fn stitched_windows_equal_the_full_image_bit_for_bit() {
    let scene = scene();
    for integrator in INTEGRATORS {
        let options = RenderOptions { width: 37, height: 23, spp: 4, integrator, threads: 2, ..RenderOptions::default() };
        let (full, _) = render_image(&scene, &options, &RenderControl::default()).unwrap();
        let mut stitched = vec![[f32::NAN; 3]; 37 * 23];
        // Uneven windows that do not line up with the renderer's 16-pixel tiles.
        for (y0, h) in [(0, 9), (9, 13), (22, 1)] {
            for (x0, w) in [(0, 5), (5, 20), (25, 12)] {
                let window = Some(PixelWindow { x0, y0, width: w, height: h });
                let (tile, _) = render_image(&scene, &RenderOptions { window, ..options.clone() }, &RenderControl::default()).unwrap();
                assert_eq!((tile.width, tile.height), (w, h));
                for y in 0..h {
                    for x in 0..w {
                        stitched[((y0 + y) * 37 + x0 + x) as usize] = tile.get(x, y);
                    }
                }
            }
        }
        let bits = |p: &[[f32; 3]]| p.iter().flat_map(|c| c.map(f32::to_bits)).collect::<Vec<_>>();
        assert_eq!(bits(&stitched), bits(&full.pixels), "{integrator:?}");
        assert!(full.pixels.iter().any(|p| p[0] > 0.0), "the image is not black");
    }
}

#[test]
fn a_window_outside_the_image_is_an_error() {
    let scene = scene();
    for window in [PixelWindow { x0: 30, y0: 0, width: 8, height: 1 }, PixelWindow { x0: 0, y0: 0, width: 0, height: 1 }] {
        let options = RenderOptions { width: 37, height: 23, window: Some(window), ..RenderOptions::default() };
        let err = render(&scene, &options, &RenderControl::default()).unwrap_err().to_string();
        assert!(err.contains("inside the 37x23 image"), "{err}");
    }
}
