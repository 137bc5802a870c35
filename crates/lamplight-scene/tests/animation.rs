//! Animated scene files (issue 29): the exact errors of `[animation]` and
//! `animate` tables, errors found in one frame's scene naming the frame, and a
//! frame's scene rendering as the static scene it describes.

use std::path::Path;

use lamplight_core::{render_image, RenderControl, RenderOptions};
use lamplight_scene::instantiate::SceneFile;

const CAMERA: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n";
const ANIMATION: &str = "[animation]\nframes = [1, 10]\n";

fn error(text: &str) -> String {
    match SceneFile::parse(Path::new("s.toml"), text).and_then(|f| f.build()) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn animated(objects: &str) -> String {
    format!("{ANIMATION}{CAMERA}[[objects]]\n{objects}")
}

#[test]
fn malformed_animations_give_their_exact_errors() {
    let cases: Vec<(String, &str)> = vec![
        (format!("[animation]\nframes = [5, 2]\n{CAMERA}"), "s.toml:2:10: animation: frames: [5, 2] must have 0 <= start <= end <= 1048574"),
        (format!("[animation]\nframes = [1.5, 3]\n{CAMERA}"), "s.toml:2:10: animation: frames: expected [start, end], two whole numbers, got an array of 2"),
        (format!("[animation]\nframes = [-1, 3]\n{CAMERA}"), "s.toml:2:10: animation: frames: [-1, 3] must have 0 <= start <= end <= 1048574"),
        (format!("{ANIMATION}fps = 0\n{CAMERA}"), "s.toml:3:7: animation: fps: must be a positive number of frames per second, at most 1000, got 0"),
        (format!("{ANIMATION}fpss = 30\n{CAMERA}"), "s.toml:3:1: animation: unknown parameter 'fpss' (did you mean 'fps'?)"),
        (format!("[animation]\nfps = 30\n{CAMERA}"), "s.toml:1:1: animation: needs `frames` ([start, end])"),
        (
            format!("{CAMERA}[[objects]]\ntype = \"sphere\"\nanimate.radius = {{ frames = [1, 2], values = [1, 2] }}\n"),
            "s.toml:7:9: sphere: animate: needs the scene's [animation] table (frames = [start, end])",
        ),
        (
            animated("type = \"sphere\"\ntranslate = [0, 1, 0]\nanimate.translate = { frames = [1, 2], values = [[0, 0, 0], [1, 0, 0]] }\n"),
            "s.toml:10:9: sphere: animate.translate: 'translate' is also given a fixed value; give it in one place",
        ),
        (
            animated("type = \"sphere\"\nanimate.radius = { frames = [1, 5, 5], values = [1, 2, 3] }\n"),
            "s.toml:9:36: sphere: animate.radius: frames[2]: must be later than frames[1] = 5, got 5",
        ),
        (
            animated("type = \"sphere\"\nanimate.radius = { frames = [1, 5], values = [1, 2, 3] }\n"),
            "s.toml:9:46: sphere: animate.radius: values: has 3 values for 2 frames, expected one per key",
        ),
        (
            animated("type = \"sphere\"\nanimate.radius = { frames = [], values = [] }\n"),
            "s.toml:9:29: sphere: animate.radius: frames: has 0 keys, expected 1 to 100000",
        ),
        (
            animated("type = \"sphere\"\nanimate.radius = { frames = [1, 2], values = [1, 2], interpolation = \"cubic\" }\n"),
            "s.toml:9:70: sphere: animate.radius: interpolation: unknown value \"cubic\" (values: linear, step, cubicspline)",
        ),
        (
            animated("type = \"sphere\"\nanimate.radius = { frames = [1, 2], values = [1, 2], in_tangents = [0, 0] }\n"),
            "s.toml:9:54: sphere: animate.radius: 'in_tangents' has no effect with the other parameters given",
        ),
        (
            animated("type = \"sphere\"\nanimate.radius = { frames = [1, 2], seconds = [0, 1], values = [1, 2] }\n"),
            "s.toml:9:18: sphere: animate.radius: takes either frames or seconds, not both",
        ),
        (
            animated("type = \"sphere\"\nanimate.radius = { values = [1, 2] }\n"),
            "s.toml:9:18: sphere: animate.radius: needs `frames` or `seconds` (the keys' times)",
        ),
        (
            animated("type = \"sphere\"\nanimate.center = { frames = [1, 2], values = [[0, 0, 0], 1] }\n"),
            "s.toml:9:58: sphere: animate.center: values[1]: expected [x, y, z], as values[0], got a number 1",
        ),
        (
            animated("type = \"sphere\"\nanimate.rotate = { frames = [1, 2], values = [[0, 0, 0], \"left\"] }\n"),
            "s.toml:9:58: sphere: animate.rotate: values[1]: expected a table { axis = [x, y, z], degrees = N }, { x = N, y = N, z = N } or { quaternion = [x, y, z, w] }, or [x, y, z] degrees, got a string \"left\"",
        ),
        (
            animated("type = \"sphere\"\nanimate.radius = { frames = [1, 2], values = [1, 2], interpolation = \"cubicspline\", out_tangents = [0, [1, 2, 3]] }\n"),
            "s.toml:9:104: sphere: animate.radius: out_tangents: expected a number for each key, got an array of 3",
        ),
        (
            animated("type = \"group\"\nanimate.matrix = { frames = [1], values = [1] }\n"),
            "s.toml:9:9: group: animate.matrix: a matrix cannot be animated; animate translate, rotate and scale",
        ),
        (animated("type = \"sphere\"\nanimate = 3\n"), "s.toml:9:11: sphere: animate: expected a table of animated keys, such as animate.translate = { frames = [...], values = [...] }, got a number 3"),
        (
            animated("type = \"sphere\"\nanimate.radious = { frames = [1], values = [1] }\n"),
            "s.toml:9:9: frame 1: sphere: unknown parameter 'radious' (did you mean 'radius'?)",
        ),
    ];
    let wrong: Vec<String> = cases
        .iter()
        .filter(|(text, expected)| error(text) != *expected)
        .map(|(text, _)| format!("{text}\n  gives: {}", error(text)))
        .collect();
    assert!(wrong.is_empty(), "{}", wrong.join("\n\n"));
}

#[test]
fn an_error_in_one_frame_names_the_frame() {
    // The radius passes through 0 at frame 5: frames 1 to 4 build, frame 5 does not.
    let text = animated("type = \"sphere\"\ncenter = [0, 0, 0]\nanimate.radius = { frames = [1, 9], values = [1, -1] }\n");
    let file = SceneFile::parse(Path::new("s.toml"), &text).unwrap();
    assert!(file.build_frame(Some(4)).is_ok());
    assert_eq!(
        file.build_frame(Some(5)).unwrap_err().to_string(),
        "s.toml:10:9: frame 5: sphere: invalid radius: must be a positive number, got 0"
    );
}

fn render(file: &SceneFile, frame: Option<i64>) -> Vec<[f32; 3]> {
    let scene = file.build_frame(frame).unwrap().scene;
    let options = RenderOptions { width: 48, height: 32, threads: 2, ..RenderOptions::default() };
    render_image(&scene, &options, &RenderControl::default()).unwrap().0.pixels
}

#[test]
fn a_frame_renders_as_the_static_scene_it_describes() {
    let light = "[[objects]]\ntype = \"point_light\"\nposition = [2, 4, 5]\nintensity = 30\n";
    let moving = format!(
        "{ANIMATION}{CAMERA}{light}[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 0.5\n\
         animate.translate = {{ frames = [1, 9], values = [[-2, 0, 0], [2, 0, 0]] }}\n"
    );
    let moving = SceneFile::parse(Path::new("s.toml"), &moving).unwrap();
    // Frame 3 is a quarter of the way: x = -1.
    let fixed = format!("{CAMERA}{light}[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 0.5\ntranslate = [-1, 0, 0]\n");
    let fixed = SceneFile::parse(Path::new("s.toml"), &fixed).unwrap();
    assert_eq!(render(&moving, Some(3)), render(&fixed, None));
    assert_ne!(render(&moving, Some(3)), render(&moving, Some(4)), "the sphere moves");
    // Without a frame: the first one.
    assert_eq!(render(&moving, None), render(&moving, Some(1)));
    // A static scene is the same at every frame.
    assert_eq!(render(&fixed, Some(7)), render(&fixed, None));
}
