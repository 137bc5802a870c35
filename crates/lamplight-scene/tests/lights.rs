//! Lights through the scene format, against their analytic irradiance.

use std::path::Path;

use lamplight_core::{render_image, RenderControl, RenderOptions};
use lamplight_scene::build::SceneFile;

/// A white Lambertian floor (`kd = 1`, no ambient) seen from the light's own
/// position straight down, so that pixel `(x, y)` sees the floor point at angle
/// `theta` from the spot's axis with `cos(theta) = 1 / |dir|`, `dir` the pixel's
/// unnormalized direction through the unit-distance window.
#[test]
fn spot_light_matches_its_irradiance_inside_across_and_outside_the_cone() {
    let (w, h, height, intensity) = (64u32, 64u32, 2.0, 8.0);
    let text = format!(
        "[camera]\neye = [0, {height}, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\nvfov = 100\n\
         [materials.floor]\ncolor = 1\nkd = 1\nka = 0\n\
         [[objects]]\ntype = \"rectangle\"\nmaterial = \"floor\"\ncorner = [-50, 0, -50]\nedge_u = [0, 0, 100]\nedge_v = [100, 0, 0]\n\
         [[objects]]\ntype = \"spot_light\"\nposition = [0, {height}, 0]\nlook_at = [0, 0, 0]\nintensity = {intensity}\ninner_angle = 20\nouter_angle = 40\n"
    );
    let scene = SceneFile::parse(Path::new("spot.toml"), &text).unwrap().build().unwrap();
    let options = RenderOptions { width: w, height: h, threads: 1, ..RenderOptions::default() };
    let image = render_image(&scene, &options, &RenderControl::default()).unwrap().0;
    let tan_half = 50f64.to_radians().tan();
    let (cos_inner, cos_outer) = (20f64.to_radians().cos(), 40f64.to_radians().cos());
    let (mut inside, mut across, mut outside) = (0, 0, 0);
    for y in 0..h {
        for x in 0..w {
            let alpha = (2.0 * (x as f64 + 0.5) / w as f64 - 1.0) * tan_half;
            let beta = (1.0 - 2.0 * (y as f64 + 0.5) / h as f64) * tan_half;
            let cos = 1.0 / (1.0 + alpha * alpha + beta * beta).sqrt();
            let s = if cos >= cos_inner {
                inside += 1;
                1.0
            } else if cos <= cos_outer {
                outside += 1;
                0.0
            } else {
                across += 1;
                let t = (cos - cos_outer) / (cos_inner - cos_outer);
                t * t * (3.0 - 2.0 * t)
            };
            // L = kd * E / pi * pi: the lecture's kd (L.N) Lin, Lin = I s / d^2, d = height / cos.
            let expected = intensity * s * cos * cos * cos / (height * height);
            let got = image.get(x, y)[0] as f64;
            assert!((got - expected).abs() <= 1e-5 * expected.max(1.0), "pixel ({x}, {y}): {got} vs {expected}");
        }
    }
    assert!(inside > 100 && across > 100 && outside > 100, "{inside} {across} {outside}");
}
