//! glTF animation import: Khronos' `BoxAnimated` (tests/data/gltf/BoxAnimated,
//! CC BY 4.0, see its README) posed at chosen frames against its keys
//! interpolated by hand; files the test writes, built like Khronos'
//! `InterpolationTest` (a cube per interpolation mode and channel), posed
//! against analytic transforms; and a rendered frame against a static file
//! placing the cube by hand (the same bytes).

use std::f64::consts::FRAC_PI_4;
use std::path::{Path, PathBuf};

use base64::Engine;
use glam::DQuat as Quat;
use lamplight_core::math::{Mat4, Vec3};
use lamplight_core::{render_image, RenderControl, RenderOptions};
use lamplight_scene::import::{self, gltf_animation, Imported};
use lamplight_scene::request::SceneRequest;

pub(crate) fn box_animated() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gltf/BoxAnimated/BoxAnimated.gltf")
}

/// `imported` posed at `seconds` of its first animation.
fn posed(path: &Path, imported: &Imported, seconds: f64) -> Imported {
    let mut out = imported.clone();
    out.pose(path, 0, seconds).unwrap();
    out
}

pub(crate) fn assert_close(got: Mat4, want: Mat4, what: &str) {
    let diff = (got - want).to_cols_array().iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(diff < 1e-6, "{what}: got {got}, expected {want} (largest difference {diff})");
}

pub(crate) fn trs(t: [f64; 3], r: Quat, s: f64) -> Mat4 {
    Mat4::from_scale_rotation_translation(Vec3::splat(s), r, Vec3::from_array(t))
}

#[test]
fn box_animated_moves_as_its_keys_say() {
    let path = box_animated();
    let imported = import::load(&path).unwrap();
    assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    // Keys: translation of node 0 at 0, 1.25, 2.5, 3.70833 s: y = 0, 2.52, 2.52, 0;
    // rotation of node 2 (under node 0 by node 1) at 1.25 and 2.5 s: identity, then
    // (1, 0, 0, 4.49e-11), half a turn about x. 3.70833 s at 24 fps is frame 88.99992: frames 0 to 89.
    let frames = imported.frames().unwrap();
    assert_eq!((frames.start, frames.end, frames.fps), (0, 89, 24.0));
    assert_eq!(gltf_animation::file_frames(&path), Some(frames.clone()));
    // As a GLB (its JSON chunk alone, the buffer still a data URI), whose range is read from the JSON chunk.
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("BoxAnimated.glb");
    let mut json = std::fs::read(&path).unwrap();
    json.resize(json.len().next_multiple_of(4), b' ');
    let mut bytes = b"glTF".to_vec();
    bytes.extend(2u32.to_le_bytes());
    bytes.extend((20 + json.len() as u32).to_le_bytes());
    bytes.extend((json.len() as u32).to_le_bytes());
    bytes.extend(b"JSON");
    bytes.extend(&json);
    std::fs::write(&glb, bytes).unwrap();
    assert_eq!(gltf_animation::file_frames(&glb), Some(frames.clone()));
    assert_eq!(import::load(&glb).unwrap().frames(), Some(frames));
    let y_max = f64::from(2.52f32);
    let half_turn = Quat::from_rotation_x(std::f64::consts::PI);
    // (frame, inner box's translation y, its rotation) interpolated by hand from the keys.
    let cases = [
        // The first frame: the rest pose.
        (0, 0.0, Quat::IDENTITY),
        // 0.625 s, halfway up the first translation key pair; the rotation holds its first key.
        (15, y_max / 2.0, Quat::IDENTITY),
        // 1.875 s: up (between the two equal keys), halfway through the flip: slerp, a quarter turn about x.
        (45, y_max, Quat::from_rotation_x(std::f64::consts::FRAC_PI_2)),
        // 2.5 s: the flip's last key.
        (60, y_max, half_turn),
        // 3.125 s: sinking, s = 0.625 / 1.20833 of the last pair: y = 2.52 (1 - s); the flip holds.
        (75, y_max * (1.0 - 0.625 / (3.708_329_916_000_366 - 2.5)), half_turn),
        // The last frame, past the last key: back down.
        (89, 0.0, half_turn),
    ];
    for (frame, y, rotation) in cases {
        let mut at = imported.clone();
        at.pose_frame(&path, frame).unwrap();
        // Instances in walk order: the outer box (node 3, never moves), then the inner one.
        assert_close(at.instances[0].transform, Mat4::IDENTITY, &format!("outer box at frame {frame}"));
        assert_close(at.instances[1].transform, trs([0.0, y, 0.0], rotation, 1.0), &format!("inner box at frame {frame}"));
    }
    // Halfway through the flip the box's top (+y) faces +z.
    let mut at = imported.clone();
    at.pose_frame(&path, 45).unwrap();
    assert!((at.instances[1].transform.transform_vector3(Vec3::Y) - Vec3::Z).length() < 1e-6);
}

