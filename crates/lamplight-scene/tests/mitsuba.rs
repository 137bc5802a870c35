//! Mitsuba 3 XML scenes without Mitsuba: structure, parameters, transforms,
//! exact error messages at line:col, and renders equal to the TOML they mean.

use std::path::{Path, PathBuf};

use lamplight_core::params::{Table, Value};
use lamplight_core::RenderControl;
use lamplight_scene::formats::mitsuba;
use lamplight_scene::request::{Naming, Request, SceneRequest};

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A scene of a camera, `body` and a film of 16 x 12.
fn scene(body: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <default name="spp" value="4"/>
    <integrator type="path"><integer name="max_depth" value="4"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="0, 1, 5" target="0, 0.5, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="12"/><rfilter type="box"/></film>
    </sensor>
{body}
</scene>
"#
    )
}

const BODY: &str = r#"    <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.8, 0.2, 0.1"/></bsdf>
    <shape type="sphere"><point name="center" value="0, 0.5, 0"/><float name="radius" value="0.5"/><ref id="red"/></shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate y="2"/></transform>
        <emitter type="area"><rgb name="radiance" value="10"/></emitter>
    </shape>
    <emitter type="point"><point name="position" value="1, 2, 1"/><float name="intensity" value="2.5"/></emitter>
"#;

/// The error of reading `text`, with the folder stripped.
fn error(text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "s.xml", text);
    match mitsuba::read(&path, &[]) {
        Ok(_) => panic!("read but should fail:\n{text}"),
        Err(e) => e.to_string().replace(&format!("{}/", dir.path().display()), ""),
    }
}

fn table(text: &str, defines: &[(&str, &str)]) -> (Table, Vec<String>) {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "s.xml", text);
    let defines: Vec<(String, String)> = defines.iter().map(|(a, b)| (a.to_string(), b.to_string())).collect();
    let (t, source) = mitsuba::read_table(&path, &defines).unwrap();
    let warnings = source.warnings.iter().map(|w| w.replace(&format!("{}/", dir.path().display()), "")).collect();
    (t, warnings)
}

fn get<'a>(t: &'a Table, path: &[&str]) -> &'a Value {
    let mut v = &t.get(path[0]).unwrap_or_else(|| panic!("no {}", path[0])).item.value;
    for key in &path[1..] {
        v = match v {
            Value::Table(t) => &t.get(key).unwrap_or_else(|| panic!("no {key}")).item.value,
            Value::Array(items) => &items[key.parse::<usize>().unwrap()].value,
            _ => panic!("{key}: not a table"),
        };
    }
    v
}

fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Number(n) => vec![*n],
        Value::Integer(i) => vec![*i as f64],
        Value::Array(items) => items.iter().flat_map(|i| numbers(&i.value)).collect(),
        other => panic!("not numbers: {other:?}"),
    }
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
}

/// Renders `path` as `lamplight render` would, and returns the sRGB bytes.
fn render(path: &Path, defines: &[(String, String)]) -> Vec<u8> {
    let scene = SceneRequest::resolve_with(path.to_str().unwrap(), defines).unwrap();
    let job = Request { threads: Some(2), ..Request::default() }.resolve(&scene.defaults, Naming::Flags).unwrap();
    let built = scene.build().unwrap();
    job.run(&built, &RenderControl::default()).unwrap().image.to_srgb8()
}

