//! What `lamplight render` says and does about a scene's lights (issue 27): a
//! light shut in by geometry is named, with what blocks it; an environment map
//! from the command line is interpolated between its pixels; a model file whose
//! own lights reach too little of the view keeps the automatic lights.

use std::path::Path;
use std::process::{Command, Output, Stdio};

fn lamplight(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lamplight")).args(args).current_dir(dir).stdin(Stdio::null()).output().expect("the binary runs")
}

/// Renders `scene` in `dir`, expecting success; returns stderr's warning lines.
fn warnings(dir: &Path, scene: &str) -> Vec<String> {
    let out = lamplight(dir, &["render", scene, "-o", "out.png", "-q"]);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "lamplight render {scene}: {err}");
    err.lines().filter(|l| l.starts_with("lamplight: warning: ")).map(str::to_string).collect()
}

/// A grey floor and a sphere of radius 0.5 at height 1 (named `name`, if any),
/// lit by a point light at `light`; a little ambient light, so that only the
/// shut-in light is missing from the image.
fn sphere_scene(light: [f64; 3], name: Option<&str>) -> String {
    let name = name.map(|n| format!("name = \"{n}\"\n")).unwrap_or_default();
    format!(
        r#"ambient = 0.2

[render]
width = 64
height = 48

[camera]
eye = [0.0, 2.0, 6.0]
look_at = [0.0, 0.5, 0.0]
up = [0.0, 1.0, 0.0]
vfov = 40

[materials.grey]
color = [0.6, 0.6, 0.6]

[[objects]]
type = "rectangle"
material = "grey"
corner = [-5.0, 0.0, -5.0]
edge_u = [0.0, 0.0, 10.0]
edge_v = [10.0, 0.0, 0.0]

[[objects]]
type = "sphere"
{name}material = "grey"
center = [0.0, 1.0, 0.0]
radius = 0.5

[[objects]]
type = "point_light"
position = {light:?}
intensity = 2.0
"#
    )
}

#[test]
fn a_point_light_inside_a_closed_sphere_is_named_with_the_sphere_that_blocks_it() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("shut_in.toml"), sphere_scene([0.0, 1.0, 0.0], Some("shell"))).unwrap();
    // 142 of the 16 x 16 probe rays see the floor, which faces the light; the
    // sphere's outside, which does not, casts no shadow ray.
    assert_eq!(
        warnings(dir.path(), "shut_in.toml"),
        ["lamplight: warning: light 0 (PointLight) lights nothing the camera sees: every shadow ray towards it \
          from what the camera sees (142 probed) is blocked by object 1 \"shell\" (Sphere)"]
    );
    // An unnamed blocker is named by its index and kind.
    std::fs::write(dir.path().join("unnamed.toml"), sphere_scene([0.0, 1.0, 0.0], None)).unwrap();
    assert_eq!(
        warnings(dir.path(), "unnamed.toml"),
        ["lamplight: warning: light 0 (PointLight) lights nothing the camera sees: every shadow ray towards it \
          from what the camera sees (142 probed) is blocked by object 1 (Sphere)"]
    );
}

#[test]
fn a_light_that_reaches_what_the_camera_sees_gets_no_warning() {
    let dir = tempfile::tempdir().unwrap();
    // The same scene with the light above the sphere: the sphere shadows part
    // of the floor, and the rest is lit.
    std::fs::write(dir.path().join("free.toml"), sphere_scene([0.0, 2.5, 0.0], Some("shell"))).unwrap();
    assert_eq!(warnings(dir.path(), "free.toml"), Vec::<String>::new());
    // luxo's light sits in its lamp's shade, with the bulb its own object.
    assert_eq!(warnings(dir.path(), "luxo"), Vec::<String>::new());
}

