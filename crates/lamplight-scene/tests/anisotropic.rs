//! Anisotropic roughness (issue 26): `phong`'s `roughness_u`/`roughness_v` in
//! TOML, Mitsuba's `alpha_u`/`alpha_v` on `roughconductor` and `roughdielectric`
//! and `anisotropic` on the principled BSDFs, read into anisotropic lobes, and
//! the exact errors of bad input. The lobes themselves are tested in
//! `lamplight-core` (`bsdfs/anisotropic/tests.rs`).

use std::path::Path;

use lamplight_core::bsdfs::principled::PrincipledParams;
use lamplight_core::bsdfs::principled_thin::ThinParams;
use lamplight_core::bsdfs::{Distribution, Lobe};
use lamplight_core::materials::{bsdf_for, Model};
use lamplight_core::math::Vec3;
use lamplight_core::Scene;
use lamplight_scene::instantiate::SceneFile;

use crate::common::mitsuba_xml::{error as xml_error, one_sphere as xml, read};

const CAMERA: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n";

fn lobes(s: &Scene) -> Vec<Lobe> {
    bsdf_for(&s.materials[s.objects[0].material], Vec3::ZERO, true).lobes().to_vec()
}

/// Parses and builds `text` (after a camera) as `s.toml`.
fn toml(rest: &str) -> Result<Scene, String> {
    let text = format!("{CAMERA}{rest}");
    SceneFile::parse(Path::new("s.toml"), &text).and_then(|f| f.settings().and_then(|_| f.build())).map_err(|e| e.to_string())
}

const METAL: &str = "[materials.m]\nreflection = { type = \"conductor\", metal = \"gold\" }\nkd = 0\n";

#[test]
fn toml_roughness_u_and_v_make_anisotropic_metal_and_glass() {
    let s = toml(&format!("{METAL}roughness_u = 0.1\nroughness_v = 0.4\ndistribution = \"beckmann\"\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n"))
        .unwrap();
    let [Lobe::RoughConductor(c)] = lobes(&s)[..] else { panic!("{:?}", lobes(&s)) };
    assert_eq!((c.alpha, c.alpha_v, c.distribution), (0.1, 0.4, Distribution::Beckmann));
    assert!(bsdf_for(&s.materials[0], Vec3::ZERO, true).needs_tangent());
    let glass =
        "[materials.m]\nreflection = { type = \"dielectric\", ior = 1.5 }\nrefraction = { type = \"fresnel\", ior = 1.5 }\nkd = 0\n";
    let s = toml(&format!(
        "{glass}roughness_u = 0.3\nroughness_v = 0.05\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n"
    ))
    .unwrap();
    let [Lobe::RoughGlass(g)] = lobes(&s)[..] else { panic!("{:?}", lobes(&s)) };
    assert_eq!((g.alpha, g.alpha_v, g.distribution), (0.3, 0.05, Distribution::Ggx));
    // An isotropic roughness needs no tangent: the frame around the normal stays.
    let s = toml(&format!("{METAL}roughness = 0.2\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n"))
        .unwrap();
    let [Lobe::RoughConductor(c)] = lobes(&s)[..] else { panic!() };
    assert_eq!((c.alpha, c.alpha_v), (0.2, 0.2));
    assert!(!bsdf_for(&s.materials[0], Vec3::ZERO, true).needs_tangent());
}

#[test]
fn toml_bad_anisotropic_roughness_gives_its_exact_errors() {
    let object = "[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n";
    let cases = [
        ("roughness_u = 0.1\n", "s.toml:8:15: material \"m\": roughness_u: needs `roughness_v` too (anisotropic roughness takes both `roughness_u` and `roughness_v`)"),
        ("roughness_v = 0.1\n", "s.toml:8:15: material \"m\": roughness_v: needs `roughness_u` too (anisotropic roughness takes both `roughness_u` and `roughness_v`)"),
        (
            "roughness = 0.2\nroughness_u = 0.1\nroughness_v = 0.3\n",
            "s.toml:8:13: material \"m\": roughness: give either `roughness` or `roughness_u` and `roughness_v`, not both",
        ),
        ("roughness_u = 1.5\nroughness_v = 0.3\n", "s.toml:8:15: material \"m\": roughness_u: must be between 0 and 1, got 1.5"),
        ("roughness_u = 0.5\nroughness_v = -0.1\n", "s.toml:9:15: material \"m\": roughness_v: must be between 0 and 1, got -0.1"),
    ];
    for (rest, expected) in cases {
        assert_eq!(toml(&format!("{METAL}{rest}{object}")).err().as_deref(), Some(expected), "{rest}");
    }
}