#[test]
fn a_small_xml_renders_as_the_toml_it_means() {
    let dir = tempfile::tempdir().unwrap();
    let xml = write(dir.path(), "s.xml", &scene(BODY));
    let pi = std::f64::consts::PI;
    let toml = format!(
        r#"[render]
integrator = "path"
max_depth = 4
width = 16
height = 12
filter = "box"
spp = 4

[camera]
eye = [0, 1, 5]
look_at = [0, 0.9, 4.0]
up = [0, 1, 0]
hfov = 45

[materials.red]
color = [0.8, 0.2, 0.1]
kd = 1
ka = 0
ks = 0

[materials.light]
color = 0
kd = 1
ka = 0
ks = 0
emission = 10

[[objects]]
type = "sphere"
center = [0, 0.5, 0]
radius = 0.5
material = "red"

[[objects]]
type = "rectangle"
corner = [-1, 1, 0]
edge_u = [2, 0, 0]
edge_v = [0, -2, 0]
flip_normals = true
matrix = [[0.5, 0, 0, 0], [0, {c}, -0.5, 2], [0, 0.5, {c}, 0], [0, 0, 0, 1]]
material = "light"

[[objects]]
type = "point_light"
position = [1, 2, 1]
intensity = {i}
"#,
        c = 0.5 * (pi / 2.0).cos(),
        i = 2.5 / pi
    );
    let toml = write(dir.path(), "s.toml", &toml);
    // The camera's look_at differs (0.9 vs the normalized direction); compare the
    // renders, which depend only on the direction.
    let (a, b) = (render(&xml, &[]), render(&toml, &[]));
    assert_eq!(a.len(), 16 * 12 * 3);
    assert_eq!(a, b, "the XML and the TOML it means render to the same bytes");
}

#[test]
fn convert_writes_toml_that_renders_to_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let xml = write(dir.path(), "s.xml", &scene(BODY));
    let out = dir.path().join("s.toml");
    let converted = lamplight_scene::convert::convert(&xml, &out, &[]).unwrap();
    std::fs::write(&out, &converted.toml).unwrap();
    assert!(converted.toml.starts_with("# Converted from"));
    assert_eq!(render(&xml, &[]), render(&out, &[]));
    // -D reaches the converted file too.
    let d = vec![("spp".to_string(), "2".to_string())];
    let converted = lamplight_scene::convert::convert(&xml, &out, &d).unwrap();
    assert!(converted.toml.contains("spp = 2\n"), "{}", converted.toml);
}

#[test]
fn defaults_are_replaced_by_defines() {
    let (t, _) = table(&scene(BODY), &[]);
    assert_eq!(numbers(get(&t, &["render", "spp"])), [4.0]);
    let (t, _) = table(&scene(BODY), &[("spp", "64")]);
    assert_eq!(numbers(get(&t, &["render", "spp"])), [64.0]);
}

#[test]
fn transforms_compose_in_mitsubas_order() {
    // scale 2, then rotate 90 about z, then translate x 1: p -> T R S p.
    let body = r#"<shape type="sphere"><transform name="to_world">
        <scale value="2"/><rotate z="1" angle="90"/><translate x="1"/></transform></shape>
    <shape type="sphere"><transform name="to_world"><matrix value="1 0 0 4  0 1 0 5  0 0 1 6  0 0 0 1"/></transform></shape>
    <shape type="sphere"><transform name="to_world"><rotate value="0, 0, 2" angle="90"/><scale x="3"/></transform></shape>"#;
    let (t, _) = table(&scene(body), &[]);
    let m = numbers(get(&t, &["objects", "0", "matrix"]));
    let expected = [0.0, -2.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 1.0];
    assert!(m.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-12), "{m:?}");
    let m = numbers(get(&t, &["objects", "1", "matrix"]));
    assert!(close(&m, &[1.0, 0.0, 0.0, 4.0, 0.0, 1.0, 0.0, 5.0, 0.0, 0.0, 1.0, 6.0, 0.0, 0.0, 0.0, 1.0]), "{m:?}");
    // Rotate about a non-unit z axis (normalized), then scale x by 3: S R.
    let m = numbers(get(&t, &["objects", "2", "matrix"]));
    let expected = [0.0, -3.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];
    assert!(m.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-12), "{m:?}");
    // lookat: eye at the origin of the matrix, looking down its +z.
    let eye = numbers(get(&t, &["camera", "eye"]));
    let look = numbers(get(&t, &["camera", "look_at"]));
    let d = [look[0] - eye[0], look[1] - eye[1], look[2] - eye[2]];
    let n = (0.25f64 + 25.0).sqrt();
    assert!(close(&eye, &[0.0, 1.0, 5.0]) && close(&d, &[0.0, -0.5 / n, -5.0 / n]), "{eye:?} {d:?}");
}

