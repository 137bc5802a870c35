//! The `blend` material: two materials mixed by a weight. In a white furnace
//! (a uniform sky of radiance 1, no other light) a convex surface reflects its
//! albedo: a diffuse surface of `kd = 0.8` shows 0.8 and a perfect mirror 1,
//! so a blend of weight `w` must show `0.8 (1 - w) + w`.

use std::path::Path;

use lamplight_core::{integrators, render_image, RenderControl, RenderOptions};
use lamplight_scene::instantiate::SceneFile;

const DIFFUSE: &str = "{ color = 1, kd = 0.8, ka = 0, ks = 0 }";
const MIRROR: &str = "{ color = 1, kd = 0, ka = 0, ks = 0, reflection = { type = \"constant\", weight = 1 } }";

/// A square of `material` (a material table) filling an orthographic view, in a furnace.
fn furnace(material: &str, extra: &str) -> String {
    format!(
        "background = 1\n[camera]\ntype = \"orthographic\"\neye = [0.5, 0.5, 5]\nlook_at = [0.5, 0.5, 0]\nhalf_width = 0.5\nhalf_height = 0.5\n\
         {extra}[materials.m]\n{material}\n\
         [[objects]]\ntype = \"rectangle\"\ncorner = [0, 0, 0]\nedge_u = [1, 0, 0]\nedge_v = [0, 1, 0]\nmaterial = \"m\"\n"
    )
}

fn blend(weight: &str) -> String {
    format!("type = \"blend\"\na = {DIFFUSE}\nb = {MIRROR}\nweight = {weight}")
}

fn render(text: &str, integrator: &str, threads: usize) -> Vec<[f32; 3]> {
    let scene = SceneFile::parse(Path::new("s.toml"), text).unwrap().build().unwrap_or_else(|e| panic!("{e}"));
    let options = RenderOptions {
        width: 8,
        height: 8,
        spp: 64,
        threads,
        integrator: integrators::find(integrator).unwrap(),
        ..RenderOptions::default()
    };
    render_image(&scene, &options, &RenderControl::default()).unwrap().0.pixels
}

fn mean(pixels: &[[f32; 3]]) -> f64 {
    pixels.iter().map(|p| f64::from(p[0] + p[1] + p[2]) / 3.0).sum::<f64>() / pixels.len() as f64
}

/// Table `table` (one of the above) written as the body of a `[materials.m]` entry.
fn body(table: &str) -> String {
    let inner = table.strip_prefix("{ ").and_then(|t| t.strip_suffix(" }")).unwrap();
    match inner.split_once(", reflection") {
        Some((plain, reflection)) => format!("{}\nreflection{reflection}", plain.replace(", ", "\n")),
        None => inner.replace(", ", "\n"),
    }
}

#[test]
fn weights_0_and_1_render_exactly_the_components() {
    for integrator in ["path", "whitted"] {
        let a = render(&furnace(&body(DIFFUSE), ""), integrator, 2);
        let b = render(&furnace(&body(MIRROR), ""), integrator, 2);
        assert_eq!(render(&furnace(&blend("0"), ""), integrator, 2), a, "{integrator}: weight 0 is `a`, byte for byte");
        assert_eq!(render(&furnace(&blend("1"), ""), integrator, 2), b, "{integrator}: weight 1 is `b`, byte for byte");
    }
    // A component's own textures and bump map are evaluated where it is picked.
    let color = "{ type = \"uv_checker\", even = 0.2, odd = 0.9, uv_scale = [4, 4] }";
    let bump = "{ type = \"uv_checker\", even = 0, odd = 1, uv_scale = [3, 3] }";
    let keys = format!("color = {color}, kd = 1, ka = 0, ks = 0, bump = {bump}, bump_scale = 0.05");
    let alone = render(&furnace(&format!("color = {color}\nkd = 1\nka = 0\nks = 0\nbump = {bump}\nbump_scale = 0.05"), ""), "path", 2);
    let picked = render(&furnace(&format!("type = \"blend\"\na = {{ {keys} }}\nb = {MIRROR}\nweight = 0"), ""), "path", 2);
    assert_eq!(picked, alone);
}

#[test]
fn a_blend_in_the_furnace_reflects_the_mixed_albedo() {
    for w in [0.25, 0.5] {
        let image = render(&furnace(&blend(&w.to_string()), ""), "path", 1);
        let expected = 0.8 * (1.0 - w) + w;
        // Each sample is one component: 0.8 (the diffuse estimate, with its own
        // noise) or 1; per pixel sd <= 0.2 / 8 = 0.025, 5 sd; over 64 pixels 0.0031, 5 sd.
        for p in &image {
            assert!((f64::from(p[0]) - expected).abs() < 0.125, "w = {w}: pixel {p:?}, expected {expected}");
        }
        assert!((mean(&image) - expected).abs() < 0.016, "w = {w}: mean {}, expected {expected}", mean(&image));
        assert_eq!(image, render(&furnace(&blend(&w.to_string()), ""), "path", 3), "threads change no byte");
    }
}

