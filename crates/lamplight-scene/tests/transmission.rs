//! The `pbr` material's `transmission` (glTF `KHR_materials_transmission`,
//! thin-walled) in rendered scenes with known answers.

use std::path::Path;

use lamplight_core::{integrators, render_image, RenderControl, RenderOptions};
use lamplight_scene::instantiate::SceneFile;

const CAMERA: &str =
    "[camera]\ntype = \"orthographic\"\neye = [0.5, 0.5, 5]\nlook_at = [0.5, 0.5, 0]\nhalf_width = 0.5\nhalf_height = 0.5\n";
const PANE: &str = "[[objects]]\ntype = \"rectangle\"\ncorner = [0, 0, 0]\nedge_u = [1, 0, 0]\nedge_v = [0, 1, 0]\nmaterial = \"pane\"\n";

fn render(text: &str, threads: usize) -> Vec<[f32; 3]> {
    let scene = SceneFile::parse(Path::new("s.toml"), text).unwrap().build().unwrap_or_else(|e| panic!("{e}"));
    let options =
        RenderOptions { width: 8, height: 8, spp: 64, threads, integrator: integrators::find("path").unwrap(), ..RenderOptions::default() };
    render_image(&scene, &options, &RenderControl::default()).unwrap().0.pixels
}

#[test]
fn a_clear_white_pane_in_the_furnace_keeps_all_light() {
    // Reflection F and transmission 1 - F of one smooth lobe: the sky of
    // radiance 1 seen through and in the pane adds to 1; half transmission
    // over a white diffuse base is 1 as well (to the model's 1e-3 at normal incidence).
    for t in ["1", "0.5"] {
        let text = format!(
            "background = 1\n{CAMERA}[materials.pane]\ntype = \"pbr\"\nbase_color = 1\nmetallic = 0\nroughness = 0\ntransmission = {t}\n{PANE}"
        );
        let image = render(&text, 1);
        let mean = image.iter().map(|p| f64::from(p[0] + p[1] + p[2]) / 3.0).sum::<f64>() / image.len() as f64;
        assert!((mean - 1.0).abs() < 5e-3, "t = {t}: mean {mean}");
        for p in &image {
            assert!((f64::from(p[1]) - 1.0).abs() < 0.05, "t = {t}: {p:?}");
        }
        assert_eq!(image, render(&text, 3), "threads change no byte");
    }
}

#[test]
fn a_transmission_texture_lets_light_through_where_it_says() {
    // A glowing square behind a white pane whose left half (u < 0.5) is
    // opaque and right half clear: the camera sees black on the left, and the
    // glow times 1 - F (F = 0.04 head on) on the right.
    let text = format!(
        "{CAMERA}[materials.pane]\ntype = \"pbr\"\nbase_color = 1\nmetallic = 0\nroughness = 0\n\
         transmission = {{ type = \"uv_checker\", even = 0, odd = 1, uv_scale = [2, 1] }}\n\
         [materials.glow]\nkd = 0\nka = 0\nemission = 1\ntwo_sided = true\n{PANE}\
         [[objects]]\ntype = \"rectangle\"\ncorner = [-1, -1, -1]\nedge_u = [3, 0, 0]\nedge_v = [0, 3, 0]\nmaterial = \"glow\"\n"
    );
    let image = render(&text, 2);
    // Per sample the clear half gives 0 (the reflection of black, chosen with
    // probability 0.05) or 0.96 / 0.95: per pixel sd 0.028, over 32 pixels 0.005.
    let mut right = 0.0;
    for y in 0..8 {
        for x in 0..8 {
            let g = f64::from(image[y * 8 + x][1]);
            if x < 4 {
                assert!(g < 0.02, "pixel ({x}, {y}) is opaque: {g}");
            } else {
                assert!((g - 0.96).abs() < 0.12, "pixel ({x}, {y}) lets 1 - F through: {g}");
                right += g / 32.0;
            }
        }
    }
    assert!((right - 0.96).abs() < 0.02, "the clear half: {right}");
}

#[test]
fn transmission_outside_0_to_1_is_an_error_at_its_value() {
    let text = format!("{CAMERA}[materials.pane]\ntype = \"pbr\"\ntransmission = 1.5\n{PANE}");
    let err = SceneFile::parse(Path::new("s.toml"), &text).and_then(|f| f.build()).unwrap_err().to_string();
    assert_eq!(err, "s.toml:9:16: material \"pane\": transmission: must be between 0 and 1, got 1.5");
}
