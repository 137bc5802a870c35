//! Frames of small descriptions against hand-computed values.

use lamplight_core::params::{Item, Value};

use crate::description::{Node, SceneDescription};
use crate::formats::native;

fn parse(objects: &str) -> SceneDescription {
    let text = format!("[animation]\nframes = [1, 9]\nfps = 4\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n{objects}");
    native::parse(std::path::Path::new("s.toml"), text).map(|(d, _)| d).unwrap()
}

fn numbers(item: &Item) -> Vec<f64> {
    match &item.value {
        Value::Number(x) => vec![*x],
        Value::Integer(n) => vec![*n as f64],
        Value::Array(a) => a.iter().flat_map(numbers).collect(),
        Value::Table(t) => t.entries.iter().flat_map(|e| numbers(&e.item)).collect(),
        other => panic!("not numbers: {other:?}"),
    }
}

fn first(desc: &SceneDescription) -> &Node {
    &desc.objects[0]
}

fn transform(desc: &SceneDescription, frame: f64, key: &str) -> Vec<f64> {
    let at = desc.at_frame(frame).unwrap();
    assert!(at.animation.is_none() && first(&at).params.get("animate").is_none());
    numbers(&first(&at).transform.get(key).unwrap_or_else(|| panic!("no {key} at frame {frame}")).item)
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
}

#[test]
fn linear_translation_and_holding_outside_the_keys() {
    let d = parse("[[objects]]\ntype = \"sphere\"\nanimate.translate = { frames = [3, 7], values = [[0, 0, 0], [4, -8, 2]] }\n");
    assert_eq!(transform(&d, 5.0, "translate"), [2.0, -4.0, 1.0]);
    assert_eq!(transform(&d, 4.0, "translate"), [1.0, -2.0, 0.5]);
    // Before the first key and after the last, the end values hold (glTF).
    assert_eq!(transform(&d, 1.0, "translate"), [0.0, 0.0, 0.0]);
    assert_eq!(transform(&d, 9.0, "translate"), [4.0, -8.0, 2.0]);
}

#[test]
fn step_holds_each_value_until_the_next_key() {
    let d = parse("[[objects]]\ntype = \"sphere\"\nanimate.scale = { frames = [1, 4, 8], values = [1, 2, 3], interpolation = \"step\" }\n");
    for (frame, expected) in [(1.0, 1.0), (3.0, 1.0), (3.99, 1.0), (4.0, 2.0), (7.5, 2.0), (8.0, 3.0), (9.0, 3.0)] {
        assert_eq!(transform(&d, frame, "scale"), [expected], "frame {frame}");
    }
}

#[test]
fn a_quarter_turn_slerps_through_45_degrees() {
    let d = parse(
        "[[objects]]\ntype = \"sphere\"\nanimate.rotate = { frames = [1, 9], values = [{ y = 0 }, { axis = [0, 1, 0], degrees = 90 }] }\n",
    );
    let (s, c) = (22.5f64.to_radians().sin(), 22.5f64.to_radians().cos());
    assert!(close(&transform(&d, 5.0, "rotate"), &[0.0, s, 0.0, c]), "{:?}", transform(&d, 5.0, "rotate"));
    // On a key: the value as written.
    let at = d.at_frame(9.0).unwrap();
    let on_key = &first(&at).transform.get("rotate").unwrap().item;
    assert!(matches!(&on_key.value, Value::Table(t) if t.get("axis").is_some() && t.get("degrees").is_some()), "{on_key:?}");
}

#[test]
fn cubic_spline_uses_the_tangents_scaled_by_the_interval() {
    // Keys 2 frames apart, 0 -> 10, out-tangent 2, in-tangent -4 (per frame): 6.5 halfway, 2.5 a quarter in.
    let d = parse(
        "[[objects]]\ntype = \"sphere\"\nanimate.radius = { frames = [3, 5], values = [0, 10], interpolation = \"cubicspline\", \
         in_tangents = [0, -4], out_tangents = [2, 0] }\n",
    );
    let radius = |frame: f64| numbers(&first(&d.at_frame(frame).unwrap()).params.get("radius").unwrap().item);
    assert_eq!(radius(4.0), [6.5]);
    assert_eq!(radius(3.5), [2.5]);
    assert_eq!(radius(5.0), [10.0]);
    assert_eq!(radius(1.0), [0.0]);
}

