//! Mesh files rendered directly (issue 27): a mesh without normals is flat, as
//! glTF requires and Blender imports it, unless `--smooth` asks for Mitsuba's
//! angle-weighted vertex normals.

use std::path::Path;
use std::process::{Command, Output, Stdio};

fn lamplight(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lamplight")).args(args).current_dir(dir).stdin(Stdio::null()).output().expect("the binary runs")
}

/// A tent of two triangles without normals: the right slope from the eave
/// (1, 0, 0) up to the ridge x = 0, y = 1 (z from -1 to 1), facing (1, 1, 0),
/// and its mirror image facing (-1, 1, 0). Each ridge vertex has the same angle
/// in both triangles, so its angle-weighted normal is straight up. The 3/4
/// view that frames a bare model looks at the right slope's outside.
const TENT: &str = "v -1 0 0\nv 0 1 -1\nv 0 1 1\nv 1 0 0\nf 1 3 2\nf 4 2 3\n";

/// The camera ray's hit point and shading normal at the first pixel of the
/// middle row, from the left, that sees the right slope, as `explain --json` gives them.
fn right_slope_hit(dir: &Path, smooth: bool) -> ([f64; 3], [f64; 3]) {
    let size = ["--width", "24", "--height", "24", "--antialias", "off"];
    for x in 0..24 {
        let pixel = format!("{x},12");
        let mut args = vec!["explain", "tent.obj", "--pixel", &pixel, "--json"];
        args.extend(size);
        if smooth {
            args.push("--smooth");
        }
        let out = lamplight(dir, &args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let hit = &json["samples"][0]["ray"]["hit"];
        let vec3 = |v: &serde_json::Value| [0, 1, 2].map(|k| v[k].as_f64().unwrap());
        if hit.is_object() && hit["point"][0].as_f64().unwrap() > 0.05 {
            assert_eq!(hit["normal_flipped"], false, "the camera sees the tent's outside");
            return (vec3(&hit["point"]), vec3(&hit["shading_normal"]));
        }
    }
    panic!("no pixel of the middle row sees the right slope");
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6)
}

#[test]
fn a_mesh_without_normals_is_flat_and_smooth_with_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("tent.obj"), TENT).unwrap();
    let h = std::f64::consts::FRAC_1_SQRT_2;
    // Flat: the face's normal wherever the slope is hit.
    let (_, normal) = right_slope_hit(d, false);
    assert!(close(normal, [h, h, 0.0]), "{normal:?}");
    // Smooth: at the point p = x E + (1 - x) R (E the eave, R on the ridge),
    // the eave's normal (h, h, 0) weighted by x and the ridge's (0, 1, 0) by
    // 1 - x, normalised.
    let (p, normal) = right_slope_hit(d, true);
    let w = p[0];
    let n = [h * w, h * w + (1.0 - w), 0.0];
    let length = (n[0] * n[0] + n[1] * n[1]).sqrt();
    let expected = n.map(|c| c / length);
    assert!(close(normal, expected), "at {p:?}: {normal:?}, expected {expected:?}");
    assert!(!close(normal, [h, h, 0.0]), "smooth differs from flat inside the slope: {normal:?}");
}

#[test]
fn smooth_is_refused_where_a_scene_file_says_it_per_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let out = lamplight(dir.path(), &["render", "luxo", "--smooth", "-o", "luxo.png"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "lamplight: error: --smooth applies to a mesh file rendered directly (.obj, .ply, .gltf, .glb); 'luxo' is not one: \
         in a scene file, give the mesh `shading = \"smooth\"`\n"
    );
    assert!(!dir.path().join("luxo.png").exists());
}
