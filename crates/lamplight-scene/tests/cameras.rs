//! Camera kinds through the scene format: each `[camera] type` renders what its
//! core camera renders, and the built scene serves any image size.

use std::path::Path;

use lamplight_core::camera::{Camera, Fov, Orthographic, Perspective, ThinLens};
use lamplight_core::math::Vec3;
use lamplight_core::{render_image, RenderControl, RenderOptions, Scene};
use lamplight_scene::instantiate::SceneFile;

const SCENE: &str = "[render]\nspp = 4\n\
    [materials.white]\ncolor = 1\nkd = 1\nka = 0\n\
    [[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [0, 0, 0]\nradius = 1\n\
    [[objects]]\ntype = \"sphere\"\nmaterial = \"white\"\ncenter = [1.5, 0, -6]\nradius = 1\n\
    [[objects]]\ntype = \"directional_light\"\ndirection = [0, 0, -1]\nradiance = 2\n";

fn scene(camera: &str) -> Scene {
    let text = format!("[camera]\n{camera}\n{SCENE}");
    SceneFile::parse(Path::new("c.toml"), &text).unwrap_or_else(|e| panic!("{e}")).build().unwrap()
}

fn bytes(scene: &Scene, width: u32, height: u32) -> Vec<u8> {
    let options = RenderOptions { width, height, spp: 4, threads: 2, ..RenderOptions::default() };
    render_image(scene, &options, &RenderControl::default()).unwrap().0.to_srgb8()
}

/// The file's scene with its camera replaced by `camera`, built in code.
fn with(camera: impl Camera + 'static) -> Scene {
    let mut s = scene("eye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40");
    s.settings.camera = std::sync::Arc::new(camera);
    s
}

#[test]
fn thin_lens_in_a_file_is_the_core_thin_lens() {
    let file = scene("type = \"thin_lens\"\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\nlens_radius = 0.2\nfocal_distance = 5");
    let pinhole = Perspective::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
    let core = with(ThinLens::new(pinhole.clone(), 0.2, 5.0).unwrap());
    assert_eq!(bytes(&file, 48, 32), bytes(&core, 48, 32));
    // focal_distance defaults to the distance to look_at.
    let default_focus = scene("type = \"thin_lens\"\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\nlens_radius = 0.2");
    assert_eq!(bytes(&default_focus, 48, 32), bytes(&core, 48, 32));
    // An open lens blurs the far sphere: the image differs from the pinhole's.
    assert_ne!(bytes(&file, 48, 32), bytes(&with(pinhole), 48, 32));
}

#[test]
fn orthographic_in_a_file_is_the_core_orthographic_at_any_size() {
    let file = scene("type = \"orthographic\"\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nhalf_width = 2\nhalf_height = 1.5");
    let core = with(Orthographic::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, 2.0, 1.5).unwrap());
    for (w, h) in [(48, 32), (32, 48), (40, 30)] {
        assert_eq!(bytes(&file, w, h), bytes(&core, w, h), "{w}x{h}");
    }
    // Parallel rays at 20 pixels a unit: the near sphere spans x in [-1, 1] (pixels
    // 20..60 of row 30) and the far one, as big though six units further, shows
    // beside it over [1, 2] up to the window's edge (pixels 60..80), lit along -z.
    let image = {
        let options = RenderOptions { width: 80, height: 60, threads: 1, ..RenderOptions::default() };
        render_image(&file, &options, &RenderControl::default()).unwrap().0
    };
    let lit: Vec<u32> = (0..80).filter(|&x| image.get(x, 30)[0] > 0.0).collect();
    assert_eq!(lit, (20..80).collect::<Vec<_>>());
}

#[test]
fn a_bad_camera_kind_and_key_are_reported_at_their_place() {
    let err = |camera: &str| {
        SceneFile::parse(Path::new("c.toml"), &format!("[camera]\n{camera}\n{SCENE}")).unwrap().build().unwrap_err().to_string()
    };
    // The list comes from the registry, so a new camera changes no test.
    let types: Vec<&str> = lamplight_scene::registry::CAMERAS.iter().map(|k| k.name).collect();
    assert_eq!(types[..4], ["perspective", "window", "thin_lens", "orthographic"]);
    assert_eq!(
        err("type = \"fisheye\"\neye = [0, 0, 5]"),
        format!("c.toml:2:8: camera: unknown camera type \"fisheye\" (camera types: {})", types.join(", "))
    );
    assert_eq!(
        err("type = \"thin_lens\"\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\nlens_radius = -1"),
        "c.toml:6:15: camera: invalid lens_radius: must be a non-negative number, got -1"
    );
    assert_eq!(
        err("type = \"orthographic\"\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40"),
        "c.toml:5:1: camera: unknown parameter 'vfov' (it takes: eye, look_at, up, half_width, half_height)"
    );
}
