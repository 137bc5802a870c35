//! Image textures, the UV checker and the `pbr` material in rendered scene
//! files: texels read back through a render, textured parameters against the
//! same material with the texel's constant, and the shared glTF samples with
//! their own textures.

use crate::common;

use std::path::Path;

use lamplight_core::film::{srgb_decode, Image};
use lamplight_core::{integrators, render_image, RenderControl, RenderOptions};
use lamplight_scene::instantiate::SceneFile;

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
    render_lit_quad(dir, material, integrator, spp, "[0, 0, -1]")
}

/// [`render_quad`] lit by a directional light travelling along `light`.
fn render_lit_quad(dir: &Path, material: &str, integrator: &str, spp: u32, light: &str) -> Image {
    let text = format!(
        "[render]\nintegrator = \"{integrator}\"\n[camera]\ntype = \"orthographic\"\neye = [2, 1, 10]\nlook_at = [2, 1, 0]\nhalf_width = 2\nhalf_height = 1\n\
         [[objects]]\ntype = \"directional_light\"\ndirection = {light}\nradiance = 1\n\
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
    let image = render_quad(
        dir.path(),
        "kd = 0\nka = 0\nemission = { type = \"image\", file = \"t.png\", color_space = \"linear\" }",
        "whitted",
        1,
    );
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
        "e.toml:6:47: material \"m\": kd: wrap: unknown value \"tile\" (values: repeat, mirror, clamp)"
    );
    assert_eq!(error("type = \"pbr\"\nmetallic = 2"), "e.toml:7:12: material \"m\": metallic: must be between 0 and 1, got 2");
}

/// The base colour the camera sees on the model, pixel by pixel: the textured
/// colour at each camera ray's hit (through UVs, the image and its sampler), and
/// the mean of the texture itself.
fn seen_and_texture_means(file: &str) -> Option<([f64; 3], [f64; 3], usize)> {
    let data = common::shared_data("gltf_samples_show_their_texture_colours")?;
    let path = data.join(file);
    let scene = lamplight_scene::instantiate::imported::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let (w, h) = (64u32, 64u32);
    let mut sum = [0.0; 3];
    let mut n = 0;
    for y in 0..h {
        for x in 0..w {
            let ray = scene.settings.camera.ray(x as f64, y as f64, w, h, (0.5, 0.5));
            let Some(hit) = scene.first_intersect(&ray, f64::INFINITY) else { continue };
            let c = scene.material_at(&hit).color.constant().unwrap();
            for k in 0..3 {
                sum[k] += c[k];
            }
            n += 1;
        }
    }
    // The texture's own mean, decoded as the importer decodes it: the image of the material's base colour.
    let image = scene.materials.iter().find_map(|m| image_of(&m.color)).expect("a textured base colour");
    let (tw, th) = image.size();
    let mut mean = [0.0; 3];
    for y in 0..th {
        for x in 0..tw {
            let t = image.texel(0, x, y);
            for k in 0..3 {
                mean[k] += f64::from(t[k]) / (tw * th) as f64;
            }
        }
    }
    Some((sum.map(|s| s / n as f64), mean, n))
}

#[test]
fn gltf_samples_show_their_texture_colours() {
    // Absolute tolerances per channel: the box shows its whole texture on every
    // face (measured within 0.025); the duck's camera sees part of its atlas (the
    // yellow body, not all of the eyes and beak: within 0.08).
    for (file, tolerance) in [("gltf/BoxTextured.glb", 0.04), ("gltf/Duck.glb", 0.1)] {
        let Some((seen, texture, pixels)) = seen_and_texture_means(file) else { return };
        println!("{file}: {pixels} pixels, seen mean {seen:.3?}, texture mean {texture:.3?}");
        assert!(pixels > 200, "{file}: the model covers {pixels} pixels");
        for k in 0..3 {
            assert!((seen[k] - texture[k]).abs() <= tolerance, "{file} channel {k}: seen {seen:?}, texture {texture:?}");
        }
    }
}

/// The image inside a (possibly scaled) image texture.
fn image_of(t: &lamplight_core::materials::Texture) -> Option<std::sync::Arc<lamplight_core::materials::ImageData>> {
    use lamplight_core::materials::Texture;
    match t {
        Texture::Image(i) => Some(i.image.clone()),
        Texture::Scale(f) => f.iter().find_map(image_of),
        _ => None,
    }
}

