//! Image textures, the UV checker and the `pbr` material in rendered scene
//! files: texels read back through a render, textured parameters against the
//! same material with the texel's constant, and the shared glTF samples with
//! their own textures.

mod common;

use std::path::Path;

use lamplight_core::film::{srgb_decode, Image};
use lamplight_core::{integrators, render_image, RenderControl, RenderOptions};
use lamplight_scene::build::SceneFile;

/// A 4 x 2 PNG, texel `(x, y)` (row 0 at the top) of 8-bit sRGB `(60 x + 10, 200 - 90 y, 128)`.
fn texel8(x: u32, y: u32) -> [u8; 3] {
    [(60 * x + 10) as u8, (200 - 90 * y) as u8, 128]
}

fn write_png(dir: &Path) {
    let img = image::RgbImage::from_fn(4, 2, |x, y| image::Rgb(texel8(x, y)));
    img.save(dir.join("t.png")).unwrap();
}

/// The rectangle `[0, 4] x [0, 2]` in `z = 0` (so `(u, v) = (x / 4, y / 2)`)
/// seen by an orthographic camera one pixel per texel, with `material`.
fn render_quad(dir: &Path, material: &str, integrator: &str, spp: u32) -> Image {
    let text = format!(
        "[render]\nintegrator = \"{integrator}\"\n[camera]\ntype = \"orthographic\"\neye = [2, 1, 10]\nlook_at = [2, 1, 0]\nhalf_width = 2\nhalf_height = 1\n\
         [[objects]]\ntype = \"directional_light\"\ndirection = [0, 0, -1]\nradiance = 1\n\
         [materials.m]\n{material}\n\
         [[objects]]\ntype = \"rectangle\"\ncorner = [0, 0, 0]\nedge_u = [4, 0, 0]\nedge_v = [0, 2, 0]\nmaterial = \"m\"\n"
    );
    let path = dir.join("s.toml");
    std::fs::write(&path, &text).unwrap();
    let file = SceneFile::read(&path).unwrap_or_else(|e| panic!("{e}"));
    let built = file.build_with_warnings().unwrap_or_else(|e| panic!("{e}"));
    let integrator = integrators::find(integrator).unwrap();
    let options = RenderOptions { width: 4, height: 2, spp, threads: 1, integrator, ..RenderOptions::default() };
    render_image(&built.scene, &options, &RenderControl::default()).unwrap().0
}

#[test]
fn every_texel_reads_back_through_a_render() {
    let dir = tempfile::tempdir().unwrap();
    write_png(dir.path());
    for filter in ["nearest", "bilinear", "trilinear"] {
        // Emission only: the pixel is the texel, decoded from sRGB.
        let m = format!("kd = 0\nka = 0\nemission = {{ type = \"image\", file = \"t.png\", filter = \"{filter}\" }}");
        let image = render_quad(dir.path(), &m, "whitted", 1);
        for y in 0..2 {
            for x in 0..4 {
                let expected = texel8(x, y).map(|c| srgb_decode(f64::from(c) / 255.0) as f32);
                let got = image.get(x, y);
                assert!(got.iter().zip(expected).all(|(g, e)| (g - e).abs() < 1e-6), "{filter} ({x}, {y}): {got:?} vs {expected:?}");
            }
        }
    }
    // Linear: the texel's value divided by 255, undecoded.
    let image = render_quad(dir.path(), "kd = 0\nka = 0\nemission = { type = \"image\", file = \"t.png\", color_space = \"linear\" }", "whitted", 1);
    assert!((image.get(1, 1)[1] - 110.0 / 255.0).abs() < 1e-6, "{:?}", image.get(1, 1));
}

#[test]
fn a_textured_parameter_equals_the_constant_of_its_texel() {
    let dir = tempfile::tempdir().unwrap();
    write_png(dir.path());
    // kd, roughness, base colour and metallic from the image against renders of
    // the texel's own value as a constant, pixel by pixel, under both integrators.
    for (integrator, spp) in [("whitted", 1), ("path", 4)] {
        for (textured, constant) in [
            ("kd = { type = \"image\", file = \"t.png\", filter = \"nearest\" }\nka = 0", "kd = KD\nka = 0"),
            (
                "type = \"pbr\"\nbase_color = { type = \"image\", file = \"t.png\", filter = \"nearest\" }\nmetallic = { type = \"image\", file = \"t.png\", filter = \"nearest\", channel = \"b\", color_space = \"linear\" }\nroughness = 0.5",
                "type = \"pbr\"\nbase_color = KD\nmetallic = 0.50196078431372548\nroughness = 0.5",
            ),
        ] {
            let image = render_quad(dir.path(), textured, integrator, spp);
            for y in 0..2 {
                for x in 0..4 {
                    let kd = texel8(x, y).map(|c| srgb_decode(f64::from(c) / 255.0));
                    let m = constant.replace("KD", &format!("[{}, {}, {}]", kd[0], kd[1], kd[2]));
                    let reference = render_quad(dir.path(), &m, integrator, spp);
                    let (a, b) = (image.get(x, y), reference.get(x, y));
                    assert!(a.iter().zip(b).all(|(a, b)| (a - b).abs() <= 1e-5 * b.abs().max(1.0)), "{integrator} {textured} ({x}, {y}): {a:?} vs {b:?}");
                }
            }
        }
    }
}

#[test]
fn bad_texture_tables_name_their_key() {
    let dir = tempfile::tempdir().unwrap();
    write_png(dir.path());
    let error = |material: &str| {
        let text = format!("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 30\n[materials.m]\n{material}\n");
        let path = dir.path().join("e.toml");
        std::fs::write(&path, &text).unwrap();
        match SceneFile::read(&path).and_then(|f| f.build_with_warnings()) {
            Ok(_) => panic!("{material} was accepted"),
            Err(e) => e.to_string().replace(&format!("{}/", dir.path().display()), ""),
        }
    };
    let missing = error("kd = { type = \"image\", file = \"none.png\" }");
    assert!(missing.starts_with("e.toml:6:") && missing.contains("none.png") && missing.contains("no such file"), "{missing}");
    assert_eq!(
        error("kd = { type = \"image\", file = \"t.png\", wrap = \"tile\" }"),
        "e.toml:6:47: material \"m\": kd: wrap: unknown value \"tile\", expected \"repeat\", \"mirror\" or \"clamp\""
    );
    assert_eq!(
        error("type = \"pbr\"\nmetallic = 2"),
        "e.toml:7:12: material \"m\": metallic: must be between 0 and 1, got 2"
    );
}