#[test]
fn mitsuba_alpha_u_and_v_read_as_anisotropic_lobes() {
    let (s, warnings) = read(&xml(
        r#"<bsdf type="roughconductor"><float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.3"/><string name="distribution" value="ggx"/></bsdf>"#,
    ));
    assert!(warnings.is_empty(), "{warnings:?}");
    let [Lobe::RoughConductor(c)] = lobes(&s)[..] else { panic!("{:?}", lobes(&s)) };
    assert_eq!((c.alpha, c.alpha_v, c.distribution), (0.05, 0.3, Distribution::Ggx));
    let (s, warnings) =
        read(&xml(r#"<bsdf type="roughdielectric"><float name="alpha_u" value="0.4"/><float name="alpha_v" value="0.1"/></bsdf>"#));
    assert!(warnings.is_empty(), "{warnings:?}");
    let [Lobe::RoughGlass(g)] = lobes(&s)[..] else { panic!("{:?}", lobes(&s)) };
    assert_eq!((g.alpha, g.alpha_v, g.distribution), (0.4, 0.1, Distribution::Beckmann));
    // Equal values are the isotropic roughness.
    let (s, _) = read(&xml(r#"<bsdf type="roughconductor"><float name="alpha_u" value="0.2"/><float name="alpha_v" value="0.2"/></bsdf>"#));
    let [Lobe::RoughConductor(c)] = lobes(&s)[..] else { panic!() };
    assert_eq!((c.alpha, c.alpha_v), (0.2, 0.2));
}

#[test]
fn mitsuba_bad_anisotropic_roughness_gives_its_exact_errors() {
    let cases = [
        (
            r#"<bsdf type="roughconductor"><float name="alpha_u" value="0.1"/></bsdf>"#,
            "s.xml:3:26: bsdf \"roughconductor\": give both alpha_u and alpha_v (as Mitsuba)",
        ),
        (
            r#"<bsdf type="roughdielectric"><float name="alpha_v" value="0.1"/></bsdf>"#,
            "s.xml:3:26: bsdf \"roughdielectric\": give both alpha_u and alpha_v (as Mitsuba)",
        ),
        (
            r#"<bsdf type="roughconductor"><float name="alpha" value="0.1"/><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.2"/></bsdf>"#,
            "s.xml:3:26: bsdf \"roughconductor\": give either alpha or alpha_u and alpha_v, not both (as Mitsuba)",
        ),
        (
            r#"<bsdf type="roughconductor"><float name="alpha_u" value="1.5"/><float name="alpha_v" value="0.2"/></bsdf>"#,
            "s.xml:3:83: bsdf \"roughconductor\": alpha_u: must be between 0 and 1, got 1.5",
        ),
    ];
    for (bsdf, expected) in cases {
        assert_eq!(xml_error(&xml(bsdf)), expected);
    }
}

#[test]
fn mitsuba_principled_anisotropic_is_read_with_mitsubas_mapping() {
    let (s, warnings) =
        read(&xml(r#"<bsdf type="principled"><float name="anisotropic" value="0.6"/><float name="roughness" value="0.4"/></bsdf>"#));
    assert!(warnings.is_empty(), "{warnings:?}");
    let Some(Model::Principled(p)) = &s.materials[0].model else { panic!() };
    assert_eq!(*p, PrincipledParams { roughness: 0.4, anisotropic: 0.6, ..PrincipledParams::default() });
    assert!(bsdf_for(&s.materials[0], Vec3::ZERO, true).needs_tangent());
    let (s, warnings) = read(&xml(r#"<bsdf type="principledthin"><float name="anisotropic" value="0.3"/></bsdf>"#));
    assert!(warnings.is_empty(), "{warnings:?}");
    let Some(Model::PrincipledThin(p)) = &s.materials[0].model else { panic!() };
    assert_eq!(*p, ThinParams { anisotropic: 0.3, ..ThinParams::default() });
    // As a texture: a slot evaluated per hit, like the other scalars.
    let (s, warnings) = read(&xml(
        r#"<bsdf type="principled"><texture type="checkerboard" name="anisotropic"><float name="color0" value="0.2"/><float name="color1" value="0.9"/></texture></bsdf>"#,
    ));
    assert!(warnings.is_empty(), "{warnings:?}");
    let m = &s.materials[0];
    assert!(m.textures.as_ref().is_some_and(|t| t.iter().any(|(slot, _)| slot.name() == "principled.anisotropic")), "{:?}", m.textures);
}