#[test]
fn seconds_count_from_the_first_frame_at_the_frame_rate() {
    // fps 4: frame 1 is 0 s, frame 5 is 1 s, frame 9 is 2 s.
    let d = parse("[[objects]]\ntype = \"sphere\"\nanimate.translate = { seconds = [0, 2], values = [[0, 0, 0], [8, 0, 0]] }\n");
    assert_eq!(transform(&d, 5.0, "translate"), [4.0, 0.0, 0.0]);
    assert_eq!(transform(&d, 2.0, "translate"), [1.0, 0.0, 0.0]);
}

#[test]
fn the_camera_and_nested_nodes_are_animated_too() {
    let text = "[animation]\nframes = [0, 10]\n[camera]\nlook_at = [0, 0, 0]\nvfov = 40\nanimate.eye = { frames = [0, 10], values = [[0, 0, 5], [10, 0, 5]] }\n\
                [[objects]]\ntype = \"group\"\nchildren = [{ type = \"sphere\", animate.translate = { frames = [0, 10], values = [[0, 0, 0], [0, 10, 0]] } }]\n";
    let (d, _) = native::parse(std::path::Path::new("s.toml"), text.into()).unwrap();
    let at = d.at_frame(3.0).unwrap();
    assert_eq!(numbers(&at.camera.as_ref().unwrap().params.get("eye").unwrap().item), [3.0, 0.0, 5.0]);
    let child = &at.objects[0].children.as_ref().unwrap()[0];
    assert_eq!(numbers(&child.transform.get("translate").unwrap().item), [0.0, 3.0, 0.0]);
    let listed = d.animated().unwrap();
    assert_eq!(listed.iter().map(|a| a.path.as_str()).collect::<Vec<_>>(), ["camera", "objects[0].children[0]"]);
}

#[test]
fn tangents_of_keys_in_seconds_are_per_second() {
    // fps 4: keys at 0 s (frame 1) and 0.5 s (frame 3), 0 -> 10, out-tangent 8/s,
    // in-tangent -8/s. Frame 2 is halfway: 5 + 0.5 (0.125) 8 + 0.5 (-0.125) (-8) = 6.
    let d = parse(
        "[[objects]]\ntype = \"sphere\"\nanimate.radius = { seconds = [0, 0.5], values = [0, 10], interpolation = \"cubicspline\", \
         in_tangents = [0, -8], out_tangents = [8, 0] }\n",
    );
    assert_eq!(numbers(&first(&d.at_frame(2.0).unwrap()).params.get("radius").unwrap().item), [6.0]);
}

#[test]
fn a_cubic_spline_rotation_is_normalised() {
    // Zero tangents, symmetric halfway: (q0 + q1) / 2 normalised, 45 degrees about y.
    let d = parse(
        "[[objects]]\ntype = \"sphere\"\nanimate.rotate = { frames = [1, 9], values = [[0, 0, 0], [0, 90, 0]], interpolation = \"cubicspline\" }\n",
    );
    let q = transform(&d, 5.0, "rotate");
    let (s, c) = (22.5f64.to_radians().sin(), 22.5f64.to_radians().cos());
    assert!(close(&q, &[0.0, s, 0.0, c]), "{q:?}");
    // A quarter of the way: h01 = 0.15625, so the weights are 0.84375 and 0.15625 before normalising.
    let q = transform(&d, 3.0, "rotate");
    let (h, w) = (std::f64::consts::FRAC_1_SQRT_2, [0.84375, 0.15625]);
    let raw = [0.0, w[1] * h, 0.0, w[0] + w[1] * h];
    let len = (raw[1] * raw[1] + raw[3] * raw[3]).sqrt();
    assert!(close(&q, &[0.0, raw[1] / len, 0.0, raw[3] / len]), "{q:?}");
}
