//! The timeline of an animated scene (issue 29): a `frame` message renders
//! that frame (the image `lamplight render --frames N` makes, byte for byte),
//! out-of-range frames are refused in the request layer's words, a static
//! scene reports no animation, and play steps through the frames' previews at
//! most at the scene's fps and stops at the last, which is then refined.
//! See: docs/view.md, "The timeline".

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use lamplight_core::film::Image;
use lamplight_core::RenderControl;
use lamplight_scene::request::{Naming, Request, SceneRequest};
use lamplight_view::renderer::Frame;
use lamplight_view::{ViewOptions, Viewer};
use serde_json::{json, Value};

fn start(scene: &str, width: u32) -> Viewer {
    let request = Request { width: Some(width), ..Request::default() };
    Viewer::start(ViewOptions { scene: scene.into(), listen: Some("127.0.0.1:0".parse().unwrap()), request, save_dir: None }).unwrap()
}

/// Sends the page's `message`; the error it is answered with at once, if any.
fn send(viewer: &Viewer, message: Value) -> Option<String> {
    let runtime = tokio::runtime::Builder::new_current_thread().enable_all().build().unwrap();
    let (tx, _rx) = tokio::sync::mpsc::channel(4);
    let explainer = lamplight_view::explainer::Explainer::default();
    let reply = runtime.block_on(async { lamplight_view::messages::handle(&viewer.app, &message.to_string(), &tx, &explainer) });
    reply.map(|r| serde_json::from_str::<Value>(&r).unwrap()["message"].as_str().unwrap().to_string())
}

/// The latest `state` message.
fn state(viewer: &Viewer) -> Value {
    (**viewer.app.status.borrow()).clone()
}

/// Waits for a frame that `wanted` accepts; every frame seen on the way goes to `seen`.
fn wait_for(viewer: &Viewer, seen: &mut Vec<Arc<Frame>>, wanted: impl Fn(&Frame) -> bool) -> Arc<Frame> {
    let deadline = Instant::now() + Duration::from_secs(120);
    loop {
        if let Some(frame) = viewer.app.latest_frame() {
            if !seen.last().is_some_and(|s| Arc::ptr_eq(s, &frame)) {
                seen.push(frame.clone());
            }
            if wanted(&frame) {
                return frame;
            }
        }
        assert!(Instant::now() < deadline, "no such frame came");
        std::thread::sleep(Duration::from_millis(1));
    }
}

/// The final frame of frame `n`.
fn final_frame(viewer: &Viewer, n: i64) -> Arc<Frame> {
    wait_for(viewer, &mut Vec::new(), |f| f.last && f.wanted.loaded.frame == Some(n))
}

/// Frame `frame` of `scene` at `width` pixels, as the request layer renders it
/// (`lamplight render SCENE --frames FRAME --width WIDTH`).
fn rendered(scene: &str, frame: i64, width: u32) -> Image {
    let scene = SceneRequest::resolve(scene).unwrap();
    let job = Request { width: Some(width), frame: Some(frame), ..Request::default() }.resolve(&scene.defaults, Naming::Flags).unwrap();
    let built = scene.instantiate(&job).unwrap();
    job.run(&built.scene, &RenderControl::default()).unwrap().image
}

fn turntable_copy() -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("turntable.toml");
    std::fs::copy(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/turntable.toml"), &file).unwrap();
    (dir, file.display().to_string())
}

