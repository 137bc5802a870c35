//! Lights through the scene format, against their analytic irradiance.

use std::path::Path;

use lamplight_core::{render_image, RenderControl, RenderOptions};
use lamplight_scene::instantiate::SceneFile;

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

/// A 4 x 2 image of grey levels (linear, so `T` is the byte over 255): the top
/// row 255, 51, 102, 153 from left to right, the bottom row 0, 204, 255, 51.
fn slide_png(dir: &Path) -> [[f64; 4]; 2] {
    let rows = [[255u8, 51, 102, 153], [0, 204, 255, 51]];
    let image = image::GrayImage::from_fn(4, 2, |x, y| image::Luma([rows[y as usize][x as usize]]));
    image.save(dir.join("slide.png")).unwrap();
    rows.map(|r| r.map(|v| v as f64 / 255.0))
}

/// Renders a white floor 2 below a light at the camera's position looking
/// straight down with the camera's frame (right +x, up -z), and checks every
/// pixel against `expected(alpha, beta, cos)`: `alpha`, `beta` the pixel's
/// direction through the unit-distance window, `cos` its angle to the axis.
fn floor_under_a_light(light: &str, expected: impl Fn(f64, f64, f64) -> Option<f64>) {
    let dir = tempfile::tempdir().unwrap();
    let (w, h, height) = (64u32, 64u32, 2.0);
    let text = format!(
        "[camera]\neye = [0, {height}, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\nvfov = 100\n\
         [materials.floor]\ncolor = 1\nkd = 1\nka = 0\n\
         [[objects]]\ntype = \"rectangle\"\nmaterial = \"floor\"\ncorner = [-50, 0, -50]\nedge_u = [0, 0, 100]\nedge_v = [100, 0, 0]\n\
         [[objects]]\nposition = [0, {height}, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\n{light}\n"
    );
    let scene = SceneFile::parse(&dir.path().join("light.toml"), &text).unwrap().build().unwrap();
    let options = RenderOptions { width: w, height: h, threads: 1, ..RenderOptions::default() };
    let image = render_image(&scene, &options, &RenderControl::default()).unwrap().0;
    let tan_half = 50f64.to_radians().tan();
    let (mut lit, mut checked) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            let alpha = (2.0 * (x as f64 + 0.5) / w as f64 - 1.0) * tan_half;
            let beta = (1.0 - 2.0 * (y as f64 + 0.5) / h as f64) * tan_half;
            let cos = 1.0 / (1.0 + alpha * alpha + beta * beta).sqrt();
            let Some(expected) = expected(alpha, beta, cos) else { continue };
            checked += 1;
            lit += usize::from(expected > 0.0);
            let got = image.get(x, y)[0] as f64;
            assert!((got - expected).abs() <= 1e-5 * expected.max(1.0), "pixel ({x}, {y}): {got} vs {expected}");
        }
    }
    assert!(lit > 300 && checked > 2000, "{lit} lit of {checked} checked");
}

/// The texel `(s, t)` falls in, or `None` within `margin` of a texel edge (where
/// a pixel's one ray may fall either way).
fn texel(rows: &[[f64; 4]; 2], s: f64, t: f64, margin: f64) -> Option<f64> {
    let (x, y) = (s * 4.0, (1.0 - t) * 2.0);
    let near_edge = |c: f64| (c - c.round()).abs() < margin;
    if near_edge(x) || near_edge(y) {
        return None;
    }
    if !(0.0..4.0).contains(&x) || !(0.0..2.0).contains(&y) {
        return Some(f64::NAN);
    }
    Some(rows[y as usize][x as usize])
}

#[test]
fn a_projector_lights_a_facing_floor_with_its_image_over_the_squared_distance() {
    let dir = tempfile::tempdir().unwrap();
    let rows = slide_png(dir.path());
    let path = dir.path().join("slide.png");
    // 60 degrees across x at the image's aspect 2: tan_x = tan 30, tan_y = tan_x / 2.
    let (tan_x, strength) = (30f64.to_radians().tan(), 3.0);
    let light = format!(
        "type = \"projector\"\nstrength = {strength}\nfov = 60\ntexture = {{ type = \"image\", file = {path:?}, filter = \"nearest\", color_space = \"linear\" }}"
    );
    floor_under_a_light(&light, |alpha, beta, _| {
        let (s, t) = (0.5 + alpha / (2.0 * tan_x), 0.5 + beta / tan_x);
        // The lecture's kd (L.N) Lin with Lin = strength T d / z^3: strength T / z^2.
        texel(&rows, s, t, 0.02).map(|v| if v.is_nan() { 0.0 } else { strength * v / 4.0 })
    });
}

#[test]
fn a_textured_spot_multiplies_its_cone_by_the_image_across_the_outer_angle() {
    let dir = tempfile::tempdir().unwrap();
    let rows = slide_png(dir.path());
    let path = dir.path().join("slide.png");
    let tan_outer = 40f64.to_radians().tan();
    let light = format!(
        "type = \"spot_light\"\nintensity = 8\ninner_angle = 40\nouter_angle = 40\ntexture = {{ type = \"image\", file = {path:?}, filter = \"nearest\", color_space = \"linear\" }}"
    );
    floor_under_a_light(&light, |alpha, beta, cos| {
        let (s, t) = (0.5 + alpha / (2.0 * tan_outer), 0.5 + beta / (2.0 * tan_outer));
        if (cos - 40f64.to_radians().cos()).abs() < 0.01 {
            return None; // the cone's edge
        }
        let inside = cos > 40f64.to_radians().cos();
        // I T cos / d^2 with d = height / cos, height 2.
        texel(&rows, s, t, 0.02).map(|v| if !inside || v.is_nan() { 0.0 } else { 8.0 * v * cos * cos * cos / 4.0 })
    });
}
