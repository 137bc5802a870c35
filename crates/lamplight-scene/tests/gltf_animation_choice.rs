//! Choosing which animation of a glTF file plays (`--animation Walk`,
//! `--animation 2`, Python `animation=`): the frames follow the chosen
//! animation, a frame renders as the cube placed by hand at that animation's
//! value, `lamplight info` lists every animation, and a name or index the file
//! lacks is one error listing the file's animations.

use std::path::Path;

use lamplight_core::{render_image, RenderControl, RenderOptions};
use lamplight_scene::request::{AnimationChoice, Naming, SceneRequest};

use crate::gltf_animation::Builder;

/// A cube with a camera and a light; without `still`, three animations of the
/// cube: 0 "Survey" (x 0 to 1 in 1 s), 1 "Walk" (y 0 to 2 in 2 s), 2 "Run"
/// (scale 1 to 3 in 0.5 s). `still` places the cube by hand instead (no animations).
pub(crate) fn clips_file(still: Option<&str>) -> String {
    let mut b = Builder::default();
    b.cube();
    let t01 = b.floats(&[0.0, 1.0], "SCALAR");
    let t02 = b.floats(&[0.0, 2.0], "SCALAR");
    let t005 = b.floats(&[0.0, 0.5], "SCALAR");
    let right = b.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0], "VEC3");
    let up = b.floats(&[0.0, 0.0, 0.0, 0.0, 2.0, 0.0], "VEC3");
    let grows = b.floats(&[1.0, 1.0, 1.0, 3.0, 3.0, 3.0], "VEC3");
    let cube = still.map_or(r#"{"mesh": 0}"#.to_string(), |trs| format!(r#"{{"mesh": 0, {trs}}}"#));
    let nodes = format!(
        r#"{cube}, {{"camera": 0, "translation": [0.5, 0.3, 9]}}, {{"extensions": {{"KHR_lights_punctual": {{"light": 0}}}}, "translation": [2, 3, 4]}}"#
    );
    let clip = |name: &str, input: usize, output: usize, path: &str| {
        format!(
            r#"{{"name": "{name}", "samplers": [{{"input": {input}, "output": {output}}}], "channels": [{{"sampler": 0, "target": {{"node": 0, "path": "{path}"}}}}]}}"#
        )
    };
    let animations = match still {
        Some(_) => String::new(),
        None => [clip("Survey", t01, right, "translation"), clip("Walk", t02, up, "translation"), clip("Run", t005, grows, "scale")]
            .join(",\n  "),
    };
    let extra = r#", "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 40}]}}"#;
    b.json("0, 1, 2", &nodes, &animations, extra)
}

fn choose(path: &Path, choice: &str, naming: Naming) -> Result<SceneRequest, String> {
    let choice: AnimationChoice = choice.parse().unwrap();
    SceneRequest::resolve(path.to_str().unwrap()).unwrap().with_animation(Some(&choice), naming).map_err(|e| e.0)
}

fn render(request: &SceneRequest, frame: Option<i64>) -> Vec<[f32; 3]> {
    let scene = request.build_frame(frame).unwrap().scene;
    let options = RenderOptions { width: 32, height: 24, threads: 2, ..RenderOptions::default() };
    render_image(&scene, &options, &RenderControl::default()).unwrap().0.pixels
}