#[test]
fn a_normal_map_turns_the_shading_normal() {
    let dir = tempfile::tempdir().unwrap();
    // Light from 45 degrees towards +x: a flat diffuse quad receives cos 45; a
    // map of texel (1, 0.5, 1), the normal (1, 0, 1) / sqrt 2, faces the light.
    let light = "[-1, 0, -1]";
    let flat = render_lit_quad(dir.path(), "kd = 1\nka = 0\ncolor = 1", "whitted", 1, light);
    let mapped = render_lit_quad(dir.path(), "kd = 1\nka = 0\ncolor = 1\nnormal_map = [1, 0.5, 1]", "whitted", 1, light);
    let tilted_away = render_lit_quad(dir.path(), "kd = 1\nka = 0\ncolor = 1\nnormal_map = [0, 0.5, 1]", "whitted", 1, light);
    let (f, m, a) = (flat.get(1, 1)[0], mapped.get(1, 1)[0], tilted_away.get(1, 1)[0]);
    assert!((m / f - std::f32::consts::SQRT_2).abs() < 1e-5, "mapped {m} flat {f}");
    assert!(a.abs() < 1e-6, "a normal turned away from the light is dark: {a}");
    // glTF's normalTexture.scale: 0 is the flat surface.
    let none = render_lit_quad(dir.path(), "kd = 1\nka = 0\ncolor = 1\nnormal_map = [1, 0.5, 1]\nnormal_scale = 0", "whitted", 1, light);
    assert!((none.get(1, 1)[0] - f).abs() < 1e-6);
    // The path tracer sees the same tilt (direct light from a delta light only, at 1 spp).
    let path_flat = render_lit_quad(dir.path(), "kd = 1\nka = 0\ncolor = 1", "path", 1, light);
    let path_mapped = render_lit_quad(dir.path(), "kd = 1\nka = 0\ncolor = 1\nnormal_map = [1, 0.5, 1]", "path", 1, light);
    assert!((path_mapped.get(1, 1)[0] / path_flat.get(1, 1)[0] - std::f32::consts::SQRT_2).abs() < 1e-4);
}

#[test]
fn cut_outs_let_camera_and_shadow_rays_through() {
    // The quad's left half (u < 0.5) is cut out by a two-cell UV checker; behind
    // it, a glowing quad.
    let text = "[camera]\ntype = \"orthographic\"\neye = [2, 1, 10]\nlook_at = [2, 1, 0]\nhalf_width = 2\nhalf_height = 1\n\
        [materials.glow]\nkd = 0\nka = 0\nemission = 1\n\
        [materials.cut]\nkd = 0\nka = 0\nalpha = { type = \"uv_checker\", even = 0, odd = 1, uv_scale = [2, 1] }\nalpha_cutoff = 0.5\n\
        [[objects]]\ntype = \"rectangle\"\ncorner = [0, 0, 0]\nedge_u = [4, 0, 0]\nedge_v = [0, 2, 0]\nmaterial = \"glow\"\n\
        [[objects]]\ntype = \"rectangle\"\ncorner = [0, 0, 1]\nedge_u = [4, 0, 0]\nedge_v = [0, 2, 0]\nmaterial = \"cut\"\n";
    let scene = SceneFile::parse(Path::new("s.toml"), text).unwrap().build().unwrap_or_else(|e| panic!("{e}"));
    let options = RenderOptions { width: 4, height: 2, threads: 1, ..RenderOptions::default() };
    let image = render_image(&scene, &options, &RenderControl::default()).unwrap().0;
    for y in 0..2 {
        assert_eq!((image.get(0, y), image.get(1, y)), ([1.0; 3], [1.0; 3]), "seen through the hole");
        assert_eq!((image.get(2, y), image.get(3, y)), ([0.0; 3], [0.0; 3]), "the covered half");
    }
    // Shadow rays from the glowing quad's surface upwards: through the hole, blocked elsewhere.
    use lamplight_core::math::Vec3;
    assert_eq!(
        scene.transmittance(&lamplight_core::ray::Ray::unit(Vec3::new(0.5, 1.0, 0.5), Vec3::Z), 5.0, None),
        lamplight_core::math::Rgb::ONE
    );
    assert_eq!(
        scene.transmittance(&lamplight_core::ray::Ray::unit(Vec3::new(3.5, 1.0, 0.5), Vec3::Z), 5.0, None),
        lamplight_core::math::Rgb::ZERO
    );
}