#[test]
fn box_animated_info_lists_its_animation() {
    let request = SceneRequest::resolve(box_animated().to_str().unwrap()).unwrap();
    assert_eq!(request.animation().map(|a| (a.start, a.end)), Some((0, 89)));
    let text = lamplight_scene::info::describe(&request).unwrap();
    let rows: Vec<&str> = text.lines().skip_while(|l| !l.starts_with("animation:")).take(4).collect();
    assert_eq!(
        rows,
        [
            "animation:  frames 0 to 89 (90 frames at 24 fps; animations[0] plays, keys from 0 to 3.7083 s; described at frame 0)",
            "animated:   2 channels of 2 nodes",
            "  nodes[2]: rotation (linear, 2 keys at 1.25 to 2.5 s)",
            "  nodes[0]: translation (linear, 4 keys at 0 to 3.7083 s)",
        ]
    );
}

/// A glTF file written by the test: a unit cube and the accessors added.
#[derive(Default)]
pub(crate) struct Builder {
    buffer: Vec<u8>,
    views: Vec<String>,
    accessors: Vec<String>,
}

impl Builder {
    /// An accessor of `values` (`ty`: SCALAR, VEC3, VEC4); scalars get their min and max.
    pub(crate) fn floats(&mut self, values: &[f64], ty: &str) -> usize {
        let width = match ty {
            "SCALAR" => 1,
            "VEC3" => 3,
            _ => 4,
        };
        let minmax = if ty == "SCALAR" {
            let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
            format!(r#", "min": [{lo}], "max": [{hi}]"#)
        } else {
            String::new()
        };
        let bytes: Vec<u8> = values.iter().flat_map(|&x| (x as f32).to_le_bytes()).collect();
        self.add(&bytes, &format!(r#""componentType": 5126, "count": {}, "type": "{ty}"{minmax}"#, values.len() / width))
    }

    fn add(&mut self, bytes: &[u8], accessor: &str) -> usize {
        let offset = self.buffer.len();
        self.buffer.extend(bytes);
        self.buffer.resize(self.buffer.len().next_multiple_of(4), 0);
        self.views.push(format!(r#"{{"buffer": 0, "byteOffset": {offset}, "byteLength": {}}}"#, bytes.len()));
        self.accessors.push(format!(r#"{{"bufferView": {}, {accessor}}}"#, self.views.len() - 1));
        self.accessors.len() - 1
    }

    /// The cube's POSITION and indices accessors (-0.5 to 0.5 on each axis).
    pub(crate) fn cube(&mut self) -> (usize, usize) {
        let corners: Vec<f64> = (0..8).flat_map(|i| [0, 1, 2].map(|a| if i >> a & 1 == 1 { 0.5 } else { -0.5 })).collect();
        let bytes: Vec<u8> = corners.iter().flat_map(|&x| (x as f32).to_le_bytes()).collect();
        let positions =
            self.add(&bytes, r#""componentType": 5126, "count": 8, "type": "VEC3", "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]"#);
        let faces: [u16; 36] = [0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5];
        let bytes: Vec<u8> = faces.iter().flat_map(|i| i.to_le_bytes()).collect();
        let indices = self.add(&bytes, r#""componentType": 5123, "count": 36, "type": "SCALAR""#);
        (positions, indices)
    }

    /// The file: the scene's `roots`, `nodes`, `animations` (JSON arrays' insides) and the rest as given.
    pub(crate) fn json(&self, roots: &str, nodes: &str, animations: &str, extra: &str) -> String {
        let data = base64::engine::general_purpose::STANDARD.encode(&self.buffer);
        format!(
            r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [{roots}]}}],
  "nodes": [{nodes}],
  "meshes": [{{"name": "cube", "primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "animations": [{animations}],
  "accessors": [{}],
  "bufferViews": [{}],
  "buffers": [{{"byteLength": {}, "uri": "data:application/octet-stream;base64,{data}"}}]{extra}}}"#,
            self.accessors.join(",\n"),
            self.views.join(",\n"),
            self.buffer.len(),
        )
    }
}

/// Quaternion `[x, y, z, w]` of `deg` degrees about y.
fn about_y(deg: f64) -> [f64; 4] {
    Quat::from_rotation_y(deg.to_radians()).to_array()
}

/// Khronos' InterpolationTest, as its README describes it: one cube per
/// interpolation mode (STEP, LINEAR, CUBICSPLINE) and channel (translation,
/// rotation, scale), nodes 0 to 8 in that order (mode-major), and a parent
/// (node 9) moving up 10 in 1 s with a child cube (node 10) 1 to its right.
/// A second animation and a morph-weights channel check the warnings.
pub(crate) fn interpolation_test() -> String {
    let mut b = Builder::default();
    b.cube();
    let t012 = b.floats(&[0.0, 1.0, 2.0], "SCALAR");
    let t02 = b.floats(&[0.0, 2.0], "SCALAR");
    let t01 = b.floats(&[0.0, 1.0], "SCALAR");
    let translate = b.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 2.0, 0.0], "VEC3");
    let rotate = b.floats(&[about_y(0.0), about_y(90.0), about_y(180.0)].concat(), "VEC4");
    let scale = b.floats(&[1.0, 1.0, 1.0, 3.0, 3.0, 3.0, 1.0, 1.0, 1.0], "VEC3");
    // CUBICSPLINE: (in-tangent, value, out-tangent) per key, per second.
    let translate_spline = b.floats(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 3.0, 0.0, 0.0, -1.0, 0.0, 0.0, 4.0, 0.0, 0.0, 0.0, 0.0, 0.0], "VEC3");
    let rotate_spline = b.floats(&[[0.0; 4], about_y(0.0), [0.0; 4], [0.0; 4], about_y(90.0), [0.0; 4]].concat(), "VEC4");
    let scale_spline = b.floats(&[0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 2.0, 2.0, 2.0, 0.0, 0.0, 0.0], "VEC3");
    let up = b.floats(&[0.0, 0.0, 0.0, 0.0, 10.0, 0.0], "VEC3");
    let weights = b.floats(&[0.0, 1.0], "SCALAR");
    let mut samplers = Vec::new();
    let mut channels = Vec::new();
    let tracks = [
        ("STEP", t012, translate, "translation"),
        ("STEP", t012, rotate, "rotation"),
        ("STEP", t012, scale, "scale"),
        ("LINEAR", t012, translate, "translation"),
        ("LINEAR", t012, rotate, "rotation"),
        ("LINEAR", t012, scale, "scale"),
        ("CUBICSPLINE", t02, translate_spline, "translation"),
        ("CUBICSPLINE", t01, rotate_spline, "rotation"),
        ("CUBICSPLINE", t02, scale_spline, "scale"),
        ("LINEAR", t01, up, "translation"),
        ("LINEAR", t01, weights, "weights"),
    ];
    for (i, (mode, input, output, property)) in tracks.into_iter().enumerate() {
        samplers.push(format!(r#"{{"input": {input}, "output": {output}, "interpolation": "{mode}"}}"#));
        let node = if i == 10 { 0 } else { i };
        channels.push(format!(r#"{{"sampler": {i}, "target": {{"node": {node}, "path": "{property}"}}}}"#));
    }
    let mut nodes: Vec<String> = (0..9).map(|_| r#"{"mesh": 0}"#.to_string()).collect();
    nodes.push(r#"{"name": "parent", "children": [10]}"#.into());
    nodes.push(r#"{"name": "child", "mesh": 0, "translation": [1, 0, 0]}"#.into());
    let animations = format!(
        r#"{{"name": "modes", "samplers": [{}], "channels": [{}]}},
  {{"name": "second", "samplers": [{{"input": {t01}, "output": {up}}}], "channels": [{{"sampler": 0, "target": {{"node": 0, "path": "translation"}}}}]}}"#,
        samplers.join(", "),
        channels.join(",\n  ")
    );
    b.json("0, 1, 2, 3, 4, 5, 6, 7, 8, 9", &nodes.join(",\n  "), &animations, "")
}

#[test]
fn every_interpolation_mode_gives_its_analytic_transform() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("interpolation.gltf");
    std::fs::write(&path, interpolation_test()).unwrap();
    let imported = import::load(&path).unwrap();
    assert_eq!(imported.warnings, ["glTF animation of morph target weights ignored: morph targets are not supported"]);
    // The longest channel ends at 2 s: frames 0 to 48 at 24 fps.
    assert_eq!(imported.frames().map(|a| (a.start, a.end)), Some((0, 48)));
    assert_eq!(gltf_animation::file_frames(&path).map(|a| (a.start, a.end)), Some((0, 48)));
    let y = |deg: f64| Quat::from_rotation_y(deg.to_radians());
    let id = Quat::IDENTITY;
    // CUBICSPLINE rotation between the identity and 90 degrees with zero tangents at s = 0.25:
    // h00 = 0.84375, h01 = 0.15625, q = normalize(h00 q0 + h01 q1), angle = 2 atan2(q.y, q.w).
    let (qy, qw) = (0.15625 * FRAC_PI_4.sin(), 0.84375 + 0.15625 * FRAC_PI_4.cos());
    let spline_quarter = Quat::from_rotation_y(2.0 * qy.atan2(qw));
    // (node, seconds, expected local = world transform)
    let cases: &[(usize, f64, Mat4)] = &[
        // STEP: each key's value holds until the next key.
        (0, 0.999, trs([0.0, 0.0, 0.0], id, 1.0)),
        (0, 1.0, trs([1.0, 0.0, 0.0], id, 1.0)),
        (0, 1.001, trs([1.0, 0.0, 0.0], id, 1.0)),
        (0, 1.999, trs([1.0, 0.0, 0.0], id, 1.0)),
        (0, 2.5, trs([1.0, 2.0, 0.0], id, 1.0)),
        (1, 0.999, trs([0.0; 3], id, 1.0)),
        (1, 1.001, trs([0.0; 3], y(90.0), 1.0)),
        (2, 0.5, trs([0.0; 3], id, 1.0)),
        (2, 1.5, trs([0.0; 3], id, 3.0)),
        // LINEAR: halfway between keys; rotations by slerp (45 and 135 degrees).
        (3, 0.5, trs([0.5, 0.0, 0.0], id, 1.0)),
        (3, 1.5, trs([1.0, 1.0, 0.0], id, 1.0)),
        (4, 0.5, trs([0.0; 3], y(45.0), 1.0)),
        (4, 1.5, trs([0.0; 3], y(135.0), 1.0)),
        (4, 0.25, trs([0.0; 3], y(22.5), 1.0)),
        (5, 0.5, trs([0.0; 3], id, 2.0)),
        // CUBICSPLINE translation, keys 2 s apart: v0 = 0, b0 = 3, a1 = -1, v1 = 4 (x).
        // s = 0.5: h00 = 0.5, dt h10 = 0.25, h01 = 0.5, dt h11 = -0.25: 0.75 + 2 + 0.25 = 3.
        (6, 1.0, trs([3.0, 0.0, 0.0], id, 1.0)),
        // s = 0.25: dt h10 = 0.28125, h01 = 0.15625, dt h11 = -0.09375: 0.84375 + 0.625 + 0.09375 = 1.5625.
        (6, 0.5, trs([1.5625, 0.0, 0.0], id, 1.0)),
        // CUBICSPLINE rotation: halfway is 45 degrees (the normalised average); a quarter as above.
        (7, 0.5, trs([0.0; 3], y(45.0), 1.0)),
        (7, 0.25, trs([0.0; 3], spline_quarter, 1.0)),
        // CUBICSPLINE scale, keys 2 s apart: v0 = 1, b0 = 1, a1 = 0, v1 = 2; s = 0.5: 0.5 + 0.25 + 1 = 1.75.
        (8, 1.0, trs([0.0; 3], id, 1.75)),
        // Before the first key and after the last the end values hold.
        (6, -1.0, trs([0.0; 3], id, 1.0)),
        (8, 5.0, trs([0.0; 3], id, 2.0)),
        // The parent's motion moves its child: the child's world is the parent's (y = 5 at 0.5 s) times its own (x = 1).
        (9, 0.5, trs([1.0, 5.0, 0.0], id, 1.0)),
    ];
    for &(node, seconds, want) in cases {
        // Instances in walk order: nodes 0 to 8, then the child (node 10).
        let got = posed(&path, &imported, seconds).instances[node].transform;
        assert_close(got, want, &format!("instance {node} at {seconds} s"));
    }
}

#[test]
fn broken_animations_give_their_exact_errors() {
    let dir = tempfile::tempdir().unwrap();
    let file = |input: &[f64], output: &[f64], mode: &str| {
        let mut b = Builder::default();
        b.cube();
        let input = b.floats(input, "SCALAR");
        let output = b.floats(output, "VEC3");
        let animation = format!(
            r#"{{"samplers": [{{"input": {input}, "output": {output}, "interpolation": "{mode}"}}], "channels": [{{"sampler": 0, "target": {{"node": 0, "path": "scale"}}}}]}}"#
        );
        b.json("0", r#"{"mesh": 0}"#, &animation, "")
    };
    let error = |text: String| common_error(dir.path(), &text);
    assert_eq!(
        error(file(&[0.0, 1.0, 1.0], &[1.0; 9], "LINEAR")),
        "a.gltf: at animations[0].samplers[0].input: time 2 (1) is not after time 1 (1): times must increase"
    );
    assert_eq!(
        error(file(&[0.0, 1.0], &[1.0; 3], "LINEAR")),
        "a.gltf: at animations[0].samplers[0].output: has 1 values for 2 key times, expected 2"
    );
    assert_eq!(
        error(file(&[0.0, 1.0], &[1.0; 6], "CUBICSPLINE")),
        "a.gltf: at animations[0].samplers[0].output: has 2 values for 2 key times, expected 6 (in-tangent, value and out-tangent per key)"
    );
}

fn common_error(dir: &Path, text: &str) -> String {
    crate::common::error_of(dir, "a.gltf", text.as_bytes())
}

/// A cube moved by LINEAR translation (0 to 1 in x over 1 s) and scale (1 to 3), seen by a camera, lit
/// by a point light; `still` places it by hand instead, with no animation.
fn render_file(still: Option<&str>) -> String {
    let mut b = Builder::default();
    b.cube();
    let times = b.floats(&[0.0, 1.0], "SCALAR");
    let moves = b.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0], "VEC3");
    let grows = b.floats(&[1.0, 1.0, 1.0, 3.0, 3.0, 3.0], "VEC3");
    let cube = still.map_or(r#"{"mesh": 0}"#.to_string(), |trs| format!(r#"{{"mesh": 0, {trs}}}"#));
    let nodes = format!(
        r#"{cube}, {{"camera": 0, "translation": [0.5, 0.3, 7]}}, {{"extensions": {{"KHR_lights_punctual": {{"light": 0}}}}, "translation": [2, 3, 4]}}"#
    );
    let animation = if still.is_some() {
        String::new()
    } else {
        format!(
            r#"{{"samplers": [{{"input": {times}, "output": {moves}}}, {{"input": {times}, "output": {grows}}}],
  "channels": [{{"sampler": 0, "target": {{"node": 0, "path": "translation"}}}}, {{"sampler": 1, "target": {{"node": 0, "path": "scale"}}}}]}}"#
        )
    };
    let extra = r#", "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 40}]}}"#;
    b.json("0, 1, 2", &nodes, &animation, extra)
}

fn render(path: &Path, frame: Option<i64>) -> Vec<[f32; 3]> {
    let request = SceneRequest::resolve(path.to_str().unwrap()).unwrap();
    let scene = request.build_frame(frame).unwrap().scene;
    let options = RenderOptions { width: 32, height: 24, threads: 2, ..RenderOptions::default() };
    render_image(&scene, &options, &RenderControl::default()).unwrap().0.pixels
}

#[test]
fn a_frame_renders_as_the_cube_placed_by_hand() {
    let dir = tempfile::tempdir().unwrap();
    let (moving, still) = (dir.path().join("moving.gltf"), dir.path().join("still.gltf"));
    std::fs::write(&moving, render_file(None)).unwrap();
    // Frame 12 at 24 fps is 0.5 s: halfway, x = 0.5 and scale 2.
    std::fs::write(&still, render_file(Some(r#""translation": [0.5, 0, 0], "scale": [2, 2, 2]"#))).unwrap();
    let frame_12 = render(&moving, Some(12));
    assert_eq!(frame_12, render(&still, None), "frame 12 is the hand-placed cube, to the byte");
    assert_ne!(frame_12, render(&moving, Some(0)), "the cube moves");
    // Without a frame: the first; a file without animations is the same at every frame.
    assert_eq!(render(&moving, None), render(&moving, Some(0)));
    let request = SceneRequest::resolve(still.to_str().unwrap()).unwrap();
    assert_eq!(request.animation(), None);
}

#[test]
fn a_cube_scaled_to_nothing_is_left_out_and_a_scene_file_without_animation_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let mut b = Builder::default();
    b.cube();
    let times = b.floats(&[0.0, 1.0], "SCALAR");
    let shrinks = b.floats(&[1.0, 1.0, 1.0, 0.0, 0.0, 0.0], "VEC3");
    let animation = format!(
        r#"{{"samplers": [{{"input": {times}, "output": {shrinks}}}], "channels": [{{"sampler": 0, "target": {{"node": 1, "path": "scale"}}}}]}}"#
    );
    let path = dir.path().join("shrink.gltf");
    std::fs::write(&path, b.json("0, 1", r#"{"mesh": 0, "translation": [2, 0, 0]}, {"mesh": 0}"#, &animation, "")).unwrap();
    let imported = import::load(&path).unwrap();
    assert_eq!(posed(&path, &imported, 0.5).instances.len(), 2);
    assert_close(posed(&path, &imported, 0.5).instances[1].transform, trs([0.0; 3], Quat::IDENTITY, 0.5), "half size");
    let gone = posed(&path, &imported, 1.0);
    assert_eq!(gone.instances.len(), 1, "the shrunk cube is not drawn");
    assert_close(gone.instances[0].transform, trs([2.0, 0.0, 0.0], Quat::IDENTITY, 1.0), "the other cube stays");
    // Frame 24 (1 s) renders with the one cube left.
    let request = SceneRequest::resolve(path.to_str().unwrap()).unwrap();
    assert_eq!(request.build_frame(Some(24)).unwrap().scene.objects.len(), 1);
    // In a scene file's [meshes] without [animation] the file stands at its time 0, and a warning says so.
    let scene = format!(
        "[camera]\neye = [0, 2, 8]\nlook_at = [0, 0, 0]\nvfov = 40\n[meshes.box]\nfile = {:?}\n[[objects]]\ntype = \"mesh\"\nmesh = \"box\"\n",
        path.display().to_string()
    );
    let file = lamplight_scene::instantiate::SceneFile::parse(&dir.path().join("s.toml"), &scene).unwrap();
    let built = file.build_with_warnings().unwrap();
    assert_eq!(built.scene.objects.len(), 2);
    assert_eq!(
        built.warnings,
        [format!(
            "{}: the scene has no [animation], so the glTF animation stands at its time 0: add [animation] (frames = [START, END], fps) \
             to play it, or give the mesh `animation = false` for the rest pose",
            path.display()
        )]
    );
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 64, rng_seed: proptest::test_runner::RngSeed::Fixed(0x29a1), ..Default::default() })]

    /// Mutations of the interpolation file load to an error or to animations
    /// that pose at any time (and give their frames) without a panic or a
    /// transform that is not finite.
    #[test]
    fn mutated_animations_never_panic(edits in crate::common::edits(), cut in 0usize..8000) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.gltf");
        std::fs::write(&path, crate::common::mutate(interpolation_test().as_bytes(), &edits, cut)).unwrap();
        let _ = gltf_animation::file_frames(&path);
        if let Ok(imported) = import::load(&path) {
            let _ = imported.frames();
            for seconds in [-1.0, 0.0, 0.25, 1.0, 1.5, 100.0] {
                let mut at = imported.clone();
                if at.pose(&path, 0, seconds).is_ok() {
                    assert!(at.instances.iter().all(|i| i.transform.is_finite()));
                }
            }
        }
    }
}