#[test]
fn the_frame_message_renders_that_frame_as_render_does_and_reload_keeps_it() {
    let (_dir, file) = turntable_copy();
    let viewer = start(&file, 48);
    let s = state(&viewer);
    assert_eq!(s["animation"], json!({ "start": 1, "end": 48, "fps": 24.0 }));
    assert_eq!((s["frame"].clone(), s["playing"].clone()), (json!(1), json!(false)), "it opens on the first frame");
    let first = final_frame(&viewer, 1);
    assert_eq!(send(&viewer, json!({ "type": "frame", "frame": 13 })), None);
    let thirteen = final_frame(&viewer, 13);
    let expected = rendered(&file, 13, 48);
    assert_eq!((thirteen.image.width, thirteen.image.height), (48, 27));
    assert!(thirteen.image.pixels == expected.pixels, "frame 13 differs from `lamplight render --frames 13`'s");
    assert!(first.image.pixels != expected.pixels, "frames 1 and 13 are different pictures");
    assert_eq!(state(&viewer)["frame"], 13);
    // A camera move renders the frame's build again: no rebuild.
    let built = viewer.app.lock().loaded.clone();
    let camera = viewer.app.lock().probed;
    viewer.app.set_camera(Some(lamplight_view::camera::ViewCamera { vfov: 30.0, ..camera })).unwrap();
    assert!(Arc::ptr_eq(&built, &viewer.app.lock().loaded), "a camera move rebuilt the scene");
    viewer.app.set_camera(None).unwrap();
    // A reload reads the file again and stays on frame 13.
    viewer.app.reload();
    assert_eq!(viewer.app.lock().request.frame, Some(13));
    assert!(!Arc::ptr_eq(&built, &viewer.app.lock().loaded), "the reload read the scene again");
    let reloaded = wait_for(&viewer, &mut Vec::new(), |f| f.last && !Arc::ptr_eq(&f.wanted.loaded, &built));
    assert_eq!(reloaded.wanted.loaded.frame, Some(13));
    assert!(reloaded.image.pixels == expected.pixels, "the reloaded frame 13 differs from render's");
}

#[test]
fn frames_outside_the_animation_are_refused_in_the_request_layer_s_words() {
    let (_dir, file) = turntable_copy();
    let viewer = start(&file, 16);
    for (frame, message) in [
        (json!(49), "frame must be a frame of the scene's animation, from 1 to 48, got 49"),
        (json!(0), "frame must be a frame of the scene's animation, from 1 to 48, got 0"),
        (json!(-3), "frame must be a frame number from 0 to 1048574, got -3"),
        (json!(2.5), "frame must be a whole number, got 2.5"),
        (json!("12"), "frame must be a whole number, got \"12\""),
    ] {
        assert_eq!(send(&viewer, json!({ "type": "frame", "frame": frame })).as_deref(), Some(message), "{frame}");
    }
    assert_eq!(viewer.app.lock().request.frame, Some(1), "the refused frames changed nothing");
}

#[test]
fn a_static_scene_reports_no_animation_and_has_no_frames() {
    let viewer = start("business-card", 16);
    let s = state(&viewer);
    assert_eq!((s["animation"].clone(), s["frame"].clone(), s["playing"].clone()), (Value::Null, Value::Null, json!(false)));
    assert_eq!(
        send(&viewer, json!({ "type": "frame", "frame": 1 })).as_deref(),
        Some("frame: the scene is not animated (it has no [animation] table), so it has no frames to show")
    );
    assert_eq!(
        send(&viewer, json!({ "type": "play" })).as_deref(),
        Some("play: the scene is not animated (it has no [animation] table), so it has no frames to play")
    );
    assert_eq!(send(&viewer, json!({ "type": "pause" })), None, "pausing what does not play is nothing");
}

/// A sphere crossing the view over frames 1 to 6 at `fps`.
fn moving_sphere(fps: u32) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("moving.toml");
    let scene = format!(
        r#"ambient = 0.2

[animation]
frames = [1, 6]
fps = {fps}

[camera]
eye = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
vfov = 40

[materials.red]
color = [0.8, 0.2, 0.2]

[[objects]]
type = "sphere"
material = "red"
center = [0.0, 0.0, 0.0]
radius = 0.5
animate.translate = {{ frames = [1, 6], values = [[-1.5, 0.0, 0.0], [1.5, 0.0, 0.0]] }}

[[objects]]
type = "point_light"
position = [0.0, 3.0, 5.0]
intensity = 20.0
"#
    );
    std::fs::write(&file, scene).unwrap();
    (dir, file)
}

