//! Mitsuba plugins that stand for others (issue 26): `merge` is its nested
//! shapes, the differentiable integrators render their primal image, and a
//! reference to a medium is said, not dropped.

use std::path::{Path, PathBuf};

use lamplight_core::params::{Table, Value};
use lamplight_core::RenderControl;
use lamplight_scene::formats::mitsuba;
use lamplight_scene::request::{Naming, Request, SceneRequest};

/// A scene of a camera, `integrator`, `body` and a film of 16 x 12, 4 spp.
fn scene(integrator: &str, body: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    {integrator}
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="0, 1, 5" target="0, 0.5, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="12"/><rfilter type="box"/></film>
    </sensor>
    <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.8, 0.2, 0.1"/></bsdf>
{body}
</scene>
"#
    )
}

const PATH4: &str = r#"<integrator type="path"><integer name="max_depth" value="4"/></integrator>"#;

/// A red sphere on a floor, lit by a rectangle above: light bounces, so the
/// depth limit shows in the image.
const SHAPES: &str = r#"<shape type="sphere"><point name="center" value="0, 0.5, 0"/><float name="radius" value="0.5"/><ref id="red"/></shape>
    <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform></shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate y="2"/></transform>
        <emitter type="area"><rgb name="radiance" value="10"/></emitter>
    </shape>"#;

struct Read {
    table: Table,
    warnings: Vec<String>,
    image: Vec<u8>,
}

/// Reads `text` (written as `s.xml`) and renders it as `lamplight render` would.
fn read(text: &str) -> Read {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), text);
    let (table, source) = mitsuba::read_table(&path, &[]).unwrap();
    let warnings = source.warnings.iter().map(|w| w.replace(&format!("{}/", dir.path().display()), "")).collect();
    let scene = SceneRequest::resolve_with(path.to_str().unwrap(), &[]).unwrap();
    let job = Request { threads: Some(2), ..Request::default() }.resolve(&scene.defaults, Naming::Flags).unwrap();
    let image = job.run(&scene.build().unwrap(), &RenderControl::default()).unwrap().image.to_srgb8();
    Read { table, warnings, image }
}

fn write(dir: &Path, text: &str) -> PathBuf {
    let path = dir.join("s.xml");
    std::fs::write(&path, text).unwrap();
    path
}

fn error(text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), text);
    match mitsuba::read(&path, &[]) {
        Ok(_) => panic!("read but should fail:\n{text}"),
        Err(e) => e.to_string().replace(&format!("{}/", dir.path().display()), ""),
    }
}

/// `[render] max_depth` of a read scene.
fn max_depth(t: &Table) -> i64 {
    let Value::Table(render) = &t.entries.iter().find(|e| e.key == "render").unwrap().item.value else { panic!("render is a table") };
    match render.entries.iter().find(|e| e.key == "max_depth").map(|e| &e.item.value) {
        Some(Value::Integer(d)) => *d,
        other => panic!("{other:?}"),
    }
}

#[test]
fn merge_renders_as_its_nested_shapes() {
    let plain = read(&scene(PATH4, SHAPES));
    let merged = read(&scene(PATH4, &format!(r#"<shape type="merge">{SHAPES}</shape>"#)));
    assert!(merged.warnings.is_empty(), "{:?}", merged.warnings);
    assert_eq!(merged.image, plain.image, "the same image as the shapes outside a merge");
    // Not an empty scene by chance: the lit sphere is there.
    assert!(plain.image.iter().any(|&b| b > 40));
    // What is not a shape is said, at its place.
    let odd = read(&scene(PATH4, &format!(r#"<shape type="merge">{SHAPES}<bsdf type="diffuse"/></shape>"#)));
    assert_eq!(odd.warnings, ["s.xml:15:13: shape \"merge\": nested <bsdf> is not supported, ignored"]);
    assert_eq!(odd.image, plain.image);
}

#[test]
fn differentiable_integrators_render_their_primal_image() {
    let path = read(&scene(PATH4, SHAPES));
    for kind in ["prb", "prb_basic", "prb_projective", "prbvolpath"] {
        let settings =
            if kind == "prb_projective" { r#"<integer name="sppc" value="8"/><string name="guiding" value="grid"/>"# } else { "" };
        let integrator = format!(r#"<integrator type="{kind}"><integer name="max_depth" value="4"/>{settings}</integrator>"#);
        let prb = read(&scene(&integrator, SHAPES));
        assert!(prb.warnings.is_empty(), "{kind}: {:?}", prb.warnings);
        assert_eq!(prb.image, path.image, "{kind}: path's image");
        // Mitsuba's differentiable integrators stop at 6 by default, its path never.
        let default = read(&scene(&format!(r#"<integrator type="{kind}"/>"#), SHAPES));
        assert_eq!(max_depth(&default.table), 6, "{kind}");
    }
    assert_eq!(max_depth(&read(&scene(r#"<integrator type="path"/>"#, SHAPES)).table), 64);
    let direct = read(&scene(r#"<integrator type="direct_projective"><string name="guiding" value="none"/></integrator>"#, SHAPES));
    assert!(direct.warnings.is_empty(), "{:?}", direct.warnings);
    assert_eq!(direct.image, read(&scene(r#"<integrator type="direct"/>"#, SHAPES)).image);
    assert_eq!(max_depth(&direct.table), 2);
    assert_eq!(
        error(&scene(r#"<integrator type="prb"><integer name="max_depth" value="0"/></integrator>"#, SHAPES)),
        "s.xml:2:61: integrator \"prb\": max_depth: must be -1 or between 1 and 64, got 0"
    );
    assert_eq!(
        error(&scene(r#"<integrator type="aov"/>"#, SHAPES)),
        "s.xml:2:23: integrator: \"aov\" is not supported (lamplight reads path, direct, ptracer, volpath, the prb integrators and moment)"
    );
}

#[test]
fn a_reference_to_a_medium_is_a_warning() {
    let body = format!(
        r#"<medium type="homogeneous" id="fog"/>
    <shape type="sphere"><ref id="red"/><ref id="fog" name="interior"/></shape>
    {SHAPES}"#
    );
    let fog = read(&scene(PATH4, &body));
    assert_eq!(
        fog.warnings,
        [
            "s.xml:10:1: <medium>: not supported, ignored",
            "s.xml:11:41: shape \"sphere\": <ref id=\"fog\"> names a <medium>, which is not supported, ignored"
        ]
    );
}
