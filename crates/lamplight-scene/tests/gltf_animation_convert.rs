//! `lamplight convert` of an animated glTF file: the TOML gets `[animation]`
//! (frames 0 to the animation's last key at 24 fps) and its `[meshes]` entry
//! plays the file's animation at the scene's time, so each frame of the
//! converted scene renders to the bytes of the file's own frame: Khronos'
//! BoxAnimated and the InterpolationTest-like file of `gltf_animation.rs`, at
//! frames 0, 15, 45 and 89 (89 past the latter's last key: the end values hold).

use std::path::Path;

use lamplight_core::RenderControl;
use lamplight_scene::request::{Naming, Request, SceneRequest};

use crate::gltf_animation::{box_animated, interpolation_test};

/// The sRGB bytes of frame `frame` of `path` at 24 x 16 by `integrator`.
fn render(path: &Path, frame: i64, integrator: &str, spp: u32) -> Vec<u8> {
    crate::convert::render_frame(path, Some(frame), integrator, spp)
}

fn assert_frames_match(input: &Path, output: &Path, frames: &str) {
    let converted = lamplight_scene::convert::convert(input, output, &[]).unwrap();
    std::fs::write(output, &converted.toml).unwrap();
    assert!(converted.toml.contains(frames), "{}", converted.toml);
    for frame in [0, 15, 45, 89] {
        let (a, b) = (render(input, frame, "whitted", 1), render(output, frame, "whitted", 1));
        assert!(a == b, "{}: frame {frame} of the file and of its conversion differ", input.display());
    }
    let (a, b) = (render(input, 45, "path", 2), render(output, 45, "path", 2));
    assert!(a == b, "{}: the path tracer's frame 45 differs", input.display());
    assert!(render(output, 0, "whitted", 1) != render(output, 45, "whitted", 1), "the converted scene moves");
}

#[test]
fn box_animated_converts_to_the_same_frames() {
    let dir = tempfile::tempdir().unwrap();
    assert_frames_match(&box_animated(), &dir.path().join("box.toml"), "animation = { frames = [0, 89], fps = 24 }\n");
}

#[test]
fn the_interpolation_file_converts_to_the_same_frames() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("interpolation.gltf");
    std::fs::write(&input, interpolation_test()).unwrap();
    assert_frames_match(&input, &dir.path().join("interpolation.toml"), "animation = { frames = [0, 48], fps = 24 }\n");
}

#[test]
fn a_chosen_animation_converts_to_the_same_frames() {
    use lamplight_scene::request::AnimationChoice;
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("clips.gltf");
    std::fs::write(&input, crate::gltf_animation_choice::clips_file(None)).unwrap();
    let output = dir.path().join("walk.toml");
    let walk = AnimationChoice::Name("Walk".into());
    let converted = lamplight_scene::convert::convert_with(&input, &output, &[], Some(&walk)).unwrap();
    std::fs::write(&output, &converted.toml).unwrap();
    assert!(converted.toml.contains("animation = { frames = [0, 48], fps = 24 }\n"), "{}", converted.toml);
    assert!(converted.toml.contains("animation = 1\n"), "the mesh plays Walk: {}", converted.toml);
    assert!(converted.warnings.is_empty(), "{:?}", converted.warnings);
    let direct = SceneRequest::resolve(input.to_str().unwrap()).unwrap().with_animation(Some(&walk), Naming::Flags).unwrap();
    let toml = SceneRequest::resolve(output.to_str().unwrap()).unwrap();
    let job = Request { width: Some(24), height: Some(16), spp: Some(1), threads: Some(2), ..Request::default() }
        .resolve(&toml.defaults, Naming::Flags)
        .unwrap();
    for frame in [0, 15, 45] {
        let render =
            |r: &SceneRequest| job.run(&r.build_frame(Some(frame)).unwrap().scene, &RenderControl::default()).unwrap().image.to_srgb8();
        assert!(render(&direct) == render(&toml), "frame {frame} of Walk and of its conversion differ");
    }
    let jog = AnimationChoice::Name("Jog".into());
    assert_eq!(
        lamplight_scene::convert::convert_with(&input, &output, &[], Some(&jog)).unwrap_err().to_string(),
        format!(
            "{}: --animation \"Jog\" names no animation of the file: it has animations 0 \"Survey\", 1 \"Walk\", 2 \"Run\"",
            input.display()
        )
    );
}

/// A part its animation scales to nothing keeps its `part = i`: the converted
/// scene leaves it out of the frames where the file's own render does.
#[test]
fn a_part_scaled_to_nothing_converts_to_the_same_frames() {
    let dir = tempfile::tempdir().unwrap();
    let mut b = crate::gltf_animation::Builder::default();
    b.cube();
    let times = b.floats(&[0.0, 1.0], "SCALAR");
    let shrinks = b.floats(&[1.0, 1.0, 1.0, 0.0, 0.0, 0.0], "VEC3");
    let animation = format!(
        r#"{{"samplers": [{{"input": {times}, "output": {shrinks}}}], "channels": [{{"sampler": 0, "target": {{"node": 0, "path": "scale"}}}}]}}"#
    );
    let input = dir.path().join("shrink.gltf");
    // Node 0 (part 0) shrinks away by 1 s (frame 24); node 1 (part 1) stands beside it.
    std::fs::write(&input, b.json("0, 1", r#"{"mesh": 0}, {"mesh": 0, "translation": [2, 0, 0]}"#, &animation, "")).unwrap();
    let output = dir.path().join("shrink.toml");
    let converted = lamplight_scene::convert::convert(&input, &output, &[]).unwrap();
    std::fs::write(&output, &converted.toml).unwrap();
    assert!(converted.toml.contains("part = 1"), "{}", converted.toml);
    for frame in [0, 12, 24] {
        let (a, b) = (render(&input, frame, "whitted", 1), render(&output, frame, "whitted", 1));
        assert!(a == b, "frame {frame} of the file and of its conversion differ");
    }
    let toml = SceneRequest::resolve(output.to_str().unwrap()).unwrap();
    assert_eq!(toml.build_frame(Some(24)).unwrap().scene.objects.len(), 1, "part 0 is gone at frame 24");
}