#[test]
fn fov_axes_and_mirrors_map_to_the_camera() {
    let cam = |sensor: &str| {
        let text = scene("").replace(r#"<float name="fov" value="45"/>"#, sensor);
        table(&text, &[]).0
    };
    let t = cam(r#"<float name="fov" value="40"/><string name="fov_axis" value="y"/>"#);
    assert_eq!(numbers(get(&t, &["camera", "vfov"])), [40.0]);
    // Diagonal 50 degrees on 16 x 12: tan(v/2) = tan(25) / sqrt(1 + (4/3)^2) = tan(25) 3/5.
    let t = cam(r#"<float name="fov" value="50"/><string name="fov_axis" value="diagonal"/>"#);
    let v = numbers(get(&t, &["camera", "vfov"]))[0];
    assert!((v - 2.0 * (25f64.to_radians().tan() * 0.6).atan().to_degrees()).abs() < 1e-9, "{v}");
    let t = cam(r#"<float name="fov" value="40"/><string name="fov_axis" value="smaller"/>"#);
    assert_eq!(numbers(get(&t, &["camera", "vfov"])), [40.0], "16 x 12: the smaller axis is y");
    let text = scene("").replace("<lookat", r#"<scale x="-1"/><lookat"#);
    let (t, _) = table(&text, &[]);
    assert_eq!(get(&t, &["camera", "type"]), &Value::String("window".into()));
    let right = numbers(get(&t, &["camera", "right"]));
    assert!(right[0] < 0.0, "mirrored: the image's right is -x, {right:?}");
}

#[test]
fn malformed_and_unsupported_scenes_give_their_exact_errors() {
    let cases: &[(&str, &str)] = &[
        ("<scene version=\"3.0.0\">\n  <shape type=\"sphere\">\n</scene>\n", "s.xml:3:1: malformed XML: expected 'shape' tag, not 'scene'"),
        ("", "s.xml: is empty, expected a Mitsuba scene (<scene version=\"3.0.0\">)"),
        ("<scene version=\"3.0.0\">\n", "s.xml:1:1: malformed XML: the root node was opened but never closed"),
        ("<scene version=\"3.0.0\">\n  <float name=\"x\" value=\"1\"/>\n</scene>\n<x/>", "s.xml:4:1: malformed XML: unknown token"),
        ("<scene>\n</scene>\n", "s.xml:1:1: <scene>: needs the attribute `version` (such as \"3.0.0\")"),
        ("<shape version=\"3.0.0\"/>\n", "s.xml:1:1: expected a <scene> root element, got <shape>"),
        (
            "<scene version=\"3.0.0\">\n  <float name=\"x\" value=\"$nope\"/>\n</scene>\n",
            "s.xml:2:26: undefined parameter $nope (give it with <default name=\"nope\" value=\"...\"/> or -D nope=VALUE)",
        ),
        ("<scene version=\"3.0.0\">\n</scene>\n", "s.xml:1:1: scene: has no <sensor>, expected one (lamplight renders one camera)"),
        (
            "<scene version=\"3.0.0\">\n  <include filename=\"missing.xml\"/>\n</scene>\n",
            "s.xml:2:22: include: no such file \"missing.xml\"",
        ),
    ];
    for (text, expected) in cases {
        assert_eq!(&error(text), expected, "{text}");
    }
    let body_cases: &[(&str, &str)] = &[
        (r#"<shape type="sphere"><bsdf type="velvet"/></shape>"#, "s.xml:10:34: bsdf \"velvet\": unknown BSDF"),
        (r#"<shape type="sphere"><bsdf type="measured"/></shape>"#, "s.xml:10:34: bsdf \"measured\": not yet supported (no lamplight material gives its image)"),
        (r#"<shape type="sphere"><float name="radius" value="big"/></shape>"#, "s.xml:10:50: shape \"sphere\": radius: expected a finite number, got \"big\""),
        (r#"<shape type="sphere"><ref id="nothing"/></shape>"#, "s.xml:10:31: ref: no object has id \"nothing\""),
        (r#"<shape type="sphere"><integer name="radius" value="1"/><integer name="radius" value="2"/></shape>"#, "s.xml:10:71: shape \"sphere\": property \"radius\" is given twice"),
        (r#"<shape type="cube"><transform name="to_world"><scale x="0"/></transform></shape>"#, "s.xml:10:47: shape \"cube\": to_world: scale: must not be 0 (it would flatten the geometry)"),
        (r#"<shape type="sphere"><bsdf type="conductor"><string name="material" value="Xx"/></bsdf></shape>"#, "s.xml:10:76: bsdf \"conductor\": material: unknown conductor \"Xx\" (expected one of none, a-C, Ag, Al, AlAs, AlAs_palik, AlSb, AlSb_palik, Au, Be, Be_palik, Cr, CsI, CsI_palik, Cu, Cu_palik, Cu2O, Cu2O_palik, CuO, CuO_palik, d-C, d-C_palik, Hg, Hg_palik, HgTe, HgTe_palik, Ir, Ir_palik, K, K_palik, Li, Li_palik, MgO, MgO_palik, Mo, Mo_palik, Na_palik, Nb, Nb_palik, Ni_palik, Rh, Rh_palik, Se, Se_palik, SiC, SiC_palik, SnTe, SnTe_palik, Ta, Ta_palik, Te, Te_palik, ThF4, ThF4_palik, TiC, TiC_palik, TiN, TiN_palik, TiO2, TiO2_palik, VC, VC_palik, V_palik, VN, VN_palik, W)"),
        (r#"<emitter type="sunsky"/>"#, "s.xml:10:16: emitter \"sunsky\": not supported (the scene would lose a light)"),
        (r#"<emitter type="projector"/>"#, "s.xml:10:1: emitter \"projector\": needs irradiance (a texture)"),
        (
            r#"<emitter type="projector"><rgb name="irradiance" value="1"/><transform name="to_world"><scale x="-1"/></transform></emitter>"#,
            "s.xml:10:61: emitter \"projector\": a mirroring to_world is not supported",
        ),
        (
            r#"<emitter type="projector"><rgb name="irradiance" value="1"/><float name="fov" value="180"/></emitter>"#,
            "s.xml:10:86: emitter \"projector\": fov: must be between 0 and 180 degrees, got 180",
        ),
    ];
    let wrong: Vec<String> =
        body_cases.iter().filter(|(body, expected)| error(&scene(body)) != *expected).map(|(body, _)| error(&scene(body))).collect();
    assert!(wrong.is_empty(), "unexpected errors:\n{}", wrong.join("\n"));
}

#[test]
fn skipped_parts_are_warnings_at_their_place() {
    let body = r#"<shape type="hair"/>
    <shape type="sphere"><float name="bogus" value="1"/><bsdf type="diffuse"/></shape>
    <medium type="homogeneous"/>"#;
    let (_, warnings) = table(&scene(body), &[]);
    assert_eq!(
        warnings,
        [
            "s.xml:10:14: shape \"hair\": not supported, skipped",
            "s.xml:11:53: shape \"sphere\": property \"bogus\" is not supported, ignored",
            "s.xml:12:5: <medium>: not supported, ignored",
        ]
    );
}

/// A bump-mapped rectangle lit from the side: the height texture and scale of
/// Mitsuba's `bumpmap`.
fn bumped(scale: &str) -> String {
    scene(&format!(
        r#"<emitter type="directional"><vector name="direction" value="1, -0.5, -1"/><rgb name="irradiance" value="2"/></emitter>
    <shape type="rectangle"><bsdf type="bumpmap"><float name="scale" value="{scale}"/>
        <texture name="height" type="checkerboard"><transform name="to_uv"><scale value="3"/></transform></texture>
        <bsdf type="diffuse"/></bsdf></shape>"#
    ))
}

#[test]
fn bumpmap_reads_as_the_nested_bsdf_with_its_bump() {
    let dir = tempfile::tempdir().unwrap();
    let xml = write(dir.path(), "b.xml", &bumped("0.5"));
    let out = dir.path().join("b.toml");
    let converted = lamplight_scene::convert::convert(&xml, &out, &[]).unwrap();
    assert!(converted.toml.contains("bump = { type = \"uv_checker\""), "{}", converted.toml);
    assert!(converted.toml.contains("bump_scale = 0.5\n"), "{}", converted.toml);
    std::fs::write(&out, &converted.toml).unwrap();
    let with_bump = render(&xml, &[]);
    assert_eq!(with_bump, render(&out, &[]), "the XML and its TOML render alike");
    let flat = render(&write(dir.path(), "f.xml", &bumped("0")), &[]);
    assert_ne!(with_bump, flat, "the bump changes the shading");
    let (_, warnings) = table(&bumped("0.5"), &[]);
    assert!(warnings.is_empty(), "{warnings:?}");
    let two = bumped("1").replace("<bsdf type=\"diffuse\"/>", "<texture type=\"checkerboard\"/><bsdf type=\"diffuse\"/>");
    assert_eq!(error(&two), "s.xml:13:9: bsdf \"bumpmap\": expected one nested <texture> (the height)");
}

#[test]
fn includes_paths_and_old_names_are_read() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("parts")).unwrap();
    write(
        &dir.path().join("parts"),
        "materials.xml",
        r#"<scene version="3.0.0"><bsdf type="diffuse" id="inc"><rgb name="reflectance" value="$r, 0.5, 0.5"/></bsdf></scene>"#,
    );
    let text = scene(
        r#"<path value="parts"/><default name="r" value="0.25"/><include filename="materials.xml"/>
    <shape type="sphere"><ref id="inc"/></shape>"#,
    );
    let path = write(dir.path(), "s.xml", &text);
    let (t, _) = mitsuba::read_table(&path, &[]).unwrap();
    assert_eq!(numbers(get(&t, &["materials", "inc", "color"])), [0.25, 0.5, 0.5]);
    // Version 0.6 names: fovAxis, sampleCount.
    let old = scene("")
        .replace("3.0.0", "0.6.0")
        .replace("sample_count", "sampleCount")
        .replace(r#"<float name="fov" value="45"/>"#, r#"<float name="fov" value="30"/><string name="fovAxis" value="y"/>"#);
    let (t, _) = table(&old, &[]);
    assert_eq!(numbers(get(&t, &["camera", "vfov"])), [30.0]);
    assert_eq!(numbers(get(&t, &["render", "spp"])), [4.0]);
}

#[test]
fn spectra_become_rgb_as_in_scalar_rgb() {
    let body = r#"<bsdf type="diffuse" id="a"><spectrum name="reflectance" value="0.3"/></bsdf>
    <bsdf type="diffuse" id="b"><spectrum name="reflectance" value="400:0.5, 700:0.5"/></bsdf>
    <shape type="sphere"><ref id="a"/></shape><shape type="sphere"><ref id="b"/></shape>
    <emitter type="point"><spectrum name="intensity" value="3.14159265358979"/></emitter>"#;
    let (t, _) = table(&scene(body), &[]);
    assert_eq!(numbers(get(&t, &["materials", "a", "color"])), [0.3, 0.3, 0.3]);
    let b = numbers(get(&t, &["materials", "b", "color"]));
    assert!(close(&b.iter().map(|v| (v * 1e4).round()).collect::<Vec<_>>(), &[4977.0, 4999.0, 4975.0]), "{b:?}");
    // A flat emission spectrum is not white in sRGB (Mitsuba: 1.20488 0.948229 0.909267).
    let i = numbers(get(&t, &["objects", "2", "intensity"]));
    assert!(i.iter().zip([1.20488, 0.948229, 0.909267]).all(|(a, b)| (a - b).abs() < 2e-4), "{i:?}");
}

#[test]
fn mutated_scenes_never_panic() {
    // A fixed-seed stand-in for the `mitsuba` fuzz target: byte edits and cuts of a
    // whole scene read to a scene or to one error, never a panic.
    let base = scene(BODY).into_bytes();
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let path = Path::new("/nonexistent-lamplight-fuzz/s.xml");
    for _ in 0..400 {
        let mut bytes = base.clone();
        for _ in 0..1 + next() % 4 {
            let at = (next() % bytes.len() as u64) as usize;
            bytes[at] = b"<>/=\"$ 0a-.x"[(next() % 12) as usize];
        }
        if next() % 4 == 0 {
            bytes.truncate((next() % bytes.len() as u64) as usize);
        }
        let Ok(text) = String::from_utf8(bytes) else { continue };
        if let Ok((table, source)) = mitsuba::parse_table(path, text, &[]) {
            if let Ok(description) = lamplight_scene::description::SceneDescription::from_table(table) {
                let file = lamplight_scene::instantiate::SceneFile { description, source };
                let _ = file.build();
            }
        }
    }
}

#[test]
fn one_sided_bsdfs_read_as_front_sided_materials() {
    // Mitsuba's reflecting BSDFs are black from the back; twosided, dielectrics and null are not;
    // wrappers are what they wrap.
    let body = r#"    <bsdf type="diffuse" id="d"/>
    <bsdf type="conductor" id="c"/>
    <bsdf type="twosided" id="t"><bsdf type="diffuse"/></bsdf>
    <bsdf type="dielectric" id="g"/>
    <bsdf type="mask" id="m"><float name="opacity" value="1"/><bsdf type="roughconductor"><string name="distribution" value="ggx"/></bsdf></bsdf>
    <bsdf type="mask" id="mt"><float name="opacity" value="1"/><bsdf type="twosided"><bsdf type="diffuse"/></bsdf></bsdf>
    <bsdf type="null" id="n"/>
"#;
    let shapes: String =
        ["d", "c", "t", "g", "m", "mt", "n"].iter().map(|id| format!("    <shape type=\"sphere\"><ref id=\"{id}\"/></shape>\n")).collect();
    let (t, _) = table(&scene(&format!("{body}{shapes}    <shape type=\"disk\"/>\n")), &[]);
    let materials = t.entries.iter().find(|e| e.key == "materials").expect("materials");
    let Value::Table(materials) = &materials.item.value else { panic!("materials is a table") };
    let sided = |name: &str| -> Option<String> {
        let m = materials.entries.iter().find(|e| e.key == name).unwrap_or_else(|| panic!("no material {name}"));
        let Value::Table(m) = &m.item.value else { panic!("{name} is a table") };
        m.entries.iter().find(|e| e.key == "sided").map(|e| match &e.item.value {
            Value::String(s) => s.clone(),
            other => panic!("{other:?}"),
        })
    };
    for (name, expected) in [
        ("d", Some("front")),
        ("c", Some("front")),
        ("t", None),
        ("g", None),
        ("m", Some("front")),
        ("mt", None),
        ("n", None),
        // The default BSDF of the bare disk: Mitsuba's diffuse 0.5, one-sided too.
        (mitsuba::bsdfs::DEFAULT_MATERIAL, Some("front")),
    ] {
        assert_eq!(sided(name).as_deref(), expected, "material {name}");
    }
}

#[test]
fn hide_emitters_reads_as_the_render_setting() {
    let hidden = scene(BODY).replace(
        r#"<integer name="max_depth" value="4"/>"#,
        r#"<integer name="max_depth" value="4"/><boolean name="hide_emitters" value="true"/>"#,
    );
    let (t, warnings) = table(&hidden, &[]);
    assert!(warnings.is_empty(), "{warnings:?}");
    let render = t.entries.iter().find(|e| e.key == "render").expect("render");
    let Value::Table(render) = &render.item.value else { panic!("render is a table") };
    let hide = render.entries.iter().find(|e| e.key == "hide_emitters").expect("hide_emitters");
    assert!(matches!(hide.item.value, Value::Bool(true)), "{:?}", hide.item.value);
    let (t, _) = table(&scene(BODY), &[]);
    let Value::Table(render) = &t.entries.iter().find(|e| e.key == "render").unwrap().item.value else { panic!() };
    assert!(render.entries.iter().all(|e| e.key != "hide_emitters"));
}

#[test]
fn rr_depth_reaches_the_path_tracer_with_mitsubas_counting_and_default() {
    let rr = |value: Option<&str>| {
        let extra = value.map_or(String::new(), |v| format!(r#"<integer name="rr_depth" value="{v}"/>"#));
        scene(BODY).replace(r#"<integer name="max_depth" value="4"/>"#, &format!(r#"<integer name="max_depth" value="4"/>{extra}"#))
    };
    let read = |text: &str| {
        let (t, _) = table(text, &[]);
        let Value::Table(render) = &t.entries.iter().find(|e| e.key == "render").unwrap().item.value else { panic!() };
        match render.entries.iter().find(|e| e.key == "rr_depth").map(|e| &e.item.value) {
            Some(Value::Integer(i)) => *i,
            other => panic!("{other:?}"),
        }
    };
    assert_eq!(read(&rr(None)), 5, "Mitsuba's default");
    assert_eq!(read(&rr(Some("2"))), 2);
    assert_eq!(read(&rr(Some("1000"))), 64, "past the deepest path it never starts");
    assert_eq!(error(&rr(Some("0"))), "s.xml:3:98: integrator \"path\": rr_depth: must be a positive integer, got 0");
    // Roulette from the first bounce changes the noise (the bytes) of light that
    // bounces (off a floor here), not what the image means.
    let floor = r#"<shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform></shape>"#;
    let rr = |value: Option<&str>| rr(value).replace("</scene>", &format!("{floor}\n</scene>"));
    let dir = tempfile::tempdir().unwrap();
    let early = render(&write(dir.path(), "a.xml", &rr(Some("1"))), &[]);
    let late = render(&write(dir.path(), "b.xml", &rr(Some("64"))), &[]);
    assert_ne!(early, late);
}

#[test]
fn flip_normals_becomes_the_nodes_flip_normals_and_keeps_the_one_sided_bsdf() {
    let text = scene(
        r#"    <bsdf type="diffuse" id="d"/>
    <shape type="rectangle"><boolean name="flip_normals" value="true"/><ref id="d"/></shape>
    <shape type="disk"><ref id="d"/></shape>
    <shape type="disk"><boolean name="flip_normals" value="true"/><ref id="d"/></shape>
    <shape type="rectangle"><ref id="d"/></shape>"#,
    );
    let (t, warnings) = table(&text, &[]);
    assert!(warnings.is_empty(), "{warnings:?}");
    let Value::Array(objects) = &t.entries.iter().find(|e| e.key == "objects").unwrap().item.value else { panic!() };
    let key = |i: usize, key: &str| {
        let Value::Table(o) = &objects[i].value else { panic!() };
        o.entries.iter().find(|e| e.key == key).map(|e| e.item.value.clone())
    };
    // A rectangle's edges already turn lamplight's normal to -z (Mitsuba's uv,
    // formats/mitsuba/shapes.rs): its node is flipped unless Mitsuba flips it.
    assert_eq!(key(0, "flip_normals"), None);
    assert_eq!(key(1, "flip_normals"), None);
    assert_eq!(key(2, "flip_normals"), Some(Value::Bool(true)));
    assert_eq!(key(3, "flip_normals"), Some(Value::Bool(true)));
    assert_eq!(key(0, "material"), key(1, "material"), "both keep the one-sided diffuse");
}
