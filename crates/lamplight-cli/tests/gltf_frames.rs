//! `lamplight render model.gltf --frames` plays a glTF file's animation (issue
//! 29): Khronos' BoxAnimated (the scene crate's test data, CC BY 4.0), its
//! frame range taken from the animation when `-o` numbers frames without
//! `--frames`, and a frame the same bytes alone and within a sequence;
//! `--animation` choosing another animation by name or index.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn box_animated() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../lamplight-scene/tests/data/gltf/BoxAnimated/BoxAnimated.gltf")
}

fn ok(dir: &Path, args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_lamplight")).args(args).current_dir(dir).stdin(Stdio::null()).output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn a_gltf_animation_renders_frame_by_frame() {
    let dir = tempfile::tempdir().unwrap();
    let model = box_animated();
    let model = model.to_str().unwrap();
    let small = ["--width", "24", "--height", "16", "--spp", "1"];
    let run = |extra: &[&str]| ok(dir.path(), &[&["render", model], &small[..], extra].concat());
    run(&["--frames", "44-46", "-o", "seq/f_####.png"]);
    run(&["--frames", "45", "-o", "alone.png"]);
    let read = |name: &str| fs::read(dir.path().join(name)).unwrap();
    assert_eq!(read("seq/f_0045.png"), read("alone.png"), "the same bytes alone and in a sequence");
    assert_ne!(read("seq/f_0044.png"), read("seq/f_0046.png"), "the box turns between frames 44 and 46");
    // `lamplight info` gives the range `-o` with a run of # takes without --frames.
    let info = ok(dir.path(), &["info", model]);
    assert!(info.contains("animation:  frames 0 to 89 (90 frames at 24 fps;"), "{info}");
}

/// BoxAnimated with its animation named "Whole" and a second one, "Turn", of
/// its rotation channel alone (keys 1.25 to 2.5 s: frames 0 to 60).
fn two_clips(dir: &Path) -> PathBuf {
    let mut json: serde_json::Value = serde_json::from_slice(&fs::read(box_animated()).unwrap()).unwrap();
    let animations = json["animations"].as_array_mut().unwrap();
    animations[0]["name"] = "Whole".into();
    let mut turn = animations[0].clone();
    turn["name"] = "Turn".into();
    turn["channels"].as_array_mut().unwrap().truncate(1);
    animations.push(turn);
    let path = dir.join("clips.gltf");
    fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
    path
}

#[test]
fn animation_chooses_which_animation_plays() {
    let dir = tempfile::tempdir().unwrap();
    let model = two_clips(dir.path());
    let model = model.to_str().unwrap();
    let small = ["--width", "16", "--height", "12", "--spp", "1"];
    let run = |extra: &[&str]| ok(dir.path(), &[&["render", model], &small[..], extra].concat());
    // The frames follow the chosen animation: -o with a run of # renders Turn's 0 to 60.
    run(&["--animation", "Turn", "-o", "turn/####.png"]);
    assert!(dir.path().join("turn/0060.png").exists() && !dir.path().join("turn/0061.png").exists());
    run(&["--animation", "1", "--frames", "45", "-o", "one.png"]);
    run(&["--frames", "45", "-o", "whole.png"]);
    let read = |name: &str| fs::read(dir.path().join(name)).unwrap();
    assert_eq!(read("turn/0045.png"), read("one.png"), "by name and by index, the same animation");
    assert_ne!(read("whole.png"), read("one.png"), "the first animation also lifts the box");
    let info = ok(dir.path(), &["info", model, "--animation", "Turn"]);
    assert!(info.contains("animation:  frames 0 to 60 (61 frames at 24 fps; animations[1] \"Turn\" plays,"), "{info}");
    assert!(info.contains("animations: 2\n  0 \"Whole\", 3.7083 s\n  1 \"Turn\", 2.5 s  (plays)\n"), "{info}");
    // A name or index the file lacks: one line, exit code 2, listing the file's animations.
    for (choice, problem) in [("Jog", "\"Jog\" names no animation of the file"), ("2", "2 is out of range")] {
        let out = Command::new(env!("CARGO_BIN_EXE_lamplight"))
            .args(["render", model, "--animation", choice])
            .current_dir(dir.path())
            .stdin(Stdio::null())
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2));
        assert_eq!(
            String::from_utf8(out.stderr).unwrap(),
            format!("lamplight: error: {model}: --animation {problem}: it has animations 0 \"Whole\", 1 \"Turn\"\n")
        );
    }
}