/// The radiance `lamplight render` sees straight ahead (along -z, the map's
/// centre: u = v = 1/2) through `--environment` holding `map` (`width x
/// height` pixels, rows from the top), with `integrator`.
fn centre_of_the_sky(map: Vec<[f32; 3]>, width: u32, height: u32, integrator: &str) -> [f32; 3] {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let sky = lamplight_core::film::Image { width, height, pixels: map };
    lamplight_scene::image_io::write_image(&d.join("sky.exr"), &sky).unwrap();
    // Nothing in view: the rays leave the scene at once. The path tracer
    // jitters its one sample within the pixel: a field of view of 1e-4
    // degrees keeps every ray within 1e-6 radians of -z.
    std::fs::write(d.join("sky.toml"), "[camera]\neye = [0, 0, 0]\nlook_at = [0, 0, -1]\nup = [0, 1, 0]\nvfov = 1e-4\n").unwrap();
    let args = ["render", "sky.toml", "--environment", "sky.exr", "--width", "1", "--height", "1", "--antialias", "off"];
    let out = lamplight(d, &[&args[..], &["--integrator", integrator, "--spp", "1", "-o", "out.exr", "-q"]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    lamplight_scene::image_io::read_exr(&d.join("out.exr")).unwrap().pixels[0]
}

#[test]
fn an_environment_map_from_the_command_line_is_interpolated_bilinearly() {
    // 4x2: straight ahead lies midway between columns 1 and 2 (pixel centres at
    // u = 3/8, 5/8) and midway between the two rows (the zenith's and the
    // nadir's, as Mitsuba's envmap places them): the mean of those four pixels,
    // (1 + 3 + 5 + 7) / 4 = 4. The nearest pixel, (2, 1), would give 7; the
    // other pixels, 100, must not enter at all.
    let far = [100.0; 3];
    let map = vec![far, [1.0; 3], [3.0; 3], far, far, [5.0; 3], [7.0; 3], far];
    for integrator in ["whitted", "path"] {
        let seen = centre_of_the_sky(map.clone(), 4, 2, integrator);
        assert!(seen.iter().all(|c| (c - 4.0).abs() < 1e-5), "{integrator}: {seen:?}");
    }
    // 2x1, one row: interpolated across, the same in every direction up and down:
    // midway between pixel centres u = 1/4 and 3/4, (2 + 6) / 2 = 4 (the nearest pixel gives 6).
    let seen = centre_of_the_sky(vec![[2.0; 3], [6.0; 3]], 2, 1, "whitted");
    assert!(seen.iter().all(|c| (c - 4.0).abs() < 1e-5), "{seen:?}");
}

/// An OBJ of two boxes: a closed orange shell of half-size 1 about the origin
/// and an emitting lamp box of half-size 0.2 about `lamp` (its only light,
/// MTL `Ke`), both wound outwards.
fn two_boxes(lamp: [f64; 3]) -> (String, String) {
    let cube = |c: [f64; 3], h: f64, first: usize, material: &str| {
        let mut s = format!("usemtl {material}\n");
        // OBJ order 1..8: (-,-,-) (+,-,-) (+,+,-) (-,+,-) (-,-,+) (+,-,+) (+,+,+) (-,+,+).
        for (x, y, z) in [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)] {
            let at = |b: i32, c0: f64| c0 + if b == 1 { h } else { -h };
            s += &format!("v {} {} {}\n", at(x, c[0]), at(y, c[1]), at(z, c[2]));
        }
        for f in [[1, 4, 3, 2], [5, 6, 7, 8], [1, 5, 8, 4], [2, 3, 7, 6], [1, 2, 6, 5], [4, 8, 7, 3]] {
            s += &format!("f {} {} {} {}\n", f[0] + first, f[1] + first, f[2] + first, f[3] + first);
        }
        s
    };
    let obj = format!("mtllib boxes.mtl\n{}{}", cube([0.0; 3], 1.0, 0, "skin"), cube(lamp, 0.2, 8, "candle"));
    let mtl = "newmtl skin\nKd 0.9 0.45 0.1\nnewmtl candle\nKd 0 0 0\nKe 4 3 1\n".to_string();
    (obj, mtl)
}

/// Renders `boxes.obj` with `flags` to EXR: the image and the warning lines.
fn render_boxes(dir: &Path, flags: &[&str]) -> (Vec<[f32; 3]>, Vec<String>) {
    let args = [&["render", "boxes.obj", "--width", "64", "--height", "48", "-o", "out.exr"][..], flags].concat();
    let out = lamplight(dir, &args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{err}");
    let warnings = err.lines().filter(|l| l.starts_with("lamplight: warning: ")).map(str::to_string).collect();
    (lamplight_scene::image_io::read_exr(&dir.join("out.exr")).unwrap().pixels, warnings)
}

fn mean(pixels: &[[f32; 3]]) -> f64 {
    pixels.iter().map(|p| (p[0] + p[1] + p[2]) as f64 / 3.0).sum::<f64>() / pixels.len() as f64
}

#[test]
fn a_model_lit_only_from_inside_keeps_the_automatic_lights_unless_told_not_to() {
    // A jack-o'-lantern without its face: the candle is shut in the pumpkin.
    let dir = tempfile::tempdir().unwrap();
    let (obj, mtl) = two_boxes([0.0; 3]);
    std::fs::write(dir.path().join("boxes.obj"), obj).unwrap();
    std::fs::write(dir.path().join("boxes.mtl"), mtl).unwrap();
    let (kept, warnings) = render_boxes(dir.path(), &[]);
    assert_eq!(
        warnings,
        ["lamplight: warning: boxes.obj: the file's own lights reach 0 % of what the camera sees (less than 25 %), so the \
          automatic lights (studio, key, fill and rim) are kept with them; --keep-auto-lights off (Python keep_auto_lights=False) \
          leaves them out"]
    );
    // The pumpkin's outside is lit (its pixels and the studio behind it).
    assert!(mean(&kept) > 0.2, "mean {}", mean(&kept));
    // `on` keeps them too, without a note; `off` is the rule before: the file's light alone, black outside.
    let (on, warnings) = render_boxes(dir.path(), &["--keep-auto-lights"]);
    assert_eq!((on == kept, warnings), (true, vec![]));
    let (off, warnings) = render_boxes(dir.path(), &["--keep-auto-lights", "off"]);
    assert_eq!(warnings, Vec::<String>::new());
    let brightest = off.iter().flatten().fold(0.0f32, |a, &b| a.max(b));
    assert!(brightest < 0.02, "the shell's outside sees only the file's ambient light: {brightest}");
    // A bad value is one line and exit code 2.
    let out = lamplight(dir.path(), &["render", "boxes.obj", "--keep-auto-lights", "maybe"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.starts_with("lamplight: error: invalid value 'maybe' for '--keep-auto-lights"), "{err}");
    assert!(err.contains("must be on, off or auto"), "{err}");
}

#[test]
fn a_model_its_own_light_reaches_keeps_that_light_alone_by_default() {
    // The lamp outside, above, right and in front: it lights the faces the camera sees.
    let dir = tempfile::tempdir().unwrap();
    let (obj, mtl) = two_boxes([2.0, 2.0, 2.0]);
    std::fs::write(dir.path().join("boxes.obj"), obj).unwrap();
    std::fs::write(dir.path().join("boxes.mtl"), mtl).unwrap();
    let (default, warnings) = render_boxes(dir.path(), &[]);
    assert_eq!(warnings, Vec::<String>::new());
    let (off, _) = render_boxes(dir.path(), &["--keep-auto-lights", "off"]);
    assert!(default == off, "the file's light alone");
    let (on, _) = render_boxes(dir.path(), &["--keep-auto-lights", "on"]);
    assert!(mean(&on) > mean(&default) + 0.05, "on adds the studio: {} vs {}", mean(&on), mean(&default));
    // A scene file states its own lights: the flag is refused there.
    let out = lamplight(dir.path(), &["render", "luxo", "--keep-auto-lights", "on"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "lamplight: error: --keep-auto-lights applies to a mesh file rendered directly (.obj, .ply, .gltf, .glb); 'luxo' is not one: \
         a scene file is lit by the lights it states\n"
    );
}