#[test]
fn play_steps_through_previews_at_most_at_fps_and_stops_on_the_last_frame_refined() {
    let (_dir, file) = moving_sphere(20);
    let file = file.display().to_string();
    let viewer = start(&file, 32);
    final_frame(&viewer, 1);
    let started = Instant::now();
    assert_eq!(send(&viewer, json!({ "type": "play" })), None);
    assert_eq!(state(&viewer)["playing"], true);
    let mut seen = Vec::new();
    let end = wait_for(&viewer, &mut seen, |f| f.last && f.wanted.loaded.frame == Some(6));
    let elapsed = started.elapsed();
    // Frames 2 to 6 start at least 1/20 s apart, and play ends 1/20 s after the last.
    assert!(elapsed >= Duration::from_millis(250), "5 steps at 20 fps took only {elapsed:?}");
    let played: Vec<&Arc<Frame>> = seen.iter().filter(|f| f.wanted.preview).collect();
    assert!(!played.is_empty(), "no frame of play was seen");
    for f in &played {
        assert!(f.spp == 1 && !f.last, "play renders previews only: {} spp, last {}", f.spp, f.last);
        assert!(f.image.width <= 32);
    }
    let numbers: Vec<i64> = played.iter().filter_map(|f| f.wanted.loaded.frame).collect();
    assert!(numbers.windows(2).all(|w| w[0] <= w[1]) && numbers[0] >= 2, "frames of play out of order: {numbers:?}");
    // It stopped on the last frame (no loop) and refined it: render's image.
    let s = state(&viewer);
    assert_eq!((s["playing"].clone(), s["frame"].clone()), (json!(false), json!(6)));
    assert!(end.image.pixels == rendered(&file, 6, 32).pixels, "the last frame differs from render's");
    // Play from the last frame starts again at the first.
    let mut again = Vec::new();
    assert_eq!(send(&viewer, json!({ "type": "play" })), None);
    wait_for(&viewer, &mut again, |f| f.wanted.preview && f.wanted.loaded.frame == Some(1));
}

#[test]
fn pause_stops_play_and_refines_the_frame_shown() {
    let (_dir, file) = moving_sphere(1);
    let viewer = start(&file.display().to_string(), 32);
    final_frame(&viewer, 1);
    assert_eq!(send(&viewer, json!({ "type": "play" })), None);
    let mut seen = Vec::new();
    wait_for(&viewer, &mut seen, |f| f.wanted.preview && f.wanted.loaded.frame == Some(2));
    assert_eq!(send(&viewer, json!({ "type": "pause" })), None);
    let refined = final_frame(&viewer, 2);
    assert!(!refined.wanted.preview);
    // At 1 fps the next step would have come within a second: none comes.
    std::thread::sleep(Duration::from_millis(1200));
    let s = state(&viewer);
    assert_eq!((s["playing"].clone(), s["frame"].clone()), (json!(false), json!(2)));
    assert!(Arc::ptr_eq(&viewer.app.latest_frame().unwrap(), &refined), "a frame came after the pause");
    // Scrubbing while playing pauses too, on the frame asked for.
    assert_eq!(send(&viewer, json!({ "type": "play" })), None);
    assert_eq!(send(&viewer, json!({ "type": "frame", "frame": 5 })), None);
    assert_eq!(state(&viewer)["playing"], false);
    final_frame(&viewer, 5);
}

#[test]
fn an_animated_gltf_file_has_a_timeline_too() {
    // Khronos' BoxAnimated: frames 0 to 90 at 24 fps (docs/animation.md, "glTF animations").
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../lamplight-scene/tests/data/gltf/BoxAnimated/BoxAnimated.gltf");
    let file = file.display().to_string();
    let viewer = start(&file, 32);
    let animation = state(&viewer)["animation"].clone();
    assert_eq!((animation["start"].clone(), animation["fps"].clone()), (json!(0), json!(24.0)));
    let end = animation["end"].as_i64().unwrap();
    assert_eq!(
        send(&viewer, json!({ "type": "frame", "frame": end + 1 })),
        Some(format!("frame must be a frame of the scene's animation, from 0 to {end}, got {}", end + 1))
    );
    assert_eq!(send(&viewer, json!({ "type": "frame", "frame": 12 })), None);
    let twelve = final_frame(&viewer, 12);
    assert!(twelve.image.pixels == rendered(&file, 12, 32).pixels, "frame 12 differs from render's");
}
