//! `lamplight render model.gltf --frames` plays a glTF file's animation (issue
//! 29): Khronos' BoxAnimated (the scene crate's test data, CC BY 4.0), its
//! frame range taken from the animation when `-o` numbers frames without
//! `--frames`, and a frame the same bytes alone and within a sequence.

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
