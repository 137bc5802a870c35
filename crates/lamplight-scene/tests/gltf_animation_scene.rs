//! A glTF file named by a scene file's `[meshes]` plays its animation at the
//! scene's time in seconds (`(frame - start) / fps`): `[meshes.NAME]
//! animation` chooses the clip by name or index, `false` keeps the rest pose,
//! and a scene without `[animation]` shows the glTF at its time 0 with a
//! warning. Each frame renders as the same scene with the cube placed by
//! hand in a still glTF file (the same bytes).

use std::path::Path;

use lamplight_core::{render_image, RenderControl, RenderOptions};
use lamplight_scene::instantiate::SceneFile;

use crate::gltf_animation_choice::clips_file;

/// A scene file in `dir` placing the mesh file `file` (with `mesh_keys`),
/// lit and seen by the scene's own light and camera; `animation` is its `[animation]` table, if any.
fn scene(dir: &Path, file: &str, mesh_keys: &str, animation: &str) -> SceneFile {
    let text = format!(
        "{animation}\n[camera]\neye = [0.5, 0.3, 9]\nlook_at = [0.5, 0.3, 0]\nvfov = 46\n\
         [meshes.box]\nfile = \"{file}\"\n{mesh_keys}\n\
         [[objects]]\ntype = \"point_light\"\nposition = [2, 3, 4]\nintensity = 40\n\
         [[objects]]\ntype = \"mesh\"\nmesh = \"box\"\n"
    );
    SceneFile::parse(&dir.join("s.toml"), &text).unwrap()
}

fn render(file: &SceneFile, frame: Option<i64>) -> Vec<[f32; 3]> {
    let scene = file.build_frame(frame).unwrap().scene;
    let options = RenderOptions { width: 32, height: 24, threads: 2, ..RenderOptions::default() };
    render_image(&scene, &options, &RenderControl::default()).unwrap().0.pixels
}

const FRAMES: &str = "[animation]\nframes = [1, 49]\nfps = 24";