#[test]
fn a_chosen_animation_plays_with_its_own_frames() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("clips.gltf");
    std::fs::write(&path, clips_file(None)).unwrap();
    let first = SceneRequest::resolve(path.to_str().unwrap()).unwrap();
    let range = |r: &SceneRequest| r.animation().map(|a| (a.start, a.end, a.fps));
    assert_eq!(range(&first), Some((0, 24, 24.0)), "the first animation: 1 s");
    let walk = choose(&path, "Walk", Naming::Flags).unwrap();
    assert_eq!(range(&walk), Some((0, 48, 24.0)), "Walk: 2 s");
    let run = choose(&path, "2", Naming::Flags).unwrap();
    assert_eq!(range(&run), Some((0, 12, 24.0)), "animations[2], Run: 0.5 s");
    // Frame 12 of Walk (0.5 s, a quarter of the way): y = 0.5; frame 6 of Run (0.25 s, halfway): scale 2.
    let still = |trs: &str, name: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, clips_file(Some(trs))).unwrap();
        SceneRequest::resolve(p.to_str().unwrap()).unwrap()
    };
    assert_eq!(render(&walk, Some(12)), render(&still(r#""translation": [0, 0.5, 0]"#, "walk.gltf"), None), "Walk at frame 12");
    assert_eq!(render(&run, Some(6)), render(&still(r#""scale": [2, 2, 2]"#, "run.gltf"), None), "Run at frame 6");
    assert_eq!(render(&first, Some(12)), render(&still(r#""translation": [0.5, 0, 0]"#, "survey.gltf"), None), "Survey at frame 12");
    // A file with several animations and none chosen says so; a chosen one is not warned about.
    let note = format!(
        "{}: glTF file has 3 animations: the first plays unless --animation (Python animation=) chooses another; lamplight info lists them",
        path.display()
    );
    assert_eq!(first.build_frame(None).unwrap().warnings, [note]);
    assert!(walk.build_frame(None).unwrap().warnings.is_empty());
}

#[test]
fn info_lists_every_animation_and_marks_the_one_playing() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("clips.gltf");
    std::fs::write(&path, clips_file(None)).unwrap();
    let text = lamplight_scene::info::describe(&choose(&path, "Walk", Naming::Flags).unwrap()).unwrap();
    let rows: Vec<&str> = text.lines().skip_while(|l| !l.starts_with("animation:")).take(7).collect();
    assert_eq!(
        rows,
        [
            "animation:  frames 0 to 48 (49 frames at 24 fps; animations[1] \"Walk\" plays, keys from 0 to 2 s; described at frame 0)",
            "animations: 3",
            "  0 \"Survey\", 1 s",
            "  1 \"Walk\", 2 s  (plays)",
            "  2 \"Run\", 0.5 s",
            "animated:   1 channel of 1 node",
            "  nodes[0]: translation (linear, 2 keys at 0 to 2 s)",
        ]
    );
}

#[test]
fn a_name_or_index_the_file_lacks_is_one_error_listing_its_animations() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("clips.gltf");
    std::fs::write(&path, clips_file(None)).unwrap();
    let p = path.display();
    let has = "it has animations 0 \"Survey\", 1 \"Walk\", 2 \"Run\"";
    assert_eq!(choose(&path, "Jog", Naming::Flags).unwrap_err(), format!("{p}: --animation \"Jog\" names no animation of the file: {has}"));
    assert_eq!(choose(&path, "3", Naming::Flags).unwrap_err(), format!("{p}: --animation 3 is out of range: {has}"));
    assert_eq!(
        choose(&path, "walk", Naming::Keywords).unwrap_err(),
        format!("{p}: animation \"walk\" names no animation of the file: {has}")
    );
    // A glTF file without animations.
    let still = dir.path().join("still.gltf");
    std::fs::write(&still, clips_file(Some(r#""scale": [2, 2, 2]"#))).unwrap();
    assert_eq!(choose(&still, "0", Naming::Flags).unwrap_err(), format!("{}: --animation 0: the file has no animations", still.display()));
    // Other files.
    let obj = dir.path().join("m.obj");
    std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    assert_eq!(
        choose(&obj, "Walk", Naming::Flags).unwrap_err(),
        format!("{}: --animation applies to a glTF file (.gltf, .glb); this file has no animations", obj.display())
    );
    let toml = dir.path().join("s.toml");
    std::fs::write(&toml, "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[[objects]]\ntype = \"sphere\"\n").unwrap();
    assert_eq!(
        choose(&toml, "Walk", Naming::Keywords).unwrap_err(),
        "animation applies to a glTF file rendered directly (.gltf, .glb); 's' is a scene file: give its glTF mesh \
         `animation = \"Walk\"` in [meshes.NAME]"
    );
    assert_eq!(
        SceneRequest::resolve("luxo").unwrap().with_animation(Some(&AnimationChoice::Index(1)), Naming::Flags).unwrap_err().0,
        "--animation applies to a glTF file rendered directly (.gltf, .glb); 'luxo' is a built-in scene"
    );
}
