//! Issue 26: a whole scene scaled by `s` renders the image of the unscaled one,
//! at both ends of the documented range (`1e-4` and `1e6` scene units), with
//! no refusal and no infinite pixel.
//!
//! Scaling a scene by `s` multiplies every length by `s`: the geometry (a group
//! of scale `s` around all of it, so meshes, transforms and light positions
//! follow), the camera's eye and target, and the checker textures' cell size
//! and offset, which are lengths in world space. Radiance is unchanged only if
//! point lights grow as the square of the size: the irradiance of intensity
//! `I` at distance `d` is `I / d^2`, so `I s^2 / (d s)^2 = I / d^2`. Directional,
//! ambient and emitted light are radiances already and stay as they are. A
//! scene of `1e6` units therefore needs point lights `1e12` times as intense,
//! which the earlier input bound (`1e12`) refused; only the film's bound on
//! what reaches a pixel remains (`lamplight_core::film::MAX_RADIANCE`).
//! `lamplight-core`'s `tests/acne.rs` checks shadow rays across the same range
//! with a directional light; this checks the rest of the image with point lights.

use std::path::{Path, PathBuf};

use lamplight_core::film::Image;
use lamplight_core::{render_image, RenderControl, RenderOptions, Scene};
use lamplight_scene::instantiate::SceneFile;

/// The documented ends of the scale range, and one in between that is not a power of two.
const SCALES: [f64; 3] = [1e-4, 3.7, 1e6];

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(format!("{name}.toml"))
}

/// `text` with the number or `[numbers]` after every `key = ` multiplied by `k`.
fn times(text: &str, key: &str, k: f64) -> String {
    let (pattern, mut out, mut rest) = (format!("{key} = "), String::new(), text);
    while let Some(at) = rest.find(&pattern) {
        let whole_word = rest[..at].chars().last().is_none_or(|c| !(c.is_alphanumeric() || c == '_'));
        let start = at + pattern.len();
        out.push_str(&rest[..start]);
        rest = &rest[start..];
        if !whole_word {
            continue;
        }
        let end = if rest.starts_with('[') { rest.find(']').unwrap() + 1 } else { rest.find([',', ' ', '\n', '}']).unwrap() };
        let scaled: Vec<String> =
            rest[..end].trim_matches(['[', ']']).split(',').map(|n| format!("{:e}", n.trim().parse::<f64>().unwrap() * k)).collect();
        out.push_str(&if rest.starts_with('[') { format!("[{}]", scaled.join(", ")) } else { scaled.join("") });
        rest = &rest[end..];
    }
    out + rest
}

/// The example file `name` with every length scaled by `s` (see the module
/// doc): its top-level objects become the children of one group of scale `s`
/// (`[[objects.children]]` appends to the group's `children`).
fn scaled_text(name: &str, s: f64) -> String {
    let mut text = std::fs::read_to_string(example(name)).unwrap();
    for (key, k) in [("eye", s), ("look_at", s), ("size", s), ("offset", s), ("intensity", s * s)] {
        text = times(&text, key, k);
    }
    let first = text.find("[[objects]]").unwrap();
    let (head, objects) = text.split_at(first);
    format!("{head}[[objects]]\ntype = \"group\"\nscale = {s:e}\n\n{}", objects.replace("[[objects]]", "[[objects.children]]"))
}

fn build(text: &str) -> Scene {
    let file = SceneFile::parse(Path::new("scaled.toml"), text).unwrap_or_else(|e| panic!("{e}"));
    file.build().unwrap_or_else(|e| panic!("refused: {e}"))
}

fn render(scene: &Scene) -> Image {
    let options = RenderOptions { width: 64, height: 36, threads: 2, ..RenderOptions::default() };
    let (image, stats) = render_image(scene, &options, &RenderControl::default()).unwrap();
    assert_eq!(stats.nonfinite_samples, 0, "no sample was dropped");
    assert!(image.pixels.iter().flatten().all(|c| c.is_finite()), "no infinite pixel");
    image
}

/// How many 8-bit channel values differ between `a` and `b`, and by at most how much
/// (what a failure reports).
fn difference(a: &Image, b: &Image) -> (usize, u8) {
    let (a, b) = (a.to_srgb8(), b.to_srgb8());
    let diffs: Vec<u8> = a.iter().zip(&b).map(|(x, y)| x.abs_diff(*y)).filter(|&d| d > 0).collect();
    (diffs.len(), diffs.iter().copied().max().unwrap_or(0))
}

/// `spheres` and `luxo` (Whitted, point lights, mirrors, glass, a mesh, a
/// checker floor) scaled to each end of the range render byte for byte the
/// unscaled 64x36 image (measured: 0 of its 6912 8-bit values differ at
/// `1e-4`, `3.7` and `1e6`; the offsets and tolerances are relative to the
/// scene's size, so rounding moves nothing across a pixel's value).
#[test]
fn scaled_builtin_scenes_render_the_unscaled_image() {
    for name in ["spheres", "luxo"] {
        let reference = render(&build(&scaled_text(name, 1.0)));
        let original = render(&SceneFile::read(&example(name)).unwrap().build().unwrap());
        assert_eq!(difference(&reference, &original), (0, 0), "{name}: the rewritten file is the example");
        for s in SCALES {
            let scaled = render(&build(&scaled_text(name, s)));
            assert_eq!(difference(&scaled, &reference), (0, 0), "{name} scaled by {s:e}: (values that differ, by at most)");
        }
    }
}

/// The issue's own case: a sphere of radius `1e6` seen from `1e7`, lit by a
/// point light of `6e13`, is the unit sphere seen from 10 under a light of 60.
#[test]
fn a_sphere_of_a_million_units_under_a_light_of_6e13() {
    let scene = |s: f64| {
        build(&format!(
            "[camera]\neye = [0, 0, {}]\nlook_at = [0, 0, 0]\nvfov = 15\n\
             [materials.m]\ncolor = [0.8, 0.5, 0.3]\nkd = 0.9\nks = 0.3\nshininess = 20\n\
             [[objects]]\ntype = \"sphere\"\nmaterial = \"m\"\ncenter = [0, 0, 0]\nradius = {s:e}\n\
             [[objects]]\ntype = \"point_light\"\nposition = [{}, {}, {}]\nintensity = {:e}\n",
            10.0 * s,
            3.0 * s,
            4.0 * s,
            6.0 * s,
            60.0 * s * s
        ))
    };
    let reference = render(&scene(1.0));
    for s in [1e-4, 1e6] {
        assert_eq!(difference(&render(&scene(s)), &reference), (0, 0), "scaled by {s:e}: (values that differ, by at most)");
    }
}