/// Root-mean-square difference of two images over the rows `rows`.
fn rmse(a: &Image, b: &Image, rows: std::ops::Range<u32>) -> f64 {
    let mut sum = 0.0;
    let mut n = 0;
    for y in rows {
        for x in 0..a.width {
            for (p, q) in a.get(x, y).iter().zip(b.get(x, y)) {
                sum += f64::from(p - q).powi(2);
                n += 1;
            }
        }
    }
    (sum / n as f64).sqrt()
}

/// Energy of the horizontal second differences (the high frequencies) over `rows`.
fn high_frequency(a: &Image, rows: std::ops::Range<u32>) -> f64 {
    let mut sum = 0.0;
    for y in rows {
        for x in 1..a.width - 1 {
            let d = 2.0 * a.get(x, y)[1] - a.get(x - 1, y)[1] - a.get(x + 1, y)[1];
            sum += f64::from(d).powi(2);
        }
    }
    sum
}

#[test]
fn a_receding_checker_floor_shows_no_moire_at_one_sample() {
    let dir = tempfile::tempdir().unwrap();
    // 64 x 64 texels in 8 x 8 checks, tiled 200 times across a floor 1000 units deep.
    image::RgbImage::from_fn(64, 64, |x, y| image::Rgb(if (x / 8 + y / 8) % 2 == 0 { [255; 3] } else { [0; 3] }))
        .save(dir.path().join("c.png"))
        .unwrap();
    let render = |filter: &str, spp: u32| {
        let text = format!(
            "[camera]\neye = [0, 1, 0]\nlook_at = [0, 0.75, -10]\nvfov = 40\n\
             [materials.floor]\nkd = 0\nka = 0\nemission = {{ type = \"image\", file = \"c.png\", filter = \"{filter}\", uv_scale = [200, 200] }}\n\
             [[objects]]\ntype = \"rectangle\"\ncorner = [-500, 0, 0]\nedge_u = [1000, 0, 0]\nedge_v = [0, 0, -1000]\nmaterial = \"floor\"\n"
        );
        let path = dir.path().join("floor.toml");
        std::fs::write(&path, &text).unwrap();
        let scene = SceneFile::read(&path).unwrap().build().unwrap_or_else(|e| panic!("{e}"));
        let options = RenderOptions { width: 96, height: 64, spp, threads: 1, ..RenderOptions::default() };
        render_image(&scene, &options, &RenderControl::default()).unwrap().0
    };
    let reference = render("bilinear", 64);
    let (aliased, filtered) = (render("bilinear", 1), render("trilinear", 1));
    // The far half of the floor, above the image's middle and below the horizon.
    let far = 16..32;
    let (e_aliased, e_filtered) = (rmse(&aliased, &reference, far.clone()), rmse(&filtered, &reference, far.clone()));
    let (hf_ref, hf_aliased, hf_filtered) =
        (high_frequency(&reference, far.clone()), high_frequency(&aliased, far.clone()), high_frequency(&filtered, far));
    println!("far floor: RMSE against 64 spp: bilinear {e_aliased:.4}, trilinear {e_filtered:.4}; HF energy: 64 spp {hf_ref:.3}, bilinear {hf_aliased:.3}, trilinear {hf_filtered:.3}");
    assert!(e_filtered < 0.5 * e_aliased, "trilinear {e_filtered} vs bilinear {e_aliased}");
    // Near the camera the checks are larger than pixels: trilinear keeps them (no
    // more error than the aliased lookup, which is right there).
    let near = 48..64;
    let (n_aliased, n_filtered) = (rmse(&aliased, &reference, near.clone()), rmse(&filtered, &reference, near));
    println!("near floor: RMSE against 64 spp: bilinear {n_aliased:.4}, trilinear {n_filtered:.4}");
    assert!(n_filtered < 0.15, "the near checks survive: {n_filtered}");
    // Isotropic trilinear filtering blurs the far floor fully (pbrt's and GPUs'
    // trilinear do the same at grazing angles); what matters is no aliased energy.
    assert!(
        hf_filtered < 2.0 * hf_ref && hf_aliased > 4.0 * hf_ref,
        "HF energy: reference {hf_ref}, bilinear {hf_aliased}, trilinear {hf_filtered}"
    );
}
