//! The scene file's `environment`: a uniform sky or a map, with strength and a
//! turn about +y, seen by every ray that leaves the scene and lighting it under
//! path tracing; bad tables are reported at their keys.

use std::path::Path;

use lamplight_core::film::Image;
use lamplight_core::{integrators, render_image, RenderControl, RenderOptions};
use lamplight_scene::instantiate::SceneFile;

/// An 8 x 4 map, each texel a different colour: texel `(x, y)` is `(x + 1, y + 1, 0.5)`.
fn write_map(dir: &Path) {
    let (w, h) = (8u32, 4u32);
    let pixels = (0..h).flat_map(|y| (0..w).map(move |x| [x as f32 + 1.0, y as f32 + 1.0, 0.5])).collect();
    lamplight_scene::image_io::write_image(&dir.join("sky.exr"), &Image { width: w, height: h, pixels }).unwrap();
}

/// The map seen through a panorama camera at the origin looking along -z, one
/// pixel per texel (Whitted: camera rays that miss see the environment).
fn panorama(dir: &Path, environment: &str) -> Image {
    let text = format!("environment = {environment}\n[camera]\ntype = \"spherical\"\neye = [0, 0, 0]\nlook_at = [0, 0, -1]\n");
    let path = dir.join("s.toml");
    std::fs::write(&path, &text).unwrap();
    let scene = SceneFile::read(&path).unwrap().build().unwrap_or_else(|e| panic!("{e}"));
    let options = RenderOptions { width: 8, height: 4, threads: 1, ..RenderOptions::default() };
    render_image(&scene, &options, &RenderControl::default()).unwrap().0
}

#[test]
fn a_map_is_seen_as_it_is_then_turned_and_scaled() {
    let dir = tempfile::tempdir().unwrap();
    write_map(dir.path());
    let plain = panorama(dir.path(), "{ file = \"sky.exr\" }");
    for y in 0..4 {
        for x in 0..8 {
            assert_eq!(plain.get(x, y), [x as f32 + 1.0, y as f32 + 1.0, 0.5], "texel ({x}, {y})");
        }
    }
    // Turned 90 degrees about +y, the panorama's column x shows the map's
    // column x + 2 (a quarter turn of 8); strength 2 doubles every value.
    let turned = panorama(dir.path(), "{ file = \"sky.exr\", rotate = 90, strength = 2 }");
    for y in 0..4 {
        for x in 0..8 {
            let [r, g, b] = plain.get((x + 2) % 8, y);
            assert_eq!(turned.get(x, y), [2.0 * r, 2.0 * g, 2.0 * b], "panorama ({x}, {y})");
        }
    }
}

#[test]
fn a_uniform_sky_lights_a_floor_under_path_tracing() {
    // A white Lambertian floor under a sky of 0.5: it reflects 0.5; the sky
    // replaces the (different) background.
    let text = "background = 9\nenvironment = { color = 0.25, strength = 2 }\n[camera]\neye = [0, 1, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\nvfov = 1\n\
                [materials.white]\ncolor = 1\nkd = 1\nka = 0\n\
                [[objects]]\ntype = \"rectangle\"\ncorner = [-50, 0, 50]\nedge_u = [100, 0, 0]\nedge_v = [0, 0, -100]\nmaterial = \"white\"\n";
    let scene = SceneFile::parse(Path::new("s.toml"), text).unwrap().build().unwrap();
    let options = RenderOptions {
        width: 2,
        height: 2,
        spp: 256,
        max_depth: Some(2),
        integrator: integrators::find("path").unwrap(),
        ..RenderOptions::default()
    };
    let image = render_image(&scene, &options, &RenderControl::default()).unwrap().0;
    for p in &image.pixels {
        for c in p {
            assert!((c - 0.5).abs() < 0.01, "{p:?}");
        }
    }
}

#[test]
fn bad_environments_are_reported_at_their_keys() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("sky.txt"), "not a map").unwrap();
    let error = |environment: &str| {
        let path = d.join("s.toml");
        std::fs::write(&path, format!("environment = {environment}\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n")).unwrap();
        SceneFile::read(&path).unwrap().build().unwrap_err().to_string().replace(&format!("{}/", d.display()), "")
    };
    assert_eq!(error("{ color = 1, file = \"sky.exr\" }"), "s.toml:1:15: scene: environment: takes either `color` or `file`");
    assert_eq!(error("{ }"), "s.toml:1:15: scene: environment: takes either `color` or `file`");
    assert_eq!(error("{ colour = 1 }"), "s.toml:1:17: scene: environment: unknown parameter 'colour' (did you mean 'color'?)");
    assert_eq!(error("{ color = 1, strength = -1 }"), "s.toml:1:39: scene: environment: strength: must be a non-negative number, got -1");
    assert_eq!(
        error("{ file = \"sky.txt\" }"),
        "s.toml:1:24: scene: environment: file: cannot read sky.txt: unknown environment map format \"txt\" (supported: .exr, .hdr)"
    );
    assert_eq!(error("{ file = \"\" }"), "s.toml:1:24: scene: environment: file: the path is empty, expected an .exr or .hdr file");
}
