//! `lamplight render SCENE --frames A-B -o out/f_####.png --video out.mp4`
//! (issue 29): the frames are encoded by ffmpeg into a video with one picture
//! per frame at the scene's fps (counted by ffprobe); without ffmpeg, one
//! line, exit code 2, and the frames kept; a bad request is refused before
//! anything renders.
//!
//! ffmpeg comes from Debian's package (`scripts/test.sh` installs it): where it
//! is missing the encoding tests skip, saying so, except under CI, where they fail.

use std::fs;
use std::path::Path;
use std::process::{Command, Output, Stdio};

/// Four frames of a sphere crossing the view, at 12 fps; 24x16, so that the
/// H.264 and VP9 encoders need no padding, and 23x15 for the padding.
const MOVING: &str = "[animation]\nframes = [1, 4]\nfps = 12\n\
    [render]\nwidth = 24\nheight = 16\nspp = 1\n\
    [camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n\
    [[objects]]\ntype = \"point_light\"\nposition = [2, 4, 5]\nintensity = 30\n\
    [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 0.6\n\
    animate.translate = { frames = [1, 4], values = [[-1.5, 0, 0], [1.5, 0, 0]] }\n";

fn lamplight(dir: &Path, args: &[&str], path: Option<&Path>) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_lamplight"));
    command.args(args).current_dir(dir).stdin(Stdio::null());
    if let Some(p) = path {
        command.env("PATH", p);
    }
    command.output().expect("the binary runs")
}

/// Whether ffmpeg and ffprobe run; under CI they must.
fn have_ffmpeg() -> bool {
    let runs = |p: &str| Command::new(p).arg("-version").stdout(Stdio::null()).stderr(Stdio::null()).status().is_ok_and(|s| s.success());
    let have = runs("ffmpeg") && runs("ffprobe");
    if !have {
        assert!(std::env::var_os("CI").is_none(), "CI must have ffmpeg and ffprobe (scripts/test.sh installs Debian's ffmpeg)");
        eprintln!("skipped: ffmpeg or ffprobe is not installed (apt-get install ffmpeg)");
    }
    have
}

/// ffprobe's decoded frame count, size and frame rate of the video's first stream.
fn probe(video: &Path) -> String {
    let out = Command::new("ffprobe")
        .args(["-v", "error", "-select_streams", "v:0", "-count_frames"])
        .args(["-show_entries", "stream=nb_read_frames,width,height,r_frame_rate", "-of", "default=noprint_wrappers=1"])
        .arg(video)
        .output()
        .unwrap();
    assert!(out.status.success(), "ffprobe {}: {}", video.display(), String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn a_sequence_becomes_a_video_with_one_picture_per_frame() {
    if !have_ffmpeg() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("moving.toml"), MOVING).unwrap();
    let out = lamplight(d, &["render", "moving.toml", "-o", "f/f_####.png", "--video", "clip.mp4", "-q"], None);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(probe(&d.join("clip.mp4")), "width=24\nheight=16\nr_frame_rate=12/1\nnb_read_frames=4\n");
    // A second video of the same frames renders nothing: the frames exist.
    let out = lamplight(d, &["render", "moving.toml", "-o", "f/f_####.png", "--video", "clip.gif", "-q"], None);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(
        String::from_utf8(out.stderr).unwrap(),
        "lamplight: skipping 4 of 4 frames whose files exist (such as f/f_0001.png); --overwrite renders them again\n"
    );
    // GIF delays are whole hundredths of a second: 1/12 s is 8 or 9 of them, so only the count is exact.
    let gif = probe(&d.join("clip.gif"));
    assert!(gif.starts_with("width=24\nheight=16\nr_frame_rate=") && gif.ends_with("\nnb_read_frames=4\n"), "{gif}");
    // An odd size is padded to even for 4:2:0; a part of the range is the video.
    let out =
        lamplight(d, &["render", "moving.toml", "--frames", "2-3", "--width", "23", "-o", "odd_#.png", "--video", "odd.webm", "-q"], None);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(probe(&d.join("odd.webm")), "width=24\nheight=16\nr_frame_rate=12/1\nnb_read_frames=2\n");
    let left: Vec<String> =
        fs::read_dir(d).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).filter(|n| n.ends_with(".tmp")).collect();
    assert!(left.is_empty(), "no temporary file is left: {left:?}");
}

#[test]
fn without_ffmpeg_the_frames_are_kept_and_the_exit_code_is_2() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("moving.toml"), MOVING).unwrap();
    let empty = d.join("no-programs");
    fs::create_dir(&empty).unwrap();
    let out = lamplight(d, &["render", "moving.toml", "-o", "f/f_####.png", "--video", "clip.mp4", "-q"], Some(&empty));
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8(out.stderr).unwrap(),
        "lamplight: error: cannot make clip.mp4: ffmpeg is not on PATH (install it: apt-get install ffmpeg, brew install ffmpeg, \
         or ffmpeg.org); the frames are kept (f/f_0001.png to f/f_0004.png)\n"
    );
    for f in 1..=4 {
        assert!(d.join(format!("f/f_{f:04}.png")).is_file(), "frame {f} is kept");
    }
    assert!(!d.join("clip.mp4").exists());
}

#[test]
fn a_bad_video_request_is_refused_before_anything_renders() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("moving.toml"), MOVING).unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["-o", "f_#.png", "--video", "clip.avi"], "lamplight: error: --video clip.avi must end in .mp4, .webm or .gif (the video's format)"),
        (
            &["-o", "f_#.exr", "--video", "clip.mp4"],
            "lamplight: error: --video clip.mp4 needs .png or .ppm frames, got -o f_#.exr (an .exr frame holds linear values a video cannot show)",
        ),
        (
            &["-o", "one.png", "--video", "clip.mp4"],
            "lamplight: error: --video clip.mp4 encodes a frame sequence: give -o a run of # for the frame number (frame_####.png), \
             with --frames or the scene's [animation]",
        ),
    ];
    for (args, expected) in cases {
        let mut all = vec!["render", "moving.toml"];
        all.extend_from_slice(args);
        let out = lamplight(d, &all, None);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert_eq!(String::from_utf8(out.stderr).unwrap().trim_end(), *expected, "{args:?}");
    }
    assert_eq!(fs::read_dir(d).unwrap().count(), 1, "nothing was written");
}