#[test]
fn a_gltf_in_a_scene_file_plays_the_chosen_animation_at_the_scenes_time() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("clips.gltf"), clips_file(None)).unwrap();
    let still = |name: &str, trs: &str| {
        std::fs::write(dir.path().join(name), clips_file(Some(trs))).unwrap();
        render(&scene(dir.path(), name, "", ""), None)
    };
    // Frame 13 of frames 1 to 49 at 24 fps is 0.5 s: Survey (the first) x = 0.5; Walk y = 0.5.
    let survey = scene(dir.path(), "clips.gltf", "", FRAMES);
    assert_eq!(render(&survey, Some(13)), still("survey.gltf", r#""translation": [0.5, 0, 0]"#), "the first animation");
    let walk = scene(dir.path(), "clips.gltf", "animation = \"Walk\"", FRAMES);
    assert_eq!(render(&walk, Some(13)), still("walk.gltf", r#""translation": [0, 0.5, 0]"#), "Walk by name");
    assert!(walk.build_frame(Some(13)).unwrap().warnings.is_empty());
    // `lamplight info` names the animation that plays and the file's others.
    std::fs::write(dir.path().join("s.toml"), walk.source.text.clone().unwrap()).unwrap();
    let request = lamplight_scene::request::SceneRequest::resolve(dir.path().join("s.toml").to_str().unwrap()).unwrap();
    let info = lamplight_scene::info::describe(&request).unwrap();
    let row = info.lines().find(|l| l.starts_with("gltf anim:")).unwrap_or_else(|| panic!("{info}"));
    assert_eq!(row, "gltf anim:  mesh \"box\" (clips.gltf): animations[1] \"Walk\" plays, keys to 2 s; the file has 0 \"Survey\", 1 \"Walk\", 2 \"Run\"");
    // Frame 7 is 0.25 s: Run (index 2) halfway, scale 2.
    let run = scene(dir.path(), "clips.gltf", "animation = 2", FRAMES);
    assert_eq!(render(&run, Some(7)), still("run.gltf", r#""scale": [2, 2, 2]"#), "Run by index");
    // false: the rest pose at every frame.
    let rest = still("rest.gltf", r#""translation": [0, 0, 0]"#);
    assert_eq!(render(&scene(dir.path(), "clips.gltf", "animation = false", FRAMES), Some(13)), rest, "the rest pose");
    // Without [animation]: glTF time 0 (here the rest pose), with a warning naming the key to add.
    let static_scene = scene(dir.path(), "clips.gltf", "animation = \"Walk\"", "");
    let built = static_scene.build_with_warnings().unwrap();
    assert_eq!(
        built.warnings,
        [format!(
            "{}: the scene has no [animation], so the glTF animation stands at its time 0: add [animation] (frames = [START, END], fps) \
             to play it, or give the mesh `animation = false` for the rest pose",
            dir.path().join("clips.gltf").display()
        )]
    );
    assert_eq!(render(&static_scene, None), rest);
}

#[test]
fn a_mesh_animation_the_file_lacks_is_an_error_at_the_mesh() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("clips.gltf"), clips_file(None)).unwrap();
    std::fs::write(dir.path().join("still.gltf"), clips_file(Some(r#""scale": [2, 2, 2]"#))).unwrap();
    let error = |file: &str, keys: &str| scene(dir.path(), file, keys, FRAMES).build_frame(Some(1)).unwrap_err().to_string();
    let s = dir.path().join("s.toml");
    let s = s.display();
    let has = "file \"clips.gltf\" has animations 0 \"Survey\", 1 \"Walk\", 2 \"Run\"";
    assert_eq!(
        error("clips.gltf", "animation = \"Jog\""),
        format!("{s}:9:8: frame 1: mesh \"box\": animation \"Jog\" names no animation of the file: {has}")
    );
    assert_eq!(error("clips.gltf", "animation = 3"), format!("{s}:9:8: frame 1: mesh \"box\": animation 3 is out of range: {has}"));
    assert_eq!(
        error("still.gltf", "animation = \"Walk\""),
        format!("{s}:9:8: frame 1: mesh \"box\": animation \"Walk\": file \"still.gltf\" has no animations")
    );
    assert_eq!(
        error("clips.gltf", "animation = 1.5"),
        format!(
            "{s}:10:13: frame 1: mesh \"box\": animation: expected an animation's name, its index from 0, or false for the rest pose, got a number 1.5"
        )
    );
}

/// Motion blur of a glTF's own animation in `[meshes]`: with a shutter, the
/// cube that Survey moves 1 to the right a second is smeared as the same
/// motion given by the scene's own `animate.translate` smears a still copy of
/// it (the keys are computed from different roundings of the same instants,
/// so the images agree to a fraction of a level, not to the bit).
#[test]
fn a_gltf_animation_in_a_scene_file_is_motion_blurred() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("clips.gltf"), clips_file(None)).unwrap();
    std::fs::write(dir.path().join("rest.gltf"), clips_file(Some(r#""translation": [0, 0, 0]"#))).unwrap();
    let blurred = |shutter: &str| format!("{FRAMES}\nshutter = {shutter}");
    let options = RenderOptions { width: 32, height: 24, spp: 64, threads: 2, ..RenderOptions::default() };
    let render_spp =
        |file: &SceneFile| render_image(&file.build_frame(Some(13)).unwrap().scene, &options, &RenderControl::default()).unwrap().0.pixels;
    // Frame 13 is 0.5 s; a shutter of 12 frames is half a second: x from 0.25 to 0.75.
    let played = render_spp(&scene(dir.path(), "clips.gltf", "", &blurred("[-6, 6]")));
    let by_hand = {
        let text = format!(
            "{}\n[camera]\neye = [0.5, 0.3, 9]\nlook_at = [0.5, 0.3, 0]\nvfov = 46\n\
             [meshes.box]\nfile = \"rest.gltf\"\n\
             [[objects]]\ntype = \"point_light\"\nposition = [2, 3, 4]\nintensity = 40\n\
             [[objects]]\ntype = \"mesh\"\nmesh = \"box\"\nanimate.translate = {{ seconds = [0, 1], values = [[0, 0, 0], [1, 0, 0]] }}\n",
            blurred("[-6, 6]")
        );
        render_spp(&SceneFile::parse(&dir.path().join("s.toml"), &text).unwrap())
    };
    let sharp = render_spp(&scene(dir.path(), "clips.gltf", "", FRAMES));
    let mean_difference = |a: &[[f32; 3]], b: &[[f32; 3]]| {
        a.iter().zip(b).map(|(p, q)| (0..3).map(|c| (p[c] - q[c]).abs() as f64).sum::<f64>()).sum::<f64>() / (3 * a.len()) as f64
    };
    let same = mean_difference(&played, &by_hand);
    let blur = mean_difference(&played, &sharp);
    assert!(same < 1e-4, "the played glTF and the same motion by hand differ by {same} on average");
    assert!(blur > 100.0 * same.max(1e-6), "the shutter blurs the moving cube: {blur} from the sharp frame");
    // A closed shutter is the sharp frame.
    assert_eq!(render_spp(&scene(dir.path(), "clips.gltf", "", &blurred("[0, 0]"))), sharp);
}
