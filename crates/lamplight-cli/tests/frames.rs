//! `lamplight render SCENE --frames A-B -o out/frame_####.png` (issue 29): a
//! frame is the same bytes alone and within a sequence; frames whose file
//! exists are skipped (said once) unless `--overwrite`; bad ranges and
//! patterns are one line with exit code 2; `lamplight info` lists the animation.

use std::fs;
use std::path::Path;
use std::process::{Command, Output, Stdio};

fn lamplight(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lamplight")).args(args).current_dir(dir).stdin(Stdio::null()).output().expect("the binary runs")
}

fn ok(dir: &Path, args: &[&str]) -> String {
    let out = lamplight(dir, args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stderr).unwrap()
}

fn usage_error(dir: &Path, args: &[&str]) -> String {
    let out = lamplight(dir, args);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "one line: {err}");
    err.trim_end().to_string()
}

/// A sphere that crosses the view over frames 1 to 5, under a light that dims.
const MOVING: &str = "[animation]\nframes = [1, 5]\nfps = 12\n\
    [render]\nwidth = 24\nheight = 16\nspp = 1\n\
    [camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n\
    [[objects]]\ntype = \"point_light\"\nposition = [2, 4, 5]\n\
    animate.intensity = { frames = [1, 5], values = [40, 10] }\n\
    [[objects]]\ntype = \"group\"\nname = \"ball\"\n\
    animate.translate = { frames = [1, 5], values = [[-1.5, 0, 0], [1.5, 0, 0]], interpolation = \"cubicspline\" }\n\
    children = [{ type = \"sphere\", center = [0, 0, 0], radius = 0.6 }]\n";

const STILL: &str = "[render]\nwidth = 16\nheight = 8\nspp = 1\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n\
    [[objects]]\ntype = \"point_light\"\nposition = [2, 4, 5]\nintensity = 30\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n";

fn scene(dir: &Path) {
    fs::write(dir.join("moving.toml"), MOVING).unwrap();
    fs::write(dir.join("still.toml"), STILL).unwrap();
}

#[test]
fn a_frame_is_the_same_bytes_alone_and_in_a_sequence() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    scene(d);
    ok(d, &["render", "moving.toml", "--frames", "1-5", "-o", "seq/f_##.png", "-q"]);
    let names: Vec<String> = {
        let mut n: Vec<String> = fs::read_dir(d.join("seq")).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
        n.sort();
        n
    };
    assert_eq!(names, ["f_01.png", "f_02.png", "f_03.png", "f_04.png", "f_05.png"]);
    ok(d, &["render", "moving.toml", "--frames", "3", "-o", "alone.png", "-q"]);
    let alone = fs::read(d.join("alone.png")).unwrap();
    assert_eq!(alone, fs::read(d.join("seq/f_03.png")).unwrap(), "frame 3 alone and in the sequence");
    assert_ne!(alone, fs::read(d.join("seq/f_02.png")).unwrap(), "the frames differ");
    // Without --frames an animated scene renders its first frame.
    ok(d, &["render", "moving.toml", "-o", "first.png", "-q"]);
    assert_eq!(fs::read(d.join("first.png")).unwrap(), fs::read(d.join("seq/f_01.png")).unwrap());
    // With a pattern and no --frames: the scene's own range.
    ok(d, &["render", "moving.toml", "-o", "all/####.png", "-q"]);
    assert_eq!(fs::read(d.join("all/0005.png")).unwrap(), fs::read(d.join("seq/f_05.png")).unwrap());
    assert!(!d.join("all/0006.png").exists() && !d.join("all/0000.png").exists());
}

