//! What `lamplight render` says and does about a scene's lights (issue 27): a
//! light shut in by geometry is named, with what blocks it.

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
