//! Malformed scene files, each with the one exact error it must give: the file,
//! the place (line:column) and what was expected.

use std::path::Path;

use lamplight_scene::instantiate::SceneFile;

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
        (format!("colour = 1\n{CAMERA}"), "s.toml:1:1: scene: unknown key 'colour' (the top level takes: ambient, background, environment, render, animation, camera, materials, meshes, definitions, objects)"),
        (with_camera("colour = 1\n"), "s.toml:5:1: camera: unknown parameter 'colour' (it takes: eye, look_at, up, vfov, hfov, fov, pixel_offset, shift)"),
        ("[camera]\neye = \"here\"\n".into(), "s.toml:2:7: camera: eye: expected [x, y, z], got a string \"here\""),
        ("[camera]\neye = [0, 0]\n".into(), "s.toml:2:7: camera: eye: expected [x, y, z], got an array of 2"),
        (with_camera("[render]\nwidth = -5\n"), "s.toml:6:9: render: width: must be between 0 and 4294967295, got -5"),
        (with_camera("[render]\nmax_depth = 1000\n"), "s.toml:6:13: render: max_depth: must be between 1 and 64, got 1000"),
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [nan, 0, 0]\nradius = 1\n"), "s.toml:7:10: sphere: center: must be finite numbers, got [NaN, 0, 0]"),
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = inf\n"), "s.toml:8:10: sphere: radius: must be a finite number, got inf"),
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = -1\n"), "s.toml:8:10: sphere: invalid radius: must be a positive number, got -1"),
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\n"), "s.toml:5:1: sphere: needs `radius` (a number)"),
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\naxis = [0, 1, 0]\n"), "s.toml:9:1: sphere: unknown parameter 'axis' (it takes: center, radius, material, flip_normals)"),
        (with_camera("[[objects]]\ntype = \"group\"\nchildren = [{ type = \"sphere\", colour = 2 }]\n"), "s.toml:7:32: sphere: unknown parameter 'colour' (it takes: center, radius, material, flip_normals)"),
        (with_camera("[[objects]]\ntype = \"sphere\"\nradius = \"big\"\n"), "s.toml:7:10: sphere: radius: expected a number, got a string \"big\""),
        (with_camera("[[objects]]\ncenter = [0, 0, 0]\n"), "s.toml:5:1: objects[0]: needs `type` (a string naming what the node is)"),
        (with_camera("[[objects]]\ntype = \"sphere\"\nradius = 1\ncenter = [0, 0, 0]\nmaterial = \"gold\"\n"), "s.toml:9:12: sphere: material: unknown material \"gold\" (materials: none defined)"),
        (with_camera("[materials.m]\ncolor = -1\n"), "s.toml:6:9: material \"m\": invalid color: must be finite and non-negative, got [-1, -1, -1]"),
        (with_camera("[materials.m]\nroughness = 1.5\n"), "s.toml:6:13: material \"m\": invalid roughness: must be between 0 and 1, got 1.5"),
        (with_camera("[materials.m]\nreflection = { type = \"mirror\" }\n"), "s.toml:6:23: material \"m\": reflection: type: unknown value \"mirror\" (values: constant, dielectric, conductor)"),
        (with_camera("[definitions.a]\ntype = \"instance\"\nof = \"a\"\n[[objects]]\ntype = \"instance\"\nof = \"a\"\n"), "s.toml:5:1: instance: cyclic instance: a -> a"),
        (with_camera("[[objects]]\ntype = \"instance\"\nof = \"nothing\"\n"), "s.toml:7:6: instance: of: unknown definition \"nothing\" (definitions: none defined)"),
        (with_camera("[meshes.m]\nfile = \"missing.obj\"\n[[objects]]\ntype = \"mesh\"\nmesh = \"m\"\n"), "s.toml:6:8: mesh \"m\": file \"missing.obj\" not found (looked for missing.obj)"),
        (huge, "s.toml:5:1: mesh \"m\": invalid indices: face 0 refers to vertex 1, but there are only 1 vertices"),
        (with_camera("[[objects]]\ntype = \"implicit\"\nexpression = \"x*x + y*y + z*z - w\"\nmin = [-1, -1, -1]\nmax = [1, 1, 1]\nlipschitz = 4\n"), "s.toml:7:14: implicit: expression: at character 19: unknown name 'w' (variables: x, y, z; constants: pi, e; functions: sin, cos, tan, sqrt, abs, exp, ln, min, max, pow)"),
        (with_camera("[[objects]]\ntype = \"group\"\nscale = 0\n"), "s.toml:7:9: group: scale: must not be 0 (it would flatten the geometry)"),
        (with_camera("[[objects]]\ntype = \"point_light\"\nposition = [0, 0, 0]\nintensity = 1\nown_object = \"bulb\"\n"), "s.toml:9:14: point_light: own_object: \"bulb\" names no shape"),
        ("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 5]\nvfov = 40\n".into(), "s.toml:1:1: camera: invalid camera: eye and lookat coincide"),
        // Issue 12: extras are refused, not dropped, with the text Python dicts get.
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0, 0]\nradius = 1\n"), "s.toml:7:10: sphere: center: expected [x, y, z], got an array of 4"),
        ("[camera]\neye = [0, 0, 5, 123]\nlook_at = [0, 0, 0]\nvfov = 40\n".into(), "s.toml:2:7: camera: eye: expected [x, y, z], got an array of 4"),
        ("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0, \"junk\", true]\nvfov = 40\n".into(), "s.toml:3:11: camera: look_at: expected [x, y, z], got an array of 5"),
        (with_camera("[[objects]]\ntype = \"quadric\"\nmatrix = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -1], [0, 0, 0, 0]]\n"), "s.toml:7:10: quadric: matrix: expected 4 rows of 4 numbers, got an array of 5"),
        (with_camera("[[objects]]\ntype = \"quadric\"\nmatrix = [[1, 0, 0, 0, 9], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -1]]\n"), "s.toml:7:10: quadric: matrix: expected 4 rows of 4 numbers, got an array of 4"),
        (with_camera("[[objects]]\ntype = \"triangle\"\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]\n"), "s.toml:7:12: triangle: vertices: expected 3 points, got 4"),
        // Issue 12: messages that say what is wrong, where.
        ("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nup = [0, 0, 0]\nvfov = 40\n".into(), "s.toml:4:6: camera: invalid up: is the zero vector [0, 0, 0], expected a direction"),
        (with_camera("[meshes.m]\nfile = \"\"\n[[objects]]\ntype = \"mesh\"\nmesh = \"m\"\n"), "s.toml:6:8: mesh \"m\": file: the path is empty, expected a mesh file"),
        (with_camera("[meshes.m]\nfile = \"s.toml\"\n[[objects]]\ntype = \"mesh\"\nmesh = \"m\"\n"), "s.toml:6:8: mesh \"m\": file \"s.toml\" not found (looked for s.toml)"),
        (with_camera("ambient = 1\nambient = 2\n"), "s.toml:6:1: duplicate key `ambient`, expected each key once per table"),
        (with_camera("[materials.m]\nkd = 1\nkd = 2\n"), "s.toml:7:1: duplicate key `kd`, expected each key once per table"),
        // Issue 12: ranges that are reversed or outside what the quantity allows.
        (with_camera("[[objects]]\ntype = \"implicit\"\nexpression = \"x*x + y*y + z*z - 1\"\nmin = [1, 1, 1]\nmax = [-1, -1, -1]\nlipschitz = 4\n"), "s.toml:9:7: implicit: max: min [1, 1, 1] must be below max [-1, -1, -1] on every axis"),
        (with_camera("[materials.m]\nreflection = { type = \"dielectric\", ior = 1.5, min = 2, max = -1 }\n"), "s.toml:6:54: material \"m\": reflection: min: must be between 0 and 1, got 2"),
        (with_camera("[materials.m]\nreflection = { type = \"dielectric\", ior = 1.5, min = 0.5, max = 0.25 }\n"), "s.toml:6:65: material \"m\": reflection: max: must be between min (0.5) and 1, got 0.25"),
        // Issue 12: bounded work per ray; issue 26: only inputs that overflow an f32 on their own
        // are refused (a scene scaled by 1e6 needs intensities of 1e12 and more).
        (with_camera("[[objects]]\ntype = \"implicit\"\nexpression = \"x*x + y*y + z*z - 1\"\nmin = [-1, -1, -1]\nmax = [1, 1, 1]\nlipschitz = 1e30\nmax_steps = 4294967295\n"), "s.toml:11:13: implicit: max_steps: must be between 1 and 65536, got 4294967295"),
        (with_camera("[[objects]]\ntype = \"point_light\"\nposition = [0, 0, 3]\nintensity = 1e300\n"), "s.toml:8:13: point_light: intensity: must be at most 3.4028235e38 in magnitude (f32's largest), got [1e300, 1e300, 1e300]"),
        (with_camera("[materials.e]\nemission = 1e39\n"), "s.toml:6:12: material \"e\": emission: must be at most 3.4028235e38 in magnitude (f32's largest), got [1e39, 1e39, 1e39]"),
        (with_camera("[materials.e]\ncolor = [1, 4e38, 0]\n"), "s.toml:6:9: material \"e\": color: must be at most 3.4028235e38 in magnitude (f32's largest), got [1, 4e38, 0]"),
        (format!("ambient = -1e39\n{CAMERA}"), "s.toml:1:11: scene: ambient: must be at most 3.4028235e38 in magnitude (f32's largest), got [-1e39, -1e39, -1e39]"),
        (with_camera("[[objects]]\ntype = \"group\"\nscale = [1, 1, 1e39]\n"), "s.toml:7:9: group: scale: must be at most 3.4028235e38 in magnitude (f32's largest), got [1, 1, 1e39]"),
        // Issue 26: a signed-distance grid's size is checked before its values are read.
        (with_camera("[[objects]]\ntype = \"sdfgrid\"\nresolution = [4096, 4096, 4096]\nvalues = []\n"), "s.toml:7:14: sdfgrid: resolution: 4096 x 4096 x 4096 = 68719476736 samples, expected at most 4194304"),
        (with_camera("[[objects]]\ntype = \"sdfgrid\"\nresolution = [2, 2, 1]\nvalues = [1, -1]\n"), "s.toml:7:14: sdfgrid: resolution: expected [nx, ny, nz] of whole numbers of at least 2, got an array of 3"),
        (with_camera("[[objects]]\ntype = \"sdfgrid\"\nresolution = [2, 2, 2]\nvalues = [1, -1]\n"), "s.toml:8:10: sdfgrid: values: has 2 numbers, expected nx ny nz = 8"),
        (with_camera("[[objects]]\ntype = \"sdfgrid\"\nresolution = [2, 2, 2]\nvalues = [1, -1, 1, 1, 1, 1, 1, 1e39]\n"), "s.toml:8:33: sdfgrid: values[7]: expected a finite number, got 1e39"),
        (format!("ambient = nan\n{CAMERA}"), "s.toml:1:11: scene: ambient: must be finite numbers, got [NaN, NaN, NaN]"),
        (format!("{CAMERA}a{} = 1\n", ".a".repeat(10_000)), "s.toml:5:130: nested more than 64 levels deep (tables, arrays and dotted keys together), expected at most 64"),
        (format!("{CAMERA}x = {}\n", "[".repeat(10_000)), "s.toml:5:69: nested more than 64 levels deep (tables, arrays and dotted keys together), expected at most 64"),
    ];
    // The list of node types comes from the registry, so a new kind changes no test.
    let blob = format!("s.toml:6:8: blob: unknown node type (node types: {})", lamplight_scene::registry::node_types().join(", "));
    let cases: Vec<(String, &str)> = cases.into_iter().chain([(with_camera("[[objects]]\ntype = \"blob\"\n"), blob.as_str())]).collect();
    // The lists of kinds come from the registry, so a new kind changes no test.
    let names = |kinds: Vec<&str>| kinds.join(", ");
    let textures = names(lamplight_scene::registry::TEXTURES.iter().map(|k| k.name).collect());
    let materials = names(lamplight_scene::registry::MATERIALS.iter().map(|k| k.name).collect());
    let mut failures = Vec::new();
    for (text, expected) in &cases {
        let expected = expected.replace("{TEXTURES}", &textures).replace("{MATERIALS}", &materials);
        let got = error(text);
        if got != expected {
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
    // A link to a device and a FIFO would be read forever or block: refused at once.
    #[cfg(unix)]
    {
        let zero = dir.path().join("z.toml");
        std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
        let expected = format!("{}: is a device, expected a scene file", zero.display());
        assert_eq!(SceneFile::read(&zero).unwrap_err().to_string(), expected);
        let fifo = dir.path().join("f.toml");
        if std::process::Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success()) {
            let expected = format!("{}: is a FIFO, expected a scene file", fifo.display());
            assert_eq!(SceneFile::read(&fifo).unwrap_err().to_string(), expected);
        }
    }
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

/// `name` with a letter added in the middle: a typo the suggestion must undo.
fn mistyped(name: &str) -> String {
    let mid = name.len().div_ceil(2);
    format!("{}q{}", &name[..mid], &name[mid..])
}

#[test]
fn no_node_kind_names_a_parameter_like_a_key_every_node_has() {
    // A node's transform keys and structure are taken before its kind reads its
    // parameters, so a parameter of the same name would never be read.
    use lamplight_scene::registry;
    let node_keys: Vec<&str> = lamplight_scene::description::TRANSFORM_KEYS.iter().copied().chain(["type", "name"]).collect();
    let kinds = registry::SHAPES
        .iter()
        .map(|k| (k.name, k.params))
        .chain(registry::LIGHTS.iter().map(|k| (k.name, k.params)))
        .chain(registry::STRUCTURAL.iter().map(|s| (s.name, s.params)));
    let clashes: Vec<String> = kinds
        .flat_map(|(name, params)| params.iter().filter(|p| node_keys.contains(&p.name)).map(move |p| format!("{name}: {}", p.name)))
        .collect();
    assert!(clashes.is_empty(), "parameters named like node keys: {clashes:?}");
}

#[test]
fn every_registered_kind_reports_a_mistyped_parameter_at_its_key() {
    use lamplight_scene::registry;
    // (label in the message, scene text, the line and column of the mistyped key, the key)
    let mut cases: Vec<(String, String, (usize, usize), &str)> = Vec::new();
    let node_kinds = registry::SHAPES
        .iter()
        .map(|k| (k.name, k.params))
        .chain(registry::LIGHTS.iter().map(|k| (k.name, k.params)))
        .chain(registry::STRUCTURAL.iter().map(|s| (s.name, s.params)));
    for (name, params) in node_kinds {
        let key = params[0].name;
        cases.push((name.into(), with_camera(&format!("[[objects]]\ntype = \"{name}\"\n{} = 1\n", mistyped(key))), (7, 1), key));
    }
    for k in registry::MATERIALS {
        let key = k.params[0].name;
        let text = with_camera(&format!("[materials.m]\ntype = \"{}\"\n{} = 1\n", k.name, mistyped(key)));
        cases.push(("material \"m\"".into(), text, (7, 1), key));
    }
    // A kind without parameters (`vertex_color`) has no key to mistype.
    for k in registry::TEXTURES.iter().filter(|k| !k.params.is_empty()) {
        let key = k.params[0].name;
        let text = with_camera(&format!("[materials.m]\ncolor = {{ type = \"{}\", {} = 1 }}\n", k.name, mistyped(key)));
        let column = "color = { type = \"\", ".len() + k.name.len() + 1;
        cases.push(("material \"m\": color".into(), text, (6, column), key));
    }
    for k in registry::CAMERAS {
        let (name, key) = (k.name, k.params[1].name);
        let text = format!("[camera]\ntype = \"{name}\"\n{} = 1\n", mistyped(key));
        cases.push(("camera".into(), text, (3, 1), key));
    }
    let key = lamplight_scene::instantiate::RENDER_PARAMS[2].name;
    cases.push(("render".into(), with_camera(&format!("[render]\n{} = 1\n", mistyped(key))), (6, 1), key));
    assert!(cases.len() > 20, "every kind is covered: {}", cases.len());
    let mut failures = Vec::new();
    for (label, text, (line, column), key) in &cases {
        let expected = format!("s.toml:{line}:{column}: {label}: unknown parameter '{}' (did you mean '{key}'?)", mistyped(key));
        let got = error(text);
        if got != expected {
            failures.push(format!("  expected: {expected}\n  got:      {got}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn wrong_types_say_what_was_expected_at_the_key() {
    let cases: Vec<(String, &str)> = vec![
        (with_camera("[[objects]]\ntype = \"group\"\nrotate = \"left\"\n"), "s.toml:7:10: group: rotate: expected a table { axis = [x, y, z], degrees = N }, { x = N, y = N, z = N } or { quaternion = [x, y, z, w] }, or [x, y, z] degrees, got a string \"left\""),
        (with_camera("[[objects]]\ntype = \"group\"\nrotate = { axis = [0, 1, 0], degree = 3 }\n"), "s.toml:7:30: group: rotate: unknown parameter 'degree' (did you mean 'degrees'?)"),
        (with_camera("[[objects]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = 1\n"), "s.toml:8:7: box: max: expected [x, y, z], got a number 1"),
        (with_camera("[[objects]]\ntype = \"cylinder\"\nfrom = [0, 0, 0]\nto = [0, 1, 0]\nradius = 1\ncaps = 1\n"), "s.toml:10:8: cylinder: caps: expected true or false, got a number 1"),
        (with_camera("[[objects]]\ntype = \"point_light\"\nposition = [0, 0, 0]\nintensity = [1, 2]\n"), "s.toml:8:13: point_light: intensity: expected a number or [r, g, b], got an array of 2"),
        (with_camera("[materials.m]\ncolor = { type = \"checkers\" }\n"), "s.toml:6:18: material \"m\": color: type: unknown texture \"checkers\" (did you mean 'checker'? textures: {TEXTURES})"),
        (with_camera("[materials.m]\nreflection = { type = \"conductor\", metal = \"glod\" }\n"), "s.toml:6:44: material \"m\": reflection: metal: unknown metal \"glod\" (did you mean 'gold'? metals: gold, silver, copper, aluminium)"),
        (with_camera("[materials.m]\ntype = \"phongg\"\n"), "s.toml:6:8: material \"m\": unknown material type \"phongg\" (did you mean 'phong'? material types: {MATERIALS})"),
        (with_camera("[[objects]]\ntype = \"spher\"\n"), "s.toml:6:8: spher: unknown node type (did you mean 'sphere'?)"),
        (with_camera("[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nchildren = []\n"), "s.toml:5:1: sphere: takes no `children` (only a group does)"),
    ];
    // The lists of kinds come from the registry, so a new kind changes no test.
    let names = |kinds: Vec<&str>| kinds.join(", ");
    let textures = names(lamplight_scene::registry::TEXTURES.iter().map(|k| k.name).collect());
    let materials = names(lamplight_scene::registry::MATERIALS.iter().map(|k| k.name).collect());
    let mut failures = Vec::new();
    for (text, expected) in &cases {
        let expected = expected.replace("{TEXTURES}", &textures).replace("{MATERIALS}", &materials);
        let got = error(text);
        if got != expected {
            failures.push(format!("input:\n{text}\n  expected: {expected}\n  got:      {got}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn rotate_takes_an_array_of_degrees() {
    let text = with_camera(
        "[[objects]]\ntype = \"group\"\nrotate = [0, 25, 0]\nchildren = [{ type = \"sphere\", center = [1, 0, 0], radius = 0.5 }]\n",
    );
    let scene = SceneFile::parse(Path::new("s.toml"), &text).unwrap().build().unwrap();
    let expected = lamplight_core::math::Mat4::from_rotation_y(25f64.to_radians()).transform_point3(lamplight_core::math::Vec3::X);
    let centre = scene.objects[0].shape.bounds().centroid();
    assert!((centre - expected).length() < 1e-12, "{centre} vs {expected}");
}

/// 4 KiB of seeded pseudo-random bytes (the renderer's own generator).
fn random_bytes(seed: u64) -> Vec<u8> {
    let mut rng = lamplight_core::sampling::Rng::for_sample(seed, 0, 0);
    (0..4096).map(|_| (rng.next_u64() >> 56) as u8).collect()
}

#[test]
fn mesh_files_that_are_not_meshes_are_refused_at_their_key_with_the_importers_text() {
    // See: issue 12 ("Garbage meshes", "a mesh path that is the scene file itself").
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let garbage = d.join("garbage.obj");
    std::fs::write(&garbage, random_bytes(12)).unwrap();
    let alone = lamplight_scene::import::load(&garbage).unwrap_err().to_string();
    assert_eq!(alone, format!("{}: has no triangles, expected a mesh", garbage.display()));
    let scene = |file: &str| with_camera(&format!("[meshes.m]\nfile = \"{file}\"\n[[objects]]\ntype = \"mesh\"\nmesh = \"m\"\n"));
    let path = d.join("s.toml");
    std::fs::write(&path, scene("garbage.obj")).unwrap();
    let err = SceneFile::read(&path).and_then(|f| f.build()).unwrap_err().to_string();
    assert_eq!(err, format!("{}:6:8: mesh \"m\": {alone}", path.display()), "the same bytes, the same text, at the key");
    std::fs::write(&path, scene("s.toml")).unwrap();
    let err = SceneFile::read(&path).and_then(|f| f.build()).unwrap_err().to_string();
    assert_eq!(err, format!("{0}:6:8: mesh \"m\": {0}: cannot read .toml files (supported: obj, ply, gltf, glb)", path.display()));
    // A PLY header with no faces, and an OBJ of points only: no triangles either.
    let ply = d.join("empty.ply");
    std::fs::write(
        &ply,
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
    )
    .unwrap();
    assert_eq!(
        lamplight_scene::import::load(&ply).unwrap_err().to_string(),
        format!("{}: has no triangles, expected a mesh", ply.display())
    );
    let obj = d.join("points.obj");
    std::fs::write(&obj, "v 0 0 0\nv 1 0 0\np 1 2\n").unwrap();
    assert_eq!(
        lamplight_scene::import::load(&obj).unwrap_err().to_string(),
        format!("{}: has no triangles, expected a mesh", obj.display())
    );
}