#[test]
fn existing_frames_are_skipped_unless_overwrite() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    scene(d);
    ok(d, &["render", "moving.toml", "--frames", "2-3", "-o", "out/f_####.png", "-q"]);
    let third = fs::read(d.join("out/f_0003.png")).unwrap();
    fs::write(d.join("out/f_0003.png"), b"stale").unwrap();
    let said = ok(d, &["render", "moving.toml", "--frames", "1-4", "-o", "out/f_####.png", "-q"]);
    assert_eq!(said, "lamplight: skipping 2 of 4 frames whose files exist (such as out/f_0002.png); --overwrite renders them again\n");
    assert_eq!(fs::read(d.join("out/f_0003.png")).unwrap(), b"stale", "a skipped frame is left as it is");
    assert!(d.join("out/f_0001.png").exists() && d.join("out/f_0004.png").exists());
    let said = ok(d, &["render", "moving.toml", "--frames", "1-4", "-o", "out/f_####.png", "-q", "--overwrite"]);
    assert_eq!(said, "");
    assert_eq!(fs::read(d.join("out/f_0003.png")).unwrap(), third);
    // Everything written: nothing to do, said once.
    let said = ok(d, &["render", "moving.toml", "--frames", "1-4", "-o", "out/f_####.png", "-q"]);
    assert_eq!(said, "lamplight: skipping 4 of 4 frames whose files exist (such as out/f_0001.png); --overwrite renders them again\n");
    let leftovers: Vec<_> =
        fs::read_dir(d.join("out")).unwrap().map(|e| e.unwrap().file_name()).filter(|n| !n.to_string_lossy().ends_with(".png")).collect();
    assert!(leftovers.is_empty(), "no temporary files: {leftovers:?}");
}

#[test]
fn a_scene_without_animation_is_the_same_at_every_frame() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    scene(d);
    ok(d, &["render", "still.toml", "--frames", "4-6", "-o", "s_#.png", "-q"]);
    ok(d, &["render", "still.toml", "-o", "plain.png", "-q"]);
    let plain = fs::read(d.join("plain.png")).unwrap();
    for f in ["s_4.png", "s_5.png", "s_6.png"] {
        assert_eq!(fs::read(d.join(f)).unwrap(), plain, "{f}");
    }
}

#[test]
fn bad_ranges_and_patterns_are_one_line_with_exit_code_2() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    scene(d);
    let cases: &[(&[&str], &str)] = &[
        (&["--frames", "5-1", "-o", "f_#.png"], "lamplight: error: --frames \"5-1\" ends before it starts (expected START <= END)"),
        (&["--frames", "x", "-o", "f_#.png"], "lamplight: error: --frames must be a frame number or a range START-END such as 1-120, got \"x\""),
        (&["--frames", "1-2000000", "-o", "f_#.png"], "lamplight: error: --frames must be frame numbers from 0 to 1048574, got \"1-2000000\""),
        (
            &["--frames", "1-3", "-o", "f.png"],
            "lamplight: error: --frames 1-3 renders 3 frames: -o f.png must hold a run of # for the frame number, such as frame_####.png",
        ),
        (
            &["--frames", "1-3", "-o", "f_#_#.png"],
            "lamplight: error: -o f_#_#.png has more than one run of #, expected one for the frame number (frame_####.png)",
        ),
        (&["-o", "f.png", "--overwrite"], "lamplight: error: --overwrite applies to frame sequences (--frames, or -o with a run of # in an animated scene)"),
        (
            &["--frames", "1-2", "-o", "f_#.exr", "--variance-output", "v.exr"],
            "lamplight: error: --variance-output writes one file; for a frame sequence put the variance in each frame's .exr (--exr-layers variance)",
        ),
    ];
    for (args, expected) in cases {
        let mut all = vec!["render", "moving.toml"];
        all.extend_from_slice(args);
        assert_eq!(usage_error(d, &all), *expected, "{args:?}");
    }
    assert_eq!(
        usage_error(d, &["render", "still.toml", "-o", "f_##.png"]),
        "lamplight: error: -o f_##.png numbers frames (#), but 'still' has no [animation] to give them; say which with --frames"
    );
    assert!(fs::read_dir(d).unwrap().all(|e| e.unwrap().path().extension().is_some_and(|x| x == "toml")), "nothing was written");
}