#[test]
fn a_textured_weight_picks_per_point_and_named_components_are_found() {
    // Left half (u < 0.5) weight 0: the diffuse `a`; right half weight 1: the mirror.
    let text = furnace(
        "type = \"blend\"\na = \"matte\"\nb = \"mirror\"\nweight = { type = \"uv_checker\", even = 0, odd = 1, uv_scale = [2, 1] }",
        &format!("[materials.matte]\n{}\n[materials.mirror]\n{}\n", body(DIFFUSE), body(MIRROR)),
    );
    let image = render(&text, "path", 2);
    let diffuse = render(&furnace(&body(DIFFUSE), ""), "path", 2);
    for y in 0..8 {
        for x in 0..8 {
            let got = image[y * 8 + x];
            if x < 4 {
                assert_eq!(got, diffuse[y * 8 + x], "pixel ({x}, {y}) is the diffuse component's");
            } else {
                assert_eq!(got, [1.0; 3], "pixel ({x}, {y}) is the mirror's");
            }
        }
    }
}

#[test]
fn emission_mixes_into_one_area_light() {
    // A quarter of an emitter of radiance 1 over black: the camera sees 0.75 everywhere, exactly.
    let text = furnace("type = \"blend\"\na = { kd = 0, ka = 0, emission = 1 }\nb = { kd = 0, ka = 0 }\nweight = 0.25", "")
        .replace("background = 1\n", "");
    for integrator in ["path", "whitted"] {
        for p in render(&text, integrator, 1) {
            assert_eq!(p, [0.75; 3], "{integrator}");
        }
    }
    let scene = SceneFile::parse(Path::new("s.toml"), &text).unwrap().build().unwrap();
    let lights = scene.light_set();
    assert_eq!(lights.area.len(), 1, "the blend is one area light");
}

#[test]
fn blends_nest_and_their_errors_name_the_place() {
    // A blend of a blend: w = 0.5 of (0.5 of 0.8 and 1) and 1 is 0.95.
    let inner = blend("0.5").replace('\n', ", ");
    let nested = format!("type = \"blend\"\na = {{ {inner} }}\nb = {MIRROR}\nweight = 0.5");
    let image = render(&furnace(&nested, ""), "path", 1);
    assert!((mean(&image) - 0.95).abs() < 0.016, "{}", mean(&image));

    let error = |text: &str| match SceneFile::parse(Path::new("s.toml"), text).and_then(|f| f.build()) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(e) => e.to_string(),
    };
    let named = |rest: &str| format!("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n{rest}");
    let cases = [
        (
            named("[materials.x]\ntype = \"blend\"\na = \"y\"\nb = {}\n[materials.y]\ntype = \"blend\"\na = \"x\"\nb = {}\n"),
            "s.toml:11:5: material \"y\": a: the blend contains itself (x -> y -> x)",
        ),
        (
            named("[materials.x]\ntype = \"blend\"\na = \"x\"\nb = {}\n"),
            "s.toml:7:5: material \"x\": a: the blend contains itself (x -> x)",
        ),
        (
            named("[materials.x]\ntype = \"blend\"\na = \"nope\"\nb = {}\n"),
            "s.toml:7:5: material \"x\": a: unknown material \"nope\" (materials: x)",
        ),
        (named("[materials.x]\ntype = \"blend\"\nb = {}\n"), "s.toml:5:1: material \"x\": needs `a` (a material name or table)"),
        (
            named("[materials.x]\ntype = \"blend\"\na = 3\nb = {}\n"),
            "s.toml:7:5: material \"x\": a: expected a material name or a material table { type = ..., ... }, got a number 3",
        ),
        (
            named("[materials.x]\ntype = \"blend\"\na = {}\nb = {}\nweight = 1.5\n"),
            "s.toml:9:10: material \"x\": weight: must be between 0 and 1, got 1.5",
        ),
        (
            named("[materials.x]\ntype = \"blend\"\na = { kd = -1 }\nb = {}\n"),
            "s.toml:7:12: material \"x\": a: invalid kd: must be finite and non-negative, got [-1, -1, -1]",
        ),
        (
            named("[materials.x]\ntype = \"blend\"\na = { alpha = 0.5 }\nb = {}\n"),
            "s.toml:7:5: material \"x\": a: a blend's components take no `alpha` (give it to the blend)",
        ),
    ];
    let mut failures = Vec::new();
    for (text, expected) in &cases {
        let got = error(text);
        if got != *expected {
            failures.push(format!("input:\n{text}\n  expected: {expected}\n  got:      {got}"));
        }
    }
    // Nine blends deep: one more than the bound.
    let mut deep = "{}".to_string();
    for _ in 0..9 {
        deep = format!("{{ type = \"blend\", a = {deep}, b = {{}} }}");
    }
    let got = error(&named(&format!("[materials.x]\ntype = \"blend\"\na = {deep}\nb = {{}}\n")));
    assert!(got.ends_with("materials nested more than 8 deep"), "{got}");
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
