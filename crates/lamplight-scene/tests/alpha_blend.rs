//! glTF-style `alpha_mode = "blend"`: stochastic transparency in both
//! integrators and in shadow rays, converging to the "over" composite.

use std::path::Path;

use lamplight_core::math::{Rgb, Vec3};
use lamplight_core::{integrators, render_image, RenderControl, RenderOptions};
use lamplight_scene::instantiate::SceneFile;

/// A blue glowing quad of coverage 0.3 in front of a red glowing one, seen
/// head-on by an orthographic camera that they fill.
fn scene(integrator: &str) -> lamplight_core::scene::Scene {
    let text = format!(
        "[render]\nintegrator = \"{integrator}\"\n[camera]\ntype = \"orthographic\"\neye = [2, 1, 10]\nlook_at = [2, 1, 0]\nhalf_width = 2\nhalf_height = 1\n\
         [materials.back]\nkd = 0\nka = 0\nemission = [1, 0, 0]\n\
         [materials.front]\nkd = 0\nka = 0\nemission = [0, 0, 1]\nalpha = 0.3\nalpha_mode = \"blend\"\n\
         [[objects]]\ntype = \"rectangle\"\ncorner = [-1, -1, 0]\nedge_u = [6, 0, 0]\nedge_v = [0, 4, 0]\nmaterial = \"back\"\n\
         [[objects]]\ntype = \"rectangle\"\ncorner = [-1, -1, 1]\nedge_u = [6, 0, 0]\nedge_v = [0, 4, 0]\nmaterial = \"front\"\n"
    );
    SceneFile::parse(Path::new("s.toml"), &text).unwrap().build().unwrap_or_else(|e| panic!("{e}"))
}

fn render(integrator: &str, threads: usize) -> lamplight_core::film::Image {
    let scene = scene(integrator);
    let options = RenderOptions {
        width: 8,
        height: 4,
        spp: 256,
        threads,
        integrator: integrators::find(integrator).unwrap(),
        ..RenderOptions::default()
    };
    render_image(&scene, &options, &RenderControl::default()).unwrap().0
}

#[test]
fn a_blended_quad_shows_the_over_composite_in_both_integrators() {
    for integrator in ["whitted", "path"] {
        let image = render(integrator, 1);
        let (mut red, mut blue) = (0.0, 0.0);
        for y in 0..4 {
            for x in 0..8 {
                let [r, g, b] = image.get(x, y);
                assert!(r + b > 0.999 && r + b < 1.001 && g == 0.0, "{integrator}: each sample sees one of the quads, got {r} {g} {b}");
                // Per pixel: 256 Bernoulli(0.3) samples, sd 0.029; 5 sd.
                assert!((f64::from(b) - 0.3).abs() < 5.0 * 0.029, "{integrator} pixel ({x}, {y}): {b}");
                red += f64::from(r) / 32.0;
                blue += f64::from(b) / 32.0;
            }
        }
        // Over all 8192 samples: sd 0.0051; 4 sd.
        assert!((blue - 0.3).abs() < 4.0 * 0.0051 && (red - 0.7).abs() < 4.0 * 0.0051, "{integrator}: {red} {blue}");
        assert_eq!(image.pixels, render(integrator, 3).pixels, "{integrator}: threads change no byte");
    }
}

#[test]
fn shadow_rays_pass_a_blended_surface_with_probability_one_minus_alpha() {
    let scene = scene("path");
    let n = 4000;
    let mut passed = Rgb::ZERO;
    for i in 0..n {
        // Upwards from the back quad through the front one, from many points.
        let x = (i as f64 + 0.5) / n as f64 * 4.0;
        passed +=
            scene.transmittance(&lamplight_core::ray::Ray::unit(Vec3::new(x, 1.0, 0.5), Vec3::new(0.01, 0.0, 1.0).normalize()), 5.0, None);
    }
    let mean = passed.x / n as f64;
    // Binomial sd sqrt(0.21 / 4000) = 0.0072; 5 sd.
    assert!((mean - 0.7).abs() < 5.0 * 0.0072, "{mean}");
}
