//! Malformed scene files, each with the one exact error it must give: the file,
//! the place (line:column) and what was expected.

use std::path::Path;

use lamplight_scene::build::SceneFile;

const CAMERA: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n";

/// Parses and builds `text` as `s.toml`, returning the error message.
fn error(text: &str) -> String {
    let path = Path::new("s.toml");
    match SceneFile::parse(path, text).and_then(|f| f.settings().and_then(|_| f.build())) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn with_camera(rest: &str) -> String {
    format!("{CAMERA}{rest}")
}

#[test]
fn malformed_inputs_give_their_exact_errors() {
    let huge =
        format!("{CAMERA}[meshes.m]\npositions = [[0,0,0]]\nindices = [[0, 1, 4000000000]]\n[[objects]]\ntype = \"mesh\"\nmesh = \"m\"\n");
    let cases: Vec<(String, &str)> = vec![
        ("".into(), "s.toml: is empty, expected a scene (at least a [camera] table)"),
        (" \n\t\n".into(), "s.toml: is empty, expected a scene (at least a [camera] table)"),
        ("# only a comment\n".into(), "s.toml: has no [camera] table, expected one"),
        ("[camera\n".into(), "s.toml:1:8: unclosed table, expected `]`"),
        ("[camera]\neye = [0, 0, 0\n".into(), "s.toml:2:15: unclosed array, expected `]`"),
        ("ambient = 1\n".into(), "s.toml: has no [camera] table, expected one"),
        (format!("colour = 1\n{CAMERA}"), "s.toml:1:1: unknown field `colour`, expected one of `ambient`, `background`, `render`, `camera`, `materials`, `meshes`, `definitions`, `objects`"),
        (with_camera("colour = 1\n"), "s.toml:5:1: unknown field `colour`, expected one of `eye`, `look_at`, `up`, `vfov`, `hfov`, `window_center`, `right`, `pixel_offset`, `fit`"),
        ("[camera]\neye = \"here\"\n".into(), "s.toml:2:7: invalid type: string \"here\", expected an array of length 3"),
        ("[camera]\neye = [0, 0]\n".into(), "s.toml:2:7: invalid length 2, expected an array of length 3"),
        (with_camera("[render]\nwidth = -5\n"), "s.toml:6:9: invalid value: integer `-5`, expected a whole number from 0 to 4294967295"),
        (with_camera("[render]\nmax_depth = 1000\n"), "s.toml:5:1: max_depth must be between 1 and 64, got 1000"),
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [nan, 0, 0]\nradius = 1\n"), "s.toml:5:1: sphere: center must be finite numbers, got [NaN, 0.0, 0.0]"),
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = inf\n"), "s.toml:5:1: sphere: radius must be finite numbers, got [inf]"),
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = -1\n"), "s.toml:5:1: sphere: invalid radius: must be a positive number, got -1"),
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\n"), "s.toml:5:1: sphere: needs `radius`"),
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\naxis = [0, 1, 0]\n"), "s.toml:5:1: sphere: unknown key `axis` for this type (valid keys: type, name, material, center, radius)"),
        (with_camera("[[objects]]\ntype = \"group\"\nchildren = [{ type = \"sphere\", colour = 2 }]\n"), "s.toml:7:32: unknown field `colour`, expected a key of this node type (see docs/scene-format.md)"),
        (with_camera("[[objects]]\ntype = \"sphere\"\nradius = \"big\"\n"), "s.toml:7:10: invalid type: string \"big\", expected a number"),
        (with_camera("[[objects]]\ntype = \"blob\"\n"), "s.toml:5:1: blob: unknown node type (expected one of: group, instance, point_light, directional_light, sphere, ellipsoid, cylinder, cone, infinite_cylinder, infinite_cone, paraboloid, hyperboloid, quadric, plane, rectangle, disk, box, triangle, torus, implicit, mesh)"),
        (with_camera("[[objects]]\ncenter = [0, 0, 0]\n"), "s.toml:5:1: missing field `type`"),
        (with_camera("[[objects]]\ntype = \"sphere\"\nradius = 1\ncenter = [0, 0, 0]\nmaterial = \"gold\"\n"), "s.toml:5:1: sphere: unknown material \"gold\" (materials: none defined)"),
        (with_camera("[materials.m]\ncolor = -1\n"), "s.toml:5:1: material \"m\": invalid color: must be finite and non-negative, got [-1, -1, -1]"),
        (with_camera("[materials.m]\nroughness = 1.5\n"), "s.toml:5:1: material \"m\": invalid roughness: must be between 0 and 1, got 1.5"),
        (with_camera("[materials.m]\nreflection = { type = \"mirror\" }\n"), "s.toml:6:23: unknown variant `mirror`, expected one of `constant`, `dielectric`, `conductor`"),
        (with_camera("[definitions.a]\ntype = \"instance\"\nof = \"a\"\n[[objects]]\ntype = \"instance\"\nof = \"a\"\n"), "s.toml:5:1: instance: cyclic instance: a -> a"),
        (with_camera("[[objects]]\ntype = \"instance\"\nof = \"nothing\"\n"), "s.toml:5:1: instance: unknown definition \"nothing\" (definitions: none defined)"),
        (with_camera("[meshes.m]\nfile = \"missing.obj\"\n[[objects]]\ntype = \"mesh\"\nmesh = \"m\"\n"), "s.toml:5:1: mesh \"m\": file \"missing.obj\" not found (looked for missing.obj)"),
        (huge, "s.toml:5:1: mesh \"m\": invalid indices: face 0 refers to vertex 1, but there are only 1 vertices"),
        (with_camera("[[objects]]\ntype = \"implicit\"\nexpression = \"x*x + y*y + z*z - w\"\nmin = [-1, -1, -1]\nmax = [1, 1, 1]\nlipschitz = 4\n"), "s.toml:5:1: implicit: expression, at character 19: unknown name 'w' (variables: x, y, z; constants: pi, e; functions: sin, cos, tan, sqrt, abs, exp, ln, min, max, pow)"),
        (with_camera("[[objects]]\ntype = \"group\"\nscale = 0\n"), "s.toml:5:1: group: scale must not be 0 (it would flatten the geometry)"),
        (with_camera("[[objects]]\ntype = \"point_light\"\nposition = [0, 0, 0]\nintensity = 1\nown_object = \"bulb\"\n"), "s.toml:5:1: point_light: own_object \"bulb\" names no shape"),
        ("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 5]\nvfov = 40\n".into(), "s.toml:1:1: camera: invalid camera: eye and lookat coincide"),
    ];
    let mut failures = Vec::new();
    for (text, expected) in &cases {
        let got = error(text);
        if got != *expected {
            failures.push(format!("input:\n{text}\n  expected: {expected}\n  got:      {got}"));
        }
        assert!(!got.contains('\n'), "one line: {got}");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn file_level_problems_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("none.toml");
    assert_eq!(SceneFile::read(&missing).unwrap_err().to_string(), format!("{}: no such file", missing.display()));
    assert_eq!(
        SceneFile::read(dir.path()).unwrap_err().to_string(),
        format!("{}: is a directory, expected a scene file", dir.path().display())
    );
    let binary = dir.path().join("bin.toml");
    std::fs::write(&binary, b"[camera]\n\xff\xfe").unwrap();
    assert_eq!(SceneFile::read(&binary).unwrap_err().to_string(), format!("{}:2:1: invalid UTF-8, expected a text file", binary.display()));
    // A file larger than any scene needs is refused before it is read.
    let large = dir.path().join("large.toml");
    let file = std::fs::File::create(&large).unwrap();
    file.set_len(lamplight_scene::formats::native::MAX_FILE_BYTES + 1).unwrap();
    assert_eq!(
        SceneFile::read(&large).unwrap_err().to_string(),
        format!("{}: is 16777217 bytes, larger than the 16777216 bytes a scene file may have", large.display())
    );
}

#[test]
fn exponential_instancing_is_stopped() {
    // Each definition places the next one twice: 2^30 spheres if nothing stopped it.
    let mut text = with_camera("[[objects]]\ntype = \"instance\"\nof = \"d0\"\n");
    for i in 0..30 {
        text += &format!("[definitions.d{i}]\ntype = \"group\"\nchildren = [{{ type = \"instance\", of = \"d{0}\" }}, {{ type = \"instance\", of = \"d{0}\", translate = [1, 0, 0] }}]\n", i + 1);
    }
    text += "[definitions.d30]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n";
    let err = error(&text);
    assert_eq!(err, "s.toml:5:1: instance: expands to more than 4194304 objects (is a definition instanced exponentially?)");
}