#[test]
fn info_lists_the_range_and_what_is_animated() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    scene(d);
    let out = lamplight(d, &["info", "moving.toml"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    let from = text.find("animation:").expect("an animation row");
    assert_eq!(
        &text[from..],
        "animation:  frames 1 to 5 (5 frames at 12 fps, 0.4167 s; described at frame 1)\n\
         animated:   2 keys of 2 nodes\n  \
           objects[0] (point_light): intensity (linear, 2 keys at frames 1 to 5)\n  \
           objects[1] (group \"ball\"): translate (cubicspline, 2 keys at frames 1 to 5)\n\
         warnings:   none\n"
    );
}

/// Ctrl-C during a sequence: exit code 130, the frames before the interrupted
/// one whole, no file for it or after it, no temporary file; the same command
/// again renders only what is missing, and every frame is then the bytes of an
/// uninterrupted run.
#[cfg(unix)]
#[test]
fn an_interrupted_sequence_resumes_where_it_stopped() {
    let reference = tempfile::tempdir().unwrap();
    scene(reference.path());
    let args = ["render", "moving.toml", "--frames", "1-5", "--width", "240", "--height", "160", "--spp", "16", "-o", "f_#.png", "-q"];
    ok(reference.path(), &args);
    let mut interrupted = 0;
    for delay_ms in [100u64, 300, 500, 700] {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        scene(d);
        let child = Command::new(env!("CARGO_BIN_EXE_lamplight"))
            .args(args)
            .current_dir(d)
            .stdin(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(delay_ms));
        // Fails harmlessly when the sequence has already ended.
        let _ = Command::new("kill").args(["-INT", &child.id().to_string()]).stderr(Stdio::null()).status();
        let out = child.wait_with_output().unwrap();
        let mut written: Vec<String> =
            fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).filter(|n| !n.ends_with(".toml")).collect();
        written.sort();
        let prefix: Vec<String> = (1..=written.len()).map(|f| format!("f_{f}.png")).collect();
        assert_eq!(written, prefix, "after {delay_ms} ms: the frames before the interrupted one, nothing else");
        if !out.status.success() {
            assert_eq!(out.status.code(), Some(130), "after {delay_ms} ms");
            interrupted += 1;
        }
        ok(d, &args);
        for f in 1..=5 {
            let name = format!("f_{f}.png");
            assert_eq!(fs::read(d.join(&name)).unwrap(), fs::read(reference.path().join(&name)).unwrap(), "after {delay_ms} ms: {name}");
        }
    }
    assert!(interrupted > 0, "no sequence lasted 100 ms: the signal was never handled");
}

/// `[animation] shutter`: `info` says the shutter, and a frame rendered with
/// it is blurred (differs from the frame without), the same bytes alone and in
/// a sequence, while a closed shutter gives the unblurred frame's bytes.
#[test]
fn a_shutter_blurs_frames_and_info_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    scene(d);
    let with = |shutter: &str| MOVING.replace("fps = 12\n", &format!("fps = 12\nshutter = {shutter}\n")).replace("spp = 1\n", "spp = 16\n");
    fs::write(d.join("blurred.toml"), with("[-0.5, 0.5]")).unwrap();
    fs::write(d.join("closed.toml"), with("[0, 0]")).unwrap();
    fs::write(d.join("sharp.toml"), MOVING.replace("spp = 1\n", "spp = 16\n")).unwrap();
    let out = lamplight(d, &["info", "blurred.toml"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("\nshutter:    [-0.5, 0.5] frames around each frame: moving shapes are motion-blurred\n"), "{text}");
    assert!(!String::from_utf8(lamplight(d, &["info", "closed.toml"]).stdout).unwrap().contains("shutter:"));
    ok(d, &["render", "blurred.toml", "--frames", "2-3", "-o", "b_#.png", "-q"]);
    ok(d, &["render", "blurred.toml", "--frames", "3", "-o", "b_alone.png", "-q"]);
    ok(d, &["render", "closed.toml", "--frames", "3", "-o", "c.png", "-q"]);
    ok(d, &["render", "sharp.toml", "--frames", "3", "-o", "s.png", "-q"]);
    let read = |n: &str| fs::read(d.join(n)).unwrap();
    assert_eq!(read("b_alone.png"), read("b_3.png"), "a blurred frame alone and in a sequence");
    assert_eq!(read("c.png"), read("s.png"), "a closed shutter is the frame without blur");
    assert_ne!(read("b_3.png"), read("s.png"), "an open shutter blurs the moving ball");
}
